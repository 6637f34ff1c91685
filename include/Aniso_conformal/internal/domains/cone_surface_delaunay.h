// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_SURFACE_DELAUNAY_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_SURFACE_DELAUNAY_H

#include <Aniso_conformal/internal/domains/cone_surface_triangulation.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstddef>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

// The Delaunay triangulation of points on a closed flat surface with cone singularities, computed
// intrinsically, so that it is one triangulation of the whole surface by construction (the charts of the
// cone domain each see a Euclidean plane, and next to a cone of negative curvature their Delaunay
// triangles disagree). The surface is given as a triangulation by edge lengths (the background of the cone
// domain in the cone metric: flat at every vertex but the cones):
//  1. each point is inserted into its face (the face split in three, lengths from the face's layout);
//  2. edge flips to the intrinsic Delaunay triangulation (Bobenko and Springborn 2007, "A discrete
//     Laplace-Beltrami operator for simplicial surfaces"; every non-Delaunay edge is flippable);
//  3. every flat vertex that is not a point is removed: its star, unfolded in the plane (angle sum 2 pi),
//     is triangulated again by ear clipping (Sharp, Soliman and Crane 2019, "Navigating intrinsic
//     triangulations", section 4, remove a vertex), and the flips of 2 are made again;
//  4. the cones left (and any vertex step 3 could not remove) are merged into their nearest point along
//     an edge (an edge collapse, when the link condition holds), so the triangles join points only; what
//     no collapse, fan or flip mends (a thin part narrower than the points' spacing: a point whose cell
//     wraps around a tip, another inside its loop) is re-triangulated as one point's star over a region
//     grown until its border is a cycle of distinct points; what that leaves unmerged or tangled gets a
//     point moved onto the cone (the nearest one allowed to move) and the triangulation is made again.

namespace Aniso_conformal {
namespace internal {

class Cone_surface_delaunay : public Cone_surface_triangulation {
public:
  using Cone_surface_triangulation::Cone_surface_triangulation;

  /// a point that triangulate() moved onto a cone: the point, and a background face and corner at that cone
  struct Moved_point {
    std::size_t point = 0;
    int face = -1, corner = -1;
  };

