// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A test input shared by test_sphere and test_features.

#ifndef ANISO_CONFORMAL_TEST_GRID_CUBE_H
#define ANISO_CONFORMAL_TEST_GRID_CUBE_H

#include <Aniso_conformal/Input_surface.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <map>
#include <vector>

namespace test {

namespace AC = Aniso_conformal;

// The surface of the cube [-1, 1]^3, each face an n x n grid of squares cut by parallel diagonals,
// oriented outward: 12 straight creases of length 2 meeting at 8 corners, and every vertex off the
// cube's edges has a link edge cocircular with it
inline AC::Input_surface make_grid_cube(int n)
{
  std::map<std::array<int, 3>, std::size_t> index;
  std::vector<Eigen::Vector3d> points;
  auto vertex = [&](std::array<int, 3> g) {
    const auto it = index.find(g);
    if(it != index.end()) return it->second;
    points.push_back(Eigen::Vector3d(g[0], g[1], g[2]) * (2.0 / n) - Eigen::Vector3d::Ones());
    return index[g] = points.size() - 1;
  };
  std::vector<AC::Input_surface::Face> faces;
  for(int a = 0; a < 3; ++a)
    for(int side : {0, n})
      for(int i = 0; i < n; ++i)
        for(int j = 0; j < n; ++j) {
          auto at = [&](int di, int dj) {
            std::array<int, 3> g;
            g[std::size_t(a)] = side;
            g[std::size_t((a + 1) % 3)] = i + di;
            g[std::size_t((a + 2) % 3)] = j + dj;
            return vertex(g);
          };
          const std::size_t p00 = at(0, 0), p10 = at(1, 0), p11 = at(1, 1), p01 = at(0, 1);
          if(side == n) {  // e_(a+1) x e_(a+2) = e_a: counterclockwise in (i, j) is outward
            faces.push_back({{p00, p10, p11}});
            faces.push_back({{p00, p11, p01}});
          } else {
            faces.push_back({{p00, p11, p10}});
            faces.push_back({{p00, p01, p11}});
          }
        }
  return AC::Input_surface(points, faces);
}

} // namespace test

#endif // ANISO_CONFORMAL_TEST_GRID_CUBE_H
