// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_METRIC_GRADATION_H
#define ANISO_CONFORMAL_INTERNAL_METRIC_GRADATION_H

#include <Aniso_conformal/Exceptions.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

// Metric gradation on a triangulated surface (Borouchaki, Hecht and Frey, "Mesh gradation control",
// IJNME 43(6), 1998; MMG's -hgrad): the size that a metric prescribes may grow by at most a factor
// `beta` per unit of metric length along the surface's edges.

namespace Aniso_conformal {
namespace internal {

// the intersection of two metrics of the plane (2 x 2, symmetric positive definite) by simultaneous
// reduction (Alauzet and Frey, "Anisotropic mesh adaptation for CFD computations", 2005, and Borouchaki
// et al. 1998): with P the generalised eigenvectors of B p = mu A p, normalised so that P^T A P = I and
// P^T B P = diag(mu), the intersection is P^-T diag(max(1, mu)) P^-1, the largest metric whose unit ball
// lies in both unit balls (along the common conjugate directions). Throws Internal_error if A is not
// positive definite.
inline Eigen::Matrix2d metric_intersection(const Eigen::Matrix2d& A, const Eigen::Matrix2d& B)
{
  const Eigen::Matrix2d a = 0.5 * (A + A.transpose()), b = 0.5 * (B + B.transpose());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(b, a);
  if(es.info() != Eigen::Success)
    throw Internal_error("metric intersection: the first metric is not positive definite");
  const Eigen::Matrix2d Pinv = es.eigenvectors().inverse();
  const Eigen::Vector2d mu = es.eigenvalues().cwiseMax(1.0);
  return Pinv.transpose() * mu.asDiagonal() * Pinv;
}

// the largest generalised eigenvalue of B p = mu A p: how much B exceeds A in its strongest direction
// (1 if B = A; A positive definite)
inline double metric_excess(const Eigen::Matrix2d& A, const Eigen::Matrix2d& B)
{
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(0.5 * (B + B.transpose()), 0.5 * (A + A.transpose()),
                                                                 Eigen::EigenvaluesOnly);
  return es.eigenvalues()[1];
}

// Grades the vertex tensors M (3 x 3, positive definite on the tangent plane of the unit normal N[v],
// zero along it) of a surface with points P, along its edges given as adjacency lists (CSR: the
// neighbours of v are adj[start[v]] ... adj[start[v + 1] - 1], both directions present):
// for an edge (i, j) of length l in `scale * M_i`, M_j <- bound(M_j ∩ eta^-2 R M_i R^T) with
// eta = 1 + (beta - 1) l and R the rotation taking N[i] to N[j] (the tensor carried into j's tangent
// plane; skipped when the normals are opposite), until no tensor grows by more than `tolerance`
// (relative, in squared length) -- Borouchaki et al.'s queue of the vertices to propagate from, each
// vertex in it at most once. `bound` (Tensor, normal) -> Tensor must never shrink a tensor (the
// intersection only grows them, so the iteration is monotone and ends; it ends in practice after a few
// sweeps). Returns the number of tensors changed. Throws Internal_error if it does not end within
// 1000 pops per vertex (a broken `bound`).
template <typename Bound>
std::size_t grade_metric(std::vector<Eigen::Matrix3d>& M, const std::vector<Eigen::Vector3d>& P, const std::vector<Eigen::Vector3d>& N,
                         const std::vector<std::uint32_t>& start, const std::vector<std::uint32_t>& adj, double scale, double beta,
                         const Bound& bound, double tolerance = 1e-3)
{
  const std::size_t n = M.size();
  std::vector<Eigen::Matrix<double, 3, 2>> B(n);
  for(std::size_t v = 0; v < n; ++v) {
    B[v].col(0) = N[v].unitOrthogonal();
    B[v].col(1) = N[v].cross(B[v].col(0));
  }
  std::deque<std::uint32_t> queue;
  std::vector<char> queued(n, 1);
  for(std::size_t v = 0; v < n; ++v) queue.push_back(std::uint32_t(v));
  std::vector<char> changed(n, 0);
  const std::size_t max_pops = 1000 * n + 1000;
  std::size_t pops = 0;
  while(!queue.empty()) {
    if(++pops > max_pops)
      throw Internal_error("metric gradation: no convergence after " + std::to_string(max_pops) + " vertex visits");
    const std::uint32_t i = queue.front();
    queue.pop_front();
    queued[i] = 0;
    for(std::uint32_t k = start[i]; k < start[i + 1]; ++k) {
      const std::uint32_t j = adj[k];
      const Eigen::Vector3d e = P[j] - P[i];
      const double l = std::sqrt(std::max(0.0, scale * e.dot(M[i] * e)));
      const double eta = 1 + (beta - 1) * l;
      // M_i carried into j's tangent plane (Rodrigues' rotation taking N[i] to N[j])
      const Eigen::Vector3d w = N[i].cross(N[j]);
      const double c = N[i].dot(N[j]);
      if(c <= -0.999) continue;  // opposite normals: no rotation is meaningful
      Eigen::Matrix3d K;
      K << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
      const Eigen::Matrix3d R = Eigen::Matrix3d::Identity() + K + K * K / (1 + c);
      const Eigen::Matrix2d from_i = B[j].transpose() * (R * M[i] * R.transpose()) * B[j] / (eta * eta);
      const Eigen::Matrix2d mj = B[j].transpose() * M[j] * B[j];
      if(metric_excess(mj, from_i) <= 1 + tolerance) continue;
      const Eigen::Matrix2d m = metric_intersection(mj, from_i);
      const Eigen::Matrix3d next = bound(Eigen::Matrix3d(B[j] * m * B[j].transpose()), N[j]);
      if(metric_excess(mj, B[j].transpose() * next * B[j]) <= 1 + tolerance) continue;
      M[j] = next;
      changed[j] = 1;
      if(!queued[j]) {
        queued[j] = 1;
        queue.push_back(j);
      }
    }
  }
  return std::size_t(std::count(changed.begin(), changed.end(), 1));
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_METRIC_GRADATION_H
