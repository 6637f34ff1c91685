// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_EDGE_LENGTHS_ADJUSTMENT_H
#define ANISO_CONFORMAL_INTERNAL_EDGE_LENGTHS_ADJUSTMENT_H

#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

// The pieces of stage 2 (adjust_edge_lengths()): the metric-Delaunay flip rule of paper Fig. 3, the local
// repair of triangles that splits cannot fix, and intrinsic mollification.

namespace Aniso_conformal {

struct Edge_adjustment_report;

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
  if(itri.has_edge(c, d)) return false;  // the new edge exists already
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
template <typename Report>
bool repair_lengths(Intrinsic_triangulation& itri, Report& report)
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
template <typename Report>
bool mollify(Intrinsic_triangulation& itri, Report& report)
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


inline std::size_t count_invalid_triangles(const Intrinsic_triangulation& itri)
{
  std::size_t n = 0;
  for(std::size_t f = 0; f < itri.number_of_faces(); ++f)
    if(!face_is_valid(itri, f)) ++n;
  return n;
}

// The edges stage 2 splits, one halfedge each, sorted: the longest edge of every triangle that still
// violates the triangle inequality, and the boundary edges that face an angle above 120 degrees (such
// nearly flat boundary triangles cannot be flipped away, and the conformal scaling would flatten them
// completely: Ruppert's encroached segments).
inline std::vector<int> edges_to_split(const Intrinsic_triangulation& itri)
{
  std::vector<int> to_split;
  for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
    if(face_is_valid(itri, f)) {
      for(int k = 0; k < 3; ++k) {
        const int h = int(3 * f) + k;
        if(!itri.is_boundary_edge(h)) continue;
        const double o = itri.length(h), a = itri.length(Intrinsic_triangulation::next(h)),
                     b = itri.length(Intrinsic_triangulation::prev(h));
        if(a * a + b * b - o * o < -a * b) to_split.push_back(h);  // cos(opposite angle) < -1/2
      }
      continue;
    }
    int longest = int(3 * f);
    for(int k = 1; k < 3; ++k)
      if(itri.length(int(3 * f + k)) > itri.length(longest)) longest = int(3 * f + k);
    to_split.push_back(itri.is_edge_representative(longest) ? longest : itri.twin(longest));
  }
  std::sort(to_split.begin(), to_split.end());
  to_split.erase(std::unique(to_split.begin(), to_split.end()), to_split.end());
  return to_split;
}

// Splits the edges `to_split` at their midpoints; returns the inserted vertices. A boundary edge is a
// piece of an input boundary edge, so its midpoint lies on the input already; an interior midpoint of a
// flipped edge is a chord and is projected onto `surface`. The metric square root of a midpoint is the
// mean of its ends'. Edges are found again by their ends, because earlier splits renumber the halfedges
// of the faces they touch.
inline std::vector<int> split_edges(Intrinsic_triangulation& itri, const Input_surface& surface, const std::vector<int>& to_split)
{
  std::vector<std::pair<int, int>> pairs;
  for(int h : to_split) pairs.emplace_back(itri.tail(h), itri.head(h));
  std::vector<int> inserted;
  for(const auto& p : pairs) {
    const int h = itri.find_halfedge(p.first, p.second);
    if(h < 0) continue;  // already split through a neighbour
    const Eigen::Vector3d mid = 0.5 * (itri.position(p.first) + itri.position(p.second));
    Surface_point sp = surface.project(mid);
    if(itri.twin(h) < 0) sp.position = mid;
    inserted.push_back(itri.split(h, sp, 0.5 * (itri.Q(p.first) + itri.Q(p.second))));
  }
  return inserted;
}

// The flip rule of stage 2 for flip_to_delaunay(): the metric-Delaunay test of paper Fig. 3, refusing
// the flips that would fold the surface; the new edge's length is left unset (the pass recomputes every
// length from the metric afterwards).
struct Metric_delaunay_flip_rule {
  bool wants_flip(const Intrinsic_triangulation& itri, int h) const
  {
    return metric_delaunay_wants_flip(itri, h) && flip_keeps_orientation(itri, h);
  }
  double flipped_length(const Intrinsic_triangulation&, int) const { return std::numeric_limits<double>::quiet_NaN(); }
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_EDGE_LENGTHS_ADJUSTMENT_H