  /*
   * The triangles of the Delaunay triangulation of `points` (indices into it), oriented like the faces.
   * A cone that no merge, fan or grown star joins to the points (a thin part narrower than the points'
   * spacing, whose link passes the same points twice: CGAL's femur at 2000 sites has a cone of 278 degrees
   * of degree 5 whose link is a b c c b), or one merged into a point whose edges stay doubled or looped
   * (femur, 1500 sites), or, when no cone was merged into such a point, one merged into a neighbour of it
   * (femur with the curvature metric, 2000 sites: a point of degree 6 whose star wraps a thin handle and
   * meets one neighbour twice), is served instead by its nearest point of index at least `first_movable` (along
   * the edges), moved onto it, and the triangulation is made again (up to 8 times); a point at a cone is a
   * vertex of the triangulation there, with the cone's angle. moved_points() lists them, none with the
   * default `first_movable` (the points' count).
   * \throws Convergence_failure if two points coincide, a point's face is not a face, the flips do not
   *         end, or a vertex other than a point cannot be merged into a point nor served by a moved point
   */
  std::vector<std::array<std::size_t, 3>> triangulate(std::vector<Point_on_face> points, std::size_t first_movable = std::size_t(-1))
  {
    m_moved.clear();
    std::vector<char> moved(points.size(), 0);
    for(int round = 0;; ++round) {
      m_relaxed = false;
      m_fan_doubling = false;
      m_unmerged.clear();
      insert_and_remove_flat_vertices(points);
      try {
        std::vector<std::array<std::size_t, 3>> out = collapse_to_points(points.size());
        m_stats.moved = m_moved.size();
        return out;
      } catch(const Convergence_failure&) {
        if(m_unmerged.empty() || round == 8 || !move_points_onto_unmerged_cones(points, moved, first_movable)) throw;
      }
    }
  }
  /// the points moved onto cones by the last triangulate()
  const std::vector<Moved_point>& moved_points() const { return m_moved; }

private:
  // For each cone of m_unmerged, its nearest point of index >= first_movable not moved yet (`moved`) along
  // the edges (its neighbours first: at most 256 vertices visited), moved onto it: `points` changed and
  // m_moved extended. false if no cone found one.
  bool move_points_onto_unmerged_cones(std::vector<Point_on_face>& points, std::vector<char>& moved, std::size_t first_movable)
  {
    bool any = false;
    const std::size_t first = m_nb + std::min(first_movable, points.size()), end = m_nb + points.size();
    // each cone's first corner in the faces (the lowest face), found in one pass
    std::map<int, std::pair<int, int>> corner;
    for(const auto& u : m_unmerged) corner.emplace(u.first, std::make_pair(-1, -1));
    for(std::size_t f = 0; f < m_faces0->size(); ++f)
      for(int k = 0; k < 3; ++k) {
        const auto it = corner.find((*m_faces0)[f][std::size_t(k)]);
        if(it != corner.end() && it->second.first < 0) it->second = {int(f), k};
      }
    for(const auto& [v, start] : m_unmerged) {
      std::size_t j = std::size_t(-1);
      std::map<int, double> dist = {{start, 0.0}};
      std::set<std::pair<double, int>> queue = {{0.0, start}};
      for(std::size_t visited = 0; !queue.empty() && visited < 256; ++visited) {
        const auto [d, x] = *queue.begin();
        queue.erase(queue.begin());
        if(std::size_t(x) >= first && std::size_t(x) < end && !moved[std::size_t(x) - m_nb]) {
          j = std::size_t(x) - m_nb;
          break;
        }
        for(int sp : spokes_of(x)) {
          const int w = head(sp);
          const double dw = d + m_len[std::size_t(sp)];
          const auto it = dist.find(w);
          if(it != dist.end() && !(dw < it->second)) continue;
          if(it != dist.end()) queue.erase({it->second, w});
          dist[w] = dw;
          queue.insert({dw, w});
        }
      }
      const auto [f, k] = corner[v];
      if(j == std::size_t(-1) || f < 0) continue;
      points[j].face = f;
      points[j].x = (*m_layout)[std::size_t(f)][std::size_t(k)];
      moved[j] = 1;
      m_moved.push_back({j, f, k});
      any = true;
    }
    return any;
  }

  // Adds to m_unmerged the cones merged into a site of `tangled`, or, if none, those merged into a
  // neighbour of one (a site whose star wraps around a thin part: the cone in the part gets a point of
  // its own).
  void add_cones_merged_near(const std::vector<int>& tangled)
  {
    auto is_tangled = [&](int x) { return std::find(tangled.begin(), tangled.end(), x) != tangled.end(); };
    for(std::size_t c = 0; c < m_nb; ++c)
      if(m_merged_into[c] >= 0 && is_tangled(m_merged_into[c])) m_unmerged.push_back({int(c), m_merged_into[c]});
    if(!m_unmerged.empty()) return;
    for(std::size_t c = 0; c < m_nb; ++c) {
      if(m_merged_into[c] < 0) continue;
      bool near = false;
      for(int sp : spokes_of(m_merged_into[c])) near = near || is_tangled(head(sp));
      if(near) m_unmerged.push_back({int(c), m_merged_into[c]});
    }
  }

