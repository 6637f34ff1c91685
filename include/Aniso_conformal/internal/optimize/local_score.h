// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_OPTIMIZE_LOCAL_SCORE_H
#define ANISO_CONFORMAL_INTERNAL_OPTIMIZE_LOCAL_SCORE_H

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

// The figures by which the surface optimisation (internal/optimize/surface_optimizer.h) judges an
// operation: one triangle's quality in the metric as compute_mesh_quality() measures it, their sum over
// the triangles an operation changes, the acceptance tests of the two phases, and the apex equilateral
// in the metric that the vertex moves aim at.

namespace Aniso_conformal {
namespace internal {

// the figures of one triangle in the metric, computed as compute_mesh_quality() does (Q_T the mean of
// the corners' square roots, in the same order), so that what the optimiser accepts is what the report
// measures
struct Triangle_figures {
  double G = 0;               // 2 sqrt(3) S / (p h)
  double smallest_angle = 0;  // degrees
  double area = 0;            // in the metric
  bool inverted = false;      // triangle_is_inverted()
};

inline Triangle_figures triangle_figures(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                         const Eigen::Matrix3d& Qa, const Eigen::Matrix3d& Qb, const Eigen::Matrix3d& Qc)
{
  const double rad = 180.0 / 3.14159265358979323846;
  const Eigen::Matrix3d QT = (Qa + Qb + Qc) / 3.0;
  const std::array<Eigen::Vector3d, 3> p = {{QT * a, QT * b, QT * c}};
  std::array<double, 3> l;
  for(int k = 0; k < 3; ++k) l[k] = (p[(k + 1) % 3] - p[k]).norm();
  Triangle_figures t;
  t.area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  const double half_perimeter = 0.5 * (l[0] + l[1] + l[2]);
  const double h = std::max({l[0], l[1], l[2]});
  t.G = (half_perimeter > 0 && h > 0) ? 2 * std::sqrt(3.0) * t.area / (half_perimeter * h) : 0.0;
  // the smallest angle faces the shortest edge (l[j] from p[j] to p[j + 1] faces corner j + 2): one atan2
  // where compute_mesh_quality() takes the least of three, the same value but when two angles tie to
  // within rounding
  int j = 0;
  for(int k = 1; k < 3; ++k)
    if(l[k] < l[j]) j = k;
  const int k = (j + 2) % 3;
  const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
  t.smallest_angle = std::atan2(u.cross(v).norm(), u.dot(v)) * rad;
  return t;
}

// the figures of the quality report over a few triangles (those an operation replaces or moves)
struct Local_score {
  std::size_t inverted = 0, below_30 = 0;
  double G_min = 1e300, angle_min = 1e300, G_sum = 0, angle_sum = 0;
  void add(const Triangle_figures& t)
  {
    inverted += t.inverted ? 1 : 0;
    below_30 += t.smallest_angle < 30 ? 1 : 0;
    G_min = std::min(G_min, t.G);
    angle_min = std::min(angle_min, t.smallest_angle);
    G_sum += t.G;
    angle_sum += t.smallest_angle;
  }
};

// The apex `x` of the triangle (a, b, x) equilateral in the metric `QT^2`, in the plane of (p, a, b),
// on p's side of (a, b): in the plane's orthonormal frame the metric is the 2x2 G = T^T QT^2 T; with
// G = L^T L (Cholesky), y = L x is Euclidean, where the apex is the midpoint plus sqrt(3)/2 |e| along
// the normal of e toward p. `false` if the triangle is degenerate or G is not positive definite.
inline bool metric_equilateral_apex(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Matrix3d& QT, Eigen::Vector3d& apex)
{
  const Eigen::Vector3d e = b - a;
  const double len = e.norm();
  if(!(len > 0)) return false;
  const Eigen::Vector3d t1 = e / len;
  Eigen::Vector3d t2 = (p - a) - (p - a).dot(t1) * t1;
  if(!(t2.norm() > 1e-12 * len)) return false;
  t2.normalize();
  Eigen::Matrix<double, 3, 2> T;
  T.col(0) = t1;
  T.col(1) = t2;
  const Eigen::Matrix<double, 3, 2> QTT = QT * T;
  const Eigen::Matrix2d G = QTT.transpose() * QTT;
  const Eigen::LLT<Eigen::Matrix2d> llt(G);
  if(llt.info() != Eigen::Success) return false;
  const Eigen::Matrix2d L = llt.matrixU();  // G = L^T L
  // a at the origin of the frame: b at (len, 0), p at (., > 0)
  const Eigen::Vector2d yb = L * Eigen::Vector2d(len, 0), yp = L * Eigen::Vector2d((p - a).dot(t1), (p - a).dot(t2));
  Eigen::Vector2d n(-yb.y(), yb.x());  // normal of (a, b) in y
  if(n.dot(yp) < 0) n = -n;
  const double ly = yb.norm();
  if(!(ly > 0)) return false;
  const Eigen::Vector2d y_apex = 0.5 * yb + (0.5 * std::sqrt(3.0) * ly / n.norm()) * n;
  const Eigen::Vector2d x = L.triangularView<Eigen::Upper>().solve(y_apex);
  apex = a + T * x;
  return apex.allFinite();
}

// the sum of G of `candidate` is larger than that of `current`, beyond rounding (the strict increase that
// rules out cycles in improves() and improves_above_floors())
inline bool raises_G_sum(const Local_score& candidate, const Local_score& current)
{
  return candidate.G_sum > current.G_sum * (1 + 1e-12);
}

// `candidate` may replace `current`: it has fewer inverted triangles, or as many and none of G_min,
// theta_min, theta_avg, %<30 worse and a larger sum of G. Since every operation replaces a fixed number
// of triangles, none of the report's G_min, G_avg, theta_min, theta_avg, %<30 can then get worse (up to
// the rounding of the report's sums), and G_sum strictly increasing rules out cycles.
inline bool improves(const Local_score& candidate, const Local_score& current)
{
  if(candidate.inverted != current.inverted) return candidate.inverted < current.inverted;
  return candidate.G_min >= current.G_min && candidate.angle_min >= current.angle_min &&
         candidate.below_30 <= current.below_30 && candidate.angle_sum >= current.angle_sum &&
         raises_G_sum(candidate, current);
}

// `candidate` may replace `current` in the second phase of Surface_optimization::ALWAYS: it has fewer
// inverted triangles, or as many, a larger sum of G, no more triangles below 30 degrees, and G_min and the
// smallest angle no lower than `G_floor` and `angle_floor` where they were above them, no lower than they
// were otherwise. With floors at least the mesh's G_min and theta_min (optimize_surface_mesh()), neither
// of these drops, %<30 never grows, G_sum strictly increases (no cycle); theta_avg may drop (it is not
// protected here).
inline bool improves_above_floors(const Local_score& candidate, const Local_score& current, double G_floor,
                                  double angle_floor)
{
  if(candidate.inverted != current.inverted) return candidate.inverted < current.inverted;
  return candidate.G_min >= std::min(current.G_min, G_floor) &&
         candidate.angle_min >= std::min(current.angle_min, angle_floor) && candidate.below_30 <= current.below_30 &&
         raises_G_sum(candidate, current);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_OPTIMIZE_LOCAL_SCORE_H
