// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_MAKE_DUPIN_CYCLIDE_H
#define ANISO_CONFORMAL_MAKE_DUPIN_CYCLIDE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Tensor_field_metric.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

/// \file make_dupin_cyclide.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the parameters of a Dupin ring cyclide (`make_dupin_cyclide()`); the defaults are the test surface
 * of the paper's Fig. 11 and Table 2 (a tube whose radius varies from `mu - c = 0.19` to `mu + c = 0.81`)
 */
struct Dupin_cyclide_parameters {
  double a = 1.0;   ///< `a > 0`
  double b = 0.95;  ///< `0 < b <= a`; `c = sqrt(a^2 - b^2)` (`c = 0` gives a ring torus, `R = a`, `r = mu`)
  double mu = 0.5;  ///< `c < mu < a` for a ring cyclide
};

/*!
 * \ingroup PkgAnisoConformalDomains
 * triangulates a Dupin ring cyclide, a closed genus-1 surface with lines of curvature along a regular
 * `nu x nv` grid of its parameters `u, v` in `[0, 2 pi)` (each grid square split along one diagonal),
 * oriented outward. With `den = a - c cos u cos v`:
 * `x = (mu (c - a cos u cos v) + b^2 cos u) / den`, `y = b sin u (a - mu cos v) / den`,
 * `z = b sin v (c cos u - mu) / den`.
 *
 * The paper's inputs are the `180 x 144` grid (25920 vertices, Table 2 and Fig. 11) and the
 * `180 x 120` grid (21600 vertices).
 * \throws Invalid_input if `nu < 3`, `nv < 3`, or the parameters do not describe a ring cyclide
 */
inline Input_surface make_dupin_cyclide(std::size_t nu, std::size_t nv, const Dupin_cyclide_parameters& p = {})
{
  if(nu < 3 || nv < 3)
    throw Invalid_input("make_dupin_cyclide(): the grid needs at least 3 x 3 vertices, " + std::to_string(nu) + " x " +
                        std::to_string(nv) + " were requested");
  if(!(p.a > 0 && p.b > 0 && p.b <= p.a))
    throw Invalid_input("make_dupin_cyclide(): need a > 0 and 0 < b <= a");
  const double c = std::sqrt(p.a * p.a - p.b * p.b);
  if(!(c < p.mu && p.mu < p.a))
    throw Invalid_input("make_dupin_cyclide(): not a ring cyclide, need c < mu < a (c = " + std::to_string(c) + ")");
  const double two_pi = 2 * 3.14159265358979323846;
  std::vector<Eigen::Vector3d> points;
  points.reserve(nu * nv);
  for(std::size_t i = 0; i < nu; ++i)
    for(std::size_t j = 0; j < nv; ++j) {
      const double u = two_pi * double(i) / double(nu), v = two_pi * double(j) / double(nv);
      const double den = p.a - c * std::cos(u) * std::cos(v);
      points.emplace_back((p.mu * (c - p.a * std::cos(u) * std::cos(v)) + p.b * p.b * std::cos(u)) / den,
                          p.b * std::sin(u) * (p.a - p.mu * std::cos(v)) / den,
                          p.b * std::sin(v) * (c * std::cos(u) - p.mu) / den);
    }
  // (A, B, C) turns counterclockwise seen from outside (the outward orientation)
  std::vector<Input_surface::Face> faces;
  faces.reserve(2 * nu * nv);
  for(std::size_t i = 0; i < nu; ++i)
    for(std::size_t j = 0; j < nv; ++j) {
      const std::size_t A = i * nv + j, B = ((i + 1) % nu) * nv + j, C = ((i + 1) % nu) * nv + (j + 1) % nv, D = i * nv + (j + 1) % nv;
      faces.push_back({{A, B, C}});
      faces.push_back({{A, C, D}});
    }
  return Input_surface(std::move(points), std::move(faces));
}

