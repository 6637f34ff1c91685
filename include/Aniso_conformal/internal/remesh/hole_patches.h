// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_REMESH_HOLE_PATCHES_H
#define ANISO_CONFORMAL_INTERNAL_REMESH_HOLE_PATCHES_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Surface_point.h>
#include <Aniso_conformal/extract_dual_mesh.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/conformal/newton_solver.h>
#include <Aniso_conformal/internal/features/edge_recovery_by_flips.h>
#include <Aniso_conformal/internal/intrinsic/midpoint_split.h>
#include <Aniso_conformal/internal/tensor.h>
#include <Aniso_conformal/parameters.h>
#include <Aniso_conformal/refine_background.h>

#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseLU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <deque>
#include <iterator>
#include <map>
#include <queue>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

// Surfaces with boundary loops in the closed domains (issue 15, item 3). Each hole is closed by a virtual
// patch, a cone from a new apex vertex to the loop (or, where that cone would fold over itself, a fill
// by Liepa's method, close_holes()), so that the surface becomes closed of the same genus
// and goes to the sphere, the flat torus or the hyperbolic disk as a closed surface does; the input is
// never modified. In the background (Intrinsic_triangulation) the patch's faces carry no CVT density and
// each loop is a seam whose edges are never flipped; sites are fixed along every seam at about equal
// metric arc length (their number from the loop's metric length and the output edge length, as the
// plane places the boundary sites of a disk), at background vertices on the seam, so that they map back
// exactly onto the input loop (loop_sites.h). The dual triangles on the patch side of each loop's chain of sites are
// removed, and what is left is checked: every loop's consecutive sites joined by an output edge (where the
// dual did not join two, the edge is recovered by flips first, recover_loop_edges()), no site
// inside a patch (then the genus and the number of loops are checked with the rest of the output).

