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
#include <Aniso_conformal/internal/remesh/patch_collars.h>
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
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

// Surfaces with boundary loops in the closed domains (issue 15, item 3). Each hole is closed by a virtual
// patch, a cone from a new apex vertex to the loop (or, where that cone would fold over itself, a fill by
// Liepa's method, close_holes()), so that the surface becomes closed of the same genus and goes to the
// sphere, the flat torus or the hyperbolic disk as a closed surface does; the input is never modified. In
// the second run after a failed one (remesh_in_domain.h, run_pipeline()), a loop that passes twice
// through one point (a pinch) is cut there into pieces joined by a bridge vertex, each closed by its own
// patch (split_loop_at_pinches(), close_pinched_loop()). In the background (Intrinsic_triangulation) the
// patch's faces carry no CVT density and each loop is a seam whose edges are never flipped; sites are
// fixed along every seam at about equal metric arc length (their number from the loop's metric length
// and the output edge length, as the plane places the boundary sites of a disk), at background vertices
// on the seam, so that they map back exactly onto the input loop (loop_sites.h). The dual triangles on
// the patch side of each loop's chain of sites are removed, and what is left is checked: every loop's
// consecutive sites joined by an output edge (where the dual did not join two, the edge is recovered by
// flips first, recover_loop_edges()), no site inside a patch (then the genus and the number of loops are
// checked with the rest of the output).

