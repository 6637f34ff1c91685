// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_TORUS_DELAUNAY_FLIPS_H
#define ANISO_CONFORMAL_INTERNAL_CVT_TORUS_DELAUNAY_FLIPS_H

#include <Aniso_conformal/internal/CVT/lawson_flips.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <tuple>
#include <utility>
#include <vector>

// The Delaunay triangulation of the CVT's sites on a flat torus R^2 / L, kept from one energy evaluation
// to the next and repaired by Lawson's edge flips, as the sphere's is (sphere_delaunay_flips.h). The
// flat torus' CVT otherwise triangulates the sites and their translates in a band around the fundamental
// cell anew at each evaluation (CGAL's Delaunay_triangulation_2, a fifth of the CVT's time on the
// cyclide to 4000 sites, one thread).
//
// A triangle of the torus is three sites with a lattice offset each: corner k lies at
// site(v[k]) + o[k].x a + o[k].y b, with (a, b) the lattice basis and site(v) the site's wrapped position;
// only the differences of a triangle's offsets matter (a common shift is the same triangle). Between two
// evaluations a site moves by a fraction of the spacing, but its wrapped position may jump by a lattice
// vector where it crosses the fundamental cell's side: the jump is taken off the offsets of its corners,
// so that every corner moves continuously. The moved triangulation is still a triangulation of the torus
// when every triangle is counterclockwise (CGAL's exact orientation on the corners as computed) and their
// areas sum to the torus' once (a covering of degree one with no folded triangle); otherwise it is
// rebuilt. Lawson's flips then make it Delaunay (on a flat torus as in the plane: every edge that is not
// locally Delaunay is flippable, as its quadrilateral is convex, each flip lowers the Dirichlet energy of
// piecewise linear functions (Rippa 1990), and the end is the Delaunay triangulation, unique up to
// cocircular sites, any of whose triangulations serves). Each flip's in-circle test is made in the frame
// of the triangle on one side (its corners as computed there); the flips are bounded, and a bound
// reached means a rebuild.

namespace Aniso_conformal {
namespace internal {

class Torus_flip_triangulation {
public:
  typedef std::array<int, 2> Offset;  // a lattice vector, in the basis (a, b)
  struct Triangle {
    std::array<int, 3> v;     // sites, counterclockwise
    std::array<Offset, 3> o;  // their lattice offsets
  };

  // the lattice basis (a, b) and the inverse of the matrix [a b]; forgets any triangulation
  void set_lattice(const std::array<Eigen::Vector2d, 2>& basis, const Eigen::Matrix2d& inverse, double area)
  {
    m_basis = basis;
    m_inverse = inverse;
    m_area = area;
    m_valid = false;
  }
  bool valid() const { return m_valid; }
  std::size_t number_of_triangles() const { return m_tri.size(); }
  const Triangle& triangle(std::size_t t) const { return m_tri[t]; }
  std::size_t last_flips() const { return m_last_flips; }
  // where corner (v, o) lies: the site's wrapped position translated by o
  Eigen::Vector2d position(int v, const Offset& o) const
  {
    return m_pos[std::size_t(v)] + double(o[0]) * m_basis[0] + double(o[1]) * m_basis[1];
  }