/*!
 * \ingroup PkgAnisoConformalDomains
 * a metric on `make_dupin_cyclide(nu, nv, p)` whose stretch spans `[stretch_min, stretch_max]` exactly
 * (the paper's Fig. 11 and Table 2 give `[2, 29]`, the defaults), one tensor per vertex
 * (`Tensor_field_metric`, in the order of `make_dupin_cyclide()`'s points).
 *
 * The paper (section 2.1, eq. 4) builds its metric from two user-specified stretching factors along the
 * principal directions and does not publish its field. This one follows the lines of curvature, which are
 * the parameter lines `u` (along the tube) and `v` (around it): with `kappa_v` the normal curvature around
 * the tube (never zero) and `kappa_u` the one along it (zero on two circles), the scale around the tube is
 * `s_v = sqrt(|kappa_v|)` (inverse length: edges across the tube are `1 / s_v` long in space, as with the
 * curvature metric) and along it `s_u = s_v / r` with the stretch `r = clamp(|kappa_v / kappa_u|,
 * stretch_min, stretch_max)`; `M = s_v^2 t_v t_v^T + s_u^2 t_u t_u^T` (tangent only; `t_u`, `t_v` the unit
 * parameter directions). The long axis is always along the tube, so the field is continuous where the two
 * curvatures are equal, and it reaches `stretch_max` on bands several vertices wide (5.8 % of the
 * `180 x 144` grid's vertices). The curvatures come from central differences of the exact
 * parameterisation (step `1e-4`, errors near `1e-8`). `benchmark/make_cyclide_metric.py` writes the same
 * field as a metric file for the tool.
 *
 * Along the tube the long axis turns within the tangent plane, so at a given number of output vertices
 * the longest elements cannot follow it with straight edges: `remesh()` bounds the stretch there
 * (`Stretch_limit_report`; at 8000 vertices to 7-13).
 * \throws Invalid_input as `make_dupin_cyclide()`, or if not `1 <= stretch_min <= stretch_max`
 */
inline Tensor_field_metric make_dupin_cyclide_stretch_field(std::size_t nu, std::size_t nv, double stretch_min = 2,
                                                            double stretch_max = 29, const Dupin_cyclide_parameters& p = {})
{
  if(nu < 3 || nv < 3)
    throw Invalid_input("make_dupin_cyclide_stretch_field(): the grid needs at least 3 x 3 vertices");
  if(!(p.a > 0 && p.b > 0 && p.b <= p.a))
    throw Invalid_input("make_dupin_cyclide_stretch_field(): need a > 0 and 0 < b <= a");
  if(!(1 <= stretch_min && stretch_min <= stretch_max && std::isfinite(stretch_max)))
    throw Invalid_input("make_dupin_cyclide_stretch_field(): need 1 <= stretch_min <= stretch_max (finite)");
  const double c = std::sqrt(p.a * p.a - p.b * p.b);
  if(!(c < p.mu && p.mu < p.a))
    throw Invalid_input("make_dupin_cyclide_stretch_field(): not a ring cyclide, need c < mu < a");
  auto point = [&](double u, double v) {
    const double den = p.a - c * std::cos(u) * std::cos(v);
    return Eigen::Vector3d((p.mu * (c - p.a * std::cos(u) * std::cos(v)) + p.b * p.b * std::cos(u)) / den,
                           p.b * std::sin(u) * (p.a - p.mu * std::cos(v)) / den, p.b * std::sin(v) * (c * std::cos(u) - p.mu) / den);
  };
  const double two_pi = 2 * 3.14159265358979323846, h = 1e-4;
  std::vector<Eigen::Matrix3d> tensors;
  tensors.reserve(nu * nv);
  for(std::size_t i = 0; i < nu; ++i)
    for(std::size_t j = 0; j < nv; ++j) {
      const double u = two_pi * double(i) / double(nu), v = two_pi * double(j) / double(nv);
      const Eigen::Vector3d x = point(u, v), up = point(u + h, v), um = point(u - h, v), vp = point(u, v + h), vm = point(u, v - h);
      const Eigen::Vector3d xu = (up - um) / (2 * h), xv = (vp - vm) / (2 * h);
      const Eigen::Vector3d xuu = (up + um - 2 * x) / (h * h), xvv = (vp + vm - 2 * x) / (h * h);
      const Eigen::Vector3d n = xu.cross(xv).normalized();
      const double kappa_u = xuu.dot(n) / xu.squaredNorm(), kappa_v = xvv.dot(n) / xv.squaredNorm();
      const double r = std::min(std::max(std::abs(kappa_v) / std::max(std::abs(kappa_u), 1e-300), stretch_min), stretch_max);
      const double s_v = std::sqrt(std::abs(kappa_v)), s_u = s_v / r;
      const Eigen::Vector3d tu = xu.normalized(), tv = xv.normalized();
      tensors.push_back(s_v * s_v * tv * tv.transpose() + s_u * s_u * tu * tu.transpose());
    }
  return Tensor_field_metric(std::move(tensors));
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_MAKE_DUPIN_CYCLIDE_H
