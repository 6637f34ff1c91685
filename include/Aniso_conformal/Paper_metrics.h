// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_PAPER_METRICS_H
#define ANISO_CONFORMAL_PAPER_METRICS_H

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

/// \file Paper_metrics.h
/// The analytic metrics of the paper's 2D experiments (Zhong et al.\ 2014, section 4.1), as functors
/// for `Analytic_metric_2`.

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMetrics
 * the metric of the paper's Fig.\ 6 on the unit square: `M = diag(s1^2, s2^2)` with
 * `s1 = 1 / (0.031 + x)`, `s2 = 1 / (0.031 + y)` (stretch ratio up to 33).
 */
struct Fig6_metric {
  /// the tensor at (x, y)
  Eigen::Matrix2d operator()(double x, double y) const
  {
    double s1 = 1.0 / (0.031 + x), s2 = 1.0 / (0.031 + y);
    Eigen::Matrix2d m;
    m << s1 * s1, 0, 0, s2 * s2;
    return m;
  }
};

/*!
 * \ingroup PkgAnisoConformalMetrics
 * the circular field of the paper's Fig.\ 7 (eq.\ 8), `M = R^T diag(Stretch^2, 1) R`, as we define it
 * (the paper shows it only as a picture): around the centre `c = (0.5, 0.5)`, with `r = |x - c|`,
 * the first row of `R` is the direction tangent to the circles, so edges are short along the circles
 * and long across them (elements point radially), and
 * `Stretch(r) = 1 + (max_stretch - 1) sin^2(pi min(r / r0, 1))` with `r0 = 0.6`: isotropic at the centre
 * and beyond `r0`, `max_stretch` (10) on the circle `r = 0.3`. The field is smooth (`M - I = O(r^2)` at
 * the centre, where the direction is undefined).
 *
 * Why tangential: a conformal embedding maps the annulus where the field is stretched to an annulus
 * whose radii ratio is `exp(-int Stretch / r dr)` for a radial stretch (about `e^-11` here: a conformal
 * factor of `1e9`, the method's known limitation, paper section 6), but only `exp(-int 1 / (Stretch r) dr)`
 * for a tangential one (a conformal factor below 10). Set `radial = true` for the other orientation.
 */
struct Circular_metric {
  double max_stretch = 10.0;  ///< largest stretch ratio
  double r0 = 0.6;            ///< radius beyond which the field is isotropic
  bool radial = false;        ///< stretch across the circles instead of along them
  /// the tensor at (x, y)
  Eigen::Matrix2d operator()(double x, double y) const
  {
    Eigen::Vector2d d(x - 0.5, y - 0.5);
    double r = d.norm();
    const double pi = 3.14159265358979323846;
    double s = std::sin(pi * std::min(r / r0, 1.0));
    double stretch = 1.0 + (max_stretch - 1.0) * s * s;
    Eigen::Matrix2d m = Eigen::Matrix2d::Identity();
    if(r > 0) {
      Eigen::Vector2d n = d / r;
      if(!radial) n = Eigen::Vector2d(-n.y(), n.x());
      m += (stretch * stretch - 1.0) * n * n.transpose();
    }
    return m;
  }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_PAPER_METRICS_H
