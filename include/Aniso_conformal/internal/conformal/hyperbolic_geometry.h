// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_HYPERBOLIC_GEOMETRY_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_HYPERBOLIC_GEOMETRY_H

#include <Aniso_conformal/internal/conformal/flat_triangle.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

// The hyperbolic plane as the upper sheet of the hyperboloid <x, x> = -1, x0 > 0, with the Minkowski
// product <x, y> = -x0 y0 + x1 y1 + x2 y2. Isometries are the Lorentz matrices that keep the sheet
// (SO+(2, 1)), acting linearly; the Klein disk is the central projection (x1, x2) / x0, where geodesics
// are straight chords. Everything the hyperbolic embedding and CVT need, in one place.

namespace Aniso_conformal {
namespace internal {


inline double minkowski_dot(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return -a.x() * b.x() + a.y() * b.y() + a.z() * b.z();
}

// hyperbolic distance between two points of the hyperboloid: <a - b, a - b> = 4 sinh^2(d / 2), which
// keeps precision for close points where acosh(-<a, b>) loses half the digits
inline double hyperbolic_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const Eigen::Vector3d d = a - b;
  return 2 * std::asinh(0.5 * std::sqrt(std::max(0.0, minkowski_dot(d, d))));
}

// the point of the hyperboloid on the ray through x (x timelike with x0 > 0)
inline Eigen::Vector3d normalize_on_hyperboloid(const Eigen::Vector3d& x)
{
  const double q = -minkowski_dot(x, x);
  return x / std::sqrt(std::max(q, 1e-300));
}

inline Eigen::Vector2d to_klein(const Eigen::Vector3d& x) { return Eigen::Vector2d(x.y() / x.x(), x.z() / x.x()); }

// the Poincare disk point of x: the stereographic projection from (-1, 0, 0), (x1, x2) / (1 + x0)
inline Eigen::Vector2d to_poincare(const Eigen::Vector3d& x) { return Eigen::Vector2d(x.y() / (1 + x.x()), x.z() / (1 + x.x())); }

inline Eigen::Vector3d from_klein(const Eigen::Vector2d& k)
{
  const double s = 1.0 / std::sqrt(std::max(1e-300, 1.0 - k.squaredNorm()));
  return Eigen::Vector3d(s, s * k.x(), s * k.y());
}

// the inverse of a Lorentz matrix: J T^T J with J = diag(-1, 1, 1)
inline Eigen::Matrix3d lorentz_inverse(const Eigen::Matrix3d& T)
{
  const Eigen::Vector3d j(-1, 1, 1);
  return j.asDiagonal() * T.transpose() * j.asDiagonal();
}

// how far T is from a Lorentz matrix: max |T^T J T - J|
inline double lorentz_defect(const Eigen::Matrix3d& T)
{
  const Eigen::Vector3d j(-1, 1, 1);
  return (T.transpose() * j.asDiagonal() * T - Eigen::Matrix3d(j.asDiagonal())).cwiseAbs().maxCoeff();
}

// the pure boost (no rotation about the apex) taking the apex (1, 0, 0) to p: a Lorentz matrix for every
// point p of the hyperboloid, with no second point to choose a direction from; hyperbolic_frame(p, q)
// has none when q is within the rounding of p (a frame fitted to an edge the metric shrinks to 1e-14 is
// no Lorentz matrix)
inline Eigen::Matrix3d hyperbolic_boost(const Eigen::Vector3d& p)
{
  const double k = 1 / (1 + p.x());
  Eigen::Matrix3d B;
  B << p.x(), p.y(), p.z(),
       p.y(), 1 + k * p.y() * p.y(), k * p.y() * p.z(),
       p.z(), k * p.y() * p.z(), 1 + k * p.z() * p.z();
  return B;
}

// the orientation-preserving isometry taking the apex (1, 0, 0) to p and the direction of the x1 axis
// to the direction of q seen from p (p != q): its columns are p, the unit tangent towards q, and the
// unit normal completing a positively oriented Minkowski-orthonormal frame. When q is nearer to p than
// 1e-6, q - <p, q> p is mostly rounding and may not even be spacelike (its normalisation then made the
// frame huge: a layout placed the far corner of a face with sides of 1e-15 on CGAL's femur, curvature
// metric, 1.24 away from its other copy): the frame is then the boost to p rotated about p towards q,
// a Lorentz matrix whatever the direction is worth.
inline Eigen::Matrix3d hyperbolic_frame(const Eigen::Vector3d& p, const Eigen::Vector3d& q)
{
  if(!(hyperbolic_distance(p, q) >= 1e-6)) {
    const Eigen::Matrix3d B = hyperbolic_boost(p);
    const Eigen::Vector3d y = lorentz_inverse(B) * q;  // q seen from the apex
    const double phi = std::atan2(y.z(), y.y());         // 0 when q is p
    Eigen::Matrix3d R;
    R << 1, 0, 0,
         0, std::cos(phi), -std::sin(phi),
         0, std::sin(phi), std::cos(phi);
    return B * R;
  }
  const double c = -minkowski_dot(p, q);
  Eigen::Vector3d e1 = q - c * p;  // Minkowski-orthogonal to p, spacelike
  e1 /= std::sqrt(std::max(1e-300, minkowski_dot(e1, e1)));
  Eigen::Vector3d e2 = p.cross(e1);
  e2.x() = -e2.x();  // J (p x e1) is Minkowski-orthogonal to p and e1
  e2 /= std::sqrt(std::max(1e-300, minkowski_dot(e2, e2)));
  Eigen::Matrix3d T;
  T.col(0) = p;
  T.col(1) = e1;
  T.col(2) = e2;
  if(T.determinant() < 0) T.col(2) = -e2;
  return T;
}

// The point r on the left of the geodesic p -> q (counterclockwise in the Klein disk) with
// d(p, r) = lpr and d(q, r) = lqr: one triangle of a layout.
inline Eigen::Vector3d hyperbolic_third_point(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double lpr, double lqr)
{
  const double d = hyperbolic_distance(p, q);
  // the angle at p, by the half-angle formula (see hyperbolic_corner_angles())
  const double s2 = std::sinh(0.5 * (lqr - d + lpr)) * std::sinh(0.5 * (lqr + d - lpr));
  const double c2 = std::sinh(0.5 * (lqr + d + lpr)) * std::sinh(0.5 * (d + lpr - lqr));
  const double alpha = 2 * std::atan2(std::sqrt(std::max(0.0, s2)), std::sqrt(std::max(0.0, c2)));
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  const Eigen::Vector3d local(std::cosh(lpr), std::sinh(lpr) * ca, std::sinh(lpr) * sa);
  return normalize_on_hyperboloid(hyperbolic_frame(p, q) * local);
}

// The angles of a hyperbolic triangle with side lengths l[k] (l[k] from corner k to k+1; the angle at
// corner k faces side k+1), by the half-angle formulas, which keep full precision for short sides
// (cosh b cosh c - cosh a cancels). A triangle violating the triangle inequality gets (0, 0, pi): the
// convex extension of the energy, as in the Euclidean solve.
inline std::array<double, 3> hyperbolic_corner_angles(const std::array<double, 3>& l, bool& degenerate)
{
  std::array<double, 3> angle;
  if((degenerate = flat_triangle_angles(l, angle))) return angle;
  for(int k = 0; k < 3; ++k) {
    const double a = l[(k + 1) % 3], b = l[k], c = l[(k + 2) % 3];  // a opposite the corner
    const double s2 = std::sinh(0.5 * (a - b + c)) * std::sinh(0.5 * (a + b - c));
    const double c2 = std::sinh(0.5 * (a + b + c)) * std::sinh(0.5 * (b + c - a));
    angle[k] = 2 * std::atan2(std::sqrt(std::max(0.0, s2)), std::sqrt(std::max(0.0, c2)));
  }
  return angle;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_HYPERBOLIC_GEOMETRY_H
