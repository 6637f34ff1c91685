// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_SURFACE_TRIANGULATION_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_SURFACE_TRIANGULATION_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/internal/conformal/flat_triangle.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

// Steps 1 to 3 of the intrinsic Delaunay triangulation of points on a closed flat surface with cone
// singularities; internal::Cone_surface_delaunay (cone_surface_delaunay.h) adds step 4 and is the one to
// use. This class is the mutable triangulation by edge lengths (halfedges 3 f + k, twins, one length per
// halfedge) that the steps edit. The surface is given as a triangulation by edge lengths (the background
// of the cone domain in the cone metric: flat at every vertex but the cones):
//  1. each point is inserted into its face (the face split in three, lengths from the face's layout);
//  2. edge flips to the intrinsic Delaunay triangulation (Bobenko and Springborn 2007, "A discrete
//     Laplace-Beltrami operator for simplicial surfaces"; every non-Delaunay edge is flippable);
//  3. every flat vertex that is not a point is removed: its star, unfolded in the plane (angle sum 2 pi),
//     is triangulated again by ear clipping (Sharp, Soliman and Crane 2019, "Navigating intrinsic
//     triangulations", section 4, remove a vertex), and the flips of 2 are made again.

namespace Aniso_conformal {
namespace internal {

class Cone_surface_triangulation {
public:
  /// a point of the surface: its face and its position in the face's layout
  struct Point_on_face {
    int face = -1;
    Eigen::Vector2d x = Eigen::Vector2d::Zero();
  };
  /// what the last triangulation did (Cone_surface_delaunay::triangulate())
  struct Statistics {
    std::size_t flips = 0;            // Delaunay flips, steps 2 and 3
    std::size_t removed = 0;          // flat vertices removed in step 3
    std::size_t collapsed = 0;        // vertices merged into a point in step 4 (cones, and flat ones step 3 left)
    std::size_t untangled = 0;        // edges flipped in step 4 because they joined two points joined already
    std::size_t grown_fans = 0;       // step 4: cones replaced by a point's star over a region grown past their faces (thin parts)
    std::size_t moved = 0;            // points moved onto a cone that no point could be merged into (Cone_surface_delaunay::moved_points())
  };

  /*
   * `faces[f]` the corners of face f, `twin[h]` the opposite halfedge of halfedge `h = 3 f + k` (from
   * corner k to corner k + 1; closed: every twin >= 0), `layout[f]` the corners' positions in a plane
   * (lengths of the flat metric), `is_cone[v]` for the vertices that are not flat (the cones).
   */
  Cone_surface_triangulation(const std::vector<std::array<int, 3>>& faces, const std::vector<int>& twin,
                             const std::vector<std::array<Eigen::Vector2d, 3>>& layout, const std::vector<char>& is_cone)
    : m_faces0(&faces), m_twin0(&twin), m_layout(&layout), m_is_cone(&is_cone)
  {
  }

  const Statistics& statistics() const { return m_stats; }

protected:
  // steps 1 to 3 on `points`: the background vertices left are the cones and the flat vertices step 3
  // could not remove (vertex `m_nb + i` is point i)
  void insert_and_remove_flat_vertices(const std::vector<Point_on_face>& points)
  {
    m_stats = Statistics();
    const std::size_t nf = m_faces0->size();
    m_nb = 0;
    for(const auto& f : *m_faces0)
      for(int v : f) m_nb = std::max(m_nb, std::size_t(v) + 1);
    m_tail.assign(3 * nf, -1);
    m_twin = *m_twin0;
    m_len.assign(3 * nf, 0.0);
    m_alive.assign(nf, 1);
    m_out.assign(m_nb + points.size(), -1);
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k) {
        const std::size_t h = 3 * f + std::size_t(k);
        m_tail[h] = (*m_faces0)[f][std::size_t(k)];
        m_len[h] = ((*m_layout)[f][std::size_t((k + 1) % 3)] - (*m_layout)[f][std::size_t(k)]).norm();
        m_out[std::size_t(m_tail[h])] = int(h);
      }
    for(std::size_t h = 0; h < 3 * nf; ++h)  // one length per edge, whichever face's layout
      if(m_twin[h] < 0 || std::size_t(m_twin[h]) >= 3 * nf) throw Invalid_input("Cone_surface_delaunay: the surface is not closed");
      else if(int(h) < m_twin[h]) m_len[std::size_t(m_twin[h])] = m_len[h] = 0.5 * (m_len[h] + m_len[std::size_t(m_twin[h])]);
    insert_points(points);
    make_delaunay();
    for(std::size_t v = 0; v < m_nb; ++v)
      if(!(*m_is_cone)[v] && m_out[v] >= 0 && remove_flat_vertex(int(v))) ++m_stats.removed;
    make_delaunay();
  }

  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
  int head(int h) const { return m_tail[std::size_t(next(h))]; }

