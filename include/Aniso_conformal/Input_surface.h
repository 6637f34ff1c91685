// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INPUT_SURFACE_H
#define ANISO_CONFORMAL_INPUT_SURFACE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Surface_point.h>
#include <Aniso_conformal/internal/directed_edges.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

/// \file Input_surface.h

namespace Aniso_conformal {

namespace internal {
// BGL's faces(g) through ADL, out of reach of Input_surface::faces()
template <typename Graph>
auto bgl_faces(const Graph& g) -> decltype(faces(g))
{
  return faces(g);
}
} // namespace internal

/*!
 * \ingroup PkgAnisoConformalMain
 * an indexed, validated, read-only copy of the input triangle mesh: positions, faces, topology
 * (Euler characteristic, boundary loops, genus), vertex normals and closest-point projection.
 *
 * Every stage works on this copy, so the user's mesh is never modified. Construction checks the
 * input and throws `Invalid_input` with a message naming the offending vertex or face and what to do
 * for: an empty mesh, a non-triangular face, a non-finite coordinate, an index out of range, a
 * degenerate face, a non-manifold edge or vertex, inconsistent orientation, an isolated vertex, several
 * connected components. Construction repairs nothing: `IO::repair_polygon_soup()` does, before it
 * (`IO::input_surface_from_polygon_soup()`, `IO::read_triangle_mesh(path, report)`).
 */
class Input_surface {
public:
  /// index triple of a triangle
  typedef std::array<std::size_t, 3> Face;

  /// \name Creation
  /// @{


  /// builds the surface from a polygon soup of triangles (vertex positions, faces as index triples)
  Input_surface(std::vector<Eigen::Vector3d> points, std::vector<Face> faces)
    : m_points(std::move(points)), m_faces(std::move(faces))
  {
    validate_and_build();
  }

  /*!
   * builds the surface as the constructor above does, from triangles repaired from an input
   * (`IO::repair_polygon_soup()`): its messages name vertex `i` by `input_vertex[i]` and face `f` by
   * `input_face[f]`, the indices the user finds in the input file. An empty map leaves those indices as
   * they are.
   * \throws Invalid_input as the constructor above, and if a map is neither empty nor of the size of
   *         `points` (`input_vertex`) or `faces` (`input_face`)
   */
  Input_surface(std::vector<Eigen::Vector3d> points, std::vector<Face> faces, std::vector<std::size_t> input_vertex,
                std::vector<std::size_t> input_face)
    : m_points(std::move(points)), m_faces(std::move(faces)), m_input_vertex(std::move(input_vertex)),
      m_input_face(std::move(input_face))
  {
    if(!m_input_vertex.empty() && m_input_vertex.size() != m_points.size())
      throw Invalid_input("Input_surface: " + std::to_string(m_input_vertex.size()) + " input vertex indices for " +
                          std::to_string(m_points.size()) + " vertices");
    if(!m_input_face.empty() && m_input_face.size() != m_faces.size())
      throw Invalid_input("Input_surface: " + std::to_string(m_input_face.size()) + " input face indices for " +
                          std::to_string(m_faces.size()) + " faces");
    validate_and_build();
  }