  /*
   * Takes the triangulation of the torus from a triangulation of the `ns` wrapped sites (points 0 .. ns - 1)
   * and translates of them (the other points; original[e] is the site point e stands for): `faces` must
   * hold every triangle with a vertex at a wrapped site (vertices in any order; each translate of a torus
   * triangle may appear). False (and not valid) unless they make 2 ns triangles of the torus, each edge
   * shared by two of them.
   */
  bool take(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& original, const std::vector<std::array<int, 3>>& faces,
            std::size_t ns)
  {
    m_valid = false;
    m_tri.clear();
    m_adj.clear();
    if(ns < 3 || points.size() < ns || original.size() != points.size()) return false;
    m_pos.assign(points.begin(), points.begin() + std::ptrdiff_t(ns));
    std::vector<Offset> offset(points.size());
    for(std::size_t e = 0; e < points.size(); ++e) {
      if(original[e] < 0 || std::size_t(original[e]) >= ns) return false;
      const Eigen::Vector2d d = m_inverse * (points[e] - m_pos[std::size_t(original[e])]);
      if(!d.allFinite()) return false;
      offset[e] = {{int(std::lround(d.x())), int(std::lround(d.y()))}};
    }
    // each torus triangle once: the rotation of its corners, offsets relative to the first, that is least
    std::vector<Triangle> all;
    all.reserve(faces.size());
    for(const auto& f : faces) {
      if(*std::min_element(f.begin(), f.end()) >= int(ns)) continue;
      std::array<int, 3> g = f;
      const CGAL::Orientation turn = orientation(points[std::size_t(g[0])], points[std::size_t(g[1])], points[std::size_t(g[2])]);
      if(turn == CGAL::COLLINEAR) return false;
      if(turn == CGAL::RIGHT_TURN) std::swap(g[1], g[2]);
      Triangle best;
      for(int r = 0; r < 3; ++r) {
        Triangle c;
        for(int k = 0; k < 3; ++k) {
          const int e = g[std::size_t((r + k) % 3)];
          c.v[std::size_t(k)] = original[std::size_t(e)];
          c.o[std::size_t(k)] = offset[std::size_t(e)];
        }
        const Offset o0 = c.o[0];
        for(auto& o : c.o) o = {{o[0] - o0[0], o[1] - o0[1]}};
        if(r == 0 || key(c) < key(best)) best = c;
      }
      all.push_back(best);
    }
    std::sort(all.begin(), all.end(), [](const Triangle& x, const Triangle& y) { return key(x) < key(y); });
    for(std::size_t i = 0; i < all.size(); ++i)
      if(i == 0 || key(all[i]) != key(all[i - 1])) m_tri.push_back(all[i]);
    if(m_tri.size() != 2 * ns) return clear();
    // the edges: the one opposite corner k of t runs from corner k + 1 to corner k + 2; its twin back.
    // Each directed edge (from, to, offset difference) must be found once, its twin once
    typedef std::array<int, 4> Edge;
    std::vector<std::pair<Edge, std::pair<int, int>>> edges;  // with (triangle, corner)
    edges.reserve(3 * m_tri.size());
    for(std::size_t t = 0; t < m_tri.size(); ++t)
      for(int k = 0; k < 3; ++k) {
        const std::size_t i = std::size_t((k + 1) % 3), j = std::size_t((k + 2) % 3);
        const Triangle& T = m_tri[t];
        edges.push_back({Edge{{T.v[i], T.v[j], T.o[j][0] - T.o[i][0], T.o[j][1] - T.o[i][1]}}, {int(t), k}});
      }
    std::sort(edges.begin(), edges.end());
    const auto by_edge = [](const std::pair<Edge, std::pair<int, int>>& x, const Edge& y) { return x.first < y; };
    const auto edge_by = [](const Edge& x, const std::pair<Edge, std::pair<int, int>>& y) { return x < y.first; };
    m_adj.assign(m_tri.size(), {{Link{-1, -1}, Link{-1, -1}, Link{-1, -1}}});
    for(const auto& e : edges) {
      const Edge twin{{e.first[1], e.first[0], -e.first[2], -e.first[3]}};
      const auto first = std::lower_bound(edges.begin(), edges.end(), twin, by_edge);
      const auto last = std::upper_bound(first, edges.end(), twin, edge_by);
      if(last - first != 1) return clear();  // no twin, or a directed edge twice: not a triangulation of the torus
      m_adj[std::size_t(e.second.first)][std::size_t(e.second.second)] = Link{first->second.first, first->second.second};
    }
    m_sites = ns;
    m_valid = true;
    return true;
  }

  // moves the sites to their new wrapped positions and flips the triangulation back to Delaunay; false
  // (and not valid) if the moved triangles no longer triangulate the torus or the flips exceed their
  // bound (then the caller rebuilds)
  bool update(const std::vector<Eigen::Vector2d>& wrapped)
  {
    m_last_flips = 0;
    if(!m_valid || wrapped.size() != m_sites) return m_valid = false;
    std::vector<Offset> jump(m_sites);
    for(std::size_t i = 0; i < m_sites; ++i) {
      const Eigen::Vector2d d = m_inverse * (wrapped[i] - m_pos[i]);
      if(!d.allFinite()) return m_valid = false;
      jump[i] = {{int(std::lround(d.x())), int(std::lround(d.y()))}};
    }
    m_pos = wrapped;
    double area = 0;
    for(Triangle& T : m_tri) {
      for(int k = 0; k < 3; ++k) {
        const Offset& j = jump[std::size_t(T.v[std::size_t(k)])];
        T.o[std::size_t(k)] = {{T.o[std::size_t(k)][0] - j[0], T.o[std::size_t(k)][1] - j[1]}};
      }
      const Eigen::Vector2d a = position(T.v[0], T.o[0]), b = position(T.v[1], T.o[1]), c = position(T.v[2], T.o[2]);
      if(orientation(a, b, c) != CGAL::LEFT_TURN) return m_valid = false;
      area += 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    }
    if(!(std::abs(area - m_area) < 0.5 * m_area)) return m_valid = false;  // degree one
    std::vector<std::pair<int, int>> stack;
    stack.reserve(3 * m_tri.size());
    for(int t = 0; t < int(m_tri.size()); ++t)
      for(int k = 0; k < 3; ++k)
        if(t <= m_adj[std::size_t(t)][std::size_t(k)].t) stack.emplace_back(t, k);
    const std::size_t bound = 10 * m_tri.size() + 100;
    while(!stack.empty()) {
      const auto [t, k] = stack.back();
      stack.pop_back();
      if(!is_delaunay(t, k)) {
        if(++m_last_flips > bound) return m_valid = false;
        flip(t, k, stack);
      }
    }
    return true;
  }