  // one new halfedge of replace(): its tail and length, and either the old halfedge it takes the place
  // of (`outer`, keeping that one's twin) or the index of its twin among the new halfedges (`pair`)
  struct New_halfedge {
    int tail = -1;
    double len = 0;
    int outer = -1;
    int pair = -1;
  };

  // Replaces the faces `old` by the new faces (three New_halfedges each, in order): reuses the old slots
  // first, then appends; the twins of the outer halfedges follow them.
  void replace(const std::vector<int>& old, const std::vector<New_halfedge>& nh)
  {
    const std::size_t nfaces = nh.size() / 3;
    std::vector<int> slot(nfaces);
    for(std::size_t i = 0; i < nfaces; ++i) {
      if(i < old.size()) slot[i] = old[i];
      else {
        slot[i] = int(m_alive.size());
        m_alive.push_back(1);
        m_tail.resize(m_tail.size() + 3, -1);
        m_twin.resize(m_twin.size() + 3, -1);
        m_len.resize(m_len.size() + 3, 0.0);
      }
    }
    for(std::size_t i = nfaces; i < old.size(); ++i) m_alive[std::size_t(old[i])] = 0;
    auto index = [&](std::size_t j) { return 3 * slot[j / 3] + int(j % 3); };
    std::vector<std::pair<int, int>> moved;  // old outer halfedge -> its twin before
    for(const auto& x : nh)
      if(x.outer >= 0) moved.push_back({x.outer, m_twin[std::size_t(x.outer)]});
    std::map<int, int> to_new;
    for(std::size_t j = 0; j < nh.size(); ++j)
      if(nh[j].outer >= 0) to_new[nh[j].outer] = index(j);
    for(std::size_t j = 0; j < nh.size(); ++j) {
      const int h = index(j);
      m_tail[std::size_t(h)] = nh[j].tail;
      m_len[std::size_t(h)] = nh[j].len;
      m_out[std::size_t(nh[j].tail)] = h;
      m_alive[std::size_t(h / 3)] = 1;
    }
    for(std::size_t j = 0; j < nh.size(); ++j) {
      const int h = index(j);
      if(nh[j].pair >= 0) {
        m_twin[std::size_t(h)] = index(std::size_t(nh[j].pair));
        continue;
      }
      int t = -1;
      for(const auto& m : moved)
        if(m.first == nh[j].outer) t = m.second;
      const auto it = to_new.find(t);
      if(it != to_new.end()) m_twin[std::size_t(h)] = it->second;
      else m_twin[std::size_t(h)] = t, m_twin[std::size_t(t)] = h;
    }
  }

  // the angle of h's face opposite h (its corner at prev(h)'s tail), accurate also in the needle-like
  // triangles that a site inserted next to a vertex or an edge makes
  double opposite_angle(int h) const
  {
    return triangle_angle(m_len[std::size_t(next(h))], m_len[std::size_t(prev(h))], m_len[std::size_t(h)]);
  }

