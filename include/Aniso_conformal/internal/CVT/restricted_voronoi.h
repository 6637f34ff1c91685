// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_RESTRICTED_VORONOI_H
#define ANISO_CONFORMAL_INTERNAL_CVT_RESTRICTED_VORONOI_H

#include <Aniso_conformal/internal/CVT/clip_integrate.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <thread>
#include <utility>
#include <vector>

// The parts of a Euclidean domain's CVT that do not depend on the domain's shape: background triangles
// with a linear density, their exact integration against the Voronoi cells of a set of sites (restricted
// Voronoi diagram), a Morton order, a point-location grid. The plane and the flat torus share them.

namespace Aniso_conformal {
namespace internal {

// a background triangle laid out in the domain, with the affine density rho(y) = r0 + rg.y through its
// corners and its integrals about its centroid (used when no bisector cuts it)
struct Background_triangle {
  std::array<Eigen::Vector2d, 3> p;
  std::array<double, 3> rho;
  int face = -1;  // index in the Intrinsic_triangulation
  Eigen::Vector2d g = Eigen::Vector2d::Zero();
  double mass = 0, central = 0;                     // int rho, int rho |y - g|^2
  Eigen::Vector2d first = Eigen::Vector2d::Zero();  // int rho (y - g)
  double r0 = 0, area = 0;
  Eigen::Vector2d rg = Eigen::Vector2d::Zero();
};

inline Background_triangle make_background_triangle(const std::array<Eigen::Vector2d, 3>& p, const std::array<double, 3>& rho,
                                                    int face)
{
  Background_triangle T;
  T.face = face;
  T.p = p;
  T.rho = rho;
  Eigen::Matrix3d A;
  for(int k = 0; k < 3; ++k) A.row(k) << 1, p[k].x(), p[k].y();
  const Eigen::Vector3d coef = A.fullPivLu().solve(Eigen::Vector3d(rho[0], rho[1], rho[2]));
  T.r0 = coef[0];
  T.rg = Eigen::Vector2d(coef[1], coef[2]);
  const Eigen::Vector2d e1 = p[1] - p[0], e2 = p[2] - p[0];
  T.area = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
  T.g = (p[0] + p[1] + p[2]) / 3.0;
  Cell_accumulator whole;
  integrate_polygon(T.p, 3, T.r0, T.rg, T.g, whole);
  T.mass = whole.mass;
  T.central = whole.energy;
  T.first = Eigen::Vector2d(whole.mx, whole.my) - whole.mass * T.g;
  return T;
}

// indices of `points` sorted along a Morton curve over the box [lo, hi]: nearby triangles are processed
// together, which keeps the nearest-site walks short and the memory accesses local
inline std::vector<std::size_t> morton_order(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& lo,
                                             const Eigen::Vector2d& hi)
{
  const Eigen::Vector2d ext = (hi - lo).cwiseMax(1e-300);
  std::vector<std::pair<std::uint64_t, std::size_t>> key(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& g = points[i];
    const std::uint64_t x = std::uint64_t(std::min(1.0, std::max(0.0, (g.x() - lo.x()) / ext.x())) * 65535.0);
    const std::uint64_t y = std::uint64_t(std::min(1.0, std::max(0.0, (g.y() - lo.y()) / ext.y())) * 65535.0);
    std::uint64_t code = 0;
    for(int b = 0; b < 16; ++b) code |= ((x >> b) & 1u) << (2 * b) | ((y >> b) & 1u) << (2 * b + 1);
    key[i] = {code, i};
  }
  std::sort(key.begin(), key.end());
  std::vector<std::size_t> order(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) order[i] = key[i].second;
  return order;
}

// runs work(0 .. chunks-1) on up to `threads` threads
template <typename Work>
void run_chunks(unsigned threads, std::size_t chunks, Work& work)
{
  const unsigned nt = std::min<unsigned>(threads, unsigned(chunks));
  if(nt <= 1) {
    for(std::size_t c = 0; c < chunks; ++c) work(c);
    return;
  }
  std::vector<std::thread> pool;
  for(unsigned t = 0; t < nt; ++t)
    pool.emplace_back([&, t]() {
      for(std::size_t c = t; c < chunks; c += nt) work(c);
    });
  for(auto& th : pool) th.join();
}

// The Delaunay neighbours of every site in CSR form (neighbours of i: nbr[start[i] .. start[i+1])), from a
// CGAL Delaunay_triangulation_2 whose vertex info is the site index; handle[i] is site i's vertex (a
// default handle, or one whose info differs, for a site that coincides with another: it keeps no cell).
template <typename DT>
void delaunay_neighbours(const DT& dt, const std::vector<typename DT::Vertex_handle>& handle, std::vector<int>& start,
                         std::vector<int>& nbr)
{
  const std::size_t ns = handle.size();
  start.assign(ns + 1, 0);
  nbr.clear();
  for(std::size_t i = 0; i < ns; ++i) {
    start[i] = int(nbr.size());
    if(handle[i] == typename DT::Vertex_handle() || handle[i]->info() != int(i)) continue;
    auto c = dt.incident_vertices(handle[i]), done = c;
    if(c != nullptr) do {
        if(!dt.is_infinite(c)) nbr.push_back(c->info());
      } while(++c != done);
  }
  start[ns] = int(nbr.size());
}

/*
 * Integrates the density of the triangles `tri` over the Voronoi cells of `sites` (Delaunay neighbours
 * in CSR form): out[i] receives the mass, first moment and energy (about sites[i]) of the part of the
 * triangles nearer to sites[i] than to any other site. Each triangle is clipped against the cells it
 * meets, found by a greedy walk on the Delaunay graph to the site nearest to a corner (exact for
 * Delaunay graphs) and a flood over the neighbours whose cells can meet it. Fixed chunks summed in
 * order: the result does not depend on the number of threads.
 */
inline void integrate_restricted_voronoi(const std::vector<Background_triangle>& tri, const std::vector<Eigen::Vector2d>& sites,
                                         const std::vector<int>& start, const std::vector<int>& nbr, unsigned threads,
                                         std::vector<Cell_accumulator>& out)
{
  const std::size_t ns = sites.size(), chunks = 16, nf = tri.size();
  std::vector<std::vector<Cell_accumulator>> acc(chunks, std::vector<Cell_accumulator>(ns));
  int any_site = 0;
  while(any_site < int(ns) && start[any_site] == start[any_site + 1] && ns > 1) ++any_site;
  auto work = [&](std::size_t chunk) {
    std::vector<int> stamp(ns, -1), stack;
    Small_polygon poly_a, poly_b;
    int seed = any_site;
    for(std::size_t f = chunk * nf / chunks; f < (chunk + 1) * nf / chunks; ++f) {
      const Background_triangle& T = tri[f];
      // triangles are in Morton order, so the previous seed is close
      double best = (sites[seed] - T.p[0]).squaredNorm();
      for(bool moved = true; moved;) {
        moved = false;
        for(int j = start[seed]; j < start[seed + 1]; ++j) {
          const double d = (sites[nbr[j]] - T.p[0]).squaredNorm();
          if(d < best) { best = d; seed = nbr[j]; moved = true; break; }
        }
      }
      stack.assign(1, seed);
      stamp[seed] = int(f);
      while(!stack.empty()) {
        const int s = stack.back();
        stack.pop_back();
        Small_polygon* poly = &poly_a;
        Small_polygon* tmp = &poly_b;
        poly->assign(T.p[0], T.p[1], T.p[2]);
        const Eigen::Vector2d& ps = sites[s];
        bool clipped = false;
        for(int j = start[s]; j < start[s + 1] && poly->n >= 3; ++j) {
          const Eigen::Vector2d& pn = sites[nbr[j]];
          if(clip_half_plane(*poly, 2.0 * (pn - ps), pn.squaredNorm() - ps.squaredNorm(), *tmp)) {
            clipped = true;
            std::swap(poly, tmp);
          }
        }
        if(poly->n < 3) continue;
        if(clipped) {
          integrate_polygon(poly->p, std::size_t(poly->n), T.r0, T.rg, ps, acc[chunk][s]);
        } else {
          // the whole triangle is in the cell: parallel-axis theorem on the precomputed moments
          Cell_accumulator& A = acc[chunk][s];
          const Eigen::Vector2d d = T.g - ps;
          A.mass += T.mass;
          A.mx += T.first.x() + T.mass * T.g.x();
          A.my += T.first.y() + T.mass * T.g.y();
          A.energy += T.central + 2 * d.dot(T.first) + d.squaredNorm() * T.mass;
          continue;  // no neighbour's cell meets T
        }
        for(int j = start[s]; j < start[s + 1]; ++j) {
          const int n = nbr[j];
          if(stamp[n] == int(f)) continue;
          // n's cell can meet T only if a corner of T is closer to n than to s
          const Eigen::Vector2d a = 2.0 * (sites[n] - ps);
          const double b = sites[n].squaredNorm() - ps.squaredNorm();
          if(a.dot(T.p[0]) <= b && a.dot(T.p[1]) <= b && a.dot(T.p[2]) <= b) continue;
          stamp[n] = int(f);
          stack.push_back(n);
        }
      }
    }
  };
  run_chunks(threads, chunks, work);
  out.assign(ns, Cell_accumulator());
  for(std::size_t i = 0; i < ns; ++i)
    for(std::size_t c = 0; c < chunks; ++c) {
      out[i].mass += acc[c][i].mass;
      out[i].mx += acc[c][i].mx;
      out[i].my += acc[c][i].my;
      out[i].energy += acc[c][i].energy;
    }
}

// m points spread over the density of `tri` (in Morton order): evenly spaced quantiles of the mass
// along the curve, shifted by one random offset, then a random point in the chosen triangle, shrunk
// towards its centroid so that no point starts on an edge. A space-filling-curve sample is already well
// spread, so the CVT starts close to its optimum; the generator changes both the offset and the points.
inline std::vector<Eigen::Vector2d> stratified_samples(const std::vector<Background_triangle>& tri, std::size_t m,
                                                       std::mt19937_64& rng)
{
  std::vector<double> cdf(tri.size());
  double acc = 0;
  for(std::size_t f = 0; f < tri.size(); ++f) {
    acc += tri[f].mass;
    cdf[f] = acc;
  }
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double offset = U(rng);
  std::vector<Eigen::Vector2d> out;
  out.reserve(m);
  for(std::size_t k = 0; k < m; ++k) {
    const double r = (double(k) + offset) / double(m) * acc;
    const std::size_t f = std::min(tri.size() - 1, std::size_t(std::lower_bound(cdf.begin(), cdf.end(), r) - cdf.begin()));
    double a = U(rng), b = U(rng);
    if(a + b > 1) { a = 1 - a; b = 1 - b; }
    const Background_triangle& T = tri[f];
    const Eigen::Vector2d p = T.p[0] + a * (T.p[1] - T.p[0]) + b * (T.p[2] - T.p[0]);
    out.push_back(T.g + 0.98 * (p - T.g));
  }
  return out;
}

// A uniform grid over triangles for point location (about two triangles per cell).
class Triangle_grid {
public:
  void build(const std::vector<Background_triangle>& tri)
  {
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for(const auto& T : tri)
      for(const auto& p : T.p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    const Eigen::Vector2d ext = hi - lo;
    const double pad = 1e-9 * std::max(ext.x(), ext.y());
    m_lo = lo - Eigen::Vector2d(pad, pad);
    const Eigen::Vector2d size = ext + Eigen::Vector2d(2 * pad, 2 * pad);
    m_cell = std::sqrt(size.x() * size.y() / std::max<double>(1.0, double(tri.size()) / 2));
    m_nx = std::max(1, int(std::ceil(size.x() / m_cell)));
    m_ny = std::max(1, int(std::ceil(size.y() / m_cell)));
    m_grid.assign(std::size_t(m_nx) * m_ny, {});
    for(std::size_t f = 0; f < tri.size(); ++f) {
      Eigen::Vector2d a = tri[f].p[0].cwiseMin(tri[f].p[1]).cwiseMin(tri[f].p[2]);
      Eigen::Vector2d b = tri[f].p[0].cwiseMax(tri[f].p[1]).cwiseMax(tri[f].p[2]);
      const double eps = 1e-9 * m_cell;
      const int x0 = std::max(0, int(std::floor((a.x() - eps - m_lo.x()) / m_cell)));
      const int x1 = std::min(m_nx - 1, int(std::floor((b.x() + eps - m_lo.x()) / m_cell)));
      const int y0 = std::max(0, int(std::floor((a.y() - eps - m_lo.y()) / m_cell)));
      const int y1 = std::min(m_ny - 1, int(std::floor((b.y() + eps - m_lo.y()) / m_cell)));
      for(int y = y0; y <= y1; ++y)
        for(int x = x0; x <= x1; ++x) m_grid[std::size_t(y) * m_nx + x].push_back(int(f));
    }
  }

  // the triangle (index into the vector given to build()) whose barycentric coordinates of p have the
  // largest minimum, among those of p's grid cell; false if p is outside the grid or that minimum is
  // below -tolerance. The coordinates are clamped to the triangle.
  bool locate(const std::vector<Background_triangle>& tri, const Eigen::Vector2d& p, int& index, Eigen::Vector3d& bary,
              double tolerance) const
  {
    const int gx = int(std::floor((p.x() - m_lo.x()) / m_cell)), gy = int(std::floor((p.y() - m_lo.y()) / m_cell));
    if(gx < 0 || gx >= m_nx || gy < 0 || gy >= m_ny) return false;
    double best = -1e300;
    for(int f : m_grid[std::size_t(gy) * m_nx + gx]) {
      const Eigen::Vector3d b = barycentric(tri[std::size_t(f)], p);
      const double m = b.minCoeff();
      if(m > best) {
        best = m;
        index = f;
        bary = b;
      }
      if(m >= 0) break;
    }
    if(best < -tolerance) return false;
    bary = bary.cwiseMax(0.0);
    bary /= bary.sum();
    return true;
  }

  static Eigen::Vector3d barycentric(const Background_triangle& T, const Eigen::Vector2d& p)
  {
    const Eigen::Vector2d e1 = T.p[1] - T.p[0], e2 = T.p[2] - T.p[0], w = p - T.p[0];
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    const double b1 = (w.x() * e2.y() - w.y() * e2.x()) / det, b2 = (e1.x() * w.y() - e1.y() * w.x()) / det;
    return Eigen::Vector3d(1 - b1 - b2, b1, b2);
  }

private:
  Eigen::Vector2d m_lo = Eigen::Vector2d::Zero();
  double m_cell = 1;
  int m_nx = 1, m_ny = 1;
  std::vector<std::vector<int>> m_grid;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_RESTRICTED_VORONOI_H
