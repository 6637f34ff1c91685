// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_ADJUST_EDGE_LENGTHS_H
#define ANISO_CONFORMAL_ADJUST_EDGE_LENGTHS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>
#include <vector>

/// \file adjust_edge_lengths.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * what `adjust_edge_lengths()` did
 */
struct Edge_adjustment_report {
  std::size_t invalid_triangles_before = 0;  ///< triangles violating the triangle inequality before any flip
  std::size_t flips = 0;                     ///< metric-Delaunay flips
  std::size_t splits = 0;                    ///< longest-edge splits
  std::size_t rounds = 0;                    ///< flip-then-split rounds
};

namespace internal {

// Metric-Delaunay test of paper Fig. 3: flip edge (a,b) with opposite vertices c, d when the angles at
// c and d sum to more than pi, the angles taken in the space transformed by the mean Q of the four
// vertices (so they are the angles of the affinely transformed quad).
inline bool metric_delaunay_wants_flip(const Intrinsic_triangulation& itri, int h)
{
  const int a = itri.tail(h), b = itri.head(h), c = itri.opposite_vertex(h), d = itri.opposite_vertex(itri.twin(h));
  const Eigen::Matrix3d Q = (itri.Q(a) + itri.Q(b) + itri.Q(c) + itri.Q(d)) / 4.0;
  auto angle = [&](int apex, int p, int q) {
    Eigen::Vector3d u = Q * (itri.position(p) - itri.position(apex)), v = Q * (itri.position(q) - itri.position(apex));
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  return angle(c, a, b) + angle(d, b, a) > 3.14159265358979323846 + 1e-12;
}

// A flip must not fold the surface: both new triangles keep the orientation of the old pair (for a
// planar input this is exactly the convexity of the quad).
inline bool flip_keeps_orientation(const Intrinsic_triangulation& itri, int h)
{
  const int a = itri.tail(h), b = itri.head(h), c = itri.opposite_vertex(h), d = itri.opposite_vertex(itri.twin(h));
  if(itri.find_halfedge(c, d) >= 0) return false;  // the new edge exists already
  auto normal = [&](int p, int q, int r) {
    return Eigen::Vector3d((itri.position(q) - itri.position(p)).cross(itri.position(r) - itri.position(p)));
  };
  const Eigen::Vector3d n0 = normal(a, b, c), n1 = normal(b, a, d);
  const Eigen::Vector3d ref = n0.normalized() + n1.normalized();
  const Eigen::Vector3d m0 = normal(c, a, d), m1 = normal(d, b, c);
  const double scale = n0.norm() + n1.norm();
  return m0.dot(ref) > 1e-10 * scale && m1.dot(ref) > 1e-10 * scale;
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * makes the metric edge lengths of `itri` a valid triangulation (paper 3.2): computes the lengths
 * (`compute_metric_edge_lengths()`), makes the triangulation metric-Delaunay by edge flips (paper
 * Fig. 3), and while some triangle still violates the triangle inequality splits its longest edge at
 * the midpoint (projected onto `surface`; its `Q` is the mean of the edge's ends), then repeats.
 *
 * \param itri the triangulation, modified in place
 * \param surface the input surface the vertices of `itri` lie on
 * \param np optional named parameters:
 *   - `max_adjustment_rounds` (unsigned, default 50): bound on flip-then-split rounds;
 *   - `visitor`: `on_iteration(Stage::EDGE_LENGTHS, round, bound, invalid_triangles)`.
 *
 * The total number of flips is bounded by 20 times the number of edges per round (a metric that varies
 * across a quad can make Lawson's algorithm cycle); flipping then stops for that round.
 * \throws Convergence_failure if invalid triangles remain after `max_adjustment_rounds` rounds
 *         (the residual is their number): the metric varies too fast for the input's resolution.
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Edge_adjustment_report adjust_edge_lengths(Intrinsic_triangulation& itri, const Input_surface& surface,
                                           const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const std::size_t max_rounds = choose_parameter(get_parameter(np, internal_np::max_adjustment_rounds), 50u);
  typename internal::Visitor_reference<NamedParameters>::type vis = internal::get_visitor(np);

  Edge_adjustment_report report;
  compute_metric_edge_lengths(itri);
  auto count_invalid = [&]() {
    std::size_t n = 0;
    for(std::size_t f = 0; f < itri.number_of_faces(); ++f)
      if(!internal::face_is_valid(itri, f)) ++n;
    return n;
  };
  report.invalid_triangles_before = count_invalid();

  for(report.rounds = 1;; ++report.rounds) {
    // 1. metric-Delaunay flips (Lawson's queue)
    std::deque<int> queue;
    std::vector<char> queued(itri.number_of_halfedges(), 0);
    for(int h = 0; h < int(itri.number_of_halfedges()); ++h)
      if(itri.twin(h) >= 0 && itri.is_edge_representative(h)) {
        queue.push_back(h);
        queued[h] = 1;
      }
    const std::size_t flip_budget = 20 * itri.number_of_halfedges() / 2 + 100;
    std::size_t flips_this_round = 0;
    while(!queue.empty() && flips_this_round < flip_budget) {
      const int h = queue.front();
      queue.pop_front();
      queued[h] = 0;
      if(itri.twin(h) < 0 || !internal::metric_delaunay_wants_flip(itri, h) || !internal::flip_keeps_orientation(itri, h))
        continue;
      const int g = itri.flip(h);
      ++flips_this_round;
      for(int e : {Intrinsic_triangulation::next(g), Intrinsic_triangulation::prev(g),
                   Intrinsic_triangulation::next(itri.twin(g)), Intrinsic_triangulation::prev(itri.twin(g))}) {
        int r = itri.is_edge_representative(e) ? e : itri.twin(e);
        if(itri.twin(r) >= 0 && !queued[r]) {
          queue.push_back(r);
          queued[r] = 1;
        }
      }
    }
    report.flips += flips_this_round;
    compute_metric_edge_lengths(itri);

    // 2. longest-edge splits of the triangles that are still invalid
    std::vector<int> to_split;
    for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
      if(internal::face_is_valid(itri, f)) continue;
      int best = int(3 * f);
      for(int k = 1; k < 3; ++k)
        if(itri.length(int(3 * f + k)) > itri.length(best)) best = int(3 * f + k);
      to_split.push_back(itri.is_edge_representative(best) ? best : itri.twin(best));
    }
    std::sort(to_split.begin(), to_split.end());
    to_split.erase(std::unique(to_split.begin(), to_split.end()), to_split.end());
    if(to_split.empty()) break;
    if(report.rounds >= max_rounds)
      throw Convergence_failure("edge-length adjustment: " + std::to_string(to_split.size()) +
                                    " triangles still violate the triangle inequality after " +
                                    std::to_string(max_rounds) +
                                    " rounds of flips and splits; smooth the metric or refine the input",
                                double(to_split.size()));
    // split by vertex pairs: earlier splits renumber halfedges of the faces they touch
    std::vector<std::pair<int, int>> pairs;
    for(int h : to_split) pairs.emplace_back(itri.tail(h), itri.head(h));
    for(const auto& p : pairs) {
      const int h = itri.find_halfedge(p.first, p.second);
      if(h < 0) continue;  // already split through a neighbour
      const Eigen::Vector3d mid = 0.5 * (itri.position(p.first) + itri.position(p.second));
      // boundary edges are pieces of input boundary edges, so their midpoints lie on the input
      // already; interior midpoints of flipped edges are chords and get projected
      Surface_point sp = surface.project(mid);
      if(itri.twin(h) < 0) sp.position = mid;
      itri.split(h, sp, 0.5 * (itri.Q(p.first) + itri.Q(p.second)));
      ++report.splits;
    }
    compute_metric_edge_lengths(itri);
    if(!vis.on_iteration(Stage::EDGE_LENGTHS, report.rounds, max_rounds, double(count_invalid())))
      throw Cancelled("cancelled by the visitor during the edge-length adjustment");
  }
  return report;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_ADJUST_EDGE_LENGTHS_H