  // 1: each point split into the face of its background face's pieces that holds it
  void insert_points(const std::vector<Point_on_face>& points)
  {
    const std::size_t nf = m_faces0->size();
    std::vector<std::vector<int>> pieces(nf);
    for(std::size_t f = 0; f < nf; ++f) pieces[f].push_back(int(f));
    std::vector<Eigen::Vector2d> xy(3 * nf);  // per halfedge, its tail in the background face's layout
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k) xy[3 * f + std::size_t(k)] = (*m_layout)[f][std::size_t(k)];
    for(std::size_t i = 0; i < points.size(); ++i) {
      const int f = points[i].face;
      if(f < 0 || std::size_t(f) >= nf || !points[i].x.allFinite())
        throw Convergence_failure("dual mesh: site " + std::to_string(i) + " is not on a face of the cone surface", 0);
      int best = -1;
      double best_min = -1e300;
      Eigen::Vector3d best_b = Eigen::Vector3d::Constant(1.0 / 3);
      for(int t : pieces[std::size_t(f)]) {
        const Eigen::Vector3d b = barycentric_2({{xy[std::size_t(3 * t)], xy[std::size_t(3 * t + 1)], xy[std::size_t(3 * t + 2)]}}, points[i].x);
        if(b.minCoeff() > best_min) best_min = b.minCoeff(), best = t, best_b = b;
      }
      for(int k = 0; k < 3; ++k)  // at a point inserted before: the same point twice
        if(std::size_t(m_tail[std::size_t(3 * best + k)]) >= m_nb &&
           (xy[std::size_t(3 * best + k)] - points[i].x).norm() <= 1e-12 * (xy[std::size_t(3 * best + (k + 1) % 3)] - xy[std::size_t(3 * best + k)]).norm())
          throw Convergence_failure("dual mesh: site " + std::to_string(i) + " coincides with site " +
                                        std::to_string(std::size_t(m_tail[std::size_t(3 * best + k)]) - m_nb) + " on the cone surface",
                                    0);
      // a point at a vertex of the background (a fixed site: a corner of the input, a cone kept as an output
      // vertex) becomes that vertex, which keeps its angle sum: inserted a hair inside a face next to it, it
      // would leave the vertex to be merged into it, which a wide cone's link does not allow
      bool snapped = false;
      for(int k = 0; k < 3 && !snapped; ++k) {
        const int corner = m_tail[std::size_t(3 * best + k)];
        if(std::size_t(corner) < m_nb &&
           (xy[std::size_t(3 * best + k)] - points[i].x).norm() <= 1e-12 * (xy[std::size_t(3 * best + (k + 1) % 3)] - xy[std::size_t(3 * best + k)]).norm()) {
          rename_vertex(corner, int(m_nb + i));
          snapped = true;
        }
      }
      if(snapped) continue;
      // a point on an edge or near a corner goes a hair inside (the combinatorics do not depend on it)
      const double eps = 1e-7;
      Eigen::Vector3d b = best_b.cwiseMax(eps);
      b /= b.sum();
      const std::array<Eigen::Vector2d, 3> c = {{xy[std::size_t(3 * best)], xy[std::size_t(3 * best + 1)], xy[std::size_t(3 * best + 2)]}};
      const Eigen::Vector2d p = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
      const int pv = int(m_nb + i);
      std::array<int, 3> v;
      for(int k = 0; k < 3; ++k) v[std::size_t(k)] = m_tail[std::size_t(3 * best + k)];
      std::array<double, 3> d;
      for(int k = 0; k < 3; ++k) {
        d[std::size_t(k)] = (c[std::size_t(k)] - p).norm();
        if(!(d[std::size_t(k)] > 0))
          throw Convergence_failure("dual mesh: site " + std::to_string(i) + " coincides with another point of the cone surface", 0);
      }
      // (a, b, p), (b, c, p), (c, a, p): new halfedges 3 j + k
      std::vector<New_halfedge> nh(9);
      for(int j = 0; j < 3; ++j) {
        const int a = j, bb = (j + 1) % 3;
        nh[std::size_t(3 * j)] = {v[std::size_t(a)], m_len[std::size_t(3 * best + a)], 3 * best + a, -1};
        nh[std::size_t(3 * j + 1)] = {v[std::size_t(bb)], d[std::size_t(bb)], -1, 3 * ((j + 1) % 3) + 2};
        nh[std::size_t(3 * j + 2)] = {pv, d[std::size_t(a)], -1, 3 * ((j + 2) % 3) + 1};
      }
      const std::size_t before = m_alive.size();
      replace({best}, nh);
      pieces[std::size_t(f)].push_back(int(before));
      pieces[std::size_t(f)].push_back(int(before + 1));
      xy.resize(3 * m_alive.size());
      // new slots: best (a, b, p), before (b, c, p), before + 1 (c, a, p)
      const int s[3] = {best, int(before), int(before + 1)};
      for(int j = 0; j < 3; ++j) {
        xy[std::size_t(3 * s[j])] = c[std::size_t(j)];
        xy[std::size_t(3 * s[j] + 1)] = c[std::size_t((j + 1) % 3)];
        xy[std::size_t(3 * s[j] + 2)] = p;
      }
    }
  }

  bool is_delaunay(int h) const
  {
    return opposite_angle(h) + opposite_angle(m_twin[std::size_t(h)]) <= 3.14159265358979323846 + 1e-12;
  }

