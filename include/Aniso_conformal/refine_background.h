// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_REFINE_BACKGROUND_H
#define ANISO_CONFORMAL_REFINE_BACKGROUND_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/intrinsic/longest_edge_queue.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/internal/tensor.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <queue>
#include <string>
#include <tuple>
#include <vector>

/// \file refine_background.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * what `refine_background()` did
 */
struct Refinement_report {
  std::size_t vertices_before = 0;  ///< vertices of the background before the refinement
  std::size_t vertices_after = 0;   ///< and after
  std::size_t splits = 0;           ///< edges split
  /// the edge length, in the metric, of an equilateral mesh with the requested number of vertices and the
  /// background's area in the metric: no background edge is left longer than twice that, except where
  /// `capped` edges were
  double output_edge_length = 0;
  double longest_edge = 0;          ///< the longest background edge in the metric at the end
  /// edges created by a split whose measured length exceeded `0.95` times the split edge's key, and whose
  /// key was capped there (each counted once per triangle it was created in): where the metric turns fast
  /// along an edge, an edge left longer than `2 h` (see `refine_background()`)
  std::size_t capped = 0;
};

namespace internal {

// the least relative decrease of the refinement's keys from a split edge to the edges its split creates:
// Rivara's bisection in a constant metric decreases them by sqrt(3) / 2 (a median of a triangle whose
// longest side is split) or 1 / 2 (the halves); 0.95 leaves that alone and stops a chain of splits whose
// measured lengths do not decrease within log(l / 2 h) / log(1 / 0.95) generations
constexpr double refinement_decrease = 0.95;

// the length in the metric of the segment pq with metric square roots Qp and Qq at its ends
inline double metric_segment_length(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Matrix3d& Qp,
                                    const Eigen::Matrix3d& Qq)
{
  return (0.5 * (Qp + Qq) * (q - p)).norm();
}

// the area of `itri` in the metric: the triangles of the metric edge lengths (Heron; an invalid
// triangle counts as flat)
inline double metric_area(const Intrinsic_triangulation& itri)
{
  double area = 0;
  for(std::size_t f = 0; f < itri.number_of_faces(); ++f)
    area += heron_area(itri.length(int(3 * f)), itri.length(int(3 * f + 1)), itri.length(int(3 * f + 2)));
  return area;
}

// A queue of background edges (metric length, tail, head), longest first, as refine_seams() and
// refine_creases() fill it with the pieces of a curve of the input (a hole's loop, a crease).
typedef std::priority_queue<std::tuple<double, int, int>> Longest_edge_queue;

// Splits the edges of `queue` longer than `longest` in the metric, longest first, each at its straight
// midpoint, which lies on the input's edge the piece belongs to (the point is its own projection onto
// `input`; its metric square root is the mean of its ends'); the two halves go back in the queue. An entry
// no longer a background edge (split already, or flipped) or refused by `splittable(h)` (h its halfedge)
// is dropped. The new edges' lengths are set (compute_metric_edge_lengths()). Shared by the holes' loops
// (hole_patches.h) and the creases (crease_sites.h). Returns the number of splits.
// \throws Remeshing_failure if `itri` would need more than `most` vertices ("remesh(): <what> need ...")
template <typename Splittable>
std::size_t split_longest_at_input_midpoints(Intrinsic_triangulation& itri, const Input_surface& input, Longest_edge_queue& queue,
                                             double longest, std::size_t most, const Splittable& splittable, const std::string& what)
{
  auto length = [&](int a, int b) { return metric_segment_length(itri.position(a), itri.position(b), itri.Q(a), itri.Q(b)); };
  std::size_t splits = 0;
  while(!queue.empty() && std::get<0>(queue.top()) > longest) {
    const std::tuple<double, int, int> top = queue.top();
    queue.pop();
    const int a = std::get<1>(top), b = std::get<2>(top);
    int h = itri.find_halfedge(a, b);
    if(h < 0) h = itri.find_halfedge(b, a);
    if(h < 0 || !splittable(h)) continue;
    if(itri.number_of_vertices() >= most)
      throw Remeshing_failure("remesh(): " + what + " need more than " + std::to_string(most) + " background vertices to carry their sites");
    const Eigen::Vector3d mid = 0.5 * (itri.position(a) + itri.position(b));
    Surface_point sp = input.project(mid);
    sp.position = mid;
    const int m = itri.split(h, sp, 0.5 * (itri.Q(a) + itri.Q(b)));
    ++splits;
    queue.emplace(length(a, m), a, m);
    queue.emplace(length(m, b), m, b);
  }
  if(splits > 0) compute_metric_edge_lengths(itri);
  return splits;
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * refines the background `itri` so that it carries `number_of_sites` output vertices and resolves the
 * metric at their scale (issue 14): with `A` the area of `itri` in the metric and
 * `h = sqrt(2 A / (sqrt(3) n))` the edge length of an equilateral mesh with `n = number_of_sites`
 * vertices covering it, the longest edge in the metric is split at its midpoint while an edge is longer
 * than `2 h`, or while the background has fewer than `2 n` vertices (a CVT cell then spans several
 * background triangles, whose linear density represents the conformal factor). A background that
 * already meets both is left as it is. Once refined, the area is measured again and, while `h` falls by
 * more than 5 % (at most 4 rounds), the refinement goes on to the new `h`: on a coarse input the lengths
 * of long edges overestimate the area where the metric varies inside an input triangle (the feature
 * sizing's scale near the rims of a thin coin, its caps fans of 96 triangles: `h` 0.108 measured on the
 * input, 0.083 once refined, so the rims' sites came 1.5 times too far apart); `Refinement_report::
 * output_edge_length` is the last `h`.
 *
 * An edge is split by its key: its length as measured at the start, or, for an edge the refinement
 * created, its length but at most `0.95` times the key of the split edge it came from. The measured
 * length (the norm of the mean of the two ends' square roots of the metric applied to the edge, the
 * midpoint rule) is not monotone under splitting where the metric's principal directions turn along an
 * edge: the mean of two square roots underestimates the square root of the mean (the square root is
 * operator concave), so an edge from a new vertex inside a triangle to a far corner can measure as long as
 * the edge just split, and the bisection cycled without end (CGAL's part.off with the curvature metric at
 * 2000 vertices: vertices inserted over and over a third and two thirds along one input edge, in ever
 * thinner triangles, until the bound below). The keys make termination hold by construction: once the
 * background has `2 n` vertices only keys above `2 h` are split, a key `k` generations from an edge of the
 * start is at most `0.95^k` times the longest edge of the start, and each split creates at most four edges,
 * so the splits are finitely many. Where a key is capped the edge may be left longer than `2 h` in the
 * measured length (`Refinement_report::capped`, `Refinement_report::longest_edge`).
 *
 * Splitting the globally longest edge is Rivara's longest-edge bisection: the split edge is the longest of
 * both its triangles, so the smallest angle of the background never falls below half of what it was (in
 * the lengths measured). The new vertex is the midpoint of the edge. Before any flip every edge of `itri`
 * is an input edge or a segment inside an input face, so the midpoint is a point of the input surface:
 * its `Surface_point` is found on `surface`, and its metric square root is the metric evaluated there
 * (not an average), which resolves the metric where the input is coarse. The map back stays exact and
 * the output of a coarse flat-faced input lies on its faces.
 *
 * The edge lengths of `itri` are (re)computed at the end (`compute_metric_edge_lengths()`).
 *
 * \param itri the background, as built from `surface` and the metric's square roots (before
 *        `adjust_edge_lengths()`): no edge may have been flipped
 * \param surface the input surface the vertices of `itri` lie on
 * \param metric a model of `AnisotropicMetric`, evaluated at the new vertices
 * \param number_of_sites the number of output vertices the background must carry (>= 1)
 * \returns what it did
 * \throws Invalid_input if the metric is not positive definite at a new vertex
 * \throws Remeshing_failure if the refinement needs more than `64 n + 4 V` vertices (`V` those of the
 *         input): a metric that varies faster than any background of that size resolves (the keys bound the
 *         number of splits, not this count)
 */
template <typename AnisotropicMetric>
Refinement_report refine_background(Intrinsic_triangulation& itri, const Input_surface& surface, const AnisotropicMetric& metric,
                                    std::size_t number_of_sites)
{
  Refinement_report report;
  report.vertices_before = itri.number_of_vertices();
  const std::size_t n = std::max<std::size_t>(1, number_of_sites);
  compute_metric_edge_lengths(itri);
  report.output_edge_length = std::sqrt(2 * internal::metric_area(itri) / (std::sqrt(3.0) * double(n)));
  const std::size_t least = 2 * n, most = 64 * n + 4 * report.vertices_before;
  auto length = [&](int a, int b) { return internal::metric_segment_length(itri.position(a), itri.position(b), itri.Q(a), itri.Q(b)); };

  // rounds: the area measured on a coarse background overestimates it where the metric varies inside an
  // input triangle (the midpoint rule on a long edge between a small and a large tensor), so once refined
  // it is measured again, and the refinement goes on to the smaller length, until the length settles
  for(int round = 0; round < 4; ++round) {
    const double longest_allowed = 2 * report.output_edge_length;
    internal::Longest_edge_queue queue = internal::longest_edge_queue(itri, length);
    while(!queue.empty()) {
      const internal::Edge_key top = queue.top();
      if(std::get<0>(top) <= longest_allowed && itri.number_of_vertices() >= least) break;
      queue.pop();
      int h = itri.find_halfedge(std::get<1>(top), std::get<2>(top));
      if(h < 0) h = itri.find_halfedge(std::get<2>(top), std::get<1>(top));  // a boundary edge has one side
      if(h < 0) continue;  // split already
      if(itri.number_of_vertices() >= most)
        throw Remeshing_failure("background refinement: " + std::to_string(n) + " output vertices need a background of more than " +
                                std::to_string(most) + " vertices to resolve the metric (it varies too fast for the input's resolution)");
      const int a = itri.tail(h), b = itri.head(h);
      const Eigen::Vector3d mid = 0.5 * (itri.position(a) + itri.position(b));
      Surface_point sp = surface.project(mid);
      sp.position = mid;  // on the input already: an input edge or a segment inside an input face
      const Eigen::Matrix3d M = metric.tensor(sp);
      if(!internal::all_finite(M) || !(internal::tangent_positivity(M, surface.is_planar() ? Eigen::Vector3d(0, 0, 1)
                                                                                            : Eigen::Vector3d(surface.vertex_normals()[sp.vertices[0]])) > 1e-12))
        throw Invalid_input("background refinement: the metric is not finite or not positive definite on the tangent plane at (" +
                            std::to_string(mid.x()) + ", " + std::to_string(mid.y()) + ", " + std::to_string(mid.z()) + ")");
      const int m = itri.split(h, sp, internal::symmetric_sqrt(M));
      ++report.splits;
      // the new edges: from m to the head of each outgoing halfedge, and to the tail of the halfedge that
      // enters m in the same face (on the boundary, the one neighbour no outgoing halfedge reaches)
      const double cap = internal::refinement_decrease * std::get<0>(top);  // the key of an edge this split creates
      for(int o : itri.outgoing_halfedges(m))
        for(int x : {itri.head(o), itri.opposite_vertex(o)}) {
          const double l = length(m, x);
          if(l > cap) ++report.capped;
          queue.emplace(std::min(l, cap), m, x);
        }
    }
    if(report.splits == 0) break;  // nothing split: the area measured is that of the background as it stays
    compute_metric_edge_lengths(itri);
    const double measured = std::sqrt(2 * internal::metric_area(itri) / (std::sqrt(3.0) * double(n)));
    const bool settled = !(measured < 0.95 * report.output_edge_length);
    report.output_edge_length = std::min(report.output_edge_length, measured);
    if(settled) break;
  }
  report.vertices_after = itri.number_of_vertices();
  for(int h = 0; h < int(itri.number_of_halfedges()); ++h)
    if(itri.is_edge_representative(h)) report.longest_edge = std::max(report.longest_edge, length(itri.tail(h), itri.head(h)));
  compute_metric_edge_lengths(itri);
  return report;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_REFINE_BACKGROUND_H