namespace Aniso_conformal {
namespace internal {

// A vertex of a patch: the point at `t` from the loop's input vertex `at` (t = 0) to the apex (t = 1)
struct Patch_vertex {
  std::size_t loop = 0;
  std::size_t at = 0;
  double t = 1;
  bool bridge = false;  // a bridge vertex of split_loop_at_pinches(): the metric there is made isotropic
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
  std::vector<std::size_t> pinch_vertices;      // sorted: the loop vertices at a pinch (split_loop_at_pinches())
  std::size_t collared_loops = 0;               // loops closed by a collar and a cone (patch_collars.h)
};

// A hole of the surface (`surface_points`, `surface_faces`) filled by Liepa's method (Liepa 2003, "Filling holes in meshes"; CGAL's
// triangulate_refine_and_fair_hole(): a triangulation of the loop minimising the worst dihedral angle,
// then area, among triangles that add no edge the surface has already; refined to the density of the
// loop's edges; its new vertices moved to minimise the bi-Laplacian energy (cotangent weights, sparse
// LU), which continues the surface smoothly across the loop). `loop` is the hole's loop in the
// orientation of the faces. On success `points` receives the new vertices (their indices in the closed
// surface `first + k`), `faces` the patch's triangles (indices: the surface's below `surface_points.size()`,
// `first + k` for new vertex k), oriented as the surface; returns false, leaving both empty, if CGAL
// finds no triangulation or the fill has no vertex inside (close_holes() then uses the cone). If the
// fairing's linear solve fails, the refined triangulation is kept unfaired (flat triangles spanning the loop).
inline bool fill_hole_by_fairing(const std::vector<Eigen::Vector3d>& surface_points, const std::vector<Input_surface::Face>& surface_faces,
                                 const std::vector<std::size_t>& loop, std::size_t first, std::vector<Eigen::Vector3d>& points,
                                 std::vector<Input_surface::Face>& faces)
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef CGAL::Surface_mesh<K::Point_3> Mesh;
  typedef CGAL::Eigen_solver_traits<Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType, Eigen::COLAMDOrdering<int>>> Solver;
  points.clear();
  faces.clear();
  Mesh m;
  for(const Eigen::Vector3d& p : surface_points) m.add_vertex(K::Point_3(p.x(), p.y(), p.z()));
  for(const auto& f : surface_faces)
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
  const std::size_t nv = surface_points.size();
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

// The vertex of a fill (its `count` new vertices numbered from `first`, its triangles `fill_faces`)
// farthest from the loop in edges (breadth-first over the patch): its offset from `first`
inline std::size_t farthest_from_loop(std::size_t first, std::size_t count, const std::vector<Input_surface::Face>& fill_faces)
{
  std::vector<std::vector<std::size_t>> adjacent(count);
  std::vector<int> hops(count, -1);
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
  for(std::size_t k = 0; k < count; ++k)
    if(hops[k] > hops[apex]) apex = k;
  return apex;
}

// per position of `loop` (over `points`), the shorter of its two loop edges
inline std::vector<double> shorter_loop_edges(const std::vector<std::size_t>& loop, const std::vector<Eigen::Vector3d>& points)
{
  std::vector<double> shortest(loop.size());
  for(std::size_t i = 0, n = loop.size(); i < n; ++i)
    shortest[i] = std::min((points[loop[i]] - points[loop[(i + 1) % n]]).norm(), (points[loop[i]] - points[loop[(i + n - 1) % n]]).norm());
  return shortest;
}

// The pinches of a loop (`loop` over `points`): the pairs of its vertices at one point, or closer than
// a tenth of the shorter loop edge at either, at least two loop edges apart both ways round; found by a
// sweep along x, O(n log n) for a loop of n vertices without any
inline std::vector<std::pair<std::size_t, std::size_t>> pinch_pairs(const std::vector<std::size_t>& loop, const std::vector<Eigen::Vector3d>& points)
{
  const std::size_t n = loop.size();
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  if(n < 6) return pairs;
  const std::vector<double> shortest = shorter_loop_edges(loop, points);
  const double reach = 0.1 * *std::max_element(shortest.begin(), shortest.end());
  std::vector<std::size_t> order(n);
  for(std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return points[loop[a]].x() < points[loop[b]].x(); });
  for(std::size_t a = 0; a < n; ++a)
    for(std::size_t b = a + 1; b < n && points[loop[order[b]]].x() - points[loop[order[a]]].x() <= reach; ++b) {
      const std::size_t i = std::min(order[a], order[b]), j = std::max(order[a], order[b]);
      if(j - i >= 2 && n - (j - i) >= 2 && (points[loop[i]] - points[loop[j]]).norm() < 0.1 * std::min(shortest[i], shortest[j]))
        pairs.push_back({loop[i], loop[j]});
    }
  return pairs;
}

// `true` if a boundary loop of `s` passes twice through one point (pinch_pairs())
inline bool has_pinched_loop(const Input_surface& s)
{
  for(const auto& loop : s.boundary_loops())
    if(!pinch_pairs(loop, s.points()).empty()) return true;
  return false;
}

// A loop that passes twice through a point (a pinch: two loop vertices at the same point, or closer than a
// tenth of their shortest loop edge, as where two holes of a scan touch at a corner) cut into pieces, each to
// be closed by its own patch: repeatedly, the pinch pair (x, x') whose shorter side of the loop is shortest is
// cut off as a lobe (x ... x', b) by a new bridge vertex b, and the rest of the loop goes (... x, b, x' ...),
// so that the patches of the two sides meet along the path x - b - x' and the two copies of the point are two
// edges apart in the closed surface, not joined through one patch (a patch over the whole loop put a copy one
// patch edge from the other copy's loop neighbours: CGAL's elephant-with-holes, benchmark/boundaries.md). Each
// bridge adds a vertex, two edges and a face, so the closed surface keeps the input's genus. The bridge vertex
// is put at `points`' end, above the pinch (along -`up`, where the patches go) by the mean length of the four
// loop edges at x and x', and recorded in `patch_vertices` (its metric isotropic, Patched_metric); the two
// copies of each pinch are appended to `pinch_vertices`. Returns the pieces (vertices of the closed surface,
// in the loop's orientation); the loop itself if it has no pinch. Time O(n log n) for a loop of n vertices
// without a pinch, O(n p^2) with p pinches.
inline std::vector<std::vector<std::size_t>> split_loop_at_pinches(const std::vector<std::size_t>& loop, std::size_t l, const Eigen::Vector3d& up,
                                                                   std::vector<Eigen::Vector3d>& points,
                                                                   std::vector<Patch_vertex>& patch_vertices,
                                                                   std::vector<std::size_t>& pinch_vertices)
{
  const std::size_t n = loop.size();
  const std::vector<std::pair<std::size_t, std::size_t>> pairs = pinch_pairs(loop, points);
  if(pairs.empty()) return {loop};
  const std::vector<double> shortest = shorter_loop_edges(loop, points);
  std::map<std::size_t, std::size_t> position;  // loop vertex -> its position in `loop`
  for(std::size_t i = 0; i < n; ++i) position[loop[i]] = i;
  std::vector<std::vector<std::size_t>> pieces;
  std::vector<std::size_t> rest = loop;
  std::vector<char> cut(pairs.size(), 0);
  const std::size_t first_bridge = points.size();
  // `true` if the side rest[from ... from + span] has a loop vertex away from its ends' point (at a point
  // where the loop passes three times, the last side left can hold only copies and bridges)
  const auto away = [&](std::size_t from, std::size_t span) {
    const Eigen::Vector3d& x = points[rest[from]];
    for(std::size_t k = 1; k < span; ++k) {
      const std::size_t v = rest[(from + k) % rest.size()];
      if(v < first_bridge && (points[v] - x).norm() >= 0.1 * shortest[position[v]]) return true;
    }
    return false;
  };
  for(;;) {
    const std::size_t m = rest.size();
    std::size_t best_from = 0, best_span = m, best_pair = 0;  // the lobe: rest[best_from ... best_from + best_span] (cyclic)
    for(std::size_t q = 0; q < pairs.size(); ++q) {
      if(cut[q]) continue;
      std::size_t i = std::size_t(std::find(rest.begin(), rest.end(), pairs[q].first) - rest.begin());
      std::size_t j = std::size_t(std::find(rest.begin(), rest.end(), pairs[q].second) - rest.begin());
      if(i > j) std::swap(i, j);
      const std::size_t inner = j - i, outer = m - inner;
      if(inner < 2 || outer < 2) continue;  // the pair already two edges apart through a bridge
      if(inner < best_span && away(i, inner)) best_from = i, best_span = inner, best_pair = q;
      if(outer < best_span && away(j, outer)) best_from = j, best_span = outer, best_pair = q;
    }
    if(best_span >= m) break;
    cut[best_pair] = 1;
    const std::size_t x = rest[best_from], x2 = rest[(best_from + best_span) % m];
    pinch_vertices.push_back(x);
    pinch_vertices.push_back(x2);
    // the bridge vertex, above the pinch by the mean of the four loop edges there
    double h = 0;
    for(std::size_t v : {x, x2}) {
      const std::size_t k = position[v];
      h += (points[loop[(k + 1) % n]] - points[v]).norm() + (points[loop[(k + n - 1) % n]] - points[v]).norm();
    }
    const std::size_t bridge = points.size();
    points.push_back(0.5 * (points[x] + points[x2]) - 0.25 * h * up.normalized());
    patch_vertices.push_back({l, x, 0.5, true});
    std::vector<std::size_t> lobe, others;
    for(std::size_t k = 0; k <= best_span; ++k) lobe.push_back(rest[(best_from + k) % m]);
    lobe.push_back(bridge);
    for(std::size_t k = best_span; k <= m; ++k) others.push_back(rest[(best_from + k) % m]);
    others.push_back(bridge);
    pieces.push_back(std::move(lobe));
    rest = std::move(others);
  }
  pieces.push_back(rest);
  return pieces;
}

// Closes the pieces of a pinched loop `l` (split_loop_at_pinches()) one by one, each as a whole loop
// is closed (close_holes()): a cone over the piece, or where that cone folds, Liepa's fill of the piece
// as a hole of the surface with the pieces before it closed by their patches and those after it by
// their cones (so that the fairing sees a surface around the whole piece). A fill with an edge between
// two copies of a pinch point (shorter than a tenth of the piece's mean edge) is not kept: the cone is.
// The loop's apex (`apexes`, for the sphere's apex site) is that of its largest piece.
// \throws Remeshing_failure if a piece spans no area
inline void close_pinched_loop(const std::vector<std::vector<std::size_t>>& pieces, std::size_t l, std::vector<Eigen::Vector3d>& points,
                               std::vector<Input_surface::Face>& faces, std::vector<Patch_vertex>& patch_vertices,
                               std::vector<std::size_t>& apexes)
{
  // each piece's cone: its apex above the piece's centroid at half its mean radius, as close_holes()'s
  std::vector<Eigen::Vector3d> centroid(pieces.size()), newell(pieces.size()), top(pieces.size());
  std::vector<double> mean_edge(pieces.size(), 0);
  for(std::size_t i = 0; i < pieces.size(); ++i) {
    const std::vector<std::size_t>& piece = pieces[i];
    centroid[i] = newell[i] = Eigen::Vector3d::Zero();
    for(std::size_t v : piece) centroid[i] += points[v];
    centroid[i] /= double(piece.size());
    double radius = 0;
    for(std::size_t k = 0; k < piece.size(); ++k) {
      newell[i] += points[piece[k]].cross(points[piece[(k + 1) % piece.size()]]);
      radius += (points[piece[k]] - centroid[i]).norm();
      mean_edge[i] += (points[piece[k]] - points[piece[(k + 1) % piece.size()]]).norm() / double(piece.size());
    }
    radius /= double(piece.size());
    if(!(newell[i].norm() > 1e-12 * radius * radius))
      throw Remeshing_failure("remesh(): a piece of boundary loop " + std::to_string(l) + " between two passes through one point (" +
                              std::to_string(piece.size()) + " vertices) spans no area");
    top[i] = centroid[i] - 0.5 * radius * newell[i].normalized();
  }
  const auto cone = [&](std::size_t i, std::vector<Eigen::Vector3d>& pts, std::vector<Input_surface::Face>& fcs) {
    const std::size_t apex = pts.size();
    pts.push_back(top[i]);
    for(std::size_t k = 0; k < pieces[i].size(); ++k) fcs.push_back({{pieces[i][(k + 1) % pieces[i].size()], pieces[i][k], apex}});
    return apex;
  };
  std::size_t largest = 0;
  for(std::size_t i = 0; i < pieces.size(); ++i) {
    const std::vector<std::size_t>& piece = pieces[i];
    std::size_t apex = 0;
    bool filled = false;
    if(piece.size() <= 1000 && cone_folds(points, piece, centroid[i], newell[i])) {
      std::vector<Eigen::Vector3d> around = points;
      std::vector<Input_surface::Face> around_faces = faces;
      for(std::size_t j = i + 1; j < pieces.size(); ++j) cone(j, around, around_faces);
      std::vector<Eigen::Vector3d> fill_points;
      std::vector<Input_surface::Face> fill_faces;
      if(fill_hole_by_fairing(around, around_faces, piece, points.size(), fill_points, fill_faces)) {
        filled = true;
        for(const auto& f : fill_faces)
          for(std::size_t k = 0; k < 3; ++k) {
            const std::size_t a = f[k], b = f[(k + 1) % 3];
            const auto at = [&](std::size_t v) -> const Eigen::Vector3d& { return v < points.size() ? points[v] : fill_points[v - points.size()]; };
            if((a >= points.size() && a < around.size()) || (b >= points.size() && b < around.size()) ||  // another piece's cone apex
               (at(a) - at(b)).norm() < 0.1 * mean_edge[i])
              filled = false;
          }
      }
      if(filled) {
        apex = points.size() + farthest_from_loop(points.size(), fill_points.size(), fill_faces);
        for(const Eigen::Vector3d& q : fill_points) {
          points.push_back(q);
          patch_vertices.push_back({l, 0, 1.0});
        }
        faces.insert(faces.end(), fill_faces.begin(), fill_faces.end());
      }
    }
    if(!filled) {
      apex = cone(i, points, faces);
      patch_vertices.push_back({l, 0, 1.0});
    }
    if(piece.size() > largest) largest = piece.size(), apexes.resize(l), apexes.push_back(apex);
  }
}

// Adds to loop `l`'s patch the cone over `ring` (vertices of `points` in the loop's orientation; `frame`
// its loop_frame()): an apex above the ring's centroid at half its mean radius, then one fan of triangles.
// The patch face (b, a, apex) runs along the ring's edge a -> b backwards: its normal is about -newell,
// and the apex goes that way (onto the centroid if the ring spans no area).
inline void add_cone_patch(const std::vector<std::size_t>& ring, const Loop_frame& frame, std::size_t l, std::vector<Eigen::Vector3d>& points,
                           std::vector<Input_surface::Face>& faces, std::vector<Patch_vertex>& patch_vertices,
                           std::vector<std::size_t>& apexes)
{
  const std::size_t m = ring.size(), apex = points.size();
  points.push_back(frame.newell.norm() > 0 ? Eigen::Vector3d(frame.centroid - 0.5 * frame.radius * frame.newell.normalized()) : frame.centroid);
  patch_vertices.push_back({l, 0, 1.0});
  apexes.push_back(apex);
  for(std::size_t i = 0; i < m; ++i) faces.push_back({{ring[(i + 1) % m], ring[i], apex}});
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
//   (Liepa's search can be cubic in them), the cone is kept;
// - with `split_pinches`, a loop that passes twice through one point is cut into pieces first
//   (split_loop_at_pinches()), each closed as above (close_pinched_loop()).
// Only the patches' intrinsic lengths matter (the positions enter the metric edge lengths only), and no
// output vertex comes from them.
// \throws Remeshing_failure if a loop spans no area or the closed surface is not valid
inline Hole_patches close_holes(const Input_surface& s, bool split_pinches = false, double collar_edge_length = 0)
{
  const std::vector<std::vector<std::size_t>>& loops = s.boundary_loops();
  std::vector<Eigen::Vector3d> points = s.points();
  std::vector<Input_surface::Face> faces(s.faces().begin(), s.faces().end());
  std::vector<std::size_t> apexes;
  std::vector<Patch_vertex> patch_vertices;
  std::vector<std::size_t> pinch_vertices;
  std::size_t collared = 0;
  for(std::size_t l = 0; l < loops.size(); ++l) {
    const std::vector<std::size_t>& loop = loops[l];
    const Loop_frame frame = loop_frame(s.points(), loop);
    const Eigen::Vector3d &c = frame.centroid, &newell = frame.newell;
    const double radius = frame.radius;
    if(!(newell.norm() > 1e-12 * radius * radius) || !(radius > 0))
      throw Remeshing_failure("remesh(): boundary loop " + std::to_string(l) + " (" + std::to_string(loop.size()) +
                              " vertices) spans no area; this version closes each hole with a cone over its loop");
    const std::vector<std::vector<std::size_t>> pieces =
      split_pinches ? split_loop_at_pinches(loop, l, newell, points, patch_vertices, pinch_vertices) : std::vector<std::vector<std::size_t>>{loop};
    if(pieces.size() > 1) {
      close_pinched_loop(pieces, l, points, faces, patch_vertices, apexes);
      continue;
    }
    // a loop along both faces of a part thinner than an output edge: a collar of rings along the normals,
    // two output edges high, opens them apart (patch_collars.h), then the cone over its last ring
    const auto thin = thin_loop_pairs(s.points(), s.vertex_normals(), loop, collar_edge_length);
    if(!thin.empty()) {
      const double height = 2 * collar_edge_length;
      const int rings = int(std::clamp(std::round(height * double(loop.size()) / frame.length), 1.0, 8.0));
      const std::vector<std::size_t> last = add_patch_collar(loop, s.vertex_normals(), thin, height, rings, points, faces,
                                                             [&](std::size_t i) { patch_vertices.push_back({l, loop[i], 0.0, true}); });
      add_cone_patch(last, loop_frame(points, last), l, points, faces, patch_vertices, apexes);
      ++collared;
      continue;
    }
    std::vector<Eigen::Vector3d> fill_points;
    std::vector<Input_surface::Face> fill_faces;
    // Liepa's triangulation may fall back to a search cubic in the loop's size: the fill is tried on
    // loops of at most 1000 vertices (the scans' largest is 136)
    if(loop.size() <= 1000 && cone_folds(s.points(), loop, c, newell) && fill_hole_by_fairing(s.points(), s.faces(), loop, points.size(), fill_points, fill_faces)) {
      apexes.push_back(points.size() + farthest_from_loop(points.size(), fill_points.size(), fill_faces));
      for(const Eigen::Vector3d& q : fill_points) {
        points.push_back(q);
        patch_vertices.push_back({l, 0, 1.0});
      }
      faces.insert(faces.end(), fill_faces.begin(), fill_faces.end());
      continue;
    }
    add_cone_patch(loop, frame, l, points, faces, patch_vertices, apexes);
  }
  Hole_patches p{[&] {
                    try {
                      return Input_surface(std::move(points), std::move(faces));
                    } catch(const Invalid_input& e) {
                      throw Remeshing_failure(std::string("remesh(): the surface closed by a patch over each hole is not valid (") +
                                              e.what() + ")");
                    }
                  }(),
                  s.number_of_vertices(), s.number_of_faces(), loops, apexes, patch_vertices, {}};
  std::sort(pinch_vertices.begin(), pinch_vertices.end());
  pinch_vertices.erase(std::unique(pinch_vertices.begin(), pinch_vertices.end()), pinch_vertices.end());
  p.pinch_vertices = std::move(pinch_vertices);
  p.collared_loops = collared;
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
    for(const Patch_vertex& pv : patches.patch_vertices) {
      m_apex.push_back(pv.t >= 1 ? apex[pv.loop]
                                 : Eigen::Matrix3d((1 - pv.t) * Eigen::Matrix3d(m_metric.tensor(Surface_point::at_vertex(pv.at, patches.closed.points()[pv.at]))) +
                                                   pv.t * apex[pv.loop]));
      // a bridge vertex stands above its pinch, its tangent plane across the surface's: a tensor of the
      // surface's tangent plane would be singular on it; the isotropic tensor of the same mean scale is not
      if(pv.bridge) m_apex.back() = (0.5 * m_apex.back().trace()) * Eigen::Matrix3d::Identity();
    }
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