  // Collapses the edge of h (x -> p) into p: the faces (x, p, q) and (p, x, r) go, their outer edges are
  // glued. false (nothing done) unless the link condition holds (x and p have q and r as their only
  // common neighbours, q != r) and the faces are glued simply.
  bool collapse(int h, bool strict = true)
  {
    const int x = m_tail[std::size_t(h)], p = head(h), t = m_twin[std::size_t(h)];
    const int hn = next(h), hp = prev(h), tn = next(t), tp = prev(t);
    const int q = m_tail[std::size_t(hp)], r = m_tail[std::size_t(tp)];
    if(x == p || q == r || h / 3 == t / 3) return false;
    const int A = m_twin[std::size_t(hn)], B = m_twin[std::size_t(hp)], C = m_twin[std::size_t(tn)], D = m_twin[std::size_t(tp)];
    for(int y : {A, B, C, D})
      if(y / 3 == h / 3 || y / 3 == t / 3) return false;
    const std::vector<int> sx = spokes_of(x), sp = spokes_of(p);
    if(sx.empty() || sp.empty()) return false;
    std::set<int> nx, np;
    for(int s : sx) nx.insert(head(s));
    for(int s : sp) np.insert(head(s));
    if(nx.count(x) || np.count(p)) return false;
    std::size_t times = 0;  // p among x's neighbours: more than once would fold a face onto p
    for(int s : sx) times += head(s) == p;
    if(times != 1) return false;
    std::size_t common = 0;
    for(int y : nx)
      if(y != p && np.count(y)) {
        if(strict && y != q && y != r) return false;
        ++common;
      }
    if(strict && common != 2) return false;
    m_twin[std::size_t(A)] = B, m_twin[std::size_t(B)] = A;
    m_twin[std::size_t(C)] = D, m_twin[std::size_t(D)] = C;
    for(int s : sx) m_tail[std::size_t(s)] = p;
    m_alive[std::size_t(h / 3)] = m_alive[std::size_t(t / 3)] = 0;
    m_out[std::size_t(x)] = -1;
    m_out[std::size_t(p)] = B;
    m_out[std::size_t(q)] = A;
    m_out[std::size_t(r)] = C;
    return true;
  }

  // Removes a vertex of degree 2 (spokes x -> a, x -> b): its faces (x, a, b) and (x, b, a) go, and the
  // edges a b on their far sides become one. false if the faces are glued otherwise.
  bool remove_degree_two(const std::vector<int>& sx)
  {
    const int F = sx[0] / 3, G = sx[1] / 3;
    if(F == G) return false;
    const int A = m_twin[std::size_t(next(sx[0]))], B = m_twin[std::size_t(next(sx[1]))];
    if(A / 3 == F || A / 3 == G || B / 3 == F || B / 3 == G) return false;
    const int x = m_tail[std::size_t(sx[0])];
    m_twin[std::size_t(A)] = B, m_twin[std::size_t(B)] = A;
    m_alive[std::size_t(F)] = m_alive[std::size_t(G)] = 0;
    m_out[std::size_t(x)] = -1;
    m_out[std::size_t(m_tail[std::size_t(A)])] = A;
    m_out[std::size_t(m_tail[std::size_t(B)])] = B;
    return true;
  }

  // Removes a vertex x of degree 1 (a sharp cone inside a loop edge a a: its face (x, a, a)): the face goes,
  // and so does the loop, the face (a, a, z) on its far side closing up into the edge a z. false if the
  // faces are glued otherwise.
  bool remove_degree_one(int h)
  {
    const int F = h / 3, L = next(h), M = m_twin[std::size_t(L)], G = M / 3;
    if(G == F || m_tail[std::size_t(L)] != head(L)) return false;
    const int g1 = next(M), g2 = prev(M);
    const int A = m_twin[std::size_t(g1)], B = m_twin[std::size_t(g2)];
    if(A / 3 == F || A / 3 == G || B / 3 == F || B / 3 == G) return false;
    m_twin[std::size_t(A)] = B, m_twin[std::size_t(B)] = A;
    m_alive[std::size_t(F)] = m_alive[std::size_t(G)] = 0;
    m_out[std::size_t(m_tail[std::size_t(h)])] = -1;
    m_out[std::size_t(m_tail[std::size_t(A)])] = A;
    m_out[std::size_t(m_tail[std::size_t(B)])] = B;
    return true;
  }

  // v (a cone) removed if of degree 1 or 2, else merged into its nearest neighbouring site for which the
  // link condition holds; false if none does (yet)
  bool merge_into_site(int v)
  {
    const std::vector<int> sx = spokes_of(v);
    if(sx.empty()) return false;
    if((sx.size() == 1 && remove_degree_one(sx[0])) || (sx.size() == 2 && remove_degree_two(sx))) {
      m_merged_into[std::size_t(v)] = head(sx[0]);
      return true;
    }
    std::vector<std::pair<double, int>> candidates;
    for(int s : sx)
      if(std::size_t(head(s)) >= m_nb) candidates.push_back({m_len[std::size_t(s)], s});
    std::sort(candidates.begin(), candidates.end());
    for(int strict = 1; strict >= (m_relaxed ? 0 : 1); --strict)
      // none keeps the link condition (strict = 0): the nearest whose merge folds no face; the edges it
      // doubles are flipped away after (collapse_to_points())
      for(const auto& c : candidates)
        if(collapse(c.second, strict == 1)) {
          m_merged_into[std::size_t(v)] = head(c.second);
          return true;
        }
    return false;
  }

