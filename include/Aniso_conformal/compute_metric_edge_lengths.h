// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_COMPUTE_METRIC_EDGE_LENGTHS_H
#define ANISO_CONFORMAL_COMPUTE_METRIC_EDGE_LENGTHS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/tensor.h>

#include <Eigen/Core>

#include <cmath>
#include <string>
#include <vector>

/// \file compute_metric_edge_lengths.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * evaluates `metric` at every vertex of `surface`, checks it, and returns the symmetric square roots
 * `Q = M^{1/2}` (stage 1).
 *
 * \tparam AnisotropicMetric a model of `AnisotropicMetric`
 * \throws Invalid_input naming the vertex if a tensor has a non-finite entry, is not symmetric, or is
 *         not positive definite on the tangent plane (relative smallest eigenvalue below `1e-12`;
 *         a tensor may be singular along the normal, as the paper's eq. 4 is; at a vertex whose normal
 *         is zero, its faces' normals cancelling, it must be positive definite in space)
 */
template <typename AnisotropicMetric>
std::vector<Eigen::Matrix3d> compute_metric_square_roots(const Input_surface& surface, const AnisotropicMetric& metric)
{
  std::vector<Eigen::Matrix3d> Q(surface.number_of_vertices());
  for(std::size_t v = 0; v < Q.size(); ++v) {
    Eigen::Matrix3d M = metric.tensor(Surface_point::at_vertex(v, surface.points()[v]));
    const std::string where = "metric at vertex " + std::to_string(v);
    if(!internal::all_finite(M)) throw Invalid_input(where + ": the tensor has a non-finite (NaN or infinite) entry");
    if(internal::asymmetry(M) > 1e-9) throw Invalid_input(where + ": the tensor is not symmetric");
    const Eigen::Vector3d n = surface.is_planar() ? Eigen::Vector3d(0, 0, 1) : surface.vertex_normals()[v];
    if(!(internal::tangent_positivity(M, n) > 1e-12))
      throw Invalid_input(where + ": the tensor is not positive definite on the tangent plane");
    Q[v] = internal::symmetric_sqrt(M);
  }
  return Q;
}

/*!
 * \ingroup PkgAnisoConformalStages
 * sets the length of every edge of `itri` to its length in the metric (paper 3.2): each triangle `T`
 * uses `Q_T = (Q_a + Q_b + Q_c) / 3` and proposes `|Q_T (x_j - x_i)|` for its edges; an interior
 * edge takes the mean of its two proposals.
 */
inline void compute_metric_edge_lengths(Intrinsic_triangulation& itri)
{
  const std::size_t nh = itri.number_of_halfedges();
  std::vector<double> proposal(nh);
  for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
    const auto& c = itri.face_vertices(f);
    const Eigen::Matrix3d QT = (itri.Q(c[0]) + itri.Q(c[1]) + itri.Q(c[2])) / 3.0;
    for(int k = 0; k < 3; ++k)
      proposal[3 * f + k] = (QT * (itri.position(c[(k + 1) % 3]) - itri.position(c[k]))).norm();
  }
  for(int h = 0; h < int(nh); ++h) {
    if(!itri.is_edge_representative(h)) continue;
    const int t = itri.twin(h);
    itri.set_length(h, t < 0 ? proposal[h] : 0.5 * (proposal[h] + proposal[t]));
  }
}

namespace internal {

// Strict triangle inequality with a relative margin: the conformal solve needs triangles that are not
// flat, not merely not inverted.
inline bool satisfies_triangle_inequality(double a, double b, double c, double rel_margin = 1e-7)
{
  const double s = a + b + c;
  if(!(s > 0) || !std::isfinite(s)) return false;
  return a < b + c - rel_margin * s && b < c + a - rel_margin * s && c < a + b - rel_margin * s;
}

inline bool face_is_valid(const Intrinsic_triangulation& itri, std::size_t f)
{
  return satisfies_triangle_inequality(itri.length(int(3 * f)), itri.length(int(3 * f + 1)), itri.length(int(3 * f + 2)));
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_COMPUTE_METRIC_EDGE_LENGTHS_H
