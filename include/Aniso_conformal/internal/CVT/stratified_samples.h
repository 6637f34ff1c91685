// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_STRATIFIED_SAMPLES_H
#define ANISO_CONFORMAL_INTERNAL_CVT_STRATIFIED_SAMPLES_H

#include <Aniso_conformal/Exceptions.h>

#include <algorithm>
#include <cstddef>
#include <random>
#include <type_traits>
#include <vector>

namespace Aniso_conformal {
namespace internal {

/*
 * m points spread over the density of `nt` triangles in a space-filling-curve order (Morton): evenly
 * spaced quantiles of the mass along the curve, shifted by one random offset, then a random point in
 * the chosen triangle, shrunk towards its centroid (by 0.98) so that no point starts on an edge.
 * mass(f) is the mass of triangle f, corners(f) its three corners (an array of Eigen vectors of any
 * size: the sphere samples its chordal triangles in space). The quantile picks the first triangle whose
 * cumulative mass exceeds it (upper bound), so a triangle without mass is never picked. A space-filling
 * curve sample is already well spread, so the CVT starts close to its optimum; the generator changes
 * both the offset and the points. Returns the m points (in the corners' space, not projected).
 * \throws Internal_error if m > 0 and there is no triangle
 */
template <typename Mass, typename Corners>
auto stratified_samples(std::size_t nt, const Mass& mass, const Corners& corners, std::size_t m, std::mt19937_64& rng)
    -> std::vector<typename std::decay<decltype(corners(std::size_t(0))[0])>::type>
{
  typedef typename std::decay<decltype(corners(std::size_t(0))[0])>::type Point;
  if(m > 0 && nt == 0) throw Internal_error("stratified_samples(): no background triangle to sample");
  std::vector<double> cdf(nt);
  double acc = 0;
  for(std::size_t f = 0; f < nt; ++f) {
    acc += mass(f);
    cdf[f] = acc;
  }
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double offset = U(rng);
  std::vector<Point> out;
  out.reserve(m);
  for(std::size_t k = 0; k < m; ++k) {
    const double r = (double(k) + offset) / double(m) * acc;
    const std::size_t f = std::min(nt - 1, std::size_t(std::upper_bound(cdf.begin(), cdf.end(), r) - cdf.begin()));
    double a = U(rng), b = U(rng);
    if(a + b > 1) {
      a = 1 - a;
      b = 1 - b;
    }
    const auto& p = corners(f);
    const Point g = (p[0] + p[1] + p[2]) / 3.0;
    const Point y = p[0] + a * (p[1] - p[0]) + b * (p[2] - p[0]);
    out.push_back(g + 0.98 * (y - g));
  }
  return out;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_STRATIFIED_SAMPLES_H
