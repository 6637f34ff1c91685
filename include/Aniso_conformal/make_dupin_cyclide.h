// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_MAKE_DUPIN_CYCLIDE_H
#define ANISO_CONFORMAL_MAKE_DUPIN_CYCLIDE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>

#include <Eigen/Core>

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

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_MAKE_DUPIN_CYCLIDE_H