  // Flips the edge of h: faces (a, b, c) and (b, a, d) become (c, a, d) and (d, b, c). false (no flip) if
  // the two faces are one or glued along another edge too (an intrinsic triangulation may have those).
  bool flip(int h, bool geometric = true)
  {
    const int t = m_twin[std::size_t(h)];
    if(h / 3 == t / 3) return false;
    const int hn = next(h), hp = prev(h), tn = next(t), tp = prev(t);
    for(int x : {hn, hp, tn, tp}) {
      const int y = m_twin[std::size_t(x)];
      if(y / 3 == h / 3 || y / 3 == t / 3) return false;
    }
    const int a = m_tail[std::size_t(h)], b = m_tail[std::size_t(t)], c = m_tail[std::size_t(hp)], d = m_tail[std::size_t(tp)];
    // lay out a = 0, b = (L, 0), c above, d below, by the angles at a (the law of cosines would place c
    // and d with half the digits lost in the needle-like triangles next to an inserted site, and the flip
    // would change the angle sums at a and b: up to 0.14 rad on CGAL's femur)
    const double L = m_len[std::size_t(h)];
    const double ac = m_len[std::size_t(hp)], bc = m_len[std::size_t(hn)], ad = m_len[std::size_t(tn)], bd = m_len[std::size_t(tp)];
    const double at_a_in_abc = triangle_angle(L, ac, bc), at_a_in_abd = triangle_angle(L, ad, bd);
    const double cd = geometric ? std::hypot(ac * std::cos(at_a_in_abc) - ad * std::cos(at_a_in_abd), ac * std::sin(at_a_in_abc) + ad * std::sin(at_a_in_abd)) : 0.0;
    if(geometric && (!(cd > 0) || !std::isfinite(cd))) return false;
    std::vector<New_halfedge> nh(6);
    nh[0] = {c, ac, hp, -1};
    nh[1] = {a, ad, tn, -1};
    nh[2] = {d, cd, -1, 5};
    nh[3] = {d, bd, tp, -1};
    nh[4] = {b, bc, hn, -1};
    nh[5] = {c, cd, -1, 2};
    replace({h / 3, t / 3}, nh);
    return true;
  }

  // 2: flips to the intrinsic Delaunay triangulation
  void make_delaunay()
  {
    std::vector<int> stack;
    for(std::size_t h = 0; h < m_tail.size(); ++h)
      if(m_alive[h / 3] && int(h) < m_twin[h]) stack.push_back(int(h));
    const std::size_t bound = 200 * m_tail.size() + 1000;
    std::size_t flips = 0;
    while(!stack.empty()) {
      const int h = stack.back();
      stack.pop_back();
      if(!m_alive[std::size_t(h / 3)] || is_delaunay(h)) continue;
      const int f = h / 3, g = m_twin[std::size_t(h)] / 3;
      if(!flip(h)) continue;
      if(++flips > bound)
        throw Convergence_failure("dual mesh: the Delaunay flips on the cone surface did not end after " + std::to_string(bound), double(flips));
      for(int k = 0; k < 3; ++k) stack.push_back(3 * f + k), stack.push_back(3 * g + k);
    }
    m_stats.flips += flips;
  }

