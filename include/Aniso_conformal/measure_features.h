// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_MEASURE_FEATURES_H
#define ANISO_CONFORMAL_MEASURE_FEATURES_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Feature_graph.h>

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

/// \file measure_features.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalQuality
 * how much of the input's feature graph an output mesh keeps (issue 15, item 4): the input's counts and
 * the output's corners and crease coverage. Lengths in the input's units.
 */
struct Feature_report {
  std::size_t crease_edges = 0;    ///< crease edges of the input
  std::size_t curves = 0;          ///< feature curves of the input (open chains and closed loops)
  std::size_t corners = 0;         ///< feature vertices (corners) of the input
  std::size_t corners_kept = 0;    ///< corners with an output vertex within `tolerance` of them
  double crease_length = 0;        ///< total length of the input's creases
  double covered_length = 0;       ///< length of the creases covered by output edges (see `measure_features()`)
  /// `covered_length / crease_length`, in [0, 1]; 0 when the input has no crease
  double covered_share = 0;
  double tolerance = 0;            ///< distance under which a point lies on a feature: 1e-9 of the bounding-box diagonal
  /// crease components (crease edges connected through their vertices) shorter than one output edge in the
  /// metric, left out before the remeshing (`remesh()`: no output edge can follow them; the short crease
  /// fragments of a noisy scan); the figures above count the creases kept
  std::size_t short_components_dropped = 0;
  double short_length_dropped = 0;  ///< their total length, in the input's units
  /// ragged crease components left out before the remeshing (`remesh()`'s `drop_ragged_creases`, default
  /// `true`): components of which 20 % of the length or more are crease edges whose triangles bend at
  /// another edge by half the feature angle or more (noise or a staircase crease, not a sharp one); all the
  /// detected components when `rough_surface`. The figures above count the creases kept
  std::size_t ragged_components_dropped = 0;
  double ragged_length_dropped = 0;  ///< their total length, in the input's units
  /// ragged components made a quarter of the detected crease length or more, so every detected crease was left
  /// out (the user's marked features are kept)
  bool rough_surface = false;
};

namespace internal {
// a point of a feature curve: the curve and the arc length from its first vertex
struct Curve_point {
  std::size_t curve;
  double s;
};
} // namespace internal

/*!
 * \ingroup PkgAnisoConformalQuality
 * measures how the output mesh (`points`, `faces`) keeps the feature graph `g` of `input`:
 * - a corner is kept when an output vertex lies within `tol` of it;
 * - an output vertex lies on a feature curve when it is within `tol` of one of its edges; an output edge
 *   whose two ends lie on the same curve covers the piece of the curve between them (the shorter way
 *   round a closed one), unless that piece is more than 1.1 times as long as the edge (the edge then cuts
 *   across a bend of the curve instead of following it); the covered length is the length of the union of
 *   the covered pieces, so no piece counts twice.
 *
 * `tol` is 1e-9 of the input's bounding-box diagonal: a vertex placed on a feature is on it up to rounding.
 * Time O((V + E) log E) for V output vertices and E crease edges (an AABB tree of the creases).
 *
 * \param input the input surface `g` was detected on (`detect_features()`)
 * \param g its feature graph
 * \param points the output's vertex positions, in the input's units
 * \param faces the output's triangles (indices into `points`)
 * \returns the counts, the corners kept and the covered crease length and share
 * \throws Invalid_input if a face index is out of range or a point is not finite
 */