  // The cluster of v (the vertices other than points joined to v by edges through such vertices: cones
  // next to each other, or a cone inside a loop edge of another) and every face at it removed, the hole
  // left (a disk whose border joins points only, each once) triangulated as a fan from one border point
  // that no diagonal doubles. false (nothing done) if the hole is not such a disk or no point serves.
  bool replace_cluster_by_fan(int v)
  {
    std::set<int> cluster = {v};
    std::vector<int> queue = {v};
    std::set<int> sites_next;  // the points joined to the cluster, nearest first below
    std::vector<std::pair<double, int>> nearest;
    while(!queue.empty()) {
      const int x = queue.back();
      queue.pop_back();
      const std::vector<int> sx = spokes_of(x);
      if(sx.empty()) return false;
      for(int s : sx) {
        const int y = head(s);
        if(std::size_t(y) < m_nb && cluster.insert(y).second) queue.push_back(y);
        if(std::size_t(y) >= m_nb && sites_next.insert(y).second) nearest.push_back({m_len[std::size_t(s)], y});
      }
    }
    if(fan_over_region(cluster, -1)) return true;
    // else the region of the cluster and of one of its sites, fanned from that site inside it
    std::sort(nearest.begin(), nearest.end());
    for(const auto& p : nearest)
      if(fan_over_region(cluster, p.second)) return true;
    // else that region grown by the faces across its border, once to three times, so that its border
    // becomes a cycle of distinct sites: a thin part (a horn, a tail) narrower than the sites' spacing has
    // one site near its tip whose only neighbour is the next site down, whose cell wraps around the tip
    // (the cone's link a a b, b of degree 2); the star of b over the grown region joins it to the sites
    // beyond, which a mesh of the tip needs (tried last: in the pass whose fans may double an edge)
    for(int grow = 1; grow <= 3 && m_fan_doubling; ++grow)
      for(const auto& p : nearest)
        if(fan_over_region(cluster, p.second, grow)) {
          ++m_stats.grown_fans;
          return true;
        }
    return false;
  }

