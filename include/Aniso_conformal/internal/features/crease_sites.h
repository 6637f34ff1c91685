// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_FEATURES_CREASE_SITES_H
#define ANISO_CONFORMAL_INTERNAL_FEATURES_CREASE_SITES_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Feature_graph.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Surface_point.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/extract_dual_mesh.h>
#include <Aniso_conformal/internal/optimize/triangle_orientation.h>
#include <Aniso_conformal/refine_background.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <deque>
#include <map>
#include <queue>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

// The creases of the input (Feature_graph.h) as chains of output edges in every domain (issue 15, item
// 2; the plane places its sites around its boundary's, remesh_in_domain.h planar_dual_with_creases()).
// The crease curves are kept the way the holes' loops are (hole_patches.h), without a patch:
// 1. the background's pieces of crease edges are split at their midpoints (points of the input crease)
//    until none is longer than a third of the output edge length, before any flip (pipeline_steps.h);
// 2. fixed sites are placed along each curve at about equal metric arc length, spacing the output edge
//    length, each at the background vertex on the curve nearest in arc length (the curve's corners at its
//    ends are fixed sites already, corners_to_fix()); a fixed site at a background vertex maps back
//    exactly onto that vertex, so every such output vertex lies on the input crease (up to the rounding
//    of the midpoints, ~1e-16 of the edge);
// 3. after the dual, consecutive sites of a curve must be joined by an output edge: one that is not is
//    recovered by flipping the one output edge between them when both new triangles stay non-inverted,
//    or else by a sequence of flips along the segment between them (recover_edge_by_flips()), else left (measure_features() reports the covered share honestly); the edges that join consecutive
//    sites are handed to the surface optimisation as edges never to flip (Remeshed_surface::kept_edges).
// The background needs no tag: its vertices never move, only its connectivity changes, so a background
// vertex found on a crease stays a point of the crease whatever the embeddings flip.