namespace Aniso_conformal {
namespace internal {

// A vertex of a patch: the point at `t` from the loop's input vertex `at` (t = 0) to the apex (t = 1)
struct Patch_vertex {
  std::size_t loop = 0;
  std::size_t at = 0;
  double t = 1;
};

// The input with its holes closed: `closed` has the input's vertices first (same indices), then each
// patch's vertices; the input's faces first, then the patches' faces.
struct Hole_patches {
  Input_surface closed;
  std::size_t input_vertices = 0;
  std::size_t input_faces = 0;
  std::vector<std::vector<std::size_t>> loops;  // the input's boundary loops, in the orientation of its faces
  std::vector<std::size_t> apex;                // per loop, its patch's apex in `closed`
  std::vector<Patch_vertex> patch_vertices;     // the vertices of `closed` from input_vertices on
};

// `true` if the cone of close_holes() over `loop` (points `pts`, centroid `c`, Newell vector `newell`)
// folds over itself: some fan triangle (centroid, loop[i], loop[i + 1]), seen along `newell`, turns the
// other way round the centroid than the loop as a whole, i.e. the loop is not star-shaped about its
// centroid in its mean plane. Such a cone closes the hole with a crumpled surface: the fan triangles of
// the folds add their angles at the apex and at the loop vertices where they should cancel (CGAL's
// lion.off: apex angle sum 647 degrees, loop vertices with 2 pi minus their angle sum from -163 to +284
// degrees, against at most 74 on the scans that embed), and the flat metric has singularities of that
// strength on the seam, whose edges cannot flip: its triangles there go flat whatever their size.
inline bool cone_folds(const std::vector<Eigen::Vector3d>& pts, const std::vector<std::size_t>& loop, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& newell)
{
  const Eigen::Vector3d n = newell.normalized();
  for(std::size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector3d a = pts[loop[i]] - c, b = pts[loop[(i + 1) % loop.size()]] - c;
    if(a.cross(b).dot(n) < -1e-12 * a.norm() * b.norm()) return true;  // a radial edge (0 up to rounding) is no fold
  }
  return false;
}

// A hole of `s` filled by Liepa's method (Liepa 2003, "Filling holes in meshes"; CGAL's
// triangulate_refine_and_fair_hole(): a triangulation of the loop minimising the worst dihedral angle,
// then area, among triangles that add no edge the surface has already; refined to the density of the
// loop's edges; its new vertices moved to minimise the bi-Laplacian energy (cotangent weights, sparse
// LU), which continues the surface smoothly across the loop). `loop` is the hole's loop in the
// orientation of the faces. On success `points` receives the new vertices (their indices in the closed
// surface `first + k`), `faces` the patch's triangles (indices: the input's below `s.number_of_vertices()`,
// `first + k` for new vertex k), oriented as the surface; returns false, leaving both empty, if CGAL
// finds no triangulation or the fill has no vertex inside (close_holes() then uses the cone). If the
// fairing's linear solve fails, the refined triangulation is kept unfaired (flat triangles spanning the loop).
inline bool fill_hole_by_fairing(const Input_surface& s, const std::vector<std::size_t>& loop, std::size_t first,
                                 std::vector<Eigen::Vector3d>& points, std::vector<Input_surface::Face>& faces)
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef CGAL::Surface_mesh<K::Point_3> Mesh;
  typedef CGAL::Eigen_solver_traits<Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType, Eigen::COLAMDOrdering<int>>> Solver;
  points.clear();
  faces.clear();
  Mesh m;
  for(const Eigen::Vector3d& p : s.points()) m.add_vertex(K::Point_3(p.x(), p.y(), p.z()));
  for(const auto& f : s.faces())
    if(m.add_face(Mesh::Vertex_index(Mesh::size_type(f[0])), Mesh::Vertex_index(Mesh::size_type(f[1])),
                  Mesh::Vertex_index(Mesh::size_type(f[2]))) == Mesh::null_face())
      return false;
  // the loop edge loop[0] -> loop[1] is a halfedge of a face: its opposite is on the hole's border
  const auto h = CGAL::halfedge(Mesh::Vertex_index(Mesh::size_type(loop[0])), Mesh::Vertex_index(Mesh::size_type(loop[1])), m);
  if(!h.second || !m.is_border(m.opposite(h.first))) return false;
  std::vector<Mesh::Face_index> new_faces;
  std::vector<Mesh::Vertex_index> new_vertices;
  CGAL::Polygon_mesh_processing::triangulate_refine_and_fair_hole(m, m.opposite(h.first), std::back_inserter(new_faces),
                                                                  std::back_inserter(new_vertices),
                                                                  CGAL::parameters::sparse_linear_solver(Solver()));
  if(new_faces.empty() || new_vertices.empty()) return false;
  const std::size_t nv = s.number_of_vertices();
  std::map<std::size_t, std::size_t> index;  // vertex of m -> vertex of the closed surface
  for(Mesh::Vertex_index v : new_vertices) {
    index[std::size_t(v)] = first + points.size();
    const K::Point_3& q = m.point(v);
    points.push_back(Eigen::Vector3d(q.x(), q.y(), q.z()));
  }
  for(Mesh::Face_index f : new_faces) {
    Input_surface::Face face;
    std::size_t k = 0;
    for(Mesh::Vertex_index v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      if(k == 3) return points.clear(), faces.clear(), false;
      const std::size_t w = std::size_t(v);
      if(w < nv) face[k++] = w;
      else if(index.count(w)) face[k++] = index[w];
      else return points.clear(), faces.clear(), false;
    }
    if(k != 3) return points.clear(), faces.clear(), false;
    faces.push_back(face);
  }
  return true;
}

// Closes each boundary loop of `s` with a virtual patch, so that the closed surface has the input's genus:
// - a cone: its apex above the loop's centroid, at half the loop's mean radius, on the side the patch's
//   orientation (consistent with the surface's) points to, one fan of triangles from the apex (cutting it
//   into rings of copies of the loop made a square loop's corners go flat in the conformal map:
//   test_boundaries' plate). The cone is a topological disk whatever the loop's shape;
// - but where that cone folds over itself (cone_folds(): the loop is not star-shaped about its centroid in
//   its mean plane, as the jagged or saddle-shaped holes of scans), the hole is filled by Liepa's method
//   (fill_hole_by_fairing()), whose patch continues the surface smoothly, so that the seam carries no
//   more curvature than the surface around it; its apex (for the apex site of the sphere) is the new
//   vertex farthest from the loop in edges. If that fill fails, or the loop has more than 1000 vertices
//   (Liepa's search can be cubic in them), the cone is kept.
// Only the patches' intrinsic lengths matter (the positions enter the metric edge lengths only), and no
// output vertex comes from them.
// \throws Remeshing_failure if a loop spans no area or the closed surface is not valid
inline Hole_patches close_holes(const Input_surface& s)
{
  const std::vector<std::vector<std::size_t>>& loops = s.boundary_loops();
  std::vector<Eigen::Vector3d> points = s.points();
  std::vector<Input_surface::Face> faces(s.faces().begin(), s.faces().end());
  std::vector<std::size_t> apexes;
  std::vector<Patch_vertex> patch_vertices;
  for(std::size_t l = 0; l < loops.size(); ++l) {
    const std::vector<std::size_t>& loop = loops[l];
    Eigen::Vector3d c = Eigen::Vector3d::Zero(), newell = Eigen::Vector3d::Zero();
    for(std::size_t v : loop) c += s.points()[v];
    c /= double(loop.size());
    double radius = 0;
    for(std::size_t i = 0; i < loop.size(); ++i) {
      newell += s.points()[loop[i]].cross(s.points()[loop[(i + 1) % loop.size()]]);
      radius += (s.points()[loop[i]] - c).norm();
    }
    radius /= double(loop.size());
    if(!(newell.norm() > 1e-12 * radius * radius) || !(radius > 0))
      throw Remeshing_failure("remesh(): boundary loop " + std::to_string(l) + " (" + std::to_string(loop.size()) +
                              " vertices) spans no area; this version closes each hole with a cone over its loop");
    std::vector<Eigen::Vector3d> fill_points;
    std::vector<Input_surface::Face> fill_faces;
    // Liepa's triangulation may fall back to a search cubic in the loop's size: the fill is tried on
    // loops of at most 1000 vertices (the scans' largest is 136)
    if(loop.size() <= 1000 && cone_folds(s.points(), loop, c, newell) && fill_hole_by_fairing(s, loop, points.size(), fill_points, fill_faces)) {
      // the apex: the new vertex farthest from the loop in edges (breadth-first over the patch)
      const std::size_t first = points.size();
      std::vector<std::vector<std::size_t>> adjacent(fill_points.size());
      std::vector<int> hops(fill_points.size(), -1);
      std::deque<std::size_t> queue;
      for(const auto& f : fill_faces)
        for(std::size_t k = 0; k < 3; ++k) {
          const std::size_t a = f[k], b = f[(k + 1) % 3];
          if(a >= first && b >= first) adjacent[a - first].push_back(b - first);
          if(a >= first && b < first && hops[a - first] < 0) hops[a - first] = 1, queue.push_back(a - first);
          if(b >= first && a < first && hops[b - first] < 0) hops[b - first] = 1, queue.push_back(b - first);
        }
      while(!queue.empty()) {
        const std::size_t v = queue.front();
        queue.pop_front();
        for(std::size_t w : adjacent[v])
          if(hops[w] < 0) hops[w] = hops[v] + 1, queue.push_back(w);
      }
      std::size_t apex = 0;
      for(std::size_t k = 0; k < fill_points.size(); ++k)
        if(hops[k] > hops[apex]) apex = k;
      apexes.push_back(first + apex);
      for(const Eigen::Vector3d& q : fill_points) {
        points.push_back(q);
        patch_vertices.push_back({l, 0, 1.0});
      }
      faces.insert(faces.end(), fill_faces.begin(), fill_faces.end());
      continue;
    }
    // the patch face (b, a, apex) runs along the loop edge a -> b of the surface backwards: its normal is
    // about -newell, and the apex goes that way
    const Eigen::Vector3d top = c - 0.5 * radius * newell.normalized();
    const std::size_t m = loop.size(), apex = points.size();
    points.push_back(top);
    patch_vertices.push_back({l, 0, 1.0});
    apexes.push_back(apex);
    for(std::size_t i = 0; i < m; ++i) faces.push_back({{loop[(i + 1) % m], loop[i], apex}});
  }
  Hole_patches p{[&] {
                    try {
                      return Input_surface(std::move(points), std::move(faces));
                    } catch(const Invalid_input& e) {
                      throw Remeshing_failure(std::string("remesh(): the surface closed by a patch over each hole is not valid (") +
                                              e.what() + ")");
                    }
                  }(),
                  s.number_of_vertices(), s.number_of_faces(), loops, apexes, patch_vertices};
  if(p.closed.genus() != s.genus() || !p.closed.boundary_loops().empty())
    throw Internal_error("close_holes(): the closed surface is " + p.closed.topology_description() + ", the input " +
                         s.topology_description());
  return p;
}

// The metric on the closed surface: the input's on the input's faces; on a patch, the mean of its loop's
// tensors at the apex (a patch vertex at `t` < 1 towards it: linear between that and its loop vertex's),
// interpolated linearly over the patch's faces (a smooth extension into the hole).
template <typename AnisotropicMetric>
class Patched_metric {
public:
  typedef Eigen::Matrix3d Tensor;
  Patched_metric(const AnisotropicMetric& metric, const Hole_patches& patches) : m_metric(metric), m_nv(patches.input_vertices)
  {
    std::vector<Eigen::Matrix3d> apex;
    for(const auto& loop : patches.loops) {
      Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
      for(std::size_t v : loop) M += Eigen::Matrix3d(m_metric.tensor(Surface_point::at_vertex(v, patches.closed.points()[v])));
      apex.push_back(M / double(loop.size()));
    }
    for(const Patch_vertex& pv : patches.patch_vertices)
      m_apex.push_back(pv.t >= 1 ? apex[pv.loop]
                                 : Eigen::Matrix3d((1 - pv.t) * Eigen::Matrix3d(m_metric.tensor(Surface_point::at_vertex(pv.at, patches.closed.points()[pv.at]))) +
                                                   pv.t * apex[pv.loop]));
    m_points = patches.closed.points();
  }
  Tensor tensor(const Surface_point& p) const
  {
    if(p.vertices[0] < m_nv && p.vertices[1] < m_nv && p.vertices[2] < m_nv) return m_metric.tensor(p);
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    for(int k = 0; k < 3; ++k) {
      const double w = p.barycentric[k];
      if(w == 0) continue;
      const std::size_t v = p.vertices[std::size_t(k)];
      M += w * (v < m_nv ? Eigen::Matrix3d(m_metric.tensor(Surface_point::at_vertex(v, m_points[v]))) : m_apex[v - m_nv]);
    }
    return M;
  }

private:
  const AnisotropicMetric& m_metric;
  std::size_t m_nv;
  std::vector<Eigen::Matrix3d> m_apex;  // per patch vertex
  std::vector<Eigen::Vector3d> m_points;
};

// Tags the background built on `patches.closed`: its patch faces, and each loop as a seam
inline void tag_hole_patches(Intrinsic_triangulation& itri, const Hole_patches& patches)
{
  for(std::size_t f = patches.input_faces; f < itri.number_of_faces(); ++f) itri.set_patch_face(int(f));
  for(std::size_t l = 0; l < patches.loops.size(); ++l)
    for(std::size_t k = 0; k < patches.loops[l].size(); ++k)
      itri.set_seam_vertex(int(patches.loops[l][k]), int(l), double(k), patches.loops[l].size());
}

// the output edge length of `n` vertices over the surface without its patches (the faces not tagged),
// in the metric: sqrt(2 A / (sqrt(3) n)), as refine_background() measures it over the whole background
inline double edge_length_without_patches(const Intrinsic_triangulation& itri, std::size_t n)
{
  double area = 0;
  for(std::size_t f = 0; f < itri.number_of_faces(); ++f)
    if(!itri.is_patch_face(f)) area += heron_area(itri.length(int(3 * f)), itri.length(int(3 * f + 1)), itri.length(int(3 * f + 2)));
  return std::sqrt(2 * area / (std::sqrt(3.0) * double(std::max<std::size_t>(n, 1))));
}

// Splits every seam piece (is_seam_piece(): on the input loop) longer than `longest` in the metric at its midpoint (on the input loop's edge:
// the point is its own projection onto `input`), so that the sites placed along a seam sit at background
// vertices at about the spacing asked for. The new edges' lengths are set (compute_metric_edge_lengths()).
inline std::size_t refine_seams(Intrinsic_triangulation& itri, const Input_surface& input, double longest, std::size_t most)
{
  auto length = [&](int a, int b) { return metric_segment_length(itri.position(a), itri.position(b), itri.Q(a), itri.Q(b)); };
  Longest_edge_queue queue;
  for(int h = 0; h < int(itri.number_of_halfedges()); ++h)
    if(itri.is_edge_representative(h) && itri.is_seam_piece(h)) queue.emplace(length(itri.tail(h), itri.head(h)), itri.tail(h), itri.head(h));
  return split_longest_at_input_midpoints(itri, input, queue, longest, most, [&](int h) { return itri.is_seam_piece(h); },
                                          "the boundary loops");
}

// Makes the seam edges closer to intrinsically Delaunay, as a constrained Delaunay refinement does: the
// rest is flipped to the intrinsic Delaunay triangulation (the lengths kept), then each seam piece whose
// two facing angles add up to more than pi is split at its midpoint (on the input loop; the new edges'
// lengths the medians of its two triangles), in at most `rounds` rounds and `most` splits: a seam edge
// cannot flip, and a sliver of the input along a loop (an angle near pi facing it) can become flat in the
// conformal map. Bounded because a small angle between two seam edges would make it refine for ever
// (then the embedding's own checks decide). Returns the number of splits.
inline std::size_t make_seams_delaunay(Intrinsic_triangulation& itri, const Input_surface& input, int rounds, std::size_t most)
{
  const double pi = 3.14159265358979323846;
  std::size_t splits = 0;
  for(int round = 0; round < rounds; ++round) {
    make_intrinsic_delaunay(itri, 50, "remesh(): the Delaunay refinement of the holes' loops");
    const std::vector<double> zero(itri.number_of_vertices(), 0.0);
    const Euclidean_delaunay_flip_rule rule{zero, nullptr, true};
    std::vector<std::pair<int, int>> bad;
    for(int h = 0; h < int(itri.number_of_halfedges()); ++h)
      if(itri.is_edge_representative(h) && itri.twin(h) >= 0 && itri.is_seam_piece(h) &&
         rule.opposite_angle(itri, h) + rule.opposite_angle(itri, itri.twin(h)) > pi + 1e-10)
        bad.emplace_back(itri.tail(h), itri.head(h));
    if(bad.empty()) return splits;
    for(const auto& ab : bad) {
      const int h = itri.find_halfedge(ab.first, ab.second);
      if(h < 0 || itri.twin(h) < 0) continue;
      if(splits >= most) return splits;
      const Eigen::Vector3d mid = 0.5 * (itri.position(ab.first) + itri.position(ab.second));
      Surface_point sp = input.project(mid);
      sp.position = mid;
      split_interior_edge_at_midpoint(itri, h, sp);
      ++splits;
    }
  }
  return splits;
}

// `true` if the holes' patches need a fixed site at each apex: on the sphere when the patches cover half of
// it or more (their chordal triangles' area against all of them), as the sites of the rest could then lie
// in one hemisphere, where their Delaunay triangulation does not cover the sphere; never in the other
// domains (see closed_domain_dual())
template <typename Domain>
bool patches_need_apex_sites(const Intrinsic_triangulation& itri, const typename Domain::Embedding& emb)
{
  if constexpr(Domain::kind == Parametric_domain::SPHERE) {
    double patch = 0, all = 0;
    for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
      const auto& c = itri.face_vertices(f);
      const Eigen::Vector3d &a = emb.position[std::size_t(c[0])], &b = emb.position[std::size_t(c[1])], &d = emb.position[std::size_t(c[2])];
      const double area = 0.5 * (b - a).cross(d - a).norm();
      all += area;
      if(itri.is_patch_face(f)) patch += area;
    }
    return !(patch < 0.5 * all);
  } else {
    (void)itri;
    (void)emb;
    return false;
  }
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_REMESH_HOLE_PATCHES_H