  // The faces at `cluster` (and at the point `inside`, if >= 0) replaced: by a fan from a border point
  // (inside < 0) or from `inside`. false (nothing done) unless they form a disk whose border is one cycle
  // of points (not `inside`; distinct for a fan from `inside`); a fan from the border starts at a point
  // met once on it (the border may pass a point twice: a site whose cell wraps around a sharp cone, the
  // link a b a c of a cone) and no diagonal doubles an edge.
  bool fan_over_region(const std::set<int>& cluster, int inside, int grow = 0)
  {
    std::set<int> region;
    for(int x : cluster)
      for(int s : spokes_of(x)) region.insert(s / 3);
    if(inside >= 0) {
      const std::vector<int> si = spokes_of(inside);
      if(si.empty()) return false;
      for(int s : si) region.insert(s / 3);
    }
    for(int g = 0; g < grow; ++g) {  // the faces across the border added (the star from `inside` only)
      if(inside < 0) return false;
      std::vector<int> across;
      for(int f : region)
        for(int k = 0; k < 3; ++k) {
          const int t = m_twin[std::size_t(3 * f + k)] / 3;
          if(!region.count(t)) across.push_back(t);
        }
      region.insert(across.begin(), across.end());
    }
    // the border: halfedges of the region whose twin is outside it, walked as one cycle (around each
    // border point through the region's faces, so that a point met twice, a site whose cell wraps
    // around a sharp cone, is passed correctly)
    std::vector<int> border;
    for(int f : region)
      for(int k = 0; k < 3; ++k) {
        const int h = 3 * f + k;
        if(region.count(m_twin[std::size_t(h)] / 3)) continue;
        if(std::size_t(m_tail[std::size_t(h)]) < m_nb || std::size_t(head(h)) < m_nb) return false;
        border.push_back(h);
      }
    const std::size_t L = border.size();
    const std::size_t interior = cluster.size() + (inside >= 0 ? 1 : 0);
    // a disk: F = L + 2 V_inside - 2; a digon (L = 2) only around a site (its star: two triangles on the
    // same three points, whose doubled edge is flipped away after), as a last resort
    if(L < (inside >= 0 && m_fan_doubling ? 2u : 3u) || region.size() + 2 != L + 2 * interior) return false;
    std::vector<int> cycle = {border.front()};
    while(cycle.size() <= L) {
      int g = next(cycle.back());
      for(std::size_t turns = 0; region.count(m_twin[std::size_t(g)] / 3); ++turns) {
        if(turns > region.size()) return false;
        g = next(m_twin[std::size_t(g)]);
      }
      if(g == cycle.front()) break;
      cycle.push_back(g);
    }
    if(cycle.size() != L) return false;  // several border cycles: not a disk
    std::map<int, std::size_t> times;     // how often each border point is met
    for(int h : cycle) ++times[m_tail[std::size_t(h)]];
    if(times.count(inside)) return false;
    if(inside >= 0) {  // the star of `inside` over the whole border (whose points must be distinct)
      if(times.size() != L) return false;
      std::vector<New_halfedge> nh;
      for(std::size_t j = 0; j < L; ++j) {
        const int wj = m_tail[std::size_t(cycle[j])], wk = head(cycle[j]);
        (void)wk;
        const int base = int(nh.size());
        // (inside, w_j, w_j+1): inside -> w_j pairs with the previous triangle's w_j -> inside
        nh.push_back({inside, 0, -1, j == 0 ? int(3 * L - 1) : base - 1});
        nh.push_back({wj, 0, cycle[j], -1});
        nh.push_back({head(cycle[j]), 0, -1, j + 1 == L ? 0 : base + 3});
      }
      replace(std::vector<int>(region.begin(), region.end()), nh);
      for(int x : cluster) m_out[std::size_t(x)] = -1, m_merged_into[std::size_t(x)] = inside;
      return true;
    }
    // the neighbours of each border point outside the region
    auto outside_neighbours = [&](int w) {
      std::set<int> n;
      for(int s : spokes_of(w))
        if(!region.count(s / 3) || !region.count(m_twin[std::size_t(s)] / 3)) n.insert(head(s));
      return n;
    };
    for(std::size_t i = 0; i < L; ++i) {
      const int apex = m_tail[std::size_t(cycle[i])];
      if(times[apex] != 1) continue;  // its diagonals would join it to itself
      std::set<int> joined = outside_neighbours(apex);
      if(m_fan_doubling) joined.clear();
      bool ok = true;  // each diagonal joins the apex to a point it is not joined to yet (nor twice)
      for(std::size_t j = 2; j + 1 < L && ok; ++j) ok = joined.insert(m_tail[std::size_t(cycle[(i + j) % L])]).second;
      if(!ok) continue;
      // fan triangles (apex, w_j, w_j+1) for j = 1 .. L - 2 (w_j the tail of cycle[i + j])
      std::vector<New_halfedge> nh;
      for(std::size_t j = 1; j + 1 < L; ++j) {
        const int wj = m_tail[std::size_t(cycle[(i + j) % L])], wk = m_tail[std::size_t(cycle[(i + j + 1) % L])];
        const int base = int(nh.size());
        New_halfedge first{apex, 0, -1, -1}, side{wj, 0, cycle[(i + j) % L], -1}, back{wk, 0, -1, -1};
        if(j == 1) first.outer = cycle[i];
        else first.pair = base - 1, nh[std::size_t(base - 1)].pair = base;
        if(j + 2 == L) back.outer = cycle[(i + L - 1) % L];
        nh.push_back(first);
        nh.push_back(side);
        nh.push_back(back);
      }
      replace(std::vector<int>(region.begin(), region.end()), nh);
      for(int x : cluster) m_out[std::size_t(x)] = -1, m_merged_into[std::size_t(x)] = apex;
      return true;
    }
    return false;
  }