  // 3: removes the flat vertex v (its star unfolded and triangulated again); false if it is not flat
  // enough, its star is not a disk of distinct faces and neighbours, or no ear is found
  bool remove_flat_vertex(int v)
  {
    std::vector<int> spokes;
    int h = m_out[std::size_t(v)];
    if(h < 0 || m_tail[std::size_t(h)] != v) return false;
    do {
      spokes.push_back(h);
      if(spokes.size() > 4096) return false;
      h = m_twin[std::size_t(prev(h))];
    } while(h != spokes.front());
    const std::size_t d = spokes.size();
    if(d < 3) return false;
    std::vector<int> faces, w;
    for(int s : spokes) faces.push_back(s / 3), w.push_back(head(s));
    {
      // a neighbour may come twice (joined to v on both sides of a sharp cone): the unfolded star is
      // still a polygon of the plane
      std::vector<int> f2 = faces;
      std::sort(f2.begin(), f2.end());
      if(std::adjacent_find(f2.begin(), f2.end()) != f2.end() || std::find(w.begin(), w.end(), v) != w.end()) {
        return false;
      }
    }
    // unfold: w_i at angle theta_i, the angle at v in face i being the one opposite next(spoke i)
    std::vector<Eigen::Vector2d> P(d);
    double theta = 0;
    for(std::size_t i = 0; i < d; ++i) {
      const double r = m_len[std::size_t(spokes[i])];
      P[i] = r * Eigen::Vector2d(std::cos(theta), std::sin(theta));
      theta += opposite_angle(next(spokes[i]));
    }
    const double two_pi = 2 * 3.14159265358979323846;
    if(std::abs(theta - two_pi) > 1e-4) {
      return false;
    }
    struct Side {
      int outer;  // the old halfedge, or -1
      int pair;   // else the new halfedge on the other side
      double len;
    };
    std::vector<std::size_t> poly(d);
    std::vector<Side> side(d);  // side i: from poly vertex i to the next
    for(std::size_t i = 0; i < d; ++i) poly[i] = i, side[i] = {next(spokes[i]), -1, m_len[std::size_t(next(spokes[i]))]};
    std::vector<New_halfedge> nh;
    auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
    auto emit = [&](std::size_t a, std::size_t b, std::size_t c, const Side& ab, const Side& bc, double ca_len) {
      // face (w_a, w_b, w_c); returns the index of its halfedge c -> a
      const int base = int(nh.size());
      nh.push_back({w[a], ab.len, ab.outer, ab.pair});
      nh.push_back({w[b], bc.len, bc.outer, bc.pair});
      nh.push_back({w[c], ca_len, -1, -1});
      if(ab.pair >= 0) nh[std::size_t(ab.pair)].pair = base;
      if(bc.pair >= 0) nh[std::size_t(bc.pair)].pair = base + 1;
      return base + 2;
    };
    while(poly.size() > 3) {
      const std::size_t m = poly.size();
      std::size_t best = m;
      double best_score = -1;
      for(std::size_t k = 0; k < m; ++k) {
        const std::size_t a = poly[(k + m - 1) % m], b = poly[k], c = poly[(k + 1) % m];
        if(w[a] == w[c]) continue;
        const double area = cross(P[b] - P[a], P[c] - P[b]);
        if(!(area > 1e-14 * (P[c] - P[a]).squaredNorm())) continue;
        bool empty = true;
        for(std::size_t j = 0; j < m && empty; ++j) {
          const std::size_t q = poly[j];
          if(q == a || q == b || q == c) continue;
          empty = !(cross(P[b] - P[a], P[q] - P[a]) >= 0 && cross(P[c] - P[b], P[q] - P[b]) >= 0 && cross(P[a] - P[c], P[q] - P[c]) >= 0);
        }
        if(!empty) continue;
        // the smallest angle of the ear
        const double la = (P[c] - P[b]).norm(), lb = (P[a] - P[c]).norm(), lc = (P[b] - P[a]).norm();
        const double score = 2 * area / std::max({la * lb, lb * lc, lc * la});
        if(score > best_score) best_score = score, best = k;
      }
      if(best == m) {
        return false;
      }
      const std::size_t ka = (best + m - 1) % m;
      const std::size_t a = poly[ka], b = poly[best], c = poly[(best + 1) % m];
      const double ca = (P[a] - P[c]).norm();
      const int back = emit(a, b, c, side[ka], side[best], ca);
      side[ka] = {-1, back, ca};
      poly.erase(poly.begin() + std::ptrdiff_t(best));
      side.erase(side.begin() + std::ptrdiff_t(best));
    }
    {
      const Side last = side[2];
      const int base = emit(poly[0], poly[1], poly[2], side[0], side[1], last.len);
      nh[std::size_t(base)].outer = last.outer;
      nh[std::size_t(base)].pair = last.pair;
      if(last.pair >= 0) nh[std::size_t(last.pair)].pair = base;
    }
    replace(faces, nh);
    m_out[std::size_t(v)] = -1;
    return true;
  }

  // Vertex `from` becomes vertex `to` (a number no vertex has yet): every halfedge leaving it
  void rename_vertex(int from, int to)
  {
    std::vector<int> spokes = spokes_of(from);
    if(spokes.empty())  // not a simple cycle of spokes: every halfedge looked at
      for(std::size_t h = 0; h < m_tail.size(); ++h)
        if(m_alive[h / 3] && m_tail[h] == from) spokes.push_back(int(h));
    for(int h : spokes) m_tail[std::size_t(h)] = to;
    m_out[std::size_t(to)] = m_out[std::size_t(from)];
    m_out[std::size_t(from)] = -1;
  }

  // the halfedges leaving v, counterclockwise (empty if v is not a vertex any more or its star is not a
  // cycle of at most 4096)
  std::vector<int> spokes_of(int v) const
  {
    std::vector<int> spokes;
    int h = m_out[std::size_t(v)];
    if(h < 0 || m_tail[std::size_t(h)] != v || !m_alive[std::size_t(h / 3)]) return spokes;
    do {
      spokes.push_back(h);
      if(spokes.size() > 4096) return {};
      h = m_twin[std::size_t(prev(h))];
    } while(h != spokes.front());
    return spokes;
  }

  const std::vector<std::array<int, 3>>* m_faces0;
  const std::vector<int>* m_twin0;
  const std::vector<std::array<Eigen::Vector2d, 3>>* m_layout;
  const std::vector<char>* m_is_cone;
  std::size_t m_nb = 0;
  std::vector<int> m_tail, m_twin, m_out;
  std::vector<double> m_len;
  std::vector<char> m_alive;
  Statistics m_stats;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_SURFACE_TRIANGULATION_H
