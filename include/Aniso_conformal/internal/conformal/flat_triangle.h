// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_FLAT_TRIANGLE_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_FLAT_TRIANGLE_H

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <utility>

namespace Aniso_conformal {
namespace internal {

// The convex extension of the discrete conformal energies (Bobenko, Pinkall and Springborn): a triangle
// with side lengths l (l[k] from corner k to k+1) that violates the triangle inequality gets the angles
// of the flat triangle, pi at the corner facing the long side and 0 elsewhere; returns true then.
inline bool flat_triangle_angles(const std::array<double, 3>& l, std::array<double, 3>& angle)
{
  for(int k = 0; k < 3; ++k)
    if(l[(k + 1) % 3] >= l[k] + l[(k + 2) % 3]) {
      angle = {{0, 0, 0}};
      angle[k] = 3.14159265358979323846;
      return true;
    }
  return false;
}

// The angle (radians) opposite side `c` of a triangle with sides `a`, `b`, `c`, accurate to a few ulps
// also for needle-like triangles, where the law of cosines loses half the digits (Kahan 2014,
// "Miscalculating area and angles of a needle-like triangle", section 3: the half-angle formula with the
// differences of sides formed before any rounding error). Sides that violate the triangle inequality give
// 0 (c <= |a - b|) or pi (c >= a + b), as the convex extension of flat_triangle_angles().
inline double triangle_angle(double a, double b, double c)
{
  if(a < b) std::swap(a, b);
  double mu;
  if(b >= c && c >= 0) mu = c - (a - b);
  else if(c > b && b >= 0) mu = b - (a - c);
  else return 0;
  const double num = ((a - b) + c) * mu, den = (a + (b + c)) * ((a - c) + b);
  if(!(num > 0)) return den > 0 ? 0.0 : 3.14159265358979323846;
  if(!(den > 0)) return 3.14159265358979323846;
  return 2 * std::atan(std::sqrt(num / den));
}

// The barycentric coordinates of `x` in the planar triangle `p` (its corners in order; affine
// coordinates, negative outside). The triangle must not be degenerate (the result is not finite then).
inline Eigen::Vector3d barycentric_2(const std::array<Eigen::Vector2d, 3>& p, const Eigen::Vector2d& x)
{
  const Eigen::Vector2d e1 = p[1] - p[0], e2 = p[2] - p[0], w = x - p[0];
  const double det = e1.x() * e2.y() - e1.y() * e2.x();
  const double b1 = (w.x() * e2.y() - w.y() * e2.x()) / det, b2 = (e1.x() * w.y() - e1.y() * w.x()) / det;
  return Eigen::Vector3d(1 - b1 - b2, b1, b2);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_FLAT_TRIANGLE_H
