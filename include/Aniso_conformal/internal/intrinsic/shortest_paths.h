// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_INTRINSIC_SHORTEST_PATHS_H
#define ANISO_CONFORMAL_INTERNAL_INTRINSIC_SHORTEST_PATHS_H

#include <cstddef>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace Aniso_conformal {
namespace internal {

// Shortest paths from `source` over the nodes 0 .. n-1 (Dijkstra, binary heap; the edge lengths must
// not be negative): `edges(u, relax)` calls `relax(v, length, tag)` for every edge from u (the tag is
// the caller's name of the edge, a halfedge); `settled(u)` is called once per node reached, in the order
// of its distance; `improved(v, tag)` whenever v's distance drops through the edge `tag` (the last call
// names v's edge in the tree of shortest paths). Returns the distances (infinity where not reached).
// The vertices of the sphere's puncture (spherical_map.h) and the faces of the dual graph
// (tree_cotree.h) use it.
template <typename Edges, typename Settled, typename Improved>
std::vector<double> shortest_paths(std::size_t n, int source, const Edges& edges, const Settled& settled, const Improved& improved)
{
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<char> done(n, 0);
  typedef std::pair<double, int> Entry;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
  dist[std::size_t(source)] = 0;
  heap.push({0.0, source});
  while(!heap.empty()) {
    const Entry top = heap.top();
    heap.pop();
    const int u = top.second;
    if(top.first > dist[std::size_t(u)] || done[std::size_t(u)]) continue;
    done[std::size_t(u)] = 1;
    settled(u);
    edges(u, [&](int v, double length, int tag) {
      const double d = top.first + length;
      if(!done[std::size_t(v)] && d < dist[std::size_t(v)]) {
        dist[std::size_t(v)] = d;
        improved(v, tag);
        heap.push({d, v});
      }
    });
  }
  return dist;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_INTRINSIC_SHORTEST_PATHS_H