namespace Aniso_conformal {
namespace internal {

// Per feature curve of `g`, the background vertices of `itri` on it, in order along it, as (parameter,
// vertex): input vertex k of the curve at k, a point on its edge k (from vertex k to k + 1) at k + t.
// A closed curve lists its first vertex once (at 0). A background vertex is on a crease edge when it is
// one of its ends or its position lies on the segment (within 1e-9 of the edge's length: the midpoints of
// the refinement are exact up to rounding). Vertices on a hole's seam are left out.
inline std::vector<std::vector<std::pair<double, int>>> crease_chains(const Intrinsic_triangulation& itri, const Input_surface& input,
                                                                     const Feature_graph& g)
{
  std::vector<std::vector<std::pair<double, int>>> chains(g.curves.size());
  // crease edge (smaller, larger) -> (curve, k, forward: the curve runs from the smaller end)
  std::map<std::pair<std::size_t, std::size_t>, std::tuple<std::size_t, std::size_t, bool>> edge_of;
  for(std::size_t c = 0; c < g.curves.size(); ++c) {
    const std::vector<std::size_t>& cv = g.curves[c].vertices;
    for(std::size_t k = 0; k + 1 < cv.size(); ++k)
      edge_of[{std::min(cv[k], cv[k + 1]), std::max(cv[k], cv[k + 1])}] = std::make_tuple(c, k, cv[k] < cv[k + 1]);
    const std::size_t last = g.curves[c].closed ? cv.size() - 1 : cv.size();
    for(std::size_t k = 0; k < last; ++k)
      if(itri.seam(int(cv[k])) < 0) chains[c].emplace_back(double(k), int(cv[k]));
  }
  const auto& P = input.points();
  for(int v = 0; v < int(itri.number_of_vertices()); ++v) {
    if(itri.input_vertex(v) >= 0 || itri.seam(v) >= 0) continue;
    const Surface_point& sp = itri.point(v);
    for(int i = 0; i < 3; ++i) {
      const std::size_t a = sp.vertices[std::size_t(i)], b = sp.vertices[std::size_t((i + 1) % 3)];
      if(a == b || a >= P.size() || b >= P.size()) continue;
      const auto e = edge_of.find({std::min(a, b), std::max(a, b)});
      if(e == edge_of.end()) continue;
      const Eigen::Vector3d& p = P[std::min(a, b)];
      const Eigen::Vector3d d = P[std::max(a, b)] - p;
      const double L2 = d.squaredNorm();
      if(!(L2 > 0)) continue;
      const double t = (sp.position - p).dot(d) / L2;
      if(!(t > 0 && t < 1) || (p + t * d - sp.position).norm() > 1e-9 * std::sqrt(L2)) continue;
      const std::size_t c = std::get<0>(e->second), k = std::get<1>(e->second);
      chains[c].emplace_back(double(k) + (std::get<2>(e->second) ? t : 1 - t), v);
      break;
    }
  }
  for(auto& c : chains) std::sort(c.begin(), c.end());
  return chains;
}

// Splits every background edge between two consecutive vertices of a crease chain longer than `longest`
// in the metric at its midpoint (a point of the input crease; its metric square root the mean of its
// ends'), as refine_seams() does for the holes' loops, so that the crease sites sit at background vertices
// at about the spacing asked for. To be called before any flip (every consecutive pair of a chain is then
// a background edge). The new edges' lengths are set (compute_metric_edge_lengths()). Returns the splits.
// \throws Remeshing_failure if the background would need more than `most` vertices
inline std::size_t refine_creases(Intrinsic_triangulation& itri, const Input_surface& input, const Feature_graph& g, double longest,
                                  std::size_t most)
{
  if(g.curves.empty()) return 0;
  auto length = [&](int a, int b) { return metric_segment_length(itri.position(a), itri.position(b), itri.Q(a), itri.Q(b)); };
  Longest_edge_queue queue;
  const auto chains = crease_chains(itri, input, g);
  for(std::size_t c = 0; c < chains.size(); ++c) {
    const auto& ch = chains[c];
    const std::size_t m = ch.size();
    for(std::size_t i = 0; i + 1 < m + (g.curves[c].closed ? 1 : 0); ++i) {
      const int a = ch[i].second, b = ch[(i + 1) % m].second;
      if(a != b) queue.emplace(length(a, b), a, b);
    }
  }
  // a piece not found (a chain broken by a seam vertex) is not a background edge: left out
  return split_longest_at_input_midpoints(itri, input, queue, longest, most, [](int) { return true; }, "the creases");
}

// The crease sites: per curve, the background vertices of its sites strictly inside it (open curve) or
// all around it (closed curve), in order along it; and per curve the chain to check after the dual.
struct Crease_sites {
  std::vector<std::vector<int>> vertices;  // per curve, its sites' background vertices in order
  std::size_t size() const
  {
    std::size_t k = 0;
    for(const auto& c : vertices) k += c.size();
    return k;
  }
};

// Places the sites of every crease curve: between its ends (corners, fixed already or left out by
// corners_to_fix()) round(L / h) - 1 sites at equal metric arc length (L the curve's metric length),
// around a closed curve max(3, round(L / h)); each at the chain vertex (crease_chains()) nearest in arc
// length, never an end and never a vertex `taken` already (a corner's). In all at most `budget` sites
// (the curves with most sites lose one first). A curve with a chain too coarse for its sites gets fewer
// (the vertex of the previous site is not taken twice). A site closer than half of `h` (in the metric, as
// corners_to_fix() measures) to a fixed corner (`fixed`) or to a site placed before it is left out: two
// fixed sites that close make a sliver (CGAL's helmet at 1000 vertices, its 42 short crease curves:
// theta_min 8.4 degrees with them, 23.9 without creases followed).
inline Crease_sites place_crease_sites(const Intrinsic_triangulation& itri, const Feature_graph& g,
                                       const std::vector<std::vector<std::pair<double, int>>>& chains, double h,
                                       std::vector<char> taken, std::size_t budget, const std::vector<std::size_t>& fixed = {})
{
  std::vector<int> placed(fixed.begin(), fixed.end());
  auto apart = [&](int v) {
    for(int w : placed)
      if((0.5 * (itri.Q(v) + itri.Q(w)) * (itri.position(w) - itri.position(v))).norm() < 0.5 * h) return false;
    return true;
  };
  const std::size_t nc = g.curves.size();
  std::vector<std::vector<double>> arc(nc);  // metric arc length at each chain vertex (closed: plus the way back)
  std::vector<std::size_t> count(nc, 0);
  std::size_t total = 0;
  for(std::size_t c = 0; c < nc; ++c) {
    const auto& ch = chains[c];
    if(ch.size() < 2) continue;
    const bool closed = g.curves[c].closed;
    arc[c].push_back(0);
    for(std::size_t i = 1; i < ch.size() + (closed ? 1 : 0); ++i) {
      const int u = ch[i - 1].second, v = ch[i % ch.size()].second;
      arc[c].push_back(arc[c].back() + metric_segment_length(itri.position(u), itri.position(v), itri.Q(u), itri.Q(v)));
    }
    const double m = std::round(arc[c].back() / h);
    count[c] = closed ? std::size_t(std::max(3.0, m)) : std::size_t(std::max(0.0, m - 1));
    total += count[c];
  }
  while(total > budget) {
    std::size_t most = nc;
    for(std::size_t c = 0; c < nc; ++c)
      if(count[c] > 0 && (most == nc || count[c] > count[most])) most = c;
    if(most == nc) break;
    --count[most];
    --total;
  }
  Crease_sites out;
  out.vertices.resize(nc);
  for(std::size_t c = 0; c < nc; ++c) {
    const auto& ch = chains[c];
    const bool closed = g.curves[c].closed;
    if(count[c] == 0) continue;
    const double len = arc[c].back();
    const double step = len / double(closed ? count[c] : count[c] + 1);
    std::size_t i = 0;
    for(std::size_t k = 0; k < count[c]; ++k) {
      const double target = closed ? (double(k) + 0.5) * step : double(k + 1) * step;
      while(i + 1 < arc[c].size() && arc[c][i + 1] <= target) ++i;
      std::size_t best = (i + 1 < arc[c].size() && arc[c][i + 1] - target < target - arc[c][i]) ? i + 1 : i;
      if(!closed && best == 0) best = 1;
      if(!closed && best + 1 >= ch.size()) best = ch.size() - 2;
      if(!closed && best == 0) continue;  // a chain of two vertices: its ends only
      const int v = ch[best % ch.size()].second;
      if(taken[std::size_t(v)] || !apart(v)) continue;
      taken[std::size_t(v)] = 1;
      placed.push_back(v);
      out.vertices[c].push_back(v);
    }
  }
  return out;
}

// the smallest angle, in degrees, of the triangle `T` of `points` (in space)
inline double smallest_angle_in_space(const std::vector<Eigen::Vector3d>& points, const std::array<std::size_t, 3>& T)
{
  double m = 180;
  for(int i = 0; i < 3; ++i) {
    const Eigen::Vector3d u = points[T[std::size_t((i + 1) % 3)]] - points[T[std::size_t(i)]],
                          v = points[T[std::size_t((i + 2) % 3)]] - points[T[std::size_t(i)]];
    m = std::min(m, std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / 3.14159265358979323846);
  }
  return m;
}

// The faces of `faces` with a corner at `v`, in increasing index, from `face_of` (directed edge -> face, as
// recover_crease_edges() keeps it): those of the directed edges leaving `v`, contiguous in the map's order.
// O(log F + valence of v).
inline std::vector<std::size_t> faces_at(const std::map<std::pair<std::size_t, std::size_t>, std::size_t>& face_of, std::size_t v)
{
  std::vector<std::size_t> around;
  for(auto it = face_of.lower_bound({v, 0}); it != face_of.end() && it->first.first == v; ++it) around.push_back(it->second);
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  return around;
}

// Makes the faces `which[i]` of `faces` the triangles `with[i]` (an edge flip, or the undo of several), the
// directed edges of `face_of` (directed edge -> face) updated: all the old faces' erased, then the new
// ones' set.
inline void replace_faces(std::vector<std::array<std::size_t, 3>>& faces, std::map<std::pair<std::size_t, std::size_t>, std::size_t>& face_of,
                          const std::vector<std::size_t>& which, const std::vector<std::array<std::size_t, 3>>& with)
{
  for(const std::size_t h : which)
    for(int k = 0; k < 3; ++k) face_of.erase({faces[h][std::size_t(k)], faces[h][std::size_t((k + 1) % 3)]});
  for(std::size_t i = 0; i < which.size(); ++i) faces[which[i]] = with[i];
  for(const std::size_t h : which)
    for(int k = 0; k < 3; ++k) face_of[{faces[h][std::size_t(k)], faces[h][std::size_t((k + 1) % 3)]}] = h;
}

// Joins the output vertices `a` and `b` of `out` by an edge through a sequence of edge flips, the
// flip-based edge recovery of constrained Delaunay triangulation (Sloan, "A fast algorithm for generating
// constrained Delaunay triangulations", Computers & Structures 47(3), 1993, section 3; Shewchuk's
// "Lecture notes on Delaunay mesh generation", 1999, section 2.5), on the surface: the triangles around the
// segment from a to b are projected onto the plane normal to the area-weighted mean normal of the
// triangles at a and b. The walk from a toward b lists the output edges the segment crosses (it fails when
// the segment meets a vertex, a boundary edge or an edge of `is_kept`); each is flipped in turn when its
// two triangles make a convex quadrilateral in that plane, both its ends keep 3 neighbours or more
// (`valence`) and neither new triangle is inverted (triangle_is_inverted(), the input's normals), else it
// goes back to the end of the list; a new edge that still crosses the segment goes back too. At most
// `max_flips` flips. Then the edges of the changed triangles other than (a, b) and the kept ones are
// flipped where that raises the smallest angle of their two triangles (Lawson's local improvement, same
// guards, 3 rounds), and the whole sequence is accepted only when the smallest angle of
// the triangles it changed is at least the old ones' or `least_angle` degrees. Returns whether (a, b) is an
// edge after; when not, `out.faces`, `face_of` and `valence` are as they were. Local: the faces at a and
// b come from `face_of` (faces_at()), and an undo restores only the faces changed, their directed edges
// and the valences of the flips' ends, so a call costs O((valence + flips) log F), not O(F).
template <typename Kept>
bool recover_edge_by_flips(const Input_surface& surface, Remeshed_surface& out,
                           std::map<std::pair<std::size_t, std::size_t>, std::size_t>& face_of,
                           std::vector<std::size_t>& valence, std::size_t a, std::size_t b, double side,
                           const Kept& is_kept, std::size_t max_flips, double least_angle)
{
  if(a == b || a >= out.points.size() || b >= out.points.size()) return false;
  // the faces at a and at b, in increasing index (the sum of their normals in that order)
  const std::vector<std::size_t> at_a = faces_at(face_of, a);
  Eigen::Vector3d n(0, 0, side < 0 ? -1 : 1);
  if(!surface.is_planar()) {
    std::vector<std::size_t> around = faces_at(face_of, b);
    around.insert(around.end(), at_a.begin(), at_a.end());
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    n = Eigen::Vector3d::Zero();
    for(const std::size_t f : around) {
      const auto& F = out.faces[f];
      n += (out.points[F[1]] - out.points[F[0]]).cross(out.points[F[2]] - out.points[F[0]]);
    }
  }
  if(!(n.norm() > 0)) return false;
  n.normalize();
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1), pa = out.points[a];
  auto xy = [&](std::size_t v) {
    const Eigen::Vector3d d = out.points[v] - pa;
    return Eigen::Vector2d(d.dot(e1), d.dot(e2));
  };
  const double ab2 = (xy(b)).squaredNorm();
  if(!(ab2 > 0)) return false;
  const double eps = 1e-12 * ab2;
  // sign of the turn p -> q -> r in the plane: +1 left, -1 right, 0 within eps
  auto orient = [&](std::size_t p, std::size_t q, std::size_t r) {
    const Eigen::Vector2d P = xy(p), u = xy(q) - P, w = xy(r) - P;
    const double o = u.x() * w.y() - u.y() * w.x();
    return o > eps ? 1 : (o < -eps ? -1 : 0);
  };
  auto third = [&](std::size_t f, std::size_t p, std::size_t q) {
    const auto& F = out.faces[f];
    return F[0] + F[1] + F[2] - p - q;
  };
  auto has_edge = [&](std::size_t p, std::size_t q) { return face_of.count({p, q}) || face_of.count({q, p}); };
  // does the edge (p, q) cross the open segment (a, b)?
  auto crosses = [&](std::size_t p, std::size_t q) {
    if(p == a || p == b || q == a || q == b) return false;
    return orient(a, b, p) * orient(a, b, q) < 0 && orient(p, q, a) * orient(p, q, b) < 0;
  };
  // 1. the walk: the first crossed edge is opposite a in one of its triangles
  std::size_t x = out.points.size(), y = x;
  for(const std::size_t f : at_a) {
    const auto& F = out.faces[f];
    int k = 0;
    while(k < 3 && F[std::size_t(k)] != a) ++k;
    if(k == 3) continue;
    const std::size_t p = F[std::size_t((k + 1) % 3)], q = F[std::size_t((k + 2) % 3)];
    if(orient(a, b, p) == 0 || orient(a, b, q) == 0) {
      if(orient(a, b, p) == 0 && (xy(p) - xy(a)).dot(xy(b) - xy(a)) > 0) return false;  // a vertex on the way
      if(orient(a, b, q) == 0 && (xy(q) - xy(a)).dot(xy(b) - xy(a)) > 0) return false;
      continue;
    }
    if(crosses(p, q)) {
      x = p;
      y = q;
      break;
    }
  }
  if(x == out.points.size()) return false;
  std::vector<std::pair<std::size_t, std::size_t>> crossed;
  for(;;) {
    if(crossed.size() >= max_flips || is_kept(x, y)) return false;
    crossed.emplace_back(x, y);
    const auto g = face_of.find({y, x});
    if(g == face_of.end()) return false;  // a boundary edge
    const std::size_t r = third(g->second, x, y);
    if(r == b) break;
    const int sr = orient(a, b, r);
    if(sr == 0) return false;
    if(sr == orient(a, b, x)) x = r;
    else y = r;
  }
  // 2. flip them in turn
  // what an undo needs: the faces changed with what they were, and the flips (for the valences)
  std::vector<std::size_t> touched;
  std::vector<std::array<std::size_t, 3>> before_faces;
  std::vector<std::array<std::size_t, 4>> flipped;  // (u, v, w1, w2): u and v lost a neighbour, w1 and w2 gained one
  auto restore = [&] {
    replace_faces(out.faces, face_of, touched, before_faces);
    for(const auto& e : flipped) {
      ++valence[e[0]];
      ++valence[e[1]];
      --valence[e[2]];
      --valence[e[3]];
    }
    return false;
  };
  auto smallest_angle = [&](const std::array<std::size_t, 3>& T) { return smallest_angle_in_space(out.points, T); };
  // flips (u, v) when allowed (see above); `improve_only`: only when that raises the smallest angle
  auto flip = [&](std::size_t u, std::size_t v, bool improve_only) {
    const auto fi = face_of.find({u, v}), gi = face_of.find({v, u});
    if(fi == face_of.end() || gi == face_of.end()) return false;
    const std::size_t f = fi->second, g = gi->second;
    const std::size_t w1 = third(f, u, v), w2 = third(g, u, v);  // (u, v, w1) and (v, u, w2)
    if(w1 == w2 || has_edge(w1, w2) || valence[u] <= 3 || valence[v] <= 3 || is_kept(u, v)) return false;
    if(orient(u, v, w1) * orient(u, v, w2) >= 0 || orient(w1, w2, u) * orient(w1, w2, v) >= 0) return false;
    const std::array<std::size_t, 3> T1 = {{w1, u, w2}}, T2 = {{w2, v, w1}};
    for(const auto& T : {T1, T2})
      if(triangle_is_inverted(surface, out.points[T[0]], out.points[T[1]], out.points[T[2]], out.surface_points[T[0]],
                              out.surface_points[T[1]], out.surface_points[T[2]], side))
        return false;
    if(improve_only &&
       !(std::min(smallest_angle(T1), smallest_angle(T2)) > std::min(smallest_angle(out.faces[f]), smallest_angle(out.faces[g]))))
      return false;
    for(const std::size_t h : {f, g})
      if(std::find(touched.begin(), touched.end(), h) == touched.end()) {
        touched.push_back(h);
        before_faces.push_back(out.faces[h]);  // not changed before: as it was
      }
    replace_faces(out.faces, face_of, {f, g}, {T1, T2});
    flipped.push_back({{u, v, w1, w2}});
    --valence[u];
    --valence[v];
    ++valence[w1];
    ++valence[w2];
    return true;
  };
  std::deque<std::pair<std::size_t, std::size_t>> queue(crossed.begin(), crossed.end());
  std::size_t flips = 0, idle = 0;
  while(!queue.empty()) {
    if(flips >= max_flips || idle > queue.size()) return restore();  // a whole round without a flip: stuck
    const auto e = queue.front();
    queue.pop_front();
    const auto fi = face_of.find({e.first, e.second});
    const std::size_t w1 = fi == face_of.end() ? 0 : third(fi->second, e.first, e.second);
    const auto gi = face_of.find({e.second, e.first});
    const std::size_t w2 = gi == face_of.end() ? 0 : third(gi->second, e.first, e.second);
    if(!flip(e.first, e.second, false)) {
      queue.push_back(e);
      ++idle;
      continue;
    }
    ++flips;
    idle = 0;
    if(crosses(w1, w2)) queue.emplace_back(w1, w2);
  }
  if(!has_edge(a, b)) return restore();
  // 3. the edges of the triangles changed, but (a, b) and the kept ones: flipped where that raises the
  //    smallest angle of their two triangles (Lawson's local improvement, the same guards), 3 rounds
  for(int pass = 0; pass < 3; ++pass) {
    std::vector<std::pair<std::size_t, std::size_t>> edges;
    for(const std::size_t h : touched)
      for(int k = 0; k < 3; ++k) {
        const std::size_t u = out.faces[h][std::size_t(k)], v = out.faces[h][std::size_t((k + 1) % 3)];
        if(std::min(u, v) == std::min(a, b) && std::max(u, v) == std::max(a, b)) continue;
        edges.emplace_back(std::min(u, v), std::max(u, v));
      }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    bool any = false;
    for(const auto& e : edges)
      if(face_of.count({e.first, e.second}) && flip(e.first, e.second, true)) any = true;
    if(!any) break;
  }
  if(!has_edge(a, b)) return restore();
  double before = 180, after = 180;
  for(const auto& T : before_faces) before = std::min(before, smallest_angle(T));
  for(const std::size_t h : touched) after = std::min(after, smallest_angle(out.faces[h]));
  if(after < std::min(before, least_angle)) return restore();
  return true;
}

// Recovers and locks the crease edges of the output `out`: `chains` lists, per curve, its sites' output
// vertex indices in order along it (with its fixed corners at the ends; `closed` per chain: the last is
// joined to the first). A pair not joined by an output edge is joined by flipping the one edge (c, d)
// whose two triangles (a, c, d) and (d, c, b) hold it, when c and d keep 3 neighbours or more, neither
// new triangle is inverted (triangle_is_inverted()) and their smallest angle is at least the old two's or
// 20 degrees; a pair that one flip cannot join is joined by a sequence of flips, recover_edge_by_flips()
// (at most 64 flips, the changed triangles' smallest angle at least the old ones' or 15 degrees: at 20
// it joins none of spool's 33 such pairs, at 15 16, at 10 23, at the cost of theta_min, benchmark/features.md;
// the edges already kept or joining another pair never flipped), else the mesh is left as it was for that pair; the pairs joined are
// appended to `out.kept_edges`. Returns (pairs joined by flips, pairs left unjoined).
inline std::pair<std::size_t, std::size_t> recover_crease_edges(const Input_surface& surface, Remeshed_surface& out,
                                                                const std::vector<std::vector<std::size_t>>& chains,
                                                                const std::vector<char>& closed)
{
  // directed edge -> face, built once and kept up to date by each flip (replace_faces())
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> face_of;
  for(std::size_t f = 0; f < out.faces.size(); ++f)
    for(int k = 0; k < 3; ++k) face_of[{out.faces[f][std::size_t(k)], out.faces[f][std::size_t((k + 1) % 3)]}] = f;
  std::vector<std::size_t> valence(out.points.size(), 0);  // neighbours (on the boundary too)
  for(const auto& e : face_of)
    if(e.first.first < e.first.second || !face_of.count({e.first.second, e.first.first})) {
      ++valence[e.first.first];
      ++valence[e.first.second];
    }
  const double side = planar_side(surface);
  auto kept = [&](std::size_t a, std::size_t b) {
    const std::array<std::size_t, 2> e = {{std::min(a, b), std::max(a, b)}};
    return std::find(out.kept_edges.begin(), out.kept_edges.end(), e) != out.kept_edges.end();
  };
  // the sequence flips no edge that joins consecutive sites either, those of pairs still to come included
  std::vector<std::array<std::size_t, 2>> pairs;
  for(std::size_t c = 0; c < chains.size(); ++c)
    for(std::size_t i = 0; chains[c].size() >= 2 && i + 1 < chains[c].size() + (closed[c] ? 1 : 0); ++i) {
      const std::size_t a = chains[c][i], b = chains[c][(i + 1) % chains[c].size()];
      pairs.push_back({{std::min(a, b), std::max(a, b)}});
    }
  std::sort(pairs.begin(), pairs.end());
  auto kept_or_pair = [&](std::size_t a, std::size_t b) {
    return kept(a, b) || std::binary_search(pairs.begin(), pairs.end(), std::array<std::size_t, 2>{{std::min(a, b), std::max(a, b)}});
  };
  std::size_t recovered = 0, missing = 0;
  for(std::size_t c = 0; c < chains.size(); ++c) {
    const auto& ch = chains[c];
    const std::size_t m = ch.size();
    if(m < 2) continue;
    for(std::size_t i = 0; i + 1 < m + (closed[c] ? 1 : 0); ++i) {
      const std::size_t a = ch[i], b = ch[(i + 1) % m];
      if(a == b) continue;
      if(face_of.count({a, b}) || face_of.count({b, a})) {
        if(!kept(a, b)) out.kept_edges.push_back({{std::min(a, b), std::max(a, b)}});
        continue;
      }
      bool done = false;
      for(int pass = 0; pass < 2 && !done; ++pass) {
        const std::size_t x = pass == 0 ? a : b, y = pass == 0 ? b : a;
        for(const std::size_t f : faces_at(face_of, x)) {
          if(done) break;
          const auto& F = out.faces[f];
          int k = 0;
          while(k < 3 && F[std::size_t(k)] != x) ++k;
          if(k == 3) continue;
          const std::size_t p = F[std::size_t((k + 1) % 3)], q = F[std::size_t((k + 2) % 3)];  // face (x, p, q)
          const auto g = face_of.find({q, p});
          if(g == face_of.end()) continue;
          const auto& G = out.faces[g->second];
          std::size_t r = G[0] + G[1] + G[2] - p - q;  // face (q, p, r)
          if(r != y || valence[p] <= 3 || valence[q] <= 3 || kept(p, q)) continue;
          // (x, p, q) and (q, p, y) become (x, p, y) and (x, y, q)
          const std::array<std::size_t, 3> T1 = {{x, p, y}}, T2 = {{x, y, q}};
          bool inverted = false;
          for(const auto& T : {T1, T2})
            inverted = inverted || triangle_is_inverted(surface, out.points[T[0]], out.points[T[1]], out.points[T[2]],
                                                        out.surface_points[T[0]], out.surface_points[T[1]], out.surface_points[T[2]], side);
          if(inverted) continue;
          // nor a sliver: the smallest angle of the two new triangles (in space) at least that of the two
          // old ones, or 20 degrees (a flip joining two corners across a short crease made a 4-degree
          // triangle on CGAL's helmet)
          auto smallest_angle = [&](const std::array<std::size_t, 3>& T) { return smallest_angle_in_space(out.points, T); };
          const double before = std::min(smallest_angle(F), smallest_angle(G)), after = std::min(smallest_angle(T1), smallest_angle(T2));
          if(after < std::min(before, 20.0)) continue;
          replace_faces(out.faces, face_of, {f, g->second}, {T1, T2});
          --valence[p];
          --valence[q];
          ++valence[x];
          ++valence[y];
          done = true;
        }
      }
      if(!done) done = recover_edge_by_flips(surface, out, face_of, valence, a, b, side, kept_or_pair, 64, 15.0);
      if(done) {
        ++recovered;
        out.kept_edges.push_back({{std::min(a, b), std::max(a, b)}});
      } else {
        ++missing;
      }
    }
  }
  return {recovered, missing};
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_FEATURES_CREASE_SITES_H