  // 4: every vertex of the background left (the cones) merged into its nearest neighbouring site, then
  // the edges that join two sites twice (around a sharp cone) flipped away; the triangles over the sites
  std::vector<std::array<std::size_t, 3>> collapse_to_points(std::size_t npoints)
  {
    // in passes: a cone whose link repeats a site or holds another cone may merge once its neighbours have
    std::vector<int> left;
    m_merged_into.assign(m_nb, -1);
    for(std::size_t v = 0; v < m_nb; ++v)
      if(m_out[v] >= 0) left.push_back(int(v));
    while(!left.empty()) {
      std::vector<int> still;
      for(int v : left)
        if(merge_into_site(v)) ++m_stats.collapsed;
        else still.push_back(v);
      if(still.size() == left.size() && !m_relaxed) {  // another pass, merging without the link condition
        m_relaxed = true;
        left.swap(still);
        continue;
      }
      if(still.size() == left.size()) {  // last resort: each cluster of cones joined by edges replaced by a fan of sites
        std::vector<int> rest;
        for(int v : still)
          if(m_out[std::size_t(v)] >= 0 && !replace_cluster_by_fan(v)) rest.push_back(v);
        m_stats.collapsed += still.size() - rest.size();
        if(rest.size() < still.size()) {
          left.swap(rest);
          continue;
        }
        if(!m_fan_doubling) {  // and then fans whose diagonals may double an edge (flipped away below)
          m_fan_doubling = true;
          continue;
        }
      }
      if(still.size() == left.size()) {
        for(int v : still) m_unmerged.push_back({v, v});
        throw Convergence_failure("dual mesh: " + std::to_string(still.size()) + " " + std::string(still.size() == 1 ? "cone" : "cones") +
                                      " of the cone surface cannot be merged into a neighbouring site (too few sites around them)",
                                  double(still.size()));
      }
      left.swap(still);
    }
    // edges that join two sites twice
    std::size_t restars = 0;
    for(std::size_t round = 0;; ++round) {
      std::map<std::pair<int, int>, std::vector<int>> edges;
      for(std::size_t h = 0; h < m_tail.size(); ++h)
        if(m_alive[h / 3] && int(h) < m_twin[h]) {
          const int a = m_tail[h], b = head(int(h));
          edges[{std::min(a, b), std::max(a, b)}].push_back(int(h));
        }
      std::size_t repeated = 0, flipped = 0;
      for(const auto& e : edges) {
        if(e.second.size() < 2) continue;
        ++repeated;
        bool done = false;
        for(int h : e.second)
          if(m_alive[std::size_t(h / 3)] && flip_combinatorially(h, edges)) {
            ++flipped;
            done = true;
            break;
          }
        // blocked (the flipped edge would double another): flip an edge next to it first, in its two faces
        for(int h : e.second) {
          if(done || !m_alive[std::size_t(h / 3)]) continue;
          const int t = m_twin[std::size_t(h)];
          for(int y : {next(h), prev(h), next(t), prev(t)}) {
            const int a = m_tail[std::size_t(y)], b = head(y);
            const auto it = edges.find({std::min(a, b), std::max(a, b)});
            if(it != edges.end() && it->second.size() > 1) continue;  // a doubled edge itself
            if(flip_combinatorially(y, edges)) {
              ++flipped;
              done = true;
              break;
            }
          }
        }
      }
      m_stats.untangled += flipped;
      // loops: an edge from a site to itself, around a cone merged into it (a site whose cell wraps around
      // a thin part)
      std::vector<int> tangled;
      for(const auto& e : edges)
        if(e.second.size() > 1 || e.first.first == e.first.second) tangled.insert(tangled.end(), {e.first.first, e.first.second});
      if(tangled.empty()) break;
      if(repeated > 0 && flipped > 0 && round <= 64) continue;
      // stuck: a tangled site's star taken again over a grown region (at most 64 times in all)
      const bool mended = restars < 64 && restar_a_tangled_site(tangled);
      if(mended) {
        ++restars;
        round = 0;
        continue;
      }
      add_cones_merged_near(tangled);  // triangulate() may move points onto them
      const std::size_t loops = std::size_t(std::count_if(edges.begin(), edges.end(), [](const auto& e) { return e.first.first == e.first.second; }));
      throw Convergence_failure("dual mesh: " + std::to_string(repeated) + " pairs of sites are joined twice" +
                                    (loops ? " and " + std::to_string(loops) + " sites joined to themselves" : std::string()) +
                                    " around a cone of the cone surface (too few sites there)",
                                double(repeated + loops));
    }
    std::vector<std::array<std::size_t, 3>> out;
    for(std::size_t f = 0; f < m_alive.size(); ++f) {
      if(!m_alive[f]) continue;
      std::array<std::size_t, 3> r;
      for(int k = 0; k < 3; ++k) {
        const int z = m_tail[3 * f + std::size_t(k)];
        if(std::size_t(z) < m_nb || std::size_t(z) >= m_nb + npoints)
          throw Convergence_failure("dual mesh: a vertex of the cone surface is left without a site next to it", 0);
        r[std::size_t(k)] = std::size_t(z) - m_nb;
      }
      out.push_back(r);
    }
    return out;
  }

