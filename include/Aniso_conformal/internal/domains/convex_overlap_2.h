// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_CONVEX_OVERLAP_2_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_CONVEX_OVERLAP_2_H

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <iterator>

namespace Aniso_conformal {
namespace internal {

// `true` if the interiors of the convex polygons `a` and `b` (containers of Eigen::Vector2d, vertices in
// order, either orientation) overlap by more than `eps` across every edge's normal (the separating axis
// test: touching is not overlapping; an edge of zero length separates nothing). The cone domain's band
// (its face copies must not overlap) and the cone CVT picture (which cells meet a chart's triangles).
template <typename A, typename B>
bool convex_polygons_overlap(const A& a, const B& b, double eps = 0)
{
  auto separated_by_an_edge_of = [eps, &a, &b](const auto& p) {
    const std::size_t n = std::size(p);
    for(std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector2d e = p[(k + 1) % n] - p[k];
      const double len = e.norm();
      if(!(len > 0)) continue;
      const Eigen::Vector2d normal(-e.y(), e.x());
      double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
      for(const Eigen::Vector2d& x : a) a0 = std::min(a0, normal.dot(x) / len), a1 = std::max(a1, normal.dot(x) / len);
      for(const Eigen::Vector2d& x : b) b0 = std::min(b0, normal.dot(x) / len), b1 = std::max(b1, normal.dot(x) / len);
      if(a1 <= b0 + eps || b1 <= a0 + eps) return true;
    }
    return false;
  };
  return !separated_by_an_edge_of(a) && !separated_by_an_edge_of(b);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_CONVEX_OVERLAP_2_H
