// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
// Concept documentation (Doxygen only).

/*!
 * \ingroup PkgAnisoConformalConcepts
 * \cgalConcept
 *
 * A Riemannian metric on the input surface: a symmetric 3x3 tensor `M` at every point, so that the
 * length of a small vector `v` tangent to the surface is `sqrt(v^T M v)`. `M` must be finite, symmetric
 * and positive definite on the tangent plane; it may be singular along the normal (as the curvature
 * metric of the paper's eq. 4 is). The library evaluates it at the input vertices, at points it inserts
 * on the input (edge midpoints) and at the output vertices (to measure quality), always through a
 * `Surface_point`, which gives both the position and the input triangle with barycentric coordinates.
 * `compute_metric_square_roots()` checks the tensors and throws `Invalid_input` naming the vertex.
 *
 * For a planar domain (z = 0) the z-parts are 0 and the upper-left 2x2 block is the 2D metric.
 *
 * \cgalHasModel `Aniso_conformal::Tensor_field_metric`, `Aniso_conformal::Analytic_metric_2`,
 * `Aniso_conformal::Curvature_metric`, `Aniso_conformal::Image_metric`, `Aniso_conformal::Uniform_metric`
 */
class AnisotropicMetric {
public:
  /// `Eigen::Matrix3d`
  typedef unspecified_type Tensor;
  /// the tensor at `p` (a point of the input surface)
  Tensor tensor(const Aniso_conformal::Surface_point& p) const;
};
