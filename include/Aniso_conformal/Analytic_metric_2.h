// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_ANALYTIC_METRIC_2_H
#define ANISO_CONFORMAL_ANALYTIC_METRIC_2_H

#include <Aniso_conformal/Surface_point.h>

#include <Eigen/Core>

#include <utility>

/// \file Analytic_metric_2.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMetrics
 * a metric on a planar domain (z = 0) given by a functor `Eigen::Matrix2d f(double x, double y)`
 * returning a symmetric positive-definite 2x2 tensor. The 3x3 tensor has zero z-parts.
 *
 * \cgalModels `AnisotropicMetric`
 */
template <typename Functor>
class Analytic_metric_2 {
public:
  /// the tensor type
  typedef Eigen::Matrix3d Tensor;
  /// wraps `f`
  explicit Analytic_metric_2(Functor f) : m_f(std::move(f)) {}
  /// the tensor at `p`, evaluated at its (x, y) position
  Tensor tensor(const Surface_point& p) const
  {
    Eigen::Matrix2d m = m_f(p.position.x(), p.position.y());
    Tensor M = Tensor::Zero();
    M.topLeftCorner<2, 2>() = m;
    return M;
  }
  /// the wrapped functor
  const Functor& functor() const { return m_f; }

private:
  Functor m_f;
};

/// \ingroup PkgAnisoConformalMetrics
/// makes an `Analytic_metric_2` from `f`
template <typename Functor>
Analytic_metric_2<Functor> make_analytic_metric_2(Functor f)
{
  return Analytic_metric_2<Functor>(std::move(f));
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_ANALYTIC_METRIC_2_H
