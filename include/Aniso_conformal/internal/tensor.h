// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_TENSOR_H
#define ANISO_CONFORMAL_INTERNAL_TENSOR_H

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>

namespace Aniso_conformal {
namespace internal {

// Symmetric square root Q = M^{1/2} (DESIGN.md 3): averages of Q are well defined, averages of a
// Cholesky factor are not. Negative round-off eigenvalues (rank-2 surface tensors) are clamped to 0.
inline Eigen::Matrix3d symmetric_sqrt(const Eigen::Matrix3d& M)
{
  if(M(0, 2) == 0 && M(1, 2) == 0 && M(2, 0) == 0 && M(2, 1) == 0 && M(2, 2) == 0) {
    // planar tensor: closed form sqrt(M) = (M + sqrt(det M) I) / sqrt(tr M + 2 sqrt(det M)) for 2x2 SPD
    const Eigen::Matrix2d m = 0.5 * (M.topLeftCorner<2, 2>() + M.topLeftCorner<2, 2>().transpose());
    const double det = m.determinant(), tr = m.trace();
    if(det > 0 && tr > 0) {
      const double sd = std::sqrt(det);
      Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
      Q.topLeftCorner<2, 2>() = (m + sd * Eigen::Matrix2d::Identity()) / std::sqrt(tr + 2 * sd);
      return Q;
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (M + M.transpose()));
  Eigen::Vector3d ev = es.eigenvalues();
  for(int i = 0; i < 3; ++i) ev[i] = std::sqrt(std::max(0.0, ev[i]));
  return es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
}

inline bool all_finite(const Eigen::Matrix3d& M)
{
  for(int i = 0; i < 9; ++i)
    if(!std::isfinite(M.data()[i])) return false;
  return true;
}

// Smallest eigenvalue of M restricted to the plane orthogonal to the unit vector n, relative to the
// largest eigenvalue of M. A tensor is usable on a surface when this is clearly positive. Where the
// tangent plane is undefined (n zero: a vertex whose faces' normals cancel, as the bridge vertex of a
// pinched hole's patches, hole_patches.h), M must be positive definite in space.
inline double tangent_positivity(const Eigen::Matrix3d& M, const Eigen::Vector3d& n)
{
  if(n.squaredNorm() == 0) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (M + M.transpose()));
    const double big = std::max(std::abs(es.eigenvalues()[2]), M.cwiseAbs().maxCoeff());
    return big > 0 ? es.eigenvalues()[0] / big : 0;
  }
  Eigen::Vector3d t1 = n.unitOrthogonal();
  Eigen::Vector3d t2 = n.cross(t1);
  Eigen::Matrix<double, 3, 2> T;
  T.col(0) = t1;
  T.col(1) = t2;
  Eigen::Matrix2d m2 = T.transpose() * (0.5 * (M + M.transpose())) * T;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(m2);
  double big = std::max(std::abs(es.eigenvalues()[1]), M.cwiseAbs().maxCoeff());
  if(!(big > 0)) return 0;
  return es.eigenvalues()[0] / big;
}

// Relative asymmetry |M - M^T| / |M|.
inline double asymmetry(const Eigen::Matrix3d& M)
{
  double n = M.norm();
  return n > 0 ? (M - M.transpose()).norm() / n : 0;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_TENSOR_H
