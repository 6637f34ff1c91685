// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DIRECTED_EDGES_H
#define ANISO_CONFORMAL_INTERNAL_DIRECTED_EDGES_H

#include <algorithm>
#include <cstddef>
#include <tuple>
#include <utility>
#include <vector>

namespace Aniso_conformal {
namespace internal {

// The directed edges (tail, head) of a list of triangles, with the face each comes from, grouped by tail in
// CSR form: the edges out of v are [start[v], start[v + 1]), sorted by head, and for a repeated (tail,
// head) by face. Built in linear time (a counting sort by tail, then a sort of each vertex's few edges):
// at 1.66M vertices this replaced ordered maps of pairs that took seconds. `Index` holds a vertex, face
// and edge index (std::uint32_t halves the memory where the mesh is known to be small enough).
template <typename Index>
struct Directed_edges {
  static constexpr Index none = Index(-1);
  std::vector<Index> start, head, face;

  Directed_edges() = default;
  // the edges of faces[0, nf) (each face three vertex indices below n)
  template <typename Faces>
  Directed_edges(std::size_t n, const Faces& faces, std::size_t nf)
  {
    start.assign(n + 1, 0);
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k) ++start[std::size_t(faces[f][k]) + 1];
    for(std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    head.resize(start[n]);
    face.resize(start[n]);
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k) {
        const Index i = fill[std::size_t(faces[f][k])]++;
        head[i] = Index(faces[f][(k + 1) % 3]);
        face[i] = Index(f);
      }
    std::vector<std::pair<Index, Index>> local;
    for(std::size_t v = 0; v < n; ++v) {
      local.clear();
      for(Index i = start[v]; i < start[v + 1]; ++i) local.emplace_back(head[i], face[i]);
      std::sort(local.begin(), local.end());
      for(Index i = start[v]; i < start[v + 1]; ++i) std::tie(head[i], face[i]) = local[i - start[v]];
    }
  }

  // the first directed edge a -> b, or `none`
  Index find(std::size_t a, std::size_t b) const
  {
    const auto first = head.begin() + std::ptrdiff_t(start[a]), last = head.begin() + std::ptrdiff_t(start[a + 1]);
    const auto it = std::lower_bound(first, last, Index(b));
    return it != last && *it == Index(b) ? Index(it - head.begin()) : none;
  }
};

// The neighbours of each of the `n` vertices of the triangles behind `out`, sorted, in CSR form (the
// neighbours of v are adj[start[v]] ... adj[start[v + 1] - 1]): the heads of its directed edges (sorted,
// one each on a manifold) and the tails of the boundary edges into it (no edge back), in linear time
template <typename Index>
void vertex_neighbours(const Directed_edges<Index>& out, std::size_t n, std::vector<Index>& start, std::vector<Index>& adj)
{
  start.assign(n + 1, 0);
  std::vector<std::pair<Index, Index>> boundary;  // (tail, head) of the edges with no twin
  for(std::size_t v = 0; v < n; ++v) {
    start[v + 1] = out.start[v + 1] - out.start[v];
    for(Index i = out.start[v]; i < out.start[v + 1]; ++i)
      if(out.find(out.head[i], v) == Directed_edges<Index>::none) boundary.emplace_back(Index(v), out.head[i]);
  }
  for(const auto& b : boundary) ++start[std::size_t(b.second) + 1];
  for(std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  adj.resize(start[n]);
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for(std::size_t v = 0; v < n; ++v)
    for(Index i = out.start[v]; i < out.start[v + 1]; ++i) adj[fill[v]++] = out.head[i];
  for(const auto& b : boundary) adj[fill[b.second]++] = b.first;
  for(std::size_t v = 0; v < n; ++v) std::sort(adj.begin() + std::ptrdiff_t(start[v]), adj.begin() + std::ptrdiff_t(start[v + 1]));
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DIRECTED_EDGES_H
