// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_INTRINSIC_FLIP_TO_DELAUNAY_H
#define ANISO_CONFORMAL_INTERNAL_INTRINSIC_FLIP_TO_DELAUNAY_H

#include <Aniso_conformal/Intrinsic_triangulation.h>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <unordered_map>
#include <utility>
#include <vector>

// Lawson's edge-flip algorithm on an intrinsic triangulation, written once for every flip the pipeline
// makes (like geometry-central's flipToDelaunay with its flip type). What differs between the passes is
// the rule: which edges want a flip (the metric-Delaunay test of stage 2, paper Fig. 3; the intrinsic
// Delaunay test of a Euclidean or hyperbolic vertex-scaled metric in stage 3, Gillespie, Springborn and
// Crane 2021) and the length the new edge gets (recomputed later, the law of cosines of the unfolded
// quad, Ptolemy's relation, the hyperbolic law of cosines). A rule is a class with
//   bool wants_flip(const Intrinsic_triangulation&, int h) const;     // h: an interior halfedge
//   double flipped_length(const Intrinsic_triangulation&, int h) const;  // before the flip; NaN to leave unset
// where wants_flip() also refuses the flips the caller cannot take (a double edge, a kept star, a fold).

namespace Aniso_conformal {
namespace internal {

struct Flip_pass {
  std::size_t flips = 0;       // flips made
  std::size_t budget = 0;      // the bound on them
  bool budget_hit = false;     // edges were still queued when the bound stopped the pass
  std::size_t capped = 0;      // flips refused because their edge's vertex pair had been flipped away
                               // `flips_per_vertex_pair` times already (a local cycle stopped)
};

// the unordered pair of an edge's end vertices, as one key
inline std::uint64_t vertex_pair_key(int a, int b)
{
  if(a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint64_t(std::uint32_t(b));
}

// Flips the interior edges of `seeds` (halfedges; both of an edge may appear) and, after every flip, the
// four edges of its quad, until no queued edge wants a flip or the budget is spent. The budget is
// `flips_per_edge` times the number of edges first queued, plus 100: Delaunay flips terminate in exact
// arithmetic, so a pass that hits it is cycling through rounding, and the caller decides what that means.
// A rule that is not a Delaunay criterion (stage 2's metric-Delaunay test, whose metric varies across a
// quad) can also cycle for real: one quad flipping its diagonal back and forth, or a few quads passing a
// flip around, forever. `flips_per_vertex_pair` > 0 bounds that locally: an edge whose two end vertices
// have been joined and flipped apart that many times in this pass stays, and the rest of the queue goes
// on (the global budget would otherwise be spent on one cycle, and every other edge left unflipped).
// In exact Delaunay flipping an edge, once flipped away, never comes back (the pairs' count is at most
// 1), so a cap of 2 or more changes nothing there.
template <typename FlipRule>
Flip_pass flip_to_delaunay(Intrinsic_triangulation& itri, const FlipRule& rule, const std::vector<int>& seeds,
                           std::size_t flips_per_edge, std::size_t flips_per_vertex_pair = 0)
{
  std::deque<int> queue;
  std::vector<char> queued(itri.number_of_halfedges(), 0);
  auto enqueue = [&](int h) {
    const int r = itri.is_edge_representative(h) ? h : itri.twin(h);
    if(itri.twin(r) >= 0 && !queued[std::size_t(r)]) {
      queued[std::size_t(r)] = 1;
      queue.push_back(r);
    }
  };
  for(int h : seeds) enqueue(h);
  Flip_pass pass;
  pass.budget = flips_per_edge * queue.size() + 100;
  std::unordered_map<std::uint64_t, std::size_t> flipped_away;  // vertex pair -> times its edge was flipped
  while(!queue.empty() && pass.flips < pass.budget) {
    const int h = queue.front();
    queue.pop_front();
    queued[std::size_t(h)] = 0;
    if(itri.twin(h) < 0 || itri.is_seam_edge(h) || itri.flip_joins_seam_neighbours(h) || !rule.wants_flip(itri, h)) continue;
    if(flips_per_vertex_pair > 0) {
      std::size_t& count = flipped_away[vertex_pair_key(itri.tail(h), itri.head(h))];
      if(count >= flips_per_vertex_pair) {
        ++pass.capped;
        continue;
      }
      ++count;
    }
    const double length = rule.flipped_length(itri, h);
    const int g = itri.flip(h);
    itri.set_length(g, length);
    ++pass.flips;
    for(int e : {Intrinsic_triangulation::next(g), Intrinsic_triangulation::prev(g),
                 Intrinsic_triangulation::next(itri.twin(g)), Intrinsic_triangulation::prev(itri.twin(g))})
      enqueue(e);
  }
  pass.budget_hit = !queue.empty();
  return pass;
}

// every halfedge of `itri`, the seeds of a pass over the whole triangulation
inline std::vector<int> all_halfedges(const Intrinsic_triangulation& itri)
{
  std::vector<int> h(itri.number_of_halfedges());
  for(std::size_t i = 0; i < h.size(); ++i) h[i] = int(i);
  return h;
}

// a pass over every edge of `itri`
template <typename FlipRule>
Flip_pass flip_to_delaunay(Intrinsic_triangulation& itri, const FlipRule& rule, std::size_t flips_per_edge,
                           std::size_t flips_per_vertex_pair = 0)
{
  return flip_to_delaunay(itri, rule, all_halfedges(itri), flips_per_edge, flips_per_vertex_pair);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_INTRINSIC_FLIP_TO_DELAUNAY_H
