// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_FEATURE_GRAPH_H
#define ANISO_CONFORMAL_FEATURE_GRAPH_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>

#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

/// \file Feature_graph.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMain
 * one feature curve of the input: a chain of crease edges between two feature vertices, or a closed
 * loop of crease edges through no feature vertex (the rim of a capped cylinder).
 */
struct Feature_curve {
  /// input vertex indices along the curve, in order; the first and last are feature vertices (corners) of
  /// an open curve; a closed loop repeats its first vertex at the end, so edge `i` is
  /// (`vertices[i]`, `vertices[i + 1]`) in both cases
  std::vector<std::size_t> vertices;
  bool closed = false;  ///< a loop through no corner (then `vertices.front() == vertices.back()`)
  double length = 0;    ///< Euclidean length of the polyline, in the input's units
};

/*!
 * \ingroup PkgAnisoConformalMain
 * the sharp features of an input surface (issue 15, item 1): its crease edges, its feature vertices
 * (corners) and the curves the creases form between the corners. Boundary edges are not creases:
 * a disk's boundary and its corners are handled by the plane (`corner_angle`).
 */
struct Feature_graph {
  /// crease edges as (smaller, larger) input vertex indices, sorted
  std::vector<std::array<std::size_t, 2>> crease_edges;
  /// feature vertices (corners), input vertex indices, sorted: where 1 or 3 and more crease edges meet,
  /// or where a crease turns by more than the corner angle
  std::vector<std::size_t> corners;
  /// the crease edges as curves: open chains from corner to corner, then closed loops, in a deterministic
  /// order (by their first corner, then the smaller neighbour; loops by their smallest vertex)
  std::vector<Feature_curve> curves;
  /// total length of the creases, in the input's units
  double crease_length() const
  {
    double l = 0;
    for(const Feature_curve& c : curves) l += c.length;
    return l;
  }
  /// no crease and no corner
  bool empty() const { return crease_edges.empty() && corners.empty(); }
};

/*!
 * \ingroup PkgAnisoConformalMain
 * finds the feature graph of `surface`: an interior edge is a crease when the angle between the normals
 * of its two triangles exceeds `feature_angle` degrees (0 for two coplanar triangles, 90 along a cube's
 * edge; CGAL's `Polygon_mesh_processing::detect_sharp_edges()` decides it); a vertex is a corner when 1 or
 * 3 and more creases meet there, or when exactly 2 meet and the crease turns there by more than
 * `corner_angle` degrees (the angle between the directions of its two edges, 0 for a straight crease);
 * the creases are then chained into curves between corners, and the chains that meet no corner into
 * closed loops. `feature_angle` 180 finds nothing.
 *
 * A user's own features come on top (issue 15, item 1: what a CAD model's feature lines or a user's
 * selection mark): every edge of `marked_edges` is a crease whatever its dihedral angle, every vertex of
 * `marked_vertices` a corner; so `feature_angle` 180 with marked edges keeps exactly those. A marked edge
 * on the boundary is left out (the boundary is kept as it is already). Time O(V + E log E) for V
 * vertices and E edges, plus O(m log m) for m marked edges.
 *
 * \param surface the input
 * \param feature_angle degrees in [0, 180] (default of `remesh()`: 60)
 * \param corner_angle degrees in [0, 180) (default of `remesh()`: 30, the boundary's)
 * \param marked_edges edges to keep as creases, as pairs of input vertex indices in either order (the
 *        named parameter `feature_edges` of `remesh()`; the tool's `--features FILE`)
 * \param marked_vertices input vertex indices to keep as corners (`feature_vertices`)
 * \returns the crease edges, corners and curves (sorted as `Feature_graph` says)
 * \throws Invalid_input if an angle is out of its range or not finite, a marked vertex index is not a
 *         vertex of `surface`, or a marked edge is not an edge of `surface` (the message names the first)
 */
