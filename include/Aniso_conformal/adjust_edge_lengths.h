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
#include <limits>
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
  /// the length added to every edge by the final mollification, relative to the median edge length
  /// (0 if the splits sufficed)
  double mollification = 0;
  /// triangles repaired by changing an edge length locally when splits stalled
  std::size_t repaired_triangles = 0;
  /// rounds whose flip pass stopped at its budget (`max_flips_per_edge`) with edges still to flip
  std::size_t flip_budget_hits = 0;
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

// Local repair of the few triangles that splits cannot fix: an invalid triangle's longest edge is
// shortened to just below the sum of the other two when its other triangle stays valid, otherwise its two
// shorter edges are lengthened; a few passes. Returns true if every triangle is valid afterwards.
inline bool repair_lengths(Intrinsic_triangulation& itri, Edge_adjustment_report& report)
{
  const double shrink = 1 - 1e-4;
  for(int pass = 0; pass < 10; ++pass) {
    bool all_valid = true;
    for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
      if(face_is_valid(itri, f)) continue;
      all_valid = false;
      int k = int(3 * f);
      for(int j = 1; j < 3; ++j)
        if(itri.length(int(3 * f + j)) > itri.length(k)) k = int(3 * f + j);
      const int i = Intrinsic_triangulation::next(k), j = Intrinsic_triangulation::prev(k);
      const double target = (itri.length(i) + itri.length(j)) * shrink;
      const int t = itri.twin(k);
      bool other_ok = true;
      if(t >= 0)
        other_ok = satisfies_triangle_inequality(target, itri.length(Intrinsic_triangulation::next(t)),
                                                 itri.length(Intrinsic_triangulation::prev(t)));
      if(other_ok) {
        itri.set_length(k, target);
      } else {
        const double grow = 0.5 * (itri.length(k) / shrink - itri.length(i) - itri.length(j));
        itri.set_length(i, itri.length(i) + grow);
        itri.set_length(j, itri.length(j) + grow);
      }
      ++report.repaired_triangles;
    }
    if(all_valid) return true;
  }
  for(std::size_t f = 0; f < itri.number_of_faces(); ++f)
    if(!face_is_valid(itri, f)) return false;
  return true;
}

