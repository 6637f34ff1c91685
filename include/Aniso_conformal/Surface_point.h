// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_SURFACE_POINT_H
#define ANISO_CONFORMAL_SURFACE_POINT_H

#include <Eigen/Core>

#include <array>
#include <cstddef>

/// \file Surface_point.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMetrics
 * a point of the input surface: its position and its barycentric coordinates in a triangle of the
 * input (the three input vertex indices, as given by the vertex index map of the input mesh).
 * Models of `AnisotropicMetric` evaluate the metric at such points; a per-vertex field interpolates
 * with `barycentric`, an analytic field uses `position`.
 */
struct Surface_point {
  /// position in space (z = 0 for planar input)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  /// indices of the input vertices of the triangle that contains the point
  std::array<std::size_t, 3> vertices = {{0, 0, 0}};
  /// barycentric coordinates with respect to `vertices` (non-negative, sum 1)
  Eigen::Vector3d barycentric = Eigen::Vector3d(1, 0, 0);

  /// makes the point that coincides with input vertex `v` at `position`
  static Surface_point at_vertex(std::size_t v, const Eigen::Vector3d& position)
  {
    Surface_point p;
    p.position = position;
    p.vertices = {{v, v, v}};
    p.barycentric = Eigen::Vector3d(1, 0, 0);
    return p;
  }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_SURFACE_POINT_H
