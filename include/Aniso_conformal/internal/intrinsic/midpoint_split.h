// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_INTRINSIC_MIDPOINT_SPLIT_H
#define ANISO_CONFORMAL_INTERNAL_INTRINSIC_MIDPOINT_SPLIT_H

#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Surface_point.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

// The split of an intrinsic edge at its midpoint with the lengths of the flat metric kept: the halves
// of the edge, and the median of each of its triangles (Apollonius' theorem). Used where an edge that
// must not flip (a seam between a hole's patch and the surface) faces too large an angle.

namespace Aniso_conformal {
namespace internal {

// splits the edge of `h` (interior: two triangles) at its midpoint, the new vertex at `sp` with the mean
// metric square root of the ends, and sets the four new edges' lengths; returns the new vertex
inline int split_interior_edge_at_midpoint(Intrinsic_triangulation& itri, int h, const Surface_point& sp)
{
  const int t = itri.twin(h), a = itri.tail(h), b = itri.head(h), c = itri.opposite_vertex(h), d = itri.opposite_vertex(t);
  const double L = itri.length(h);
  auto median = [L](double x, double y) { return 0.5 * std::sqrt(std::max(0.0, 2 * x * x + 2 * y * y - L * L)); };
  const double mc = median(itri.length(Intrinsic_triangulation::next(h)), itri.length(Intrinsic_triangulation::prev(h)));
  const double md = median(itri.length(Intrinsic_triangulation::next(t)), itri.length(Intrinsic_triangulation::prev(t)));
  const int m = itri.split(h, sp, 0.5 * (itri.Q(a) + itri.Q(b)));
  itri.set_length(itri.find_halfedge(a, m), 0.5 * L);
  itri.set_length(itri.find_halfedge(m, b), 0.5 * L);
  itri.set_length(itri.find_halfedge(m, c), mc);
  itri.set_length(itri.find_halfedge(m, d), md);
  return m;
}

// the midpoint of the segment between vertices `a` and `b` of `itri`, both on one input face or edge
// (a seam piece, a piece of a boundary edge): the mean of their barycentric coordinates over the input
// vertices, the three largest weights kept and renormalised
inline Surface_point midpoint_surface_point(const Intrinsic_triangulation& itri, int a, int b)
{
  std::vector<std::pair<std::size_t, double>> w;
  for(const Surface_point* p : {&itri.point(a), &itri.point(b)})
    for(int k = 0; k < 3; ++k) {
      if(p->barycentric[k] == 0) continue;
      auto it = std::find_if(w.begin(), w.end(), [&](const std::pair<std::size_t, double>& x) { return x.first == p->vertices[std::size_t(k)]; });
      if(it == w.end()) w.emplace_back(p->vertices[std::size_t(k)], 0.5 * p->barycentric[k]);
      else it->second += 0.5 * p->barycentric[k];
    }
  std::sort(w.begin(), w.end(), [](const std::pair<std::size_t, double>& x, const std::pair<std::size_t, double>& y) { return x.second > y.second; });
  Surface_point sp;
  sp.position = 0.5 * (itri.position(a) + itri.position(b));
  double total = 0;
  for(std::size_t k = 0; k < 3; ++k) {
    const std::size_t i = std::min(k, w.size() - 1);
    sp.vertices[k] = w[i].first;
    sp.barycentric[int(k)] = k < w.size() ? w[k].second : 0.0;
    total += sp.barycentric[int(k)];
  }
  sp.barycentric /= total;
  return sp;
}

// Splits at its midpoint (split_interior_edge_at_midpoint(), midpoint_surface_point()), in that order,
// each edge (a, b) of `edges` that is still an interior edge of `itri` and whose halfedge from a to b
// `keep` accepts; an edge listed again, in either direction, is no longer an edge once split and is
// skipped. Returns the number of edges split. The retries of the spherical and cone embeddings split so
// the edges of triangles a solve left flat.
template <typename Keep>
std::size_t split_edges_at_midpoints(Intrinsic_triangulation& itri, const std::vector<std::pair<int, int>>& edges, const Keep& keep)
{
  std::size_t made = 0;
  for(const auto& ab : edges) {
    const int h = itri.find_halfedge(ab.first, ab.second);
    if(h < 0 || itri.twin(h) < 0 || !keep(h)) continue;
    split_interior_edge_at_midpoint(itri, h, midpoint_surface_point(itri, ab.first, ab.second));
    ++made;
  }
  return made;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_INTRINSIC_MIDPOINT_SPLIT_H
