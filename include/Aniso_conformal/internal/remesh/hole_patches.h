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
// exactly onto the input loop. The dual triangles on the patch side of each loop's chain of sites are
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

// The fixed sites along the loops: for each loop, background vertices on its seam in loop order
struct Loop_sites {
  std::vector<std::vector<int>> vertices;  // per loop, the background vertices of its sites, in the loop's order
  std::size_t size() const
  {
    std::size_t k = 0;
    for(const auto& l : vertices) k += l.size();
    return k;
  }
};

// A stretch of a boundary loop's chain of seam vertices (place_loop_sites()): between two kept corners, or
// the whole loop when it has none
struct Loop_stretch {
  std::size_t loop;
  std::vector<double> s;  // arc length at each chain vertex from the stretch's start (its last entry the end)
  std::vector<int> v;
  bool closed;            // a whole loop without corner
  std::size_t count;      // sites strictly inside (closed: all of them)
};

// The sites of place_loop_sites() from its stretches (a loop's chain between two kept corners, or a whole
// loop without corner) and their site counts: each stretch's corner at its start, then its sites at equal
// arc length on the nearest chain vertex (never its ends nor the previous site's vertex); per loop, in order.
// \throws Remeshing_failure if a loop's seam has too few background vertices for its sites, or a loop
// would keep fewer than 3
inline Loop_sites loop_sites_on_stretches(const std::vector<Loop_stretch>& stretches, std::size_t nl)
{
  Loop_sites out;
  out.vertices.resize(nl);
  for(const auto& st : stretches) {
    std::vector<int>& sites = out.vertices[st.loop];
    if(!st.closed) sites.push_back(st.v.front());
    const double len = st.s.back();
    const std::size_t m = st.count;
    const double step = len / double(st.closed ? m : m + 1);
    std::size_t i = 0;
    for(std::size_t k = 0; k < m; ++k) {
      const double target = st.closed ? (double(k) + 0.5) * step : double(k + 1) * step;
      while(i + 1 < st.s.size() && st.s[i + 1] <= target) ++i;
      std::size_t best = (i + 1 < st.s.size() && st.s[i + 1] - target < target - st.s[i]) ? i + 1 : i;
      // never the stretch's ends (corners) nor the vertex of the previous site
      if(!st.closed && best == 0) best = 1;
      if(!st.closed && best + 1 >= st.s.size()) best = st.s.size() - 2;
      if(best >= st.v.size() || (!sites.empty() && sites.back() == st.v[best]))
        throw Remeshing_failure("remesh(): boundary loop " + std::to_string(st.loop) +
                                " has too few background vertices for its sites (its seam is not refined enough)");
      sites.push_back(st.v[best]);
    }
  }
  for(std::size_t l = 0; l < nl; ++l) {
    std::vector<int> sorted = out.vertices[l];
    std::sort(sorted.begin(), sorted.end());
    if(std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw Remeshing_failure("remesh(): two sites of boundary loop " + std::to_string(l) +
                              " fall on the same background vertex (its seam is not refined enough)");
  }
  for(std::size_t l = 0; l < nl; ++l)
    if(out.vertices[l].size() < 3)
      throw Remeshing_failure("remesh(): boundary loop " + std::to_string(l) + " would keep " + std::to_string(out.vertices[l].size()) +
                              " output vertices; at least 3 are needed");
  return out;
}

// Places the sites of every loop: its seam's background vertices in order, the loop's corners (input
// vertices where the loop turns by more than `corner_angle_deg`) kept, and between two corners (or
// around a loop without one) evenly spaced points at about `h` of metric arc length, each at the seam
// vertex nearest in arc length (the seams are refined to a quarter of `h`). At least 3 sites a loop; in
// all at most `budget` (the longest stretches lose sites first).
inline Loop_sites place_loop_sites(const Intrinsic_triangulation& itri, const Hole_patches& patches, double h, double corner_angle_deg,
                                   std::size_t budget)
{
  const std::size_t nl = patches.loops.size();
  std::vector<std::vector<int>> chain(nl);
  for(int v = 0; v < int(itri.number_of_vertices()); ++v)
    if(itri.seam(v) >= 0) chain[std::size_t(itri.seam(v))].push_back(v);
  const double limit = corner_angle_deg * 3.14159265358979323846 / 180.0;
  std::vector<Loop_stretch> stretches;
  std::vector<std::vector<int>> corners(nl);
  for(std::size_t l = 0; l < nl; ++l) {
    auto& c = chain[l];
    std::sort(c.begin(), c.end(), [&](int a, int b) { return itri.seam_parameter(a) < itri.seam_parameter(b); });
    const auto& loop = patches.loops[l];
    std::vector<char> is_corner(c.size(), 0);
    for(std::size_t i = 0; i < c.size(); ++i) {
      if(itri.input_vertex(c[i]) < 0) continue;
      const std::size_t k = std::size_t(itri.seam_parameter(c[i]));
      const Eigen::Vector3d& p = patches.closed.points()[loop[(k + loop.size() - 1) % loop.size()]];
      const Eigen::Vector3d& v = patches.closed.points()[loop[k]];
      const Eigen::Vector3d& q = patches.closed.points()[loop[(k + 1) % loop.size()]];
      const Eigen::Vector3d a = v - p, b = q - v;
      if(std::atan2(a.cross(b).norm(), a.dot(b)) > limit) is_corner[i] = 1;
    }
    // a corner closer than half the spacing (in arc length) to the corner kept before it, or to the first
    // one around the loop, is not kept: the turns of a jagged (scanned) loop would crowd the fixed sites
    std::vector<double> arc(c.size() + 1, 0.0);
    for(std::size_t i = 1; i <= c.size(); ++i) {
      const int u = c[i - 1], v = c[i % c.size()];
      arc[i] = arc[i - 1] + metric_segment_length(itri.position(u), itri.position(v), itri.Q(u), itri.Q(v));
    }
    std::vector<std::size_t> starts;
    for(std::size_t i = 0; i < c.size(); ++i)
      if(is_corner[i] && (starts.empty() || (arc[i] - arc[starts.back()] >= 0.5 * h && arc[c.size()] - arc[i] + arc[starts.front()] >= 0.5 * h)))
        starts.push_back(i);
    const bool none = starts.empty();
    if(none) starts.push_back(0);
    for(std::size_t i : starts)
      if(!none) corners[l].push_back(c[i]);
    for(std::size_t j = 0; j < starts.size(); ++j) {
      Loop_stretch st;
      st.loop = l;
      st.closed = none;
      const std::size_t i0 = starts[j], i1 = j + 1 < starts.size() ? starts[j + 1] : starts[0] + c.size();
      double s = 0;
      for(std::size_t i = i0; i <= i1; ++i) {
        const int v = c[i % c.size()];
        if(i > i0) {
          const int u = c[(i - 1) % c.size()];
          s += metric_segment_length(itri.position(u), itri.position(v), itri.Q(u), itri.Q(v));
        }
        st.s.push_back(s);
        st.v.push_back(v);
      }
      const double m = std::round(s / h) - (none ? 0 : 1);
      st.count = std::size_t(std::max(0.0, m));
      if(none) st.count = std::max<std::size_t>(st.count, 3);
      stretches.push_back(std::move(st));
    }
  }
  // at least 3 sites a loop: a short loop between few corners gets sites in its longest stretches
  for(std::size_t l = 0; l < nl; ++l) {
    std::size_t k = corners[l].size();
    for(const auto& st : stretches)
      if(st.loop == l) k += st.count;
    for(; k < 3; ++k) {
      Loop_stretch* longest = nullptr;
      for(auto& st : stretches)
        if(st.loop == l && (!longest || st.s.back() / double(st.count + 1) > longest->s.back() / double(longest->count + 1))) longest = &st;
      ++longest->count;
    }
  }
  std::size_t total = 0;
  for(const auto& c : corners) total += c.size();
  for(const auto& st : stretches) total += st.count;
  while(total > budget) {
    Loop_stretch* longest = nullptr;
    for(auto& st : stretches)
      if(st.count > (st.closed ? 3u : 0u) && (!longest || st.count > longest->count)) longest = &st;
    if(!longest) break;
    --longest->count;
    --total;
  }
  if(total > budget)
    throw Invalid_input("remesh(): the input's " + std::to_string(nl) + " boundary loops need at least " + std::to_string(total) +
                        " output vertices (3 a loop and its corners) and more inside; only " + std::to_string(budget) +
                        " are available: ask for more vertices");
  return loop_sites_on_stretches(stretches, nl);
}

// Joins the consecutive sites of every loop that the dual left unjoined (`first[l]`: the index of loop
// l's first site, as remove_patch_triangles() reads it): a free site, or the loop's own sites across a
// spike of the surface narrower than their spacing (CGAL's mech-holes-shark.off, a loop turning by 153
// degrees), can stand between them in the Delaunay triangulation of the sites. Each missing edge is
// recovered by a sequence of edge flips along the segment between its sites (recover_edge_by_flips(), the
// flip-based edge recovery of constrained Delaunay triangulation): with `sphere` (the sites on the unit
// sphere, the domain of genus 0) in the gnomonic projection of the domain about the segment's middle,
// where the dual is a planar triangulation and a flip of a convex quadrilateral keeps it one; else, or if
// that fails, on the surface (`closed`: the input with its holes closed, which the output's surface
// points refer to), the input's normals guarding every flip. The edges joining consecutive sites of a
// loop are never flipped. At most 64 flips an edge, no angle bound (the alternative is no output).
// Returns the number of edges recovered; the output is unchanged where none was missing.
inline std::size_t recover_loop_edges(const Input_surface& closed, Remeshed_surface& out, const Loop_sites& loops,
                                      const std::vector<std::size_t>& first, const std::vector<Eigen::Vector3d>* sphere)
{
  Directed_edge_faces face_of;
  for(std::size_t f = 0; f < out.faces.size(); ++f)
    for(int k = 0; k < 3; ++k) face_of[{out.faces[f][std::size_t(k)], out.faces[f][std::size_t((k + 1) % 3)]}] = f;
  auto joined = [&](std::size_t a, std::size_t b) { return face_of.count({a, b}) && face_of.count({b, a}); };
  std::vector<std::array<std::size_t, 2>> pairs, missing;
  for(std::size_t l = 0; l < loops.vertices.size(); ++l) {
    const std::size_t k = loops.vertices[l].size();
    for(std::size_t j = 0; j < k; ++j) {
      const std::size_t a = first[l] + j, b = first[l] + (j + 1) % k;
      pairs.push_back({{std::min(a, b), std::max(a, b)}});
      if(!joined(a, b)) missing.push_back({{a, b}});
    }
  }
  if(missing.empty()) return 0;
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::size_t> valence(out.points.size(), 0);  // neighbours
  for(const auto& e : face_of)
    if(e.first.first < e.first.second || !face_of.count({e.first.second, e.first.first})) {
      ++valence[e.first.first];
      ++valence[e.first.second];
    }
  auto is_pair = [&](std::size_t a, std::size_t b) {
    return std::binary_search(pairs.begin(), pairs.end(), std::array<std::size_t, 2>{{std::min(a, b), std::max(a, b)}});
  };
  if(sphere && sphere->size() != out.points.size()) sphere = nullptr;
  std::size_t recovered = 0;
  for(const auto& ab : missing) {
    if(joined(ab[0], ab[1])) continue;  // joined by the flips of an earlier pair
    bool ok = sphere && recover_edge_by_flips(closed, out, face_of, valence, ab[0], ab[1], 0.0, is_pair, 64, 0.0, sphere);
    if(!ok) ok = recover_edge_by_flips(closed, out, face_of, valence, ab[0], ab[1], 0.0, is_pair, 64, 0.0);
    if(ok) ++recovered;
  }
  return recovered;
}

// Removes from `out` the dual triangles on the patch side of every loop's chain of sites (`first[l]`,
// the index of loop l's first site among the sites, its sites following in order; `first.back()` the
// first of the `apexes` apex sites, one a loop or none (run_pipeline_once()), removed too), and checks
// what is left: consecutive sites of a loop joined by an output edge (those the dual did not join first
// recovered by flips, recover_loop_edges() with `closed`, the input with its holes closed, and `sphere`,
// the sites on the sphere or none), no other site inside a patch, every surface point on the input's own
// vertices. A free site left on the patch side of its loop's chain (all its triangles removed: it sat in a
// part of the surface that the chain's chords cut off, such as the tip of a spike narrower than the
// spacing) is moved to the midpoint, projected onto `input`, of the longest edge of the output left whose
// ends are both free sites, and that edge is split there: the output keeps its number of vertices.
// Returns the number of loop edges recovered and of free sites so moved. Throws Convergence_failure
// otherwise (a fixed site inside a patch, a free site on both sides of a chain, no edge to split).
inline std::pair<std::size_t, std::size_t> remove_patch_triangles(Remeshed_surface& out, const Loop_sites& loops,
                                                                  const std::vector<std::size_t>& first, std::size_t apexes,
                                                                  std::size_t input_vertices, const Input_surface& closed,
                                                                  const Input_surface& input, const std::vector<Eigen::Vector3d>* sphere)
{
  const std::size_t recovered = recover_loop_edges(closed, out, loops, first, sphere);
  const std::size_t apex_first = first.back(), apex_end = apex_first + apexes;
  const std::size_t nf = out.faces.size();
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> face_of;  // directed edge -> face
  for(std::size_t f = 0; f < nf; ++f)
    for(int k = 0; k < 3; ++k) face_of[{out.faces[f][std::size_t(k)], out.faces[f][std::size_t((k + 1) % 3)]}] = f;
  std::vector<std::size_t> loop_of(out.points.size(), std::size_t(-1));
  std::map<std::pair<std::size_t, std::size_t>, char> seam;  // undirected site-chain edges
  std::vector<std::size_t> seeds;
  for(std::size_t l = 0; l < loops.vertices.size(); ++l) {
    const std::size_t k = loops.vertices[l].size();
    for(std::size_t j = 0; j < k; ++j) loop_of[first[l] + j] = l;
    for(std::size_t j = 0; j < k; ++j) {
      const std::size_t a = first[l] + j, b = first[l] + (j + 1) % k;
      const auto inside = face_of.find({a, b}), outside = face_of.find({b, a});
      if(inside == face_of.end() || outside == face_of.end())
        throw Convergence_failure("remesh(): the output does not join sites " + std::to_string(j) + " and " +
                                      std::to_string((j + 1) % k) + " of boundary loop " + std::to_string(l) +
                                      " by an edge (a site came too close to the loop)",
                                  0);
      seam[{std::min(a, b), std::max(a, b)}] = 1;
      seeds.push_back(outside->second);
    }
  }
  // flood the patch side from the triangles beyond each chain edge, never across a chain edge
  std::vector<char> removed(nf, 0);
  std::vector<std::size_t> stack;
  for(std::size_t f : seeds)
    if(!removed[f]) {
      removed[f] = 1;
      stack.push_back(f);
    }
  while(!stack.empty()) {
    const std::size_t f = stack.back();
    stack.pop_back();
    for(int k = 0; k < 3; ++k) {
      const std::size_t a = out.faces[f][std::size_t(k)], b = out.faces[f][std::size_t((k + 1) % 3)];
      if(seam.count({std::min(a, b), std::max(a, b)})) continue;
      const auto g = face_of.find({b, a});
      if(g != face_of.end() && !removed[g->second]) {
        removed[g->second] = 1;
        stack.push_back(g->second);
      }
    }
  }
  std::vector<std::array<std::size_t, 3>> kept;
  std::vector<char> used(out.points.size(), 0);
  std::vector<std::size_t> stray;  // free sites in a removed triangle
  for(std::size_t f = 0; f < nf; ++f) {
    if(removed[f]) {
      for(std::size_t v : out.faces[f])
        if(loop_of[v] == std::size_t(-1) && (v < apex_first || v >= apex_end)) {
          if(v < apex_end) throw Convergence_failure("remesh(): output vertex " + std::to_string(v) + " lies inside the patch of a hole", 0);
          stray.push_back(v);
        }
      continue;
    }
    kept.push_back(out.faces[f]);
    for(std::size_t v : out.faces[f]) used[v] = 1;
  }
  std::sort(stray.begin(), stray.end());
  stray.erase(std::unique(stray.begin(), stray.end()), stray.end());
  for(std::size_t v : stray) {
    if(used[v]) throw Convergence_failure("remesh(): output vertex " + std::to_string(v) + " lies inside the patch of a hole", 0);
    // the longest edge between two free sites, inside the output left (two triangles), split at v
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> kept_of;
    for(std::size_t f = 0; f < kept.size(); ++f)
      for(int k = 0; k < 3; ++k) kept_of[{kept[f][std::size_t(k)], kept[f][std::size_t((k + 1) % 3)]}] = f;
    double longest = 0;
    std::pair<std::size_t, std::size_t> edge(0, 0);
    for(const auto& e : kept_of) {
      const std::size_t a = e.first.first, b = e.first.second;
      if(a > b || a < apex_end || b < apex_end || !kept_of.count({b, a})) continue;
      const double length = (out.points[a] - out.points[b]).norm();
      if(length > longest) longest = length, edge = e.first;
    }
    if(!(longest > 0))
      throw Convergence_failure("remesh(): output vertex " + std::to_string(v) + " lies inside the patch of a hole", 0);
    const std::size_t a = edge.first, b = edge.second, f = kept_of[{a, b}], g = kept_of[{b, a}];
    const std::size_t c = kept[f][0] + kept[f][1] + kept[f][2] - a - b, d = kept[g][0] + kept[g][1] + kept[g][2] - a - b;
    const Surface_point sp = input.project(0.5 * (out.points[a] + out.points[b]));
    out.points[v] = sp.position;
    out.surface_points[v] = sp;
    // (a, b, c) and (b, a, d) become (a, v, c), (v, b, c), (b, v, d), (v, a, d)
    kept[f] = {{a, v, c}};
    kept[g] = {{b, v, d}};
    kept.push_back({{v, b, c}});
    kept.push_back({{v, a, d}});
    used[v] = 1;
  }
  for(std::size_t v = 0; v < used.size(); ++v) {
    const bool apex = v >= apex_first && v < apex_end;
    if(apex && used[v]) throw Convergence_failure("remesh(): the apex of a hole's patch is joined to the output outside the patch", 0);
    if(!apex && !used[v])
      throw Convergence_failure("remesh(): output vertex " + std::to_string(v) + " is left without a triangle by the holes' patches", 0);
  }
  // the apex sites out, the vertices after them renumbered
  const std::size_t na = apex_end - apex_first;
  for(auto& f : kept)
    for(std::size_t& v : f)
      if(v >= apex_end) v -= na;
  out.points.erase(out.points.begin() + std::ptrdiff_t(apex_first), out.points.begin() + std::ptrdiff_t(apex_end));
  out.surface_points.erase(out.surface_points.begin() + std::ptrdiff_t(apex_first), out.surface_points.begin() + std::ptrdiff_t(apex_end));
  out.fixed_vertices -= std::min(out.fixed_vertices, na);
  for(const Surface_point& sp : out.surface_points)
    for(std::size_t w : sp.vertices)
      if(w >= input_vertices) throw Internal_error("remesh(): an output vertex maps onto a hole's patch");
  out.faces = std::move(kept);
  return {recovered, stray.size()};
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_REMESH_HOLE_PATCHES_H