inline Feature_graph detect_features(const Input_surface& surface, double feature_angle, double corner_angle,
                                     const std::vector<std::array<std::size_t, 2>>& marked_edges = {},
                                     const std::vector<std::size_t>& marked_vertices = {})
{
  if(!(feature_angle >= 0 && feature_angle <= 180))
    throw Invalid_input("detect_features(): the feature angle must be in [0, 180] degrees, not " + std::to_string(feature_angle));
  if(!(corner_angle >= 0 && corner_angle < 180))
    throw Invalid_input("detect_features(): the corner angle must be in [0, 180) degrees, not " + std::to_string(corner_angle));
  const std::size_t nv = surface.number_of_vertices();
  for(std::size_t v : marked_vertices)
    if(v >= nv)
      throw Invalid_input("detect_features(): marked feature vertex " + std::to_string(v) + " is not a vertex of the input (it has " +
                          std::to_string(nv) + ")");
  Feature_graph g;
  if(feature_angle == 180 && marked_edges.empty() && marked_vertices.empty())
    return g;  // CGAL's convention too: nothing is sharp at 180

  typedef CGAL::Simple_cartesian<double> K;
  typedef CGAL::Surface_mesh<K::Point_3> Mesh;
  Mesh mesh;
  const auto& P = surface.points();
  std::vector<Mesh::Vertex_index> vd(P.size());
  for(std::size_t i = 0; i < P.size(); ++i) vd[i] = mesh.add_vertex(K::Point_3(P[i].x(), P[i].y(), P[i].z()));
  for(const auto& f : surface.faces())
    if(mesh.add_face(vd[f[0]], vd[f[1]], vd[f[2]]) == Mesh::null_face())
      throw Internal_error("detect_features(): a face of a validated surface was refused by CGAL::Surface_mesh");
  auto sharp = mesh.add_property_map<Mesh::Edge_index, bool>("e:aniso_conformal_sharp", false).first;
  if(feature_angle < 180) CGAL::Polygon_mesh_processing::detect_sharp_edges(mesh, feature_angle, sharp);
  for(const auto& m : marked_edges) {
    std::string name = "detect_features(): marked feature edge (" + std::to_string(m[0]) + ", " + std::to_string(m[1]) + ")";
    if(m[0] < nv && m[1] < nv && (surface.input_vertex_index(m[0]) != m[0] || surface.input_vertex_index(m[1]) != m[1]))
      name += " (vertices " + std::to_string(surface.input_vertex_index(m[0])) + " and " +  // repaired: the file's indices too
              std::to_string(surface.input_vertex_index(m[1])) + " of the input file)";
    if(m[0] >= nv || m[1] >= nv) throw Invalid_input(name + " names a vertex the input does not have (it has " + std::to_string(nv) + ")");
    const auto h = CGAL::halfedge(vd[m[0]], vd[m[1]], mesh);
    if(m[0] == m[1] || !h.second) throw Invalid_input(name + " is not an edge of the input's triangles");
    put(sharp, mesh.edge(h.first), true);
  }
  for(Mesh::Edge_index e : mesh.edges())
    if(get(sharp, e) && !mesh.is_border(e)) {  // CGAL marks the border too: the plane keeps it already
      const std::size_t a = std::size_t(mesh.vertex(e, 0)), b = std::size_t(mesh.vertex(e, 1));
      g.crease_edges.push_back({{std::min(a, b), std::max(a, b)}});
    }
  std::sort(g.crease_edges.begin(), g.crease_edges.end());
  std::vector<char> marked_corner(P.size(), 0);
  for(std::size_t v : marked_vertices) marked_corner[v] = 1;
  if(g.crease_edges.empty()) {
    for(std::size_t v = 0; v < P.size(); ++v)
      if(marked_corner[v]) g.corners.push_back(v);
    return g;
  }

  // the crease neighbours of each vertex, sorted, and the edges already chained
  std::vector<std::vector<std::size_t>> nb(P.size());
  for(const auto& e : g.crease_edges) {
    nb[e[0]].push_back(e[1]);
    nb[e[1]].push_back(e[0]);
  }
  for(auto& n : nb) std::sort(n.begin(), n.end());
  const double turn_limit = corner_angle * 3.14159265358979323846 / 180.0;
  std::vector<char> is_corner(P.size(), 0);
  for(std::size_t v = 0; v < P.size(); ++v) {
    if(marked_corner[v]) {
      is_corner[v] = 1;
    } else if(nb[v].empty()) {
      continue;
    } else if(nb[v].size() != 2) {
      is_corner[v] = 1;
    } else {
      const Eigen::Vector3d a = P[v] - P[nb[v][0]], b = P[nb[v][1]] - P[v];
      is_corner[v] = std::atan2(a.cross(b).norm(), a.dot(b)) > turn_limit;
    }
    if(is_corner[v]) g.corners.push_back(v);
  }
  auto edge_index = [&](std::size_t a, std::size_t b) {
    const std::array<std::size_t, 2> e = {{std::min(a, b), std::max(a, b)}};
    return std::size_t(std::lower_bound(g.crease_edges.begin(), g.crease_edges.end(), e) - g.crease_edges.begin());
  };
  std::vector<char> used(g.crease_edges.size(), 0);
  // walks from `start` through `next` until a corner, or back to `start`
  auto walk = [&](std::size_t start, std::size_t next) {
    Feature_curve c;
    c.vertices.push_back(start);
    std::size_t prev = start, cur = next;
    used[edge_index(prev, cur)] = 1;
    c.length += (P[cur] - P[prev]).norm();
    c.vertices.push_back(cur);
    while(!is_corner[cur] && cur != start) {
      const std::size_t nxt = nb[cur][0] == prev ? nb[cur][1] : nb[cur][0];  // a non-corner has 2 neighbours
      const std::size_t e = edge_index(cur, nxt);
      if(used[e]) throw Internal_error("detect_features(): a crease edge was reached twice");
      used[e] = 1;
      c.length += (P[nxt] - P[cur]).norm();
      c.vertices.push_back(nxt);
      prev = cur;
      cur = nxt;
    }
    return c;
  };
  for(std::size_t v : g.corners)
    for(std::size_t w : nb[v])
      if(!used[edge_index(v, w)]) g.curves.push_back(walk(v, w));
  for(std::size_t e = 0; e < g.crease_edges.size(); ++e)
    if(!used[e]) {  // a loop through no corner: every vertex on it has 2 crease neighbours
      Feature_curve c = walk(g.crease_edges[e][0], g.crease_edges[e][1]);
      c.closed = true;
      g.curves.push_back(std::move(c));
    }
  return g;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_FEATURE_GRAPH_H
