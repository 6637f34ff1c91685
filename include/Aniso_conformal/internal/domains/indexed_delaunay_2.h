// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_INDEXED_DELAUNAY_2_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_INDEXED_DELAUNAY_2_H

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace Aniso_conformal {
namespace internal {

// CGAL's Delaunay triangulation of points of the plane (the sites of the planar domain, the sites and
// their translates on the flat torus) with the point index as vertex info. handle[i] is point i's
// vertex: a default handle, or one whose info differs, for a point that coincides with another.
struct Indexed_delaunay_2 {
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef CGAL::Triangulation_vertex_base_with_info_2<int, K> Vb;
  typedef CGAL::Triangulation_data_structure_2<Vb> Tds;
  typedef CGAL::Delaunay_triangulation_2<K, Tds> Triangulation;
  typedef Triangulation::Vertex_handle Vertex_handle;

  Triangulation dt;
  std::vector<Vertex_handle> handle;

  // the triangulation of `points` (replacing the previous one), inserted at once (spatially sorted)
  void build(const std::vector<Eigen::Vector2d>& points)
  {
    dt.clear();
    std::vector<std::pair<K::Point_2, int>> pts;
    pts.reserve(points.size());
    for(std::size_t i = 0; i < points.size(); ++i) pts.emplace_back(K::Point_2(points[i].x(), points[i].y()), int(i));
    dt.insert(pts.begin(), pts.end());
    handle.assign(points.size(), Vertex_handle());
    for(auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) handle[std::size_t(v->info())] = v;
  }

  bool has_vertex(std::size_t i) const { return handle[i] != Vertex_handle() && handle[i]->info() == int(i); }
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_INDEXED_DELAUNAY_2_H
