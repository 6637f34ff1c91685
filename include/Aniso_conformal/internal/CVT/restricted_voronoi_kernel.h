// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_RESTRICTED_VORONOI_KERNEL_H
#define ANISO_CONFORMAL_INTERNAL_CVT_RESTRICTED_VORONOI_KERNEL_H

#include <Aniso_conformal/internal/CVT/clip_integrate.h>
#include <Aniso_conformal/internal/parallel_for.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

// The restricted Voronoi diagram of a set of sites over background triangles, written once for every
// domain: a greedy walk on the Delaunay graph to the site nearest to a triangle, a flood over the
// neighbours whose cells can meet it, a Sutherland-Hodgman clip of the triangle (in a 2D frame of its
// own) by each cell's bisectors, and the integration of each piece. What differs between the domains
// (how distances compare, the bisector as a half-plane of the triangle's frame, how a piece is
// integrated, what is accumulated) is a cell-geometry policy; see integrate_restricted_voronoi().

namespace Aniso_conformal {
namespace internal {

// runs work(0 .. chunks-1) on up to `threads` threads (0: one), each taking the next chunk not yet
// taken (the chunks' costs differ): parallel_for_dynamic()
template <typename Work>
void run_chunks(unsigned threads, std::size_t chunks, const Work& work)
{
  std::vector<std::size_t> order(chunks);
  for(std::size_t c = 0; c < chunks; ++c) order[c] = c;
  parallel_for_dynamic(order, std::max(1u, threads), work);
}

// Greedy walk on a Delaunay graph in CSR form (neighbours of i: nbr[start[i] .. start[i+1])) from
// `seed` to a site no neighbour of which is nearer; distance(i) orders the sites by their distance to
// the target (smaller is nearer, any monotone function of the distance). It ends at the nearest site:
// on a Delaunay graph the distance has no local minimum but the global one.
template <typename Distance>
int greedy_walk(int seed, const std::vector<int>& start, const std::vector<int>& nbr, const Distance& distance)
{
  double best = distance(seed);
  for(bool moved = true; moved;) {
    moved = false;
    for(int j = start[std::size_t(seed)]; j < start[std::size_t(seed) + 1]; ++j) {
      const double d = distance(nbr[std::size_t(j)]);
      if(d < best) {
        best = d;
        seed = nbr[std::size_t(j)];
        moved = true;
        break;
      }
    }
  }
  return seed;
}

// the first site with a Delaunay neighbour (the walks start there), or 0 if none has one
inline int first_connected_site(const std::vector<int>& start)
{
  const std::size_t ns = start.empty() ? 0 : start.size() - 1;
  for(std::size_t i = 0; i < ns; ++i)
    if(start[i] != start[i + 1]) return int(i);
  return 0;
}

// What a policy knows of the bisector of sites s and n over a background triangle T before clipping.
enum class Bisector {
  misses,   // the bisector leaves T whole on s's side: no clip
  meets,    // some corner of T is nearer to n: clip
  untested  // the kernel tests T's corners, then clips (clip_half_plane() finds out whether it cuts)
};

namespace restricted_voronoi_detail {

// Clips T (in its frame) by the bisectors of site s with its Delaunay neighbours, from poly_a / poly_b;
// returns the clipped polygon (fewer than 3 vertices: s's cell misses T), its edges labelled with the
// neighbour whose bisector each lies on (-1 on T's own edges), and whether any bisector cut it.
template <typename Policy>
const Small_polygon* clip_to_cell(const Policy& P, std::size_t f, int s, const std::vector<int>& start, const std::vector<int>& nbr,
                                  Small_polygon& poly_a, Small_polygon& poly_b, bool& clipped)
{
  const auto& T = P.triangle(f);
  Small_polygon* poly = &poly_a;
  Small_polygon* tmp = &poly_b;
  poly->assign(T.p[0], T.p[1], T.p[2]);
  clipped = false;
  for(int j = start[std::size_t(s)]; j < start[std::size_t(s) + 1]; ++j) {
    const int n = nbr[std::size_t(j)];
    Eigen::Vector2d a;
    double b;
    const Bisector side = P.bisector(f, s, n, a, b);
    if(side == Bisector::misses) continue;
    // T's corners on s's side: so is the polygon inside T (most of a cell's bisectors miss T)
    if(side == Bisector::untested && a.dot(T.p[0]) <= b && a.dot(T.p[1]) <= b && a.dot(T.p[2]) <= b) continue;
    if(clip_half_plane(*poly, a, b, *tmp, n)) {
      clipped = true;
      std::swap(poly, tmp);
      if(poly->n < 3) break;
    }
  }
  return poly;
}

} // namespace restricted_voronoi_detail

/*
 * Integrates the density of the background triangles of `P` over the Voronoi cells of `ns` sites with
 * the Delaunay neighbours `start`/`nbr` (CSR form): out[i] receives the integrals of the part of the
 * triangles nearer to site i than to any other site. Each triangle is clipped against the cells it
 * meets: unless the policy knows it lies in one cell, a greedy walk finds the site nearest to it, then
 * a flood goes from cell to cell across the pieces' edges: each visited cell clips the triangle by its
 * bisectors (Sutherland-Hodgman, clip_half_plane(), each new edge labelled with the neighbour whose
 * bisector made it), its piece, or the whole triangle when no bisector cuts it, is integrated, and the
 * neighbours that label an edge of the piece are visited next: the pieces of the cells that meet T tile
 * T, so every one is reached across an edge, and a neighbour whose bisector left no edge is not visited
 * (the exact restricted Voronoi diagram by clipping, as in Yan, Levy,
 * Liu, Sun and Wang 2009, "Isotropic remeshing with fast and exact computation of restricted Voronoi
 * diagram"). The triangles are split into 16 fixed chunks (consecutive, so a
 * walk starts next to the previous triangle's site when the triangles are in a space-filling-curve
 * order), which the threads take as they become free, each into integrals of its own, summed in chunk
 * order: the result does not depend on the number of threads. `first` is a site
 * with a Delaunay neighbour (where each chunk's first walk starts).
 *
 * The cell-geometry policy P (the plane and flat torus, the sphere, the Klein disk) provides:
 *   Accumulator                        per-site integrals, zero when default-constructed, with +=
 *   number_of_triangles()
 *   triangle(f)                        T in its 2D frame: corners T.p[0..2] (Eigen::Vector2d)
 *   in_one_cell(f, s)                  true (and s) if T is known to lie in s's cell, else false
 *   in_cell_of(f, s)                   true only if no bisector of s with a Delaunay neighbour cuts T
 *                                      (then T is added whole to s, as the clipping would; a shortcut:
 *                                      false is always correct)
 *   walk_start(f, previous)            where the walk to T's nearest site starts (previous: the last
 *                                      walk's end in this chunk)
 *   walk_target(f), distance(s, y)     the point the walk approaches and the order of the sites'
 *                                      distances to it (smaller is nearer). It must lie inside T (the
 *                                      centroid): the cell of its nearest site then meets T in a piece of
 *                                      positive area. A corner would not do: at a tie the walk may stop
 *                                      at a site whose cell touches T only there, and T would be lost
 *                                      (at a cone vertex every copy of a site around the cone is a tie)
 *   bisector(f, s, n, a, b)            the points nearer to s than to n as the half-plane a.y <= b of
 *                                      T's frame, and what is known of it (Bisector)
 *   add_piece(f, s, poly, acc)         integrals over the clipped polygon (frame), about site s
 *   add_whole(f, s, acc)               integrals over the whole of T, about site s
 */
template <typename Policy>
void integrate_restricted_voronoi(const Policy& P, std::size_t ns, const std::vector<int>& start, const std::vector<int>& nbr,
                                  int first, unsigned threads, std::vector<typename Policy::Accumulator>& out)
{
  typedef typename Policy::Accumulator Accumulator;
  const std::size_t chunks = 16, nf = P.number_of_triangles();
  std::vector<std::vector<Accumulator>> acc(chunks);
  auto work = [&](std::size_t chunk) {
    std::vector<Accumulator>& A = acc[chunk];
    A.assign(ns, Accumulator());
    std::vector<int> stamp(ns, -1), stack;
    Small_polygon poly_a, poly_b;
    int seed = first;
    for(std::size_t f = chunk * nf / chunks; f < (chunk + 1) * nf / chunks; ++f) {
      int s = -1;
      if(P.in_one_cell(f, s)) {
        P.add_whole(f, s, A[std::size_t(s)]);
        continue;
      }
      // T inside the cell of the previous walk's end: the walk would stay there and no bisector cut T
      if(P.in_cell_of(f, seed)) {
        P.add_whole(f, seed, A[std::size_t(seed)]);
        continue;
      }
      const auto y = P.walk_target(f);
      seed = greedy_walk(P.walk_start(f, seed), start, nbr, [&](int i) { return P.distance(i, y); });
      if(P.in_cell_of(f, seed)) {
        P.add_whole(f, seed, A[std::size_t(seed)]);
        continue;
      }
      stack.assign(1, seed);
      stamp[std::size_t(seed)] = int(f);
      while(!stack.empty()) {
        s = stack.back();
        stack.pop_back();
        bool clipped = false;
        const Small_polygon* poly = restricted_voronoi_detail::clip_to_cell(P, f, s, start, nbr, poly_a, poly_b, clipped);
        if(poly->n < 3) continue;  // s's cell misses T: nothing to add, no flood from it
        if(!clipped) {
          P.add_whole(f, s, A[std::size_t(s)]);
          continue;  // no neighbour's cell meets T
        }
        P.add_piece(f, s, *poly, A[std::size_t(s)]);
        // the cells that meet T are those reached across the bisector edges of the pieces found
        for(int i = 0; i < poly->n; ++i) {
          const int n = poly->e[std::size_t(i)];
          if(n < 0 || stamp[std::size_t(n)] == int(f)) continue;
          stamp[std::size_t(n)] = int(f);
          stack.push_back(n);
        }
      }
    }
  };
  run_chunks(threads, chunks, work);
  out.assign(ns, Accumulator());
  parallel_for(ns, std::max(1u, threads), [&](std::size_t i) {
    for(std::size_t c = 0; c < chunks; ++c) out[i] += acc[c][i];
  });
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_RESTRICTED_VORONOI_KERNEL_H