// Intrinsic mollification (Sharp, Soliman, Crane 2019): adds the same epsilon to every edge length,
// the smallest that makes every triangle satisfy the strict triangle inequality. Accepted only when
// epsilon is at most a tenth of the median edge length; report.mollification gets epsilon relative to
// that median either way.
inline bool mollify(Intrinsic_triangulation& itri, Edge_adjustment_report& report)
{
  std::vector<double> lengths;
  double eps = 0;
  for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
    const double l[3] = {itri.length(int(3 * f)), itri.length(int(3 * f + 1)), itri.length(int(3 * f + 2))};
    const double margin = 1e-6 * (l[0] + l[1] + l[2]);
    for(int k = 0; k < 3; ++k) {
      eps = std::max(eps, l[k] - l[(k + 1) % 3] - l[(k + 2) % 3] + margin);
      lengths.push_back(l[k]);
    }
  }
  std::nth_element(lengths.begin(), lengths.begin() + std::ptrdiff_t(lengths.size() / 2), lengths.end());
  const double median = lengths[lengths.size() / 2];
  // a zero or non-finite median (a surface flat to rounding level) must not put NaN in the message
  report.mollification = median > 0 ? eps / median : std::numeric_limits<double>::infinity();
  if(!(report.mollification <= 0.1)) return false;
  for(int h = 0; h < int(itri.number_of_halfedges()); ++h)
    if(itri.is_edge_representative(h)) itri.set_length(h, itri.length(h) + eps);
  return true;
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * makes the metric edge lengths of `itri` a valid triangulation (paper 3.2): computes the lengths
 * (`compute_metric_edge_lengths()`), makes the triangulation metric-Delaunay by edge flips (paper
 * Fig.\ 3), and while some triangle still violates the triangle inequality splits its longest edge at
 * the midpoint (projected onto `surface`; its `Q` is the mean of the edge's ends), then repeats.
 *
 * A boundary edge facing an angle above 120 degrees is split too (Ruppert's encroached segments):
 * boundary edges cannot be flipped, and the conformal scaling would flatten such a triangle.
 *
 * \param itri the triangulation, modified in place
 * \param surface the input surface the vertices of `itri` lie on
 * \param np optional named parameters:
 *   - `max_adjustment_rounds` (unsigned, default 50): bound on flip-then-split rounds;
 *   - `max_flips_per_edge` (unsigned, default 20): bound on the flips of one round, per edge it examines;
 *   - `visitor`: `on_iteration(Stage::EDGE_LENGTHS, round, bound, invalid_triangles)`.
 *
 * When three rounds of splits in a row do not reduce the number of invalid triangles (a metric that
 * jumps between neighbouring triangles, like the colour edges of an image), the remaining triangles are
 * repaired locally: the longest edge of such a triangle is shortened to just below the sum of the other
 * two when that keeps its other triangle valid, else the two others are lengthened
 * (`Edge_adjustment_report::repaired_triangles`, a few passes). If triangles remain, intrinsic
 * mollification (Sharp, Soliman, Crane 2019) lengthens every edge by the smallest `epsilon` that makes
 * every triangle valid, accepted if `epsilon` is at most a tenth of the median edge length
 * (`Edge_adjustment_report::mollification`).
 *
 * The first round examines every edge, later rounds only the edges around the vertices the splits
 * inserted. The number of flips of a round is bounded by `max_flips_per_edge` times the number of edges
 * it examines, plus 100 (a metric that varies across a quad can make Lawson's algorithm cycle); flipping
 * then stops for that round (`Edge_adjustment_report::flip_budget_hits`) and the splits go on: the
 * round bound still applies.
 * \throws Convergence_failure if invalid triangles remain after `max_adjustment_rounds` rounds, or when
 *         the splits stall and mollification would need more than a tenth of the median edge length
 *         (the residual is their number): the metric varies too fast for the input's resolution.
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Edge_adjustment_report adjust_edge_lengths(Intrinsic_triangulation& itri, const Input_surface& surface,
                                           const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const std::size_t max_rounds = choose_parameter(get_parameter(np, internal_np::max_adjustment_rounds), 50u);
  const std::size_t flips_per_edge = choose_parameter(get_parameter(np, internal_np::max_flips_per_edge), 20u);
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
  std::vector<int> inserted;  // vertices inserted by the last round's splits
  std::size_t best = std::size_t(-1), stalled = 0;  // progress of the splits

  for(report.rounds = 1;; ++report.rounds) {
    // 1. metric-Delaunay flips (Lawson's queue)
    // every edge in the first round, then only the edges around the vertices the last splits inserted
    // (Lawson's incremental insertion): elsewhere nothing changed
    std::deque<int> queue;
    std::vector<char> queued(itri.number_of_halfedges(), 0);
    auto enqueue = [&](int h) {
      const int r = itri.is_edge_representative(h) ? h : itri.twin(h);
      if(itri.twin(r) >= 0 && !queued[r]) {
        queue.push_back(r);
        queued[r] = 1;
      }
    };
    if(report.rounds == 1) {
      for(int h = 0; h < int(itri.number_of_halfedges()); ++h) enqueue(h);
    } else {
      for(int v : inserted)
        for(int h : itri.outgoing_halfedges(v)) {
          enqueue(h);
          enqueue(Intrinsic_triangulation::next(h));
        }
    }
    const std::size_t flip_budget = flips_per_edge * queue.size() + 100;
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
                   Intrinsic_triangulation::next(itri.twin(g)), Intrinsic_triangulation::prev(itri.twin(g))})
        enqueue(e);
    }
    report.flips += flips_this_round;
    if(!queue.empty()) ++report.flip_budget_hits;
    compute_metric_edge_lengths(itri);

    // 2. longest-edge splits of the triangles that are still invalid, and splits of the boundary edges
    //    that face an angle above 120 degrees: such nearly flat boundary triangles cannot be flipped
    //    away, and the conformal scaling would flatten them completely (Ruppert's encroached segments)
    std::vector<int> to_split;
    for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
      if(internal::face_is_valid(itri, f)) {
        for(int k = 0; k < 3; ++k) {
          const int h = int(3 * f) + k;
          if(!itri.is_boundary_edge(h)) continue;
          const double o = itri.length(h), a = itri.length(Intrinsic_triangulation::next(h)),
                       b = itri.length(Intrinsic_triangulation::prev(h));
          if(a * a + b * b - o * o < -a * b) to_split.push_back(h);  // cos(opposite angle) < -1/2
        }
        continue;
      }
      int best = int(3 * f);
      for(int k = 1; k < 3; ++k)
        if(itri.length(int(3 * f + k)) > itri.length(best)) best = int(3 * f + k);
      to_split.push_back(itri.is_edge_representative(best) ? best : itri.twin(best));
    }
    std::sort(to_split.begin(), to_split.end());
    to_split.erase(std::unique(to_split.begin(), to_split.end()), to_split.end());
    if(to_split.empty()) break;
    if(to_split.size() < best) {
      best = to_split.size();
      stalled = 0;
    } else if(++stalled >= 3) {
      // splitting no longer helps (a metric that jumps between neighbouring triangles): repair the few
      // triangles left by shortening or lengthening their edges, or mollify
      if(internal::repair_lengths(itri, report) || internal::mollify(itri, report)) break;
      throw Convergence_failure("edge-length adjustment: " + std::to_string(to_split.size()) +
                                    " triangles still violate the triangle inequality and splitting no longer helps"
                                    " (mollification would lengthen every edge by " +
                                    std::to_string(report.mollification) +
                                    " of the median edge length); smooth the metric or refine the input",
                                double(to_split.size()));
    }
    if(report.rounds >= max_rounds)
      throw Convergence_failure("edge-length adjustment: " + std::to_string(to_split.size()) +
                                    " triangles still violate the triangle inequality after " +
                                    std::to_string(max_rounds) +
                                    " rounds of flips and splits; smooth the metric or refine the input",
                                double(to_split.size()));
    // split by vertex pairs: earlier splits renumber halfedges of the faces they touch
    inserted.clear();
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
      inserted.push_back(itri.split(h, sp, 0.5 * (itri.Q(p.first) + itri.Q(p.second))));
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