  /*!
   * builds the surface from a model of `FaceListGraph` (e.g.\ `CGAL::Surface_mesh`, `CGAL::Polyhedron_3`).
   * Vertex `i` of the copy is the vertex whose index is `i` in the vertex index map.
   * \cgalNamedParamsBegin
   *   \cgalParamNBegin{vertex_point_map} the positions; default: the internal `CGAL::vertex_point_t` map \cgalParamNEnd
   *   \cgalParamNBegin{vertex_index_map} indices in `[0, num_vertices(tm))`; default: `get_initialized_vertex_index_map(tm)` \cgalParamNEnd
   * \cgalNamedParamsEnd
   */
  template <typename TriangleMesh, typename NamedParameters = CGAL::parameters::Default_named_parameters>
  static Input_surface from_mesh(const TriangleMesh& tm,
                                 const NamedParameters& np = CGAL::parameters::default_values())
  {
    using CGAL::parameters::choose_parameter;
    using CGAL::parameters::get_parameter;
    auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                get_const_property_map(CGAL::vertex_point, tm));
    auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    std::vector<Eigen::Vector3d> pts(num_vertices(tm));
    for(auto v : vertices(tm)) {
      const auto& p = get(vpm, v);
      pts[get(vim, v)] = Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }
    std::vector<Face> fs;
    fs.reserve(num_faces(tm));
    std::size_t fi = 0;
    for(auto f : internal::bgl_faces(tm)) {
      Face t;
      std::size_t k = 0;
      for(auto v : CGAL::vertices_around_face(halfedge(f, tm), tm)) {
        if(k < 3) t[k] = get(vim, v);
        ++k;
      }
      if(k != 3)
        throw Invalid_input("face " + std::to_string(fi) + " has " + std::to_string(k) +
                            " vertices; remesh() takes a triangle mesh: triangulate it first (on a copy: "
                            "CGAL::Polygon_mesh_processing::triangulate_faces() keeps the vertices and their indices, so "
                            "a metric indexed by vertex still lines up)");
      fs.push_back(t);
      ++fi;
    }
    return Input_surface(std::move(pts), std::move(fs));
  }
  /// @}

  /// \name Access
  /// @{
  std::size_t number_of_vertices() const { return m_points.size(); }                 ///< vertex count
  std::size_t number_of_faces() const { return m_faces.size(); }                     ///< face count
  const std::vector<Eigen::Vector3d>& points() const { return m_points; }           ///< vertex positions
  const std::vector<Face>& faces() const { return m_faces; }                        ///< triangles (consistently oriented)
  const std::vector<Eigen::Vector3d>& vertex_normals() const { return m_normals; }  ///< unit area-weighted normals
  int euler_characteristic() const { return m_euler; }                              ///< V - E + F
  /// boundary loops, each a cycle of vertex indices in the orientation of the faces
  const std::vector<std::vector<std::size_t>>& boundary_loops() const { return m_loops; }
  /// genus `(2 - chi - b) / 2`
  int genus() const { return (2 - m_euler - int(m_loops.size())) / 2; }
  /// the index of vertex `v` in the input this surface was read and repaired from (`v` itself when it was
  /// built without that map): for messages that name vertices as the user's file does
  std::size_t input_vertex_index(std::size_t v) const { return v < m_input_vertex.size() ? m_input_vertex[v] : v; }
  /// `true` if the surface is a topological disk (one boundary loop, genus 0)
  bool is_disk() const { return m_loops.size() == 1 && genus() == 0; }
  /// `true` if the surface lies in the plane z = 0
  bool is_planar() const { return m_planar; }
  /// length of the diagonal of the bounding box
  double bounding_box_diagonal() const { return m_diag; }
  /// describes the topology in words, for messages ("a disk", "a closed surface of genus 1", ...)
  std::string topology_description() const
  {
    if(m_loops.empty()) return "a closed surface of genus " + std::to_string(genus());
    if(is_disk()) return "a topological disk";
    return "a surface of genus " + std::to_string(genus()) + " with " + std::to_string(m_loops.size()) +
           " boundary loops";
  }
  /// @}

  /// \name Queries
  /// @{

  /// the point of face `f` with barycentric coordinates `b`
  Surface_point point_in_face(std::size_t f, const Eigen::Vector3d& b) const
  {
    Surface_point sp;
    sp.vertices = m_faces[f];
    sp.barycentric = b;
    sp.position = b[0] * m_points[m_faces[f][0]] + b[1] * m_points[m_faces[f][1]] + b[2] * m_points[m_faces[f][2]];
    return sp;
  }

