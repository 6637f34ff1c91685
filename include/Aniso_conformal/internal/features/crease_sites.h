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
#include <Aniso_conformal/internal/features/edge_recovery_by_flips.h>
#include <Aniso_conformal/internal/features/fixed_corner_sites.h>
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
      if(closer_than_half_an_edge(itri, v, w, h)) return false;
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
  Directed_edge_faces face_of;
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