  // the Delaunay neighbours of every site with their offsets relative to the site, in CSR form
  // (neighbours of i: nbr[start[i] .. start[i+1])): each translate of a neighbouring site once
  void neighbours(std::vector<int>& start, std::vector<std::pair<int, Offset>>& nbr) const
  {
    start.assign(m_sites + 1, 0);
    for(const Triangle& T : m_tri)
      for(int v : T.v) ++start[std::size_t(v) + 1];
    for(std::size_t i = 0; i < m_sites; ++i) start[i + 1] += start[i];
    nbr.resize(std::size_t(start[m_sites]));
    std::vector<int> next(start.begin(), start.end() - 1);
    for(const Triangle& T : m_tri)  // each directed edge i -> j lies in one counterclockwise triangle
      for(int k = 0; k < 3; ++k) {
        const std::size_t i = std::size_t(k), j = std::size_t((k + 1) % 3);
        nbr[std::size_t(next[std::size_t(T.v[i])]++)] = {T.v[j], Offset{{T.o[j][0] - T.o[i][0], T.o[j][1] - T.o[i][1]}}};
      }
  }

private:
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  struct Link {
    int t, k;  // the triangle across an edge and its corner facing the edge
  };

  static std::tuple<int, int, int, int, int, int, int> key(const Triangle& T)
  {
    return std::make_tuple(T.v[0], T.v[1], T.v[2], T.o[1][0], T.o[1][1], T.o[2][0], T.o[2][1]);
  }
  bool clear()
  {
    m_tri.clear();
    m_adj.clear();
    return m_valid = false;
  }
  static CGAL::Orientation orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c)
  {
    return CGAL::orientation(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()), K::Point_2(c.x(), c.y()));
  }
  // the far corner of the triangle across t's edge opposite corner k, as an offset in t's frame
  Offset far_offset(int t, int k) const
  {
    const Link& L = m_adj[std::size_t(t)][std::size_t(k)];
    const Triangle &T = m_tri[std::size_t(t)], &U = m_tri[std::size_t(L.t)];
    // corner k + 1 of t (a) is corner L.k + 2 of u: u's frame shifted onto t's
    const Offset& ot = T.o[std::size_t((k + 1) % 3)];
    const Offset& ou = U.o[std::size_t((L.k + 2) % 3)];
    const Offset& od = U.o[std::size_t(L.k)];
    return {{od[0] + ot[0] - ou[0], od[1] + ot[1] - ou[1]}};
  }
  // whether t's edge opposite corner k is Delaunay: the far corner not strictly inside t's circumcircle
  bool is_delaunay(int t, int k) const
  {
    const Triangle& T = m_tri[std::size_t(t)];
    const Link& L = m_adj[std::size_t(t)][std::size_t(k)];
    if(L.t == t) return true;  // an edge glued to its own triangle (a handful of sites): left as it is
    const Eigen::Vector2d a = position(T.v[0], T.o[0]), b = position(T.v[1], T.o[1]), c = position(T.v[2], T.o[2]);
    const Eigen::Vector2d d = position(m_tri[std::size_t(L.t)].v[std::size_t(L.k)], far_offset(t, k));
    return CGAL::side_of_oriented_circle(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()), K::Point_2(c.x(), c.y()),
                                         K::Point_2(d.x(), d.y())) != CGAL::ON_POSITIVE_SIDE;
  }
  // points the link of x (triangle x.t, across the edge opposite its corner x.k) at (new_t, new_k)
  void relink(const Link& x, int new_t, int new_k) { m_adj[std::size_t(x.t)][std::size_t(x.k)] = Link{new_t, new_k}; }
  // (c, a, b) in t and (d, b, a) in u become (c, a, d) in t and (d, b, c) in u, both in t's frame with their
  // first offset zero; their four outer edges go on the stack
  void flip(int t, int k, std::vector<std::pair<int, int>>& stack)
  {
    const Link L = m_adj[std::size_t(t)][std::size_t(k)];
    const int u = L.t, m = L.k;
    const Triangle T = m_tri[std::size_t(t)], U = m_tri[std::size_t(u)];
    const auto At = m_adj[std::size_t(t)], Au = m_adj[std::size_t(u)];
    const std::size_t k1 = std::size_t((k + 1) % 3), k2 = std::size_t((k + 2) % 3);
    const std::size_t m1 = std::size_t((m + 1) % 3), m2 = std::size_t((m + 2) % 3);
    const int c = T.v[std::size_t(k)], a = T.v[k1], b = T.v[k2], d = U.v[std::size_t(m)];
    const Offset oc = T.o[std::size_t(k)], oa = T.o[k1], ob = T.o[k2], od = far_offset(t, k);
    const Link t_bc = At[k1], t_ca = At[k2];  // across (b, c) and (c, a)
    const Link u_ad = Au[m1], u_db = Au[m2];  // across (a, d) and (d, b)
    m_tri[std::size_t(t)] = normalised(Triangle{{{c, a, d}}, {{oc, oa, od}}});
    m_adj[std::size_t(t)] = {{u_ad, Link{u, 1}, t_ca}};
    m_tri[std::size_t(u)] = normalised(Triangle{{{d, b, c}}, {{od, ob, oc}}});
    m_adj[std::size_t(u)] = {{t_bc, Link{t, 1}, u_db}};
    // the outer neighbours now face t (edge (a, d) opposite t's corner 0, (c, a) opposite 2) and u
    // ((b, c) opposite u's corner 0, (d, b) opposite 2); when an outer neighbour is t or u itself (two
    // triangles sharing two edges) its link was read before the rewrite and is remapped here
    fix_outer(t, 0, u_ad, t, u, k, m);
    fix_outer(t, 2, t_ca, t, u, k, m);
    fix_outer(u, 0, t_bc, t, u, k, m);
    fix_outer(u, 2, u_db, t, u, k, m);
    stack.emplace_back(t, 0);
    stack.emplace_back(t, 2);
    stack.emplace_back(u, 0);
    stack.emplace_back(u, 2);
  }
  // after a flip of t (corner k) with u (corner m): the edge opposite corner `corner` of the new triangle
  // `self` had, before the flip, the outer neighbour `x`; points x's link back at (self, corner) and, if x
  // was t or u, translates x to the new triangles' corners
  void fix_outer(int self, int corner, Link x, int t, int u, int k, int m)
  {
    if(x.t == t || x.t == u) x = remap(x, t, u, k, m);
    m_adj[std::size_t(self)][std::size_t(corner)] = x;
    relink(x, self, corner);
  }
  // an outer edge of t or u, given by (triangle, corner opposite it) before the flip, as it is after:
  // the old edge opposite t's corner k + 1, (b, c), is now opposite u's corner 0; opposite t's k + 2,
  // (c, a): t's 2; opposite u's m + 1, (a, d): t's 0; opposite u's m + 2, (d, b): u's 2
  static Link remap(const Link& x, int t, int u, int k, int m)
  {
    if(x.t == t) return x.k == (k + 1) % 3 ? Link{u, 0} : Link{t, 2};
    return x.k == (m + 1) % 3 ? Link{t, 0} : Link{u, 2};
  }
  static Triangle normalised(Triangle T)
  {
    const Offset o0 = T.o[0];
    for(auto& o : T.o) o = {{o[0] - o0[0], o[1] - o0[1]}};
    return T;
  }

  std::array<Eigen::Vector2d, 2> m_basis;
  Eigen::Matrix2d m_inverse = Eigen::Matrix2d::Identity();
  double m_area = 0;
  std::vector<Eigen::Vector2d> m_pos;  // the sites' wrapped positions
  std::vector<Triangle> m_tri;
  std::vector<std::array<Link, 3>> m_adj;  // m_adj[t][k]: across the edge opposite corner k
  std::size_t m_sites = 0, m_last_flips = 0;
  bool m_valid = false;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_TORUS_DELAUNAY_FLIPS_H
