// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_MAKE_ELLIPSOID_H
#define ANISO_CONFORMAL_MAKE_ELLIPSOID_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

/// \file make_ellipsoid.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * triangulates the ellipsoid `x^2/a^2 + y^2/b^2 + z^2/c^2 = 1`, a closed genus-0 surface, as an
 * icosphere scaled to the semi-axes: the icosahedron, each triangle split into four `subdivision_level`
 * times with the new vertices pushed to the unit sphere, then `(x, y, z) -> (a x, b y, c z)`; oriented
 * outward, deterministic. It has `10 * 4^level + 2` vertices: level 5 gives the paper's 10242 (Fig. 10,
 * with the default semi-axes 1, 0.6, 0.4), level 3 gives 642.
 *
 * \throws Invalid_input if the level is negative or above 8, or a semi-axis is not positive and finite
 */
inline Input_surface make_ellipsoid(int subdivision_level = 5, double a = 1.0, double b = 0.6, double c = 0.4)
{
  if(subdivision_level < 0 || subdivision_level > 8)
    throw Invalid_input("make_ellipsoid(): the subdivision level must be in [0, 8], not " + std::to_string(subdivision_level));
  for(double s : {a, b, c})
    if(!(s > 0) || !std::isfinite(s))
      throw Invalid_input("make_ellipsoid(): the semi-axes must be positive and finite");
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for(auto& q : p) q.normalize();
  std::vector<Input_surface::Face> f = {{{0, 11, 5}}, {{0, 5, 1}},  {{0, 1, 7}},   {{0, 7, 10}}, {{0, 10, 11}},
                                        {{1, 5, 9}},  {{5, 11, 4}}, {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},
                                        {{3, 9, 4}},  {{3, 4, 2}},  {{3, 2, 6}},   {{3, 6, 8}},  {{3, 8, 9}},
                                        {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}},  {{8, 6, 7}},  {{9, 8, 1}}};
  for(int level = 0; level < subdivision_level; ++level) {
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> midpoint;
    auto mid = [&](std::size_t i, std::size_t j) {
      const auto key = std::make_pair(std::min(i, j), std::max(i, j));
      const auto it = midpoint.find(key);
      if(it != midpoint.end()) return it->second;
      p.push_back((p[i] + p[j]).normalized());
      return midpoint[key] = p.size() - 1;
    };
    std::vector<Input_surface::Face> g;
    g.reserve(4 * f.size());
    for(const auto& tri : f) {
      const std::size_t ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
      g.push_back({{tri[0], ab, ca}});
      g.push_back({{tri[1], bc, ab}});
      g.push_back({{tri[2], ca, bc}});
      g.push_back({{ab, bc, ca}});
    }
    f.swap(g);
  }
  for(auto& q : p) q = Eigen::Vector3d(a * q.x(), b * q.y(), c * q.z());
  return Input_surface(std::move(p), std::move(f));
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_MAKE_ELLIPSOID_H