  /// the vertex normals of the face of `sp` interpolated at its barycentric coordinates (not normalised; length
  /// at most 1): the side of the surface a point is on, for tests that a move or a flip does not cross to
  /// another sheet of a thin part
  Eigen::Vector3d interpolated_normal(const Surface_point& sp) const
  {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for(int j = 0; j < 3; ++j) n += sp.barycentric[j] * m_normals[sp.vertices[std::size_t(j)]];
    return n;
  }

  /// the point of the surface closest to `p` (an AABB tree is built on first use)
  Surface_point project(const Eigen::Vector3d& p) const
  {
    if(!m_tree) build_tree();
    return surface_point(m_tree->closest_point_and_primitive(K::Point_3(p.x(), p.y(), p.z())));
  }

  /// the point of the surface closest to `p`, as `project(p)`, searched from `near`, a point of this
  /// surface near `p` (where a vertex was before a small move): its distance to `p` bounds the search
  /// of the AABB tree from the start, which then visits few nodes. Same result as `project(p)` unless
  /// several points of the surface are closest (then any one of them).
  Surface_point project(const Eigen::Vector3d& p, const Surface_point& near) const
  {
    if(!m_tree) build_tree();
    // the input vertex of `near` with the largest coordinate, and a face around it, as CGAL's hint
    int k = 0;
    for(int j = 1; j < 3; ++j)
      if(near.barycentric[j] > near.barycentric[k]) k = j;
    const std::size_t v = near.vertices[std::size_t(k)];
    if(v >= m_vertex_face.size() || m_vertex_face[v] >= m_faces.size()) return project(p);
    const Eigen::Vector3d& h = m_points[v];
    return surface_point(m_tree->closest_point_and_primitive(
        K::Point_3(p.x(), p.y(), p.z()), std::make_pair(K::Point_3(h.x(), h.y(), h.z()), m_triangles.cbegin() + std::ptrdiff_t(m_vertex_face[v]))));
  }

  /// barycentric coordinates of `q` (assumed in the plane of face `f`), clamped to the triangle
  Eigen::Vector3d barycentric(std::size_t f, const Eigen::Vector3d& q) const
  {
    const Eigen::Vector3d& a = m_points[m_faces[f][0]];
    Eigen::Vector3d e1 = m_points[m_faces[f][1]] - a, e2 = m_points[m_faces[f][2]] - a, w = q - a;
    double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), w1 = w.dot(e1), w2 = w.dot(e2);
    double det = d11 * d22 - d12 * d12;
    if(det > 1e-12 * d11 * d22) {
      double b1 = (d22 * w1 - d12 * w2) / det, b2 = (d11 * w2 - d12 * w1) / det;
      Eigen::Vector3d b(1 - b1 - b2, b1, b2);
      b = b.cwiseMax(0.0);
      if(b.sum() > 0 && b.allFinite()) return b / b.sum();
    }
    // a (nearly) degenerate triangle has no reliable plane: the closest point on its edges, whose
    // coordinates are well defined (a surface flattened to rounding level must not yield NaN)
    Eigen::Vector3d best(1, 0, 0);
    double best_d = (q - a).squaredNorm();
    for(int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p0 = m_points[m_faces[f][k]];
      const Eigen::Vector3d e = m_points[m_faces[f][(k + 1) % 3]] - p0;
      const double ee = e.squaredNorm();
      const double t = ee > 0 ? std::clamp((q - p0).dot(e) / ee, 0.0, 1.0) : 0.0;
      const double d = (p0 + t * e - q).squaredNorm();
      if(d < best_d) {
        best_d = d;
        best.setZero();
        best[k] = 1 - t;
        best[(k + 1) % 3] = t;
      }
    }
    return best;
  }
  /// @}

