// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_UNIFORM_METRIC_H
#define ANISO_CONFORMAL_UNIFORM_METRIC_H

#include <Aniso_conformal/Surface_point.h>

#include <Eigen/Core>

/// \file Uniform_metric.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMetrics
 * the isotropic metric `M = I` (Euclidean lengths): `remesh()` with it is an isotropic CVT remesher.
 * Only the shape of a metric matters, since the number of output vertices is given.
 *
 * \cgalModels `AnisotropicMetric`
 */
class Uniform_metric {
public:
  /// the tensor type
  typedef Eigen::Matrix3d Tensor;
  /// the identity
  Tensor tensor(const Surface_point&) const { return Tensor::Identity(); }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_UNIFORM_METRIC_H