  // Stuck untangling: the star of one of the `tangled` sites (those of a doubled edge or loop: all its
  // faces) replaced by its star over that region grown across its border until the border is a cycle of
  // distinct sites (fan_over_region(), up to three layers); its edges are then all new and simple, the
  // border's unchanged, so each such replacement removes a tangle for good. Their neighbours of degree 1
  // or 2 are tried first (a site inside another's loop). false if none serves.
  bool restar_a_tangled_site(std::vector<int> tangled)
  {
    std::sort(tangled.begin(), tangled.end());
    tangled.erase(std::unique(tangled.begin(), tangled.end()), tangled.end());
    std::vector<int> lonely;
    for(int v : tangled)
      for(int sp : spokes_of(v)) {
        const int w = head(sp);
        if(w != v && spokes_of(w).size() < 3 && std::find(lonely.begin(), lonely.end(), w) == lonely.end()) lonely.push_back(w);
      }
    tangled.insert(tangled.begin(), lonely.begin(), lonely.end());
    for(int grow = 0; grow <= 3; ++grow)
      for(int v : tangled)
        if(fan_over_region({}, v, grow)) {
          ++m_stats.grown_fans;
          return true;
        }
    return false;
  }

  // The flip of h's edge (a, b) to (c, d) without lengths (after the merges, only the combinatorics
  // matter), if c and d differ and are not joined yet (`edges`, kept up to date).
  bool flip_combinatorially(int h, std::map<std::pair<int, int>, std::vector<int>>& edges)
  {
    const int t = m_twin[std::size_t(h)];
    const int c = m_tail[std::size_t(prev(h))], d = m_tail[std::size_t(prev(t))];
    if(c == d) return false;
    const auto key = std::make_pair(std::min(c, d), std::max(c, d));
    if(edges.count(key) && !edges[key].empty()) return false;
    const int a = m_tail[std::size_t(h)], b = m_tail[std::size_t(t)];
    if(spokes_of(a).size() <= 3 || spokes_of(b).size() <= 3) return false;  // a or b would be left of degree 2
    if(!flip(h, false)) return false;
    edges[key].push_back(-1);  // joined now (the halfedge itself is not needed)
    auto& old = edges[{std::min(a, b), std::max(a, b)}];
    if(!old.empty()) old.pop_back();
    return true;
  }

  // the cones step 4 could not merge, or merged into a site left tangled, each with the vertex to look for
  // a point to move from (itself, or the site it merged into); set before step 4 throws
  std::vector<std::pair<int, int>> m_unmerged;
  std::vector<int> m_merged_into;  // step 4: per background vertex merged by a collapse, the point it merged into
  std::vector<Moved_point> m_moved;  // the points moved onto such cones
  bool m_relaxed = false;  // step 4: merging without the link condition (once every strict merge is done)
  bool m_fan_doubling = false;  // step 4, last resort: fans whose diagonals may double an edge (flipped away after)
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_SURFACE_DELAUNAY_H
