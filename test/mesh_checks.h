// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Topology and area of a triangle soup, and point-to-segment distances, shared by the test modules.

#ifndef ANISO_CONFORMAL_TEST_MESH_CHECKS_H
#define ANISO_CONFORMAL_TEST_MESH_CHECKS_H

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cstddef>
#include <set>
#include <utility>

namespace test {

struct Mesh_counts {
  double planar_area = 0;                       // signed area of the projection on z = 0
  std::size_t boundary_edges = 0;               // directed edges without their opposite
  std::set<std::size_t> boundary_vertices;      // tails of the boundary edges
  int euler = 0;                                // V - E + F
};

template <typename Points, typename Faces>
Mesh_counts count_mesh(const Points& points, const Faces& faces)
{
  Mesh_counts c;
  std::set<std::pair<std::size_t, std::size_t>> directed, edges;
  for(const auto& f : faces) {
    const Eigen::Vector3d a = points[f[0]], b = points[f[1]], d = points[f[2]];
    c.planar_area += 0.5 * ((b - a).cross(d - a)).z();
    for(int k = 0; k < 3; ++k) {
      directed.insert({f[k], f[(k + 1) % 3]});
      edges.insert(std::minmax(f[k], f[(k + 1) % 3]));
    }
  }
  for(const auto& d : directed)
    if(!directed.count({d.second, d.first})) {
      ++c.boundary_edges;
      c.boundary_vertices.insert(d.first);
    }
  c.euler = int(points.size()) - int(edges.size()) + int(faces.size());
  return c;
}

// distance from p to the segment ab
inline double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const Eigen::Vector3d d = b - a;
  const double t = std::max(0.0, std::min(1.0, (p - a).dot(d) / d.squaredNorm()));
  return (p - (a + t * d)).norm();
}

} // namespace test

#endif // ANISO_CONFORMAL_TEST_MESH_CHECKS_H
