// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_TREE_COTREE_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_TREE_COTREE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/intrinsic/breadth_first_faces.h>
#include <Aniso_conformal/internal/intrinsic/shortest_paths.h>

#include <algorithm>
#include <deque>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <string>
#include <vector>

namespace Aniso_conformal {
namespace internal {

// A homology basis of a closed triangulated surface by the tree-cotree decomposition (Eppstein 2003):
// a spanning tree C of the faces (the cotree), a spanning tree T of the vertices through edges not
// crossed by C; the 2g edges in neither close the generators. Cutting the surface along every edge not
// in C leaves a disk (the fundamental domain) that C unfolds.
//
// C is built first, breadth-first from a central face (the middle of a longest breadth-first path of
// the dual graph, found by two sweeps), so that every face is unfolded along a shortest dual path: the
// fundamental domain is as round as the surface allows. Building T first and C in its complement, as
// textbooks do, makes C detour around T, and on surfaces of high genus the domain then grows long
// branches that reach where the hyperbolic plane is no longer representable in double precision (a
// genus-9 part reached a hyperbolic radius beyond 20).
struct Tree_cotree {
  std::vector<int> parent;         // per vertex: its parent in T (-1 at the root)
  std::vector<char> in_tree;       // per halfedge: its edge is in T
  std::vector<char> in_cotree;     // per halfedge: its edge is in C (the dual tree)
  std::vector<int> generators;     // one halfedge per edge in neither T nor C (2g of them)
  int root_face = 0;               // the face C starts from
};

// With `dual_length` (per halfedge, the length of the dual edge across it, equal for both halves), the
// sweeps and C are shortest-path searches (Dijkstra) in those lengths instead of breadth-first ones in
// numbers of faces: where faces differ in size by orders of magnitude (the hyperbolic metric of a
// genus-11 part: edges from 0.005 to 0.95), a shortest dual path in faces can run far in the metric, and
// the layout reached a hyperbolic radius of 14.6, where double precision no longer holds the hyperboloid.
inline Face_breadth_first shortest_path_faces(const Intrinsic_triangulation& itri, int start, const std::vector<double>& dual_length)
{
  const std::size_t nf = itri.number_of_faces();
  Face_breadth_first b;  // distance in lengths rounded down is not needed: `order` is by distance
  b.distance.assign(nf, -1);
  b.via.assign(nf, -1);
  b.length = shortest_paths(
      nf, start,
      [&](int f, const auto& relax) {
        for(int k = 0; k < 3; ++k) relax(Intrinsic_triangulation::face(itri.twin(3 * f + k)), dual_length[std::size_t(3 * f + k)], 3 * f + k);
      },
      [&](int f) {
        b.distance[std::size_t(f)] = int(b.order.size());  // rank in the order (a distance in faces is not kept)
        b.order.push_back(f);
      },
      [&](int g, int h) { b.via[std::size_t(g)] = h; });
  return b;
}

inline Tree_cotree tree_cotree(const Intrinsic_triangulation& itri, const std::vector<double>* dual_length = nullptr)
{
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces()), nh = int(itri.number_of_halfedges());
  for(int h = 0; h < nh; ++h)
    if(itri.twin(h) < 0) throw Invalid_input("tree_cotree(): the triangulation has a boundary (not a closed surface)");
  Tree_cotree tc;
  tc.parent.assign(std::size_t(nv), -1);
  tc.in_tree.assign(std::size_t(nh), 0);
  tc.in_cotree.assign(std::size_t(nh), 0);
  auto any = [](int) { return true; };
  // the distance of every face from `start`: in faces, or along the dual lengths
  auto sweep = [&](int start) {
    if(!dual_length) {
      Face_breadth_first b = breadth_first_faces(itri, start, any);
      b.length.assign(b.distance.begin(), b.distance.end());
      return b;
    }
    return shortest_path_faces(itri, start, *dual_length);
  };
  // the central face: two sweeps find a longest path a - b; its middle face is central
  const Face_breadth_first s0 = sweep(0);
  if(std::find(s0.distance.begin(), s0.distance.end(), -1) != s0.distance.end())
    throw Invalid_input("tree_cotree(): the triangulation is not connected");
  const std::vector<double>& d0 = s0.length;
  const int a = int(std::max_element(d0.begin(), d0.end()) - d0.begin());
  const std::vector<double> da = sweep(a).length;
  const int b = int(std::max_element(da.begin(), da.end()) - da.begin());
  const std::vector<double> db = sweep(b).length;
  int centre = a;
  for(int f = 0; f < nf; ++f)
    if(std::max(da[std::size_t(f)], db[std::size_t(f)]) < std::max(da[std::size_t(centre)], db[std::size_t(centre)])) centre = f;
  tc.root_face = centre;
  // C: the search tree from the central face, across any edge
  const Face_breadth_first c = sweep(centre);
  for(int g : c.order)
    if(c.via[std::size_t(g)] >= 0) tc.in_cotree[std::size_t(c.via[std::size_t(g)])] = tc.in_cotree[std::size_t(itri.twin(c.via[std::size_t(g)]))] = 1;
  // T: breadth-first from vertex 0 through the edges C does not cross (they form a connected graph)
  std::vector<char> seen(std::size_t(nv), 0);
  std::deque<int> vqueue(1, 0);
  seen[0] = 1;
  while(!vqueue.empty()) {
    const int v = vqueue.front();
    vqueue.pop_front();
    for(int h : itri.outgoing_halfedges(v)) {
      const int w = itri.head(h);
      if(seen[std::size_t(w)] || tc.in_cotree[std::size_t(h)]) continue;
      seen[std::size_t(w)] = 1;
      tc.parent[std::size_t(w)] = v;
      tc.in_tree[std::size_t(h)] = tc.in_tree[std::size_t(itri.twin(h))] = 1;
      vqueue.push_back(w);
    }
  }
  if(std::find(seen.begin(), seen.end(), 0) != seen.end())
    throw Internal_error("tree_cotree(): the edges the cotree does not cross do not connect the vertices");
  for(int h = 0; h < nh; ++h)
    if(itri.is_edge_representative(h) && !tc.in_tree[std::size_t(h)] && !tc.in_cotree[std::size_t(h)]) tc.generators.push_back(h);
  return tc;
}

// the closed vertex loop of generator halfedge h: tree path from h's head to the common ancestor, back
// down to h's tail; the loop closes through h itself
inline std::vector<int> generator_loop(const Intrinsic_triangulation& itri, const Tree_cotree& tc, int h)
{
  std::vector<int> pa, pb;  // from the tail (resp. head) up to the root
  for(int v = itri.tail(h); v >= 0; v = tc.parent[std::size_t(v)]) pa.push_back(v);
  for(int v = itri.head(h); v >= 0; v = tc.parent[std::size_t(v)]) pb.push_back(v);
  while(pa.size() > 1 && pb.size() > 1 && pa[pa.size() - 2] == pb[pb.size() - 2]) { pa.pop_back(); pb.pop_back(); }
  // pa and pb now end at the lowest common ancestor
  std::vector<int> loop(pb.begin(), pb.end());  // head ... ancestor
  for(std::size_t i = pa.size() - 1; i-- > 0;) loop.push_back(pa[i]);  // ... down to the tail
  return loop;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_TREE_COTREE_H
