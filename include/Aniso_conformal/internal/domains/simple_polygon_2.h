// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_SIMPLE_POLYGON_2_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_SIMPLE_POLYGON_2_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/box_intersection_d.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <vector>

// Is a closed polygon of the plane simple, with room to spare? The planar domain asks it of the layout
// of the background's boundary (is the conformal layout an embedding?) and of the polygon of the
// boundary sites (can it constrain the dual?). Exact predicates (CGAL's EPICK) for the intersections,
// CGAL's box intersection for the pairs of edges that come close.

namespace Aniso_conformal {
namespace internal {

// The edges of the closed polygon `p` (edge i from p[i] to p[i + 1]) that touch or cross another edge, or
// come closer than `margin` to an edge they do not share a vertex with, or fold back onto the edge they
// share a vertex with (a spike: the two edges overlap). Flags `bad[i]` and returns their number (0: the
// polygon is simple and its non-adjacent edges are farther apart than `margin`). A polygon with fewer
// than 3 vertices has every edge flagged.
inline std::size_t polygon_defects(const std::vector<Eigen::Vector2d>& p, double margin, std::vector<char>& bad)
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t> Box;
  const std::size_t n = p.size();
  bad.assign(n, 0);
  if(n < 3) {
    bad.assign(n, 1);
    return n;
  }
  auto point = [&](std::size_t i) { return K::Point_2(p[i % n].x(), p[i % n].y()); };
  auto segment = [&](std::size_t i) { return K::Segment_2(point(i), point(i + 1)); };
  // adjacent edges: only a fold (collinear and going back) makes them overlap
  for(std::size_t i = 0; i < n; ++i) {
    const K::Point_2 a = point(i + n - 1), b = point(i), c = point(i + 1);
    if(a == b || b == c || (CGAL::orientation(a, b, c) == CGAL::COLLINEAR && !CGAL::collinear_are_ordered_along_line(a, b, c)))
      bad[(i + n - 1) % n] = bad[i] = 1;
  }
  std::vector<Box> boxes;
  boxes.reserve(n);
  for(std::size_t i = 0; i < n; ++i) {
    double lo[2], hi[2];
    for(int d = 0; d < 2; ++d) {
      lo[d] = std::min(p[i][d], p[(i + 1) % n][d]) - margin;
      hi[d] = std::max(p[i][d], p[(i + 1) % n][d]) + margin;
    }
    boxes.emplace_back(lo, hi, i);
  }
  const double margin2 = margin * margin;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    const std::size_t i = x.info(), j = y.info();
    if((i + 1) % n == j || (j + 1) % n == i) return;  // adjacent: handled above
    const K::Segment_2 si = segment(i), sj = segment(j);
    if(CGAL::do_intersect(si, sj) || (margin > 0 && CGAL::squared_distance(si, sj) < margin2)) bad[i] = bad[j] = 1;
  });
  return std::size_t(std::count(bad.begin(), bad.end(), char(1)));
}

// `true` if the closed polygon `p` is simple, counterclockwise, and its non-adjacent edges are farther
// apart than `margin`
inline bool is_simple_counterclockwise(const std::vector<Eigen::Vector2d>& p, double margin)
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  std::vector<char> bad;
  if(polygon_defects(p, margin, bad) > 0) return false;
  std::vector<K::Point_2> q;
  q.reserve(p.size());
  for(const Eigen::Vector2d& x : p) q.emplace_back(x.x(), x.y());
  return CGAL::orientation_2(q.begin(), q.end(), K()) == CGAL::COUNTERCLOCKWISE;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_SIMPLE_POLYGON_2_H
