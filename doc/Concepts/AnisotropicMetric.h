// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Concept documentation (read by Doxygen only; not a header to include).

/*!
 * \ingroup PkgAnisoConformalConcepts
 * A Riemannian metric on the input surface: a symmetric 3x3 tensor `M` at every point of the surface,
 * so that the length of a small vector `v` tangent to the surface is `sqrt(v^T M v)`.
 *
 * \cgalConcept
 *
 * `M` must be finite, symmetric and positive definite on the tangent plane; it may be singular along
 * the normal (the curvature metric of the paper's eq.\ 4 is). For a planar domain (z = 0) only the
 * upper-left 2x2 block matters and the z-parts are 0. Only the *shape* of the metric matters: its
 * global scale is irrelevant because the number of output vertices is given.
 *
 * The library evaluates a metric, always through `tensor()`:
 * - at every input vertex, by `compute_metric_square_roots()` (stage 1; through
 *   `Aniso_conformal::Surface_point::at_vertex()`), which checks the tensor and throws
 *   `Aniso_conformal::Invalid_input` naming the vertex; the library then works with `Q = M^(1/2)`,
 *   and points it inserts later (edge midpoints) get the mean `Q` of the edge's ends, not a new
 *   evaluation;
 * - at every output vertex, by `remesh()`, to measure the quality in the metric (stage 6);
 * - at points given by their `position` alone (the other fields of the `Surface_point` left at their
 *   defaults), by `make_square_background()`, which refines the unit square where the metric asks
 *   for it. Metrics passed to it must therefore not rely on `Surface_point::vertices` and
 *   `Surface_point::barycentric` (`Analytic_metric_2`, `Image_metric` and `Uniform_metric` do not).
 *
 * `tensor()` is called from one thread at a time.
 *
 * \cgalHasModel `Aniso_conformal::Tensor_field_metric`, `Aniso_conformal::Analytic_metric_2`,
 * `Aniso_conformal::Curvature_metric`, `Aniso_conformal::Image_metric`, `Aniso_conformal::Uniform_metric`
 *
 * \sa `examples/custom_metric.cpp`, a user-written model in 15 lines.
 */
class AnisotropicMetric {
public:
  /// \name Types
  /// @{

  /*!
   * the type `tensor()` returns: `Eigen::Matrix3d`, or any type convertible to it. The shipped models
   * define this typedef as `Eigen::Matrix3d`; the generic code uses only the return type of `tensor()`,
   * so a user model need not name it.
   */
  typedef unspecified_type Tensor;

  /// @}

  /// \name Operations
  /// @{

  /*!
   * returns the tensor `M` at the point `p` of the input surface. `p.position` is the point in space
   * (z = 0 for planar input); `p.vertices` and `p.barycentric` locate it in a triangle of the input
   * (vertex indices as given by the vertex index map of the input mesh), which is what a per-vertex
   * field interpolates with.
   */
  Tensor tensor(const Aniso_conformal::Surface_point& p) const;

  /// @}
};