inline Feature_report measure_features(const Input_surface& input, const Feature_graph& g,
                                       const std::vector<Eigen::Vector3d>& points,
                                       const std::vector<std::array<std::size_t, 3>>& faces)
{
  for(const auto& p : points)
    if(!p.allFinite()) throw Invalid_input("measure_features(): an output point is not finite");
  for(const auto& f : faces)
    for(std::size_t k = 0; k < 3; ++k)
      if(f[k] >= points.size()) throw Invalid_input("measure_features(): face index out of range");
  Feature_report r;
  r.crease_edges = g.crease_edges.size();
  r.curves = g.curves.size();
  r.corners = g.corners.size();
  r.crease_length = g.crease_length();
  r.tolerance = 1e-9 * input.bounding_box_diagonal();
  const double tol = r.tolerance;
  const auto& P = input.points();

  // corners kept: the output's points sorted by x, a window of width 2 tol around each corner
  if(!g.corners.empty()) {
    std::vector<std::size_t> by_x(points.size());
    for(std::size_t i = 0; i < by_x.size(); ++i) by_x[i] = i;
    std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) { return points[a].x() < points[b].x(); });
    for(std::size_t c : g.corners) {
      auto it = std::lower_bound(by_x.begin(), by_x.end(), P[c].x() - tol,
                                 [&](std::size_t i, double x) { return points[i].x() < x; });
      for(; it != by_x.end() && points[*it].x() <= P[c].x() + tol; ++it)
        if((points[*it] - P[c]).norm() <= tol) {
          ++r.corners_kept;
          break;
        }
    }
  }
  if(g.curves.empty() || r.crease_length <= 0) return r;

  // every crease edge as a segment of the AABB tree, with its curve and arc length at its start
  typedef CGAL::Simple_cartesian<double> K;
  typedef K::Point_3 Point;
  typedef K::Segment_3 Segment;
  std::vector<Segment> segments;
  std::vector<internal::Curve_point> start;          // of each segment
  std::vector<std::array<std::size_t, 2>> ends;      // input vertices of each segment
  std::vector<std::vector<internal::Curve_point>> at_vertex(P.size());  // curve points of each curve vertex
  auto point = [](const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); };
  for(std::size_t c = 0; c < g.curves.size(); ++c) {
    const auto& v = g.curves[c].vertices;
    double s = 0;
    for(std::size_t i = 0; i + 1 < v.size(); ++i) {
      segments.push_back(Segment(point(P[v[i]]), point(P[v[i + 1]])));
      start.push_back({c, s});
      ends.push_back({{v[i], v[i + 1]}});
      at_vertex[v[i]].push_back({c, s});
      s += (P[v[i + 1]] - P[v[i]]).norm();
    }
    at_vertex[v.back()].push_back({c, s});
  }
  typedef std::vector<Segment>::const_iterator Iterator;
  typedef CGAL::AABB_segment_primitive<K, Iterator> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> Tree;
  Tree tree(segments.begin(), segments.end());
  tree.accelerate_distance_queries();

  // the curve points of each output vertex (none when it lies on no crease)
  std::vector<std::vector<internal::Curve_point>> on(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) {
    const auto hit = tree.closest_point_and_primitive(point(points[i]));
    const Eigen::Vector3d q(hit.first.x(), hit.first.y(), hit.first.z());
    if((q - points[i]).norm() > tol) continue;
    const std::size_t e = std::size_t(hit.second - segments.begin());
    const std::size_t a = ends[e][0], b = ends[e][1];
    if((points[i] - P[a]).norm() <= tol) {
      on[i] = at_vertex[a];  // at a curve vertex: on every curve through it (a corner ends several)
    } else if((points[i] - P[b]).norm() <= tol) {
      on[i] = at_vertex[b];
    } else {
      on[i].push_back({start[e].curve, start[e].s + (points[i] - P[a]).norm()});
    }
  }

  // the covered pieces of each curve, then their union
  std::vector<std::vector<std::pair<double, double>>> pieces(g.curves.size());
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  for(const auto& f : faces)
    for(int k = 0; k < 3; ++k) edges.push_back(std::minmax(f[k], f[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for(const auto& e : edges) {
    if(on[e.first].empty() || on[e.second].empty()) continue;
    const double chord = (points[e.second] - points[e.first]).norm();
    for(const auto& a : on[e.first])
      for(const auto& b : on[e.second]) {
        if(a.curve != b.curve) continue;
        const Feature_curve& c = g.curves[a.curve];
        const bool periodic = c.vertices.front() == c.vertices.back();
        double s0 = std::min(a.s, b.s), s1 = std::max(a.s, b.s);
        if(periodic) {
          s0 = std::fmod(s0, c.length);
          s1 = std::fmod(s1, c.length);
          if(s0 > s1) std::swap(s0, s1);
        }
        const double inside = s1 - s0, around = periodic ? c.length - inside : inside;
        const double arc = std::min(inside, around);
        if(arc <= 0 || arc > 1.1 * chord + tol) continue;
        if(inside <= around) {
          pieces[a.curve].push_back({s0, s1});
        } else {  // round the closed curve's start
          pieces[a.curve].push_back({s1, c.length});
          pieces[a.curve].push_back({0, s0});
        }
      }
  }
  for(auto& p : pieces) {
    std::sort(p.begin(), p.end());
    double end = -1;
    for(const auto& x : p) {
      const double from = std::max(x.first, end);
      if(x.second > from) r.covered_length += x.second - from;
      end = std::max(end, x.second);
    }
  }
  r.covered_share = std::min(1.0, r.covered_length / r.crease_length);
  return r;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_MEASURE_FEATURES_H
