// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_LAWSON_FLIPS_H
#define ANISO_CONFORMAL_INTERNAL_CVT_LAWSON_FLIPS_H

#include <array>
#include <cstddef>
#include <mutex>
#include <unordered_map>
#include <utility>
#include <vector>

// Triangles as index triples with their neighbours across each edge, and Lawson's edge flips on them
// (Lawson 1977): the part the CVT's Delaunay repairs on the sphere (sphere_delaunay_flips.h) and in the
// plane (planar_delaunay_flips.h) share; each supplies its in-circle test. The flat torus' triangles carry
// lattice offsets and have their own (torus_delaunay_flips.h).

namespace Aniso_conformal {
namespace internal {

class Flip_adjacency {
public:
  std::vector<std::array<int, 3>> tri;  // counterclockwise
  std::vector<std::array<int, 3>> adj;  // adj[t][k]: the triangle across the edge opposite corner k; -1 on a boundary

  void clear()
  {
    tri.clear();
    adj.clear();
  }
  // the faces [begin, end) of a CGAL triangulation (vertex info: the site), each neighbour(k) as an
  // index, -1 where the neighbour is not among them
  template <typename FaceIterator>
  void assign(FaceIterator begin, FaceIterator end)
  {
    clear();
    std::unordered_map<const void*, int> index;
    for(auto f = begin; f != end; ++f) {
      index.emplace(static_cast<const void*>(&*f), int(tri.size()));
      tri.push_back({{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
    }
    adj.resize(tri.size());
    std::size_t t = 0;
    for(auto f = begin; f != end; ++f, ++t)
      for(int k = 0; k < 3; ++k) {  // CGAL: neighbor(k) faces vertex(k)
        const auto it = index.find(static_cast<const void*>(&*f->neighbor(k)));
        adj[t][std::size_t(k)] = it == index.end() ? -1 : it->second;
      }
  }
  // the corner of triangle u opposite its edge shared with triangle t (-1 if none, or if they share two)
  int corner_facing(int u, int t) const
  {
    int found = -1;
    for(int m = 0; m < 3; ++m)
      if(adj[std::size_t(u)][std::size_t(m)] == t) {
        if(found >= 0) return -1;
        found = m;
      }
    return found;
  }
  /*
   * Lawson's algorithm: every edge between two triangles is tested once, and the four around each flip
   * again; `is_delaunay(t, k, u, m)` tells whether the edge opposite corner k of t, corner m of u, is
   * locally Delaunay. Edges on a boundary, or shared twice by the same two triangles, are kept. Returns
   * false when the flips exceed `bound` (the triangulation is then left as it is at that point); `flips`
   * receives their number.
   */
  template <typename IsDelaunay>
  bool make_delaunay(const IsDelaunay& is_delaunay, std::size_t bound, std::size_t& flips)
  {
    flips = 0;
    std::vector<std::pair<int, int>> stack;
    stack.reserve(3 * tri.size());
    for(int t = 0; t < int(tri.size()); ++t)
      for(int k = 0; k < 3; ++k)
        if(t < adj[std::size_t(t)][std::size_t(k)]) stack.emplace_back(t, k);
    while(!stack.empty()) {
      const auto [t, k] = stack.back();
      stack.pop_back();
      const int u = adj[std::size_t(t)][std::size_t(k)];
      if(u < 0) continue;
      const int m = corner_facing(u, t);
      if(m < 0 || is_delaunay(t, k, u, m)) continue;
      if(++flips > bound) return false;
      flip(t, k, u, m, stack);
    }
    return true;
  }
  /*
   * The neighbours of each of `n` vertices in CSR form (neighbours of i: nbr[start[i] .. start[i+1])):
   * the head of every directed edge of a triangle (counterclockwise), and across a boundary edge its tail.
   */
  void neighbours(std::size_t n, std::vector<int>& start, std::vector<int>& nbr) const
  {
    start.assign(n + 1, 0);
    for(std::size_t t = 0; t < tri.size(); ++t)
      for(int k = 0; k < 3; ++k) {
        ++start[std::size_t(tri[t][std::size_t(k)]) + 1];
        if(adj[t][std::size_t(k)] < 0) ++start[std::size_t(tri[t][std::size_t((k + 2) % 3)]) + 1];
      }
    for(std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
    nbr.assign(std::size_t(start[n]), -1);
    std::vector<int> next(start.begin(), start.end() - 1);
    for(std::size_t t = 0; t < tri.size(); ++t)
      for(int k = 0; k < 3; ++k) {
        const int a = tri[t][std::size_t(k)], b = tri[t][std::size_t((k + 1) % 3)];
        nbr[std::size_t(next[std::size_t(a)]++)] = b;
        if(adj[t][std::size_t(k)] < 0) {  // the edge (k + 1, k + 2) on the boundary: its head's way back
          const int p = tri[t][std::size_t((k + 1) % 3)], q = tri[t][std::size_t((k + 2) % 3)];
          nbr[std::size_t(next[std::size_t(q)]++)] = p;
        }
      }
  }

private:
  // replaces the slot of `old_t` in the adjacency of triangle x (if any) by `new_t`
  void relink(int x, int old_t, int new_t)
  {
    if(x < 0) return;
    for(int j = 0; j < 3; ++j)
      if(adj[std::size_t(x)][std::size_t(j)] == old_t) {
        adj[std::size_t(x)][std::size_t(j)] = new_t;
        return;
      }
  }
  // (c, a, b) in t and (d, b, a) in u become (c, a, d) in t and (d, b, c) in u; their four outer edges
  // go on the stack
  void flip(int t, int k, int u, int m, std::vector<std::pair<int, int>>& stack)
  {
    const auto T = tri[std::size_t(t)], U = tri[std::size_t(u)];
    const auto At = adj[std::size_t(t)], Au = adj[std::size_t(u)];
    const int c = T[std::size_t(k)], a = T[std::size_t((k + 1) % 3)], b = T[std::size_t((k + 2) % 3)];
    const int d = U[std::size_t(m)];
    const int t_bc = At[std::size_t((k + 1) % 3)], t_ca = At[std::size_t((k + 2) % 3)];  // across (b, c), (c, a)
    const int u_ad = Au[std::size_t((m + 1) % 3)], u_db = Au[std::size_t((m + 2) % 3)];  // across (a, d), (d, b)
    tri[std::size_t(t)] = {{c, a, d}};
    adj[std::size_t(t)] = {{u_ad, u, t_ca}};
    tri[std::size_t(u)] = {{d, b, c}};
    adj[std::size_t(u)] = {{t_bc, t, u_db}};
    relink(u_ad, u, t);
    relink(t_bc, t, u);
    stack.emplace_back(t, 0);
    stack.emplace_back(t, 2);
    stack.emplace_back(u, 0);
    stack.emplace_back(u, 2);
  }
};

// What the sphere's and the plane's repaired triangulations share: the triangles, whether they are held
// (the last take() or update() succeeded), the flips of the last update, and the neighbour lists.
class Flip_triangulation_base {
public:
  bool valid() const { return m_valid; }
  std::size_t number_of_triangles() const { return m_mesh.tri.size(); }
  const std::array<int, 3>& triangle(std::size_t t) const { return m_mesh.tri[t]; }
  // the triangle across the edge of triangle t opposite its corner k, or -1 on the boundary (the convex hull in the plane)
  int across(std::size_t t, int k) const { return m_mesh.adj[t][std::size_t(k)]; }
  std::size_t last_flips() const { return m_last_flips; }
  // renames vertex i of every triangle new_of_old[i] (a permutation of the sites)
  void relabel(const std::vector<int>& new_of_old)
  {
    for(auto& t : m_mesh.tri)
      for(int& v : t) v = new_of_old[std::size_t(v)];
  }
  // the Delaunay neighbours of every site in CSR form (neighbours of i: nbr[start[i] .. start[i+1]))
  void neighbours(std::vector<int>& start, std::vector<int>& nbr) const { m_mesh.neighbours(m_sites, start, nbr); }

protected:
  Flip_adjacency m_mesh;  // counterclockwise
  std::size_t m_sites = 0, m_last_flips = 0;
  bool m_valid = false;
};

// A domain's last Delaunay triangulation of the sites, shared by copies of its traits and repaired at
// the next integration (one at a time: a concurrent one, failing to lock, triangulates anew)
template <typename Flips>
struct Flip_cache {
  std::mutex mutex;
  Flips flips;
  std::size_t repairs = 0;  // integrations that repaired instead of triangulating anew
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_LAWSON_FLIPS_H