private:
  typedef CGAL::Simple_cartesian<double> K;
  typedef std::vector<K::Triangle_3>::const_iterator Tri_iterator;
  typedef CGAL::AABB_triangle_primitive<K, Tri_iterator> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> Tree;

  // the surface point of a closest point and triangle found by the AABB tree
  template <typename Point_and_primitive>
  Surface_point surface_point(const Point_and_primitive& res) const
  {
    const std::size_t f = std::size_t(res.second - m_triangles.begin());
    return point_in_face(f, barycentric(f, Eigen::Vector3d(res.first.x(), res.first.y(), res.first.z())));
  }

  void build_tree() const
  {
    m_triangles.clear();
    m_vertex_face.assign(m_points.size(), std::size_t(-1));
    for(std::size_t f = 0; f < m_faces.size(); ++f)
      for(std::size_t v : m_faces[f]) m_vertex_face[v] = f;
    for(const Face& f : m_faces) {
      auto P = [&](std::size_t i) { return K::Point_3(m_points[i].x(), m_points[i].y(), m_points[i].z()); };
      m_triangles.emplace_back(P(f[0]), P(f[1]), P(f[2]));
    }
    m_tree = std::make_shared<Tree>(m_triangles.begin(), m_triangles.end());
    m_tree->accelerate_distance_queries();
  }

  // vertex `v` and face `f` as the user knows them: their index in the input they were repaired from
  std::string vertex_name(std::size_t v) const
  {
    return std::to_string(v < m_input_vertex.size() ? m_input_vertex[v] : v);
  }
  std::string face_name(std::size_t f) const { return std::to_string(f < m_input_face.size() ? m_input_face[f] : f); }
  std::string edge_name(std::size_t a, std::size_t b) const { return "(" + vertex_name(a) + ", " + vertex_name(b) + ")"; }

  typedef internal::Directed_edges<std::size_t> Directed_edges;

  void validate_and_build()
  {
    const Directed_edges directed = check_faces();
    find_boundary_loops(directed);
    check_vertex_manifoldness(directed);
    check_connected();
    m_normals.assign(m_points.size(), Eigen::Vector3d::Zero());
    for(const Face& t : m_faces) {
      Eigen::Vector3d n = (m_points[t[1]] - m_points[t[0]]).cross(m_points[t[2]] - m_points[t[0]]);
      for(int k = 0; k < 3; ++k) m_normals[t[k]] += n;
    }
    for(auto& n : m_normals) n.normalize();
  }

  // the fault of face `f` itself (an index out of range, a repeated vertex, zero area), or ""
  std::string face_fault(std::size_t f) const
  {
    const Face& t = m_faces[f];
    const std::size_t nv = m_points.size();
    for(int k = 0; k < 3; ++k)
      if(t[k] >= nv)
        return "face " + face_name(f) + " refers to vertex " + std::to_string(t[k]) + ", but there are only " +
               std::to_string(nv) + " vertices";
    if(t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return "face " + face_name(f) + " is degenerate (a repeated vertex); remove it";
    const double area2 = (m_points[t[1]] - m_points[t[0]]).cross(m_points[t[2]] - m_points[t[0]]).norm();
    if(!(area2 > 1e-14 * m_diag * m_diag))
      return "face " + face_name(f) + " is degenerate (zero area); remove it, or move its corners apart";
    return std::string();
  }

  // coordinates, indices, degenerate faces, orientation, non-manifold edges, isolated vertices; returns
  // the directed edges. The first fault in face order is reported (a face's own before its edges'), as a
  // scan of the faces one by one would meet it; linear time but for the sort of each vertex's few edges.
  Directed_edges check_faces()
  {
    const std::size_t nv = m_points.size(), nf = m_faces.size();
    if(nv == 0 || m_faces.empty()) throw Invalid_input("the input mesh is empty");
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for(std::size_t i = 0; i < nv; ++i) {
      if(!m_points[i].allFinite()) throw Invalid_input("vertex " + vertex_name(i) + " has a non-finite coordinate");
      lo = lo.cwiseMin(m_points[i]);
      hi = hi.cwiseMax(m_points[i]);
    }
    m_diag = (hi - lo).norm();
    m_planar = (lo.z() == 0 && hi.z() == 0);
    std::size_t first_bad = nf;  // the first face with a fault of its own
    std::string bad_message;
    for(std::size_t f = 0; f < nf && first_bad == nf; ++f) {
      bad_message = face_fault(f);
      if(!bad_message.empty()) first_bad = f;
    }
    // the directed edges of the faces before it: a repeated (tail, head) sits with its faces in face order
    const Directed_edges d(nv, m_faces, first_bad);
    // the earliest repeated direction in face order: the (face, corner) where a scan would meet it again
    std::size_t rep_face = nf, rep_corner = 3, rep_first = 0, rep_tail = 0, rep_head = 0;
    for(std::size_t v = 0; v < nv; ++v)
      for(std::size_t i = d.start[v] + 1; i < d.start[v + 1]; ++i) {
        if(d.head[i] != d.head[i - 1] || (i >= d.start[v] + 2 && d.head[i - 2] == d.head[i])) continue;
        const Face& t = m_faces[d.face[i]];
        const std::size_t corner = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
        if(std::make_pair(d.face[i], corner) < std::make_pair(rep_face, rep_corner)) {
          rep_face = d.face[i];
          rep_corner = corner;
          rep_first = d.face[i - 1];
          rep_tail = v;
          rep_head = d.head[i];
        }
      }
    if(rep_face < nf) {
      // an edge in three or more faces necessarily repeats a direction: when the opposite direction was met
      // before, the edge is non-manifold, otherwise two faces disagree on its orientation
      bool reverse_before = false;
      for(std::size_t i = d.start[rep_head]; i < d.start[rep_head + 1]; ++i)
        reverse_before = reverse_before || (d.head[i] == rep_tail && d.face[i] < rep_face);
      if(reverse_before)
        throw Invalid_input("edge " + edge_name(rep_tail, rep_head) +
                            " is non-manifold (shared by more than two faces); split the mesh along it into surfaces "
                            "and remesh them one at a time");
      throw Invalid_input("faces " + face_name(rep_first) + " and " + face_name(rep_face) +
                          " have inconsistent orientation along edge " + edge_name(rep_tail, rep_head) +
                          "; orient the faces consistently");
    }
    if(first_bad < nf) throw Invalid_input(bad_message);
    for(std::size_t v = 0; v < nv; ++v)
      if(d.start[v] == d.start[v + 1]) throw Invalid_input("vertex " + vertex_name(v) + " belongs to no face; remove it");
    // undirected edges: the directed ones less one per pair of opposite directions
    std::size_t pairs = 0;
    for(std::size_t v = 0; v < nv; ++v)
      for(std::size_t i = d.start[v]; i < d.start[v + 1]; ++i)
        pairs += (v < d.head[i] && d.find(d.head[i], v) != Directed_edges::none);
    m_euler = int(nv) - int(d.head.size() - pairs) + int(nf);
    return d;
  }

  // the boundary loops, each in the orientation of its faces, started at their smallest vertex in turn; a
  // vertex on the boundary twice is non-manifold
  void find_boundary_loops(const Directed_edges& d)
  {
    const std::size_t nv = m_points.size(), none = Directed_edges::none;
    // boundary halfedge tail -> its first head (boundary edges run opposite to the face orientation on the
    // outside; keep the face direction)
    std::vector<std::size_t> next(nv, none), count(nv, 0);
    for(std::size_t v = 0; v < nv; ++v)
      for(std::size_t i = d.start[v]; i < d.start[v + 1]; ++i)
        if(d.find(d.head[i], v) == none) {
          if(count[v]++ == 0) next[v] = d.head[i];
        }
    for(std::size_t v = 0; v < nv; ++v)
      if(count[v] > 1)
        throw Invalid_input("vertex " + vertex_name(v) + " is non-manifold (it touches the boundary " +
                            std::to_string(count[v]) + " times): " + split_vertex_advice);
    std::vector<char> visited(nv, 0);
    for(std::size_t b = 0; b < nv; ++b) {
      if(next[b] == none || visited[b]) continue;
      std::vector<std::size_t> loop;
      std::size_t v = b;
      while(!visited[v]) {
        visited[v] = 1;
        loop.push_back(v);
        if(next[v] == none) break;
        v = next[v];
      }
      m_loops.push_back(loop);
    }
  }

  // vertex manifoldness: the faces around each vertex must form a single fan; two faces at v are
  // neighbours when the vertex before v in one is the vertex after v in the other (the directed edges out
  // of v, sorted by head, give each face by the vertex after v)
  void check_vertex_manifoldness(const Directed_edges& d)
  {
    const std::size_t nv = m_points.size();
    std::vector<std::size_t> up;
    for(std::size_t v = 0; v < nv; ++v) {
      const std::size_t b = d.start[v], n = d.start[v + 1] - b;
      up.resize(n);
      std::iota(up.begin(), up.end(), 0);
      auto root = [&](std::size_t x) { while(up[x] != x) x = up[x] = up[up[x]]; return x; };
      std::size_t fans = n;
      for(std::size_t i = 0; i < n; ++i) {
        const Face& t = m_faces[d.face[b + i]];
        const std::size_t before = t[0] == v ? t[2] : (t[1] == v ? t[0] : t[1]);
        const std::size_t j = d.find(v, before);
        if(j == Directed_edges::none) continue;
        std::size_t x = root(i), y = root(j - b);
        if(x != y) { up[x] = y; --fans; }
      }
      if(fans != 1)
        throw Invalid_input("vertex " + vertex_name(v) + " is non-manifold (its faces form " + std::to_string(fans) +
                            " separate fans): " + split_vertex_advice);
    }
  }

  // one connected component (union-find over the faces' vertices)
  void check_connected()
  {
    const std::size_t nv = m_points.size();
    std::vector<std::size_t> parent(nv);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](std::size_t x) {
      while(parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for(const Face& t : m_faces) {
      parent[find(t[1])] = find(t[0]);
      parent[find(t[2])] = find(t[0]);
    }
    std::size_t components = 0;
    for(std::size_t i = 0; i < nv; ++i)
      if(find(i) == i) ++components;
    if(components == 1) return;
    // a triangle soup (each face with its own corners, as STL writes) is one component per face: say so
    std::map<std::array<double, 3>, std::size_t> at;
    std::size_t shared = 0;
    for(const Eigen::Vector3d& p : m_points) shared += ++at[{p.x(), p.y(), p.z()}] > 1;
    throw Invalid_input("the input mesh has " + std::to_string(components) +
                        " connected components; remesh them one at a time (split it into its components)" +
                        (shared == 0 ? std::string()
                                     : "; " + std::to_string(shared) + " of its vertices are at the position of another vertex: "
                                       "if the components are one surface whose faces do not share their vertices, weld them"));
  }

  static constexpr const char* split_vertex_advice =
    "give each fan of faces its own copy of the vertex, or split the mesh there into surfaces and remesh them one at a time";

  std::vector<Eigen::Vector3d> m_points;
  std::vector<Face> m_faces;
  std::vector<std::size_t> m_input_vertex, m_input_face;  // for messages only: the indices in the input
  std::vector<Eigen::Vector3d> m_normals;
  std::vector<std::vector<std::size_t>> m_loops;
  int m_euler = 0;
  double m_diag = 0;
  bool m_planar = false;
  mutable std::vector<K::Triangle_3> m_triangles;
  mutable std::shared_ptr<Tree> m_tree;
  mutable std::vector<std::size_t> m_vertex_face;  // per vertex, a face around it (with the tree)
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INPUT_SURFACE_H
