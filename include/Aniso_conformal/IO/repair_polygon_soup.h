// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_REPAIR_POLYGON_SOUP_H
#define ANISO_CONFORMAL_IO_REPAIR_POLYGON_SOUP_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/IO/Repair_report.h>
#include <Aniso_conformal/Input_surface.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Projection_traits_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstddef>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

/// \file repair_polygon_soup.h
/// The repairs a user expects of a mesh file (issue 14), made with CGAL's Polygon Mesh Processing on the
/// polygon soup the readers produce, before the strict validation of `Input_surface`.

namespace Aniso_conformal {
namespace IO {

namespace internal {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Repair_kernel;
typedef Repair_kernel::Point_3 Repair_point;
typedef std::vector<std::vector<std::size_t>> Polygons;

// what orient_polygon_soup() reports of the soup's non-manifold simplices (a model of
// PMPPolygonSoupOrientationVisitor; it is copied, so it writes through a pointer)
struct Orientation_findings {
  std::vector<std::array<std::size_t, 3>> non_manifold_edges;   // (a, b, faces on it)
  std::vector<std::array<std::size_t, 2>> non_manifold_vertices;  // (v, separate groups of faces around it)
};
struct Orientation_visitor : CGAL::Polygon_mesh_processing::Default_orientation_visitor {
  Orientation_findings* found;
  explicit Orientation_visitor(Orientation_findings* f) : found(f) {}
  void non_manifold_edge(std::size_t a, std::size_t b, std::size_t n) { found->non_manifold_edges.push_back({{a, b, n}}); }
  void non_manifold_vertex(std::size_t v, std::size_t n) { found->non_manifold_vertices.push_back({{v, n}}); }
};

// the input points at the position of repaired vertex `v`, as text ("3, 17 and 40"), and whether
// there are several (welding joined them)
inline std::pair<std::string, bool> input_points_of(std::size_t v, const Repair_report& r)
{
  std::vector<std::size_t> in;
  for(std::size_t i = 0; i < r.kept_vertex.size(); ++i)
    if(r.kept_vertex[i] == v) in.push_back(i);
  std::string s;
  for(std::size_t k = 0; k < in.size(); ++k)
    s += (k == 0 ? "" : (k + 1 == in.size() ? " and " : ", ")) + std::to_string(in[k]);
  return {s, in.size() > 1};
}

// "vertex 12" (the input's index), with the input points welded into it if there are several
inline std::string vertex_words(std::size_t v, const Repair_report& r)
{
  const auto [points, welded] = input_points_of(v, r);
  if(!welded) return "vertex " + std::to_string(r.input_vertex[v]);
  return "vertex " + std::to_string(r.input_vertex[v]) + " (input vertices " + points + ", welded as duplicates)";
}

// the number of groups of faces around `v` that are joined through edges at `v`, orientation ignored:
// more than one is a pinched (non-manifold) vertex, one means only the orientation could not be made
// consistent around it
inline std::size_t fans_around(std::size_t v, const Polygons& polygons)
{
  std::vector<std::size_t> around;
  for(std::size_t p = 0; p < polygons.size(); ++p)
    if(std::find(polygons[p].begin(), polygons[p].end(), v) != polygons[p].end()) around.push_back(p);
  std::vector<std::size_t> up(around.size());
  std::iota(up.begin(), up.end(), 0);
  auto root = [&](std::size_t x) { while(up[x] != x) x = up[x] = up[up[x]]; return x; };
  std::map<std::size_t, std::size_t> by_neighbour;  // a vertex joined to v by an edge -> a face on that edge
  std::size_t fans = around.size();
  for(std::size_t i = 0; i < around.size(); ++i) {
    const std::vector<std::size_t>& poly = polygons[around[i]];
    const std::size_t k = std::size_t(std::find(poly.begin(), poly.end(), v) - poly.begin()), n = poly.size();
    for(std::size_t w : {poly[(k + 1) % n], poly[(k + n - 1) % n]}) {
      auto [it, fresh] = by_neighbour.emplace(w, i);
      if(fresh) continue;
      const std::size_t a = root(i), b = root(it->second);
      if(a != b) { up[a] = b; --fans; }
    }
  }
  return fans;
}

// is `poly` the reverse of `before` (the same cycle of vertices, run the other way)?
inline bool reversed(const std::vector<std::size_t>& poly, const std::vector<std::size_t>& before)
{
  const std::size_t n = before.size(), k = std::size_t(std::find(poly.begin(), poly.end(), before[0]) - poly.begin());
  return k < poly.size() && poly[(k + 1) % n] != before[1];
}

inline void reverse_polygon(std::vector<std::size_t>& poly) { std::reverse(poly.begin() + 1, poly.end()); }

// a non-manifold edge or vertex, or a non-orientable surface, at points welding joined: repair_polygon_soup()
// then tries without welding
struct Broken_by_welding : Invalid_input {
  Broken_by_welding(const std::string& what, std::size_t welded) : Invalid_input(what), points_welded(welded) {}
  std::size_t points_welded;  // the points welding merged
};

inline Repair_report repair_polygon_soup(std::vector<Eigen::Vector3d>& points, std::vector<std::vector<std::size_t>>& polygons,
                                         const Repair_options& options);
} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * repairs a polygon soup (points, and polygons of any size as indices into them) into a triangle soup
 * that `Input_surface` accepts, with CGAL's Polygon Mesh Processing (Botsch et al., *Polygon Mesh
 * Processing*, 2010; the CGAL 5.5 manual, "Polygon Mesh Processing: Combinatorial Repairing" and
 * "Orientation"), and counts what it did. The repairs, each turned on or off by `options`, in this order:
 * 1. **weld**: points at the same position (bit for bit) are merged into the first of them
 *    (`merge_duplicate_points_in_polygon_soup()`), then polygons over the same cycle of vertices, in
 *    either direction, are kept once (`merge_duplicate_polygons_in_polygon_soup()`); a triangle soup
 *    (each face with its own corners, as STL writes) becomes one surface. If welding makes a
 *    non-manifold edge or vertex or a non-orientable surface at welded points, and the soup without
 *    welding is a valid surface (a mesh that touches itself at a point, with a vertex on each side, as
 *    CGAL's `cow.off`), the points are left apart (`Repair_report::points_left_unwelded`);
 * 2. **drop isolated points**: points that belong to no polygon are dropped
 *    (`remove_isolated_points_in_polygon_soup()`);
 * 3. **triangulate**: each polygon of 4 or more vertices is split into triangles (`triangulate_face()`:
 *    a quadrangle along the diagonal that keeps the two triangles' normals closest, a larger planar
 *    polygon by a constrained Delaunay triangulation of its projection along its normal, a larger
 *    non-planar one by hole filling on its 3D outline (`triangulate_hole_polyline()`, Liepa 2003:
 *    minimal dihedral angles, then area); no vertex is added);
 * 4. **orient**: the faces are oriented consistently (`orient_polygon_soup()`); an open surface keeps the
 *    orientation of the majority of its faces, a closed one (one component, free of self-intersections)
 *    is oriented outward (`is_outward_oriented()`, then all faces reversed if not); an input in the
 *    plane z = 0 that is clockwise seen from +z is reversed (`Repair_report::planar_clockwise`: the convention of 2D meshes, though `remesh()` takes either, and
 *    `restore_input_orientation()` turns its output back).
 *
 * What is not a repair is refused, with the index the input gives it (`Invalid_input`): an index out of
 * range, a non-finite coordinate, a polygon of fewer than 3 vertices or with a repeated vertex (welding
 * may make one: the message says so), a polygon that cannot be triangulated (its corners collinear, a
 * planar one that crosses or touches itself, or hole filling fails), and, when orienting, a non-manifold edge or vertex
 * (welding may make one too: the message says which input points it joined) and a non-orientable
 * surface. Several connected components are left for `Input_surface` to refuse.
 *
 * `points` and `polygons` are changed only on success (strong guarantee). The surface's vertices are the
 * kept points, in input order; its triangles follow the input's polygons, in order.
 *
 * \param points the positions (any finite coordinates, in the input's units)
 * \param polygons faces as indices into `points`, 3 or more each; triangles on return (unless
 *        `options.triangulate_polygons` is off)
 * \param options the repairs to make (default: all)
 * \returns what was done, with the maps between input and repaired indices (`Repair_report`)
 * \throws Invalid_input as above
 */
inline Repair_report repair_polygon_soup(std::vector<Eigen::Vector3d>& points, std::vector<std::vector<std::size_t>>& polygons,
                                         const Repair_options& options = Repair_options())
{
  try {
    return internal::repair_polygon_soup(points, polygons, options);  // changes them only on success
  } catch(const internal::Broken_by_welding& welded) {
    // welding made the surface non-manifold: if the points kept apart make a valid surface (a mesh with
    // two vertices at one position, where two parts of the surface touch), the input was right as it was
    Repair_options apart = options;
    apart.weld_duplicates = false;
    try {
      std::vector<Eigen::Vector3d> p = points;
      std::vector<std::vector<std::size_t>> q = polygons;
      Repair_report r = internal::repair_polygon_soup(p, q, apart);
      std::vector<Input_surface::Face> faces;
      for(const auto& t : q) {
        if(t.size() != 3) throw Invalid_input("not a triangle");
        faces.push_back({{t[0], t[1], t[2]}});
      }
      Input_surface check(p, std::move(faces));
      r.points_left_unwelded = welded.points_welded;
      points = std::move(p);
      polygons = std::move(q);
      return r;
    } catch(const Invalid_input&) {
      throw Invalid_input(welded.what());
    }
  }
}

namespace internal {

// the soup being repaired: points in step with `r.kept_vertex` (input point -> working point), polygons
// in step with `from` (working polygon -> input polygon)
struct Working_soup {
  std::vector<Repair_point> pts;
  Polygons polys;
  std::vector<std::size_t> from;
  Repair_report r;

  // working point -> the first input point mapped to it
  void update_input_vertex()
  {
    r.input_vertex.assign(pts.size(), Repair_report::dropped);
    for(std::size_t i = r.kept_vertex.size(); i-- > 0;)
      if(r.kept_vertex[i] != Repair_report::dropped) r.input_vertex[r.kept_vertex[i]] = i;
  }
};

// what no repair fixes and the PMP functions must not see: non-finite points, indices out of range,
// polygons of fewer than 3 vertices or with a repeated one
inline void check_soup(const std::vector<Eigen::Vector3d>& points, const Polygons& polygons)
{
  for(std::size_t i = 0; i < points.size(); ++i)
    if(!points[i].allFinite()) throw Invalid_input("vertex " + std::to_string(i) + " has a non-finite coordinate");
  for(std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& poly = polygons[f];
    if(poly.size() < 3)
      throw Invalid_input("face " + std::to_string(f) + " has " + std::to_string(poly.size()) + " vertices; a face needs 3 or more");
    for(std::size_t v : poly)
      if(v >= points.size())
        throw Invalid_input("face " + std::to_string(f) + " refers to vertex " + std::to_string(v) + ", but there are only " +
                            std::to_string(points.size()) + " vertices");
    if(std::set<std::size_t>(poly.begin(), poly.end()).size() != poly.size())
      throw Invalid_input("face " + std::to_string(f) + " is degenerate (a repeated vertex); remove it");
  }
}

// 1. weld duplicated points, then duplicated polygons (`input`: the polygons as given, for messages)
inline void weld(Working_soup& w, const Polygons& input)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  const std::vector<Repair_point> before = w.pts;
  w.r.points_welded = PMP::merge_duplicate_points_in_polygon_soup(w.pts, w.polys);
  if(w.r.points_welded > 0) {
    // CGAL keeps the first point of each position, in order: find each input point's by position
    std::map<Repair_point, std::size_t, Repair_kernel::Less_xyz_3> at(Repair_kernel().less_xyz_3_object());
    for(std::size_t i = 0; i < w.pts.size(); ++i) at.emplace(w.pts[i], i);
    for(std::size_t i = 0; i < before.size(); ++i) w.r.kept_vertex[i] = at.at(before[i]);
    for(std::size_t p = 0; p < w.polys.size(); ++p)  // polygons are still in input order here
      for(std::size_t k = 0; k < w.polys[p].size(); ++k)
        for(std::size_t j = k + 1; j < w.polys[p].size(); ++j)
          if(w.polys[p][k] == w.polys[p][j])
            throw Invalid_input("face " + std::to_string(p) + " is degenerate after welding: its vertices " +
                                std::to_string(input[p][k]) + " and " + std::to_string(input[p][j]) +
                                " are at the same position; remove the face");
  }
  const Polygons with_duplicates = w.polys;
  w.r.duplicate_polygons_removed = PMP::merge_duplicate_polygons_in_polygon_soup(w.pts, w.polys);
  if(w.r.duplicate_polygons_removed == 0) return;
  // CGAL moves the removed ones to the back: find each kept polygon's index before, keep that order
  std::map<std::vector<std::size_t>, std::vector<std::size_t>> where;  // polygon -> its indices, last first
  for(std::size_t p = with_duplicates.size(); p-- > 0;) where[with_duplicates[p]].push_back(p);
  std::vector<std::pair<std::size_t, std::size_t>> order;  // (index before, index now)
  for(std::size_t q = 0; q < w.polys.size(); ++q) {
    std::vector<std::size_t>& at = where.at(w.polys[q]);
    order.emplace_back(at.back(), q);
    at.pop_back();
  }
  std::sort(order.begin(), order.end());
  Polygons kept;
  std::vector<std::size_t> kept_from;
  for(const auto& [p, q] : order) {
    kept.push_back(std::move(w.polys[q]));
    kept_from.push_back(w.from[p]);
  }
  w.polys = std::move(kept);
  w.from = std::move(kept_from);
}

// 2. drop the points of no polygon (CGAL moves them to the back and keeps the polygons in order: read the
// new index of each point off the polygons)
inline void drop_isolated_points(Working_soup& w)
{
  const Polygons before = w.polys;
  w.r.isolated_points_dropped = CGAL::Polygon_mesh_processing::remove_isolated_points_in_polygon_soup(w.pts, w.polys);
  if(w.r.isolated_points_dropped == 0) return;
  std::vector<std::size_t> now(w.pts.size() + w.r.isolated_points_dropped, Repair_report::dropped);
  for(std::size_t p = 0; p < w.polys.size(); ++p)
    for(std::size_t k = 0; k < w.polys[p].size(); ++k) now[before[p][k]] = w.polys[p][k];
  for(std::size_t& k : w.r.kept_vertex)
    if(k != Repair_report::dropped) k = now[k];
}

// 3. triangulate, one polygon at a time on a one-face Surface_mesh (the soup need not be a mesh yet)
inline void triangulate(Working_soup& w)
{
  Polygons tris;
  std::vector<std::size_t> tri_from;
  CGAL::Surface_mesh<Repair_point> face_mesh;
  for(std::size_t p = 0; p < w.polys.size(); ++p) {
    if(w.polys[p].size() == 3) {
      tris.push_back(w.polys[p]);
      tri_from.push_back(w.from[p]);
      continue;
    }
    face_mesh.clear();
    std::vector<CGAL::Surface_mesh<Repair_point>::Vertex_index> corners;
    for(std::size_t v : w.polys[p]) corners.push_back(face_mesh.add_vertex(w.pts[v]));
    const auto f = face_mesh.add_face(corners);
    // A quadrangle is split along the diagonal that keeps the two triangles' normals closest. A planar
    // polygon of 5 or more corners is triangulated by a constrained Delaunay triangulation of its
    // projection; in CGAL 5.5 that crashes, or returns a broken mesh, when the projection is not a simple
    // polygon, or has two corners at one point (which is_simple_2() lets through): such a polygon is
    // refused first. A non-planar one is triangulated by hole filling (`triangulate_hole_polyline()`, on
    // the 3D polyline): projected along a normal with irrational components, the triangulation's inexact
    // predicates can contradict each other and break its preconditions (both found by random soups, see
    // test_repair.cpp). The result is checked before it is read.
    std::vector<Repair_point> xyz;
    for(std::size_t v : w.polys[p]) xyz.push_back(w.pts[v]);
    bool planar = true, simple = true;
    if(xyz.size() >= 5) {
      std::size_t b = 1, c = 2;
      while(c < xyz.size() && CGAL::collinear(xyz[0], xyz[b], xyz[c])) ++c;
      for(std::size_t k = 1; planar && c < xyz.size() && k < xyz.size(); ++k)
        planar = CGAL::coplanar(xyz[0], xyz[b], xyz[c], xyz[k]);
      const Repair_kernel::Vector_3 normal = CGAL::Polygon_mesh_processing::compute_face_normal(f, face_mesh);
      if(c == xyz.size() || normal == CGAL::NULL_VECTOR) {
        simple = false;  // collinear corners
      } else if(planar) {
        const CGAL::Projection_traits_3<Repair_kernel> projection(normal);
        std::vector<Repair_point> sorted = xyz;
        std::sort(sorted.begin(), sorted.end(), projection.less_xy_2_object());
        for(std::size_t k = 1; simple && k < sorted.size(); ++k)
          simple = !(projection.compare_x_2_object()(sorted[k - 1], sorted[k]) == CGAL::EQUAL &&
                     projection.compare_y_2_object()(sorted[k - 1], sorted[k]) == CGAL::EQUAL);
        simple = simple && CGAL::is_simple_2(xyz.begin(), xyz.end(), projection);
      }
    }
    if(f == face_mesh.null_face() || !simple ||
       !CGAL::Polygon_mesh_processing::triangulate_face(f, face_mesh, CGAL::parameters::use_delaunay_triangulation(planar)) ||
       !CGAL::is_valid_polygon_mesh(face_mesh) || !CGAL::is_triangle_mesh(face_mesh) ||
       face_mesh.number_of_faces() + 2 != w.polys[p].size())
      throw Invalid_input("face " + std::to_string(w.from[p]) + " (" + std::to_string(w.polys[p].size()) +
                          " vertices) cannot be triangulated: its corners are collinear, or it folds over or touches "
                          "itself seen along its normal; split it into simpler polygons");
    for(auto t : face_mesh.faces()) {
      std::vector<std::size_t> tri;
      for(auto v : CGAL::vertices_around_face(face_mesh.halfedge(t), face_mesh)) tri.push_back(w.polys[p][std::size_t(v)]);
      tris.push_back(tri);
      tri_from.push_back(w.from[p]);
      ++w.r.triangles_from_polygons;
    }
    ++w.r.polygons_triangulated;
  }
  w.polys = std::move(tris);
  w.from = std::move(tri_from);
}

// 4a. orient consistently (CGAL keeps the first polygon's orientation in each component); refuse what
// has no consistent orientation, naming it
inline void orient_consistently(Working_soup& w)
{
  const Polygons before = w.polys;
  Orientation_findings found;
  std::vector<Repair_point> oriented_points = w.pts;  // CGAL appends copies of non-manifold points
  CGAL::Polygon_mesh_processing::orient_polygon_soup(oriented_points, w.polys,
                                                     CGAL::parameters::visitor(Orientation_visitor(&found)));
  const Repair_report& r = w.r;
  // a fault at points that welding joined may be welding's doing: Broken_by_welding lets the caller try
  // without welding
  const std::string welded_note = " (after welding duplicated points, which can join surfaces that only touch)";
  auto refuse = [&](const std::string& what, bool welded) {
    if(welded) throw Broken_by_welding(what, r.points_welded);
    throw Invalid_input(what);
  };
  auto welded_at = [&](std::size_t v) { return input_points_of(v, r).second; };
  if(!found.non_manifold_edges.empty()) {
    auto e = found.non_manifold_edges.front();
    if(r.input_vertex[e[1]] < r.input_vertex[e[0]]) std::swap(e[0], e[1]);
    const bool welded = welded_at(e[0]) || welded_at(e[1]);
    refuse("the edge from " + vertex_words(e[0], r) + " to " + vertex_words(e[1], r) + " is non-manifold: " +
             std::to_string(e[2]) + " faces share it" + (welded ? welded_note : "") +
             "; split the mesh along it into surfaces and remesh them one at a time",
           welded);
  }
  for(const auto& v : found.non_manifold_vertices) {
    const std::size_t fans = fans_around(v[0], before);
    if(fans < 2) continue;  // only the orientation is broken there: see below
    const bool welded = welded_at(v[0]);
    refuse(vertex_words(v[0], r) + " is non-manifold: its faces form " + std::to_string(fans) + " separate fans" +
             (welded ? welded_note : "") +
             "; give each fan its own copy of the vertex, or split the mesh there into surfaces and remesh them one at a time",
           welded);
  }
  // an edge still run twice in one direction, or a point CGAL had to copy: no consistent orientation exists
  const std::string not_orientable = "the surface is not orientable (like a Moebius band)";
  const std::string end = std::string(r.points_welded > 0 ? welded_note : "") + "; it cannot be remeshed";
  std::vector<std::array<std::size_t, 3>> directed;  // (from, to, polygon), sorted: a repeat is adjacent
  for(std::size_t p = 0; p < w.polys.size(); ++p)
    for(std::size_t k = 0; k < w.polys[p].size(); ++k) {
      if(w.polys[p][k] >= w.pts.size())
        refuse(not_orientable + ": face " + std::to_string(w.from[p]) + " cannot be oriented consistently with its neighbours" + end,
               r.points_welded > 0);
      directed.push_back({{w.polys[p][k], w.polys[p][(k + 1) % w.polys[p].size()], p}});
    }
  std::sort(directed.begin(), directed.end());
  for(std::size_t i = 1; i < directed.size(); ++i)
    if(directed[i][0] == directed[i - 1][0] && directed[i][1] == directed[i - 1][1])
      refuse(not_orientable + ": face " + std::to_string(w.from[directed[i][2]]) +
               " cannot be oriented consistently with its neighbours (face " + std::to_string(w.from[directed[i - 1][2]]) + ")" + end,
             r.points_welded > 0);
  if(oriented_points.size() != w.pts.size()) refuse(not_orientable + end, r.points_welded > 0);
  // CGAL reverses a polygon end to end: start each from its first vertex before again; an open surface
  // keeps the orientation of most of its faces
  std::size_t flipped = 0;
  for(std::size_t p = 0; p < w.polys.size(); ++p) flipped += reversed(w.polys[p], before[p]);
  const bool majority_flipped = 2 * flipped > w.polys.size();
  for(std::size_t p = 0; p < w.polys.size(); ++p) {
    const bool flip = reversed(w.polys[p], before[p]) != majority_flipped;
    w.polys[p] = before[p];
    if(flip) reverse_polygon(w.polys[p]);
  }
}

// 4b. a closed surface points outward (CGAL's test wants one valid closed triangle mesh without
// self-intersections: a soup that is not one is left for the caller's validation to name its fault, and
// several components are refused there)
inline void orient_outward_if_closed(Working_soup& w)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  typedef CGAL::Surface_mesh<Repair_point> Mesh;
  if(!std::all_of(w.polys.begin(), w.polys.end(), [](const std::vector<std::size_t>& p) { return p.size() == 3; })) return;
  // orient_consistently() has refused what is not a polygon mesh (an edge run twice one way, a
  // non-manifold edge or vertex), so is_polygon_soup_a_polygon_mesh() (0.7 s for 250k points) is not
  // needed; the mesh built is checked instead
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(w.pts, w.polys, mesh);
  if(mesh.is_empty() || !CGAL::is_closed(mesh) || !CGAL::is_valid_polygon_mesh(mesh)) return;
  Mesh::Property_map<Mesh::Face_index, std::size_t> component = mesh.add_property_map<Mesh::Face_index, std::size_t>("f:c", 0).first;
  if(PMP::connected_components(mesh, component) != 1) return;
  // the orientation of the faces at the topmost vertex, which is that of the whole consistently oriented
  // component (O(n); orient_to_bound_a_volume() would also sort nested components, which cannot occur here)
  try {
    if(PMP::is_outward_oriented(mesh)) return;
  } catch(const CGAL::Failure_exception&) {
    // with CGAL's checks on (no NDEBUG): faces folded flat onto each other at the top vertex, a surface
    // that bounds no volume (its degenerate faces are refused by the validation); it is left as it is
    return;
  }
  for(auto& poly : w.polys) reverse_polygon(poly);
  w.r.reversed_to_outward = true;
}

// 4c. the plane z = 0, clockwise seen from +z (the signed area of the whole surface): counter-clockwise
inline void counter_clockwise_if_planar(Working_soup& w)
{
  if(!std::all_of(w.pts.begin(), w.pts.end(), [](const Repair_point& p) { return p.z() == 0; })) return;
  double area = 0;
  for(const auto& poly : w.polys)
    for(std::size_t k = 0; k < poly.size(); ++k) {
      const Repair_point &a = w.pts[poly[k]], &b = w.pts[poly[(k + 1) % poly.size()]];
      area += a.x() * b.y() - a.y() * b.x();
    }
  if(area >= 0) return;
  for(auto& poly : w.polys) reverse_polygon(poly);
  w.r.planar_clockwise = true;
}

inline Repair_report repair_polygon_soup(std::vector<Eigen::Vector3d>& points, std::vector<std::vector<std::size_t>>& polygons,
                                         const Repair_options& options)
{
  check_soup(points, polygons);
  Working_soup w;  // a copy: `points` and `polygons` are written only on success
  w.r.input_points = points.size();
  w.r.input_polygons = polygons.size();
  w.pts.reserve(points.size());
  for(const Eigen::Vector3d& p : points) w.pts.emplace_back(p.x(), p.y(), p.z());
  w.polys = polygons;
  w.r.kept_vertex.resize(points.size());
  std::iota(w.r.kept_vertex.begin(), w.r.kept_vertex.end(), std::size_t(0));
  w.from.resize(polygons.size());
  std::iota(w.from.begin(), w.from.end(), std::size_t(0));
  if(options.weld_duplicates) weld(w, polygons);
  if(options.drop_isolated_points) drop_isolated_points(w);
  w.update_input_vertex();
  if(options.triangulate_polygons) triangulate(w);
  if(options.orient) {
    const Polygons before = w.polys;
    orient_consistently(w);
    orient_outward_if_closed(w);
    for(std::size_t p = 0; p < w.polys.size(); ++p) w.r.faces_reoriented += reversed(w.polys[p], before[p]);
    counter_clockwise_if_planar(w);
  }
  std::vector<Eigen::Vector3d> repaired;
  repaired.reserve(w.pts.size());
  for(const Repair_point& p : w.pts) repaired.emplace_back(p.x(), p.y(), p.z());
  points = std::move(repaired);
  polygons = std::move(w.polys);
  w.r.input_face = std::move(w.from);
  return std::move(w.r);
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * repairs a polygon soup (`repair_polygon_soup()` with `options`) and builds the `Input_surface` of the
 * result, whose messages name vertices and faces by their index in the soup as given.
 * \param points, polygons the soup as given (see `repair_polygon_soup()`)
 * \param report receives what was repaired, with the index maps (written only on success)
 * \param options the repairs to make (default: all; `Repair_options::none()`: validation only)
 * \throws Invalid_input as `repair_polygon_soup()` and `Input_surface` do; a polygon left untriangulated
 *         (`triangulate_polygons` off) is refused
 */
inline Input_surface input_surface_from_polygon_soup(std::vector<Eigen::Vector3d> points,
                                                     std::vector<std::vector<std::size_t>> polygons, Repair_report& report,
                                                     const Repair_options& options = Repair_options())
{
  Repair_report r = repair_polygon_soup(points, polygons, options);
  std::vector<Input_surface::Face> faces;
  faces.reserve(polygons.size());
  for(std::size_t f = 0; f < polygons.size(); ++f) {
    if(polygons[f].size() != 3)
      throw Invalid_input("face " + std::to_string(r.input_face[f]) + " has " + std::to_string(polygons[f].size()) +
                          " vertices; only triangle meshes are supported: triangulate the polygons");
    faces.push_back({{polygons[f][0], polygons[f][1], polygons[f][2]}});
  }
  Input_surface s(std::move(points), std::move(faces), r.input_vertex, r.input_face);
  report = std::move(r);
  return s;
}

/*!
 * \ingroup PkgAnisoConformalIO
 * gives a remeshed surface the orientation of the input it was repaired from: if `report.planar_clockwise`
 * (a clockwise planar input, remeshed counter-clockwise), reverses every triangle of `faces` (the output
 * of `remesh()`, `Remeshed_surface::faces`); otherwise leaves them as they are.
 */
inline void restore_input_orientation(std::vector<std::array<std::size_t, 3>>& faces, const Repair_report& report)
{
  if(!report.planar_clockwise) return;
  for(auto& t : faces) std::swap(t[1], t[2]);
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_REPAIR_POLYGON_SOUP_H
