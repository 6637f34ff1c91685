// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_RESTRICTED_VORONOI_H
#define ANISO_CONFORMAL_INTERNAL_CVT_RESTRICTED_VORONOI_H

#include <Aniso_conformal/internal/CVT/clip_integrate.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi_kernel.h>
#include <Aniso_conformal/internal/CVT/stratified_samples.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

// The parts of a Euclidean domain's CVT that do not depend on the domain's shape: background triangles
// with a linear density, their exact integration against the Voronoi cells of a set of sites (the cell
// geometry of the restricted-Voronoi kernel), a Morton order, a point-location grid. The plane and the
// flat torus share them; the sphere and the Klein disk use the background triangles in frames of their own.

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

// The Delaunay neighbours of every site in CSR form (neighbours of i: nbr[start[i] .. start[i+1])), from a
// CGAL Delaunay or regular triangulation whose vertex info is the site index; handle[i] is site i's vertex (a
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

// The Voronoi cell of every site with a vertex in the CGAL triangulation `dt` (vertex info: the site
// index; handle[i] as in delaunay_neighbours()), as the polygon of the centres circumcenter(face) of its
// finite incident faces, counterclockwise; empty for a site without a vertex. For pictures.
template <typename DT, typename Centre>
std::vector<std::vector<Eigen::Vector2d>> voronoi_polygons(const DT& dt, const std::vector<typename DT::Vertex_handle>& handle,
                                                           std::size_t ns, const Centre& circumcenter)
{
  std::vector<std::vector<Eigen::Vector2d>> cells(ns);
  for(std::size_t i = 0; i < ns; ++i) {
    if(handle[i] == typename DT::Vertex_handle() || handle[i]->info() != int(i)) continue;
    auto f = dt.incident_faces(handle[i]), done = f;
    do {
      if(!dt.is_infinite(f)) {
        const auto c = circumcenter(f);
        cells[i].emplace_back(c.x(), c.y());
      }
    } while(++f != done);
  }
  return cells;
}

// the integrals of a linear density over the whole of T about the point s (in T's frame): the
// parallel-axis theorem on T's precomputed moments
inline Cell_accumulator whole_triangle_moments(const Background_triangle& T, const Eigen::Vector2d& s)
{
  const Eigen::Vector2d d = T.g - s;
  Cell_accumulator A;
  A.mass = T.mass;
  A.mx = T.first.x() + T.mass * T.g.x();
  A.my = T.first.y() + T.mass * T.g.y();
  A.energy = T.central + 2 * d.dot(T.first) + d.squaredNorm() * T.mass;
  return A;
}

// The cell geometry of a Euclidean domain (integrate_restricted_voronoi()): the triangles are laid out
// in the plane itself, distances are Euclidean, the bisector of s and n is 2 (x_n - x_s).y <= |x_n|^2 -
// |x_s|^2, and the integrals of the linear density over a piece have closed forms.
//
// A triangle whose corners all lie within half the distance r from a site s to its nearest Delaunay
// neighbour lies in s's cell, and no bisector of s cuts it: `in_cell_of` says so without clipping. On a
// background much finer than the sites this is most triangles (the disk of radius r / 2 fills about 90 %
// of a hexagonal cell). The disk is taken 5 % narrower, so that every corner is nearer to s than to any
// neighbour by 0.05 r^2 in squared distance, far above the rounding of the bisector tests (unless the
// coordinates exceed r by a factor of a million): the integration is the same bit for bit.
class Euclidean_cell_geometry {
public:
  typedef Cell_accumulator Accumulator;
  Euclidean_cell_geometry(const std::vector<Background_triangle>& tri, const std::vector<Eigen::Vector2d>& sites,
                          const std::vector<int>& start, const std::vector<int>& nbr)
    : m_tri(tri), m_sites(sites), m_safe(sites.size(), 0.0)
  {
    for(std::size_t i = 0; i + 1 < start.size() && i < sites.size(); ++i) {
      double d2 = std::numeric_limits<double>::infinity();
      for(int j = start[i]; j < start[i + 1]; ++j) d2 = std::min(d2, (sites[std::size_t(nbr[std::size_t(j)])] - sites[i]).squaredNorm());
      m_safe[i] = start[i] < start[i + 1] ? 0.9 * d2 / 4 : 0.0;  // (0.95 r / 2)^2
    }
  }
  std::size_t number_of_triangles() const { return m_tri.size(); }
  const Background_triangle& triangle(std::size_t f) const { return m_tri[f]; }
  bool in_one_cell(std::size_t, int&) const { return false; }
  bool in_cell_of(std::size_t f, int s) const
  {
    const Eigen::Vector2d& x = m_sites[std::size_t(s)];
    const double r2 = m_safe[std::size_t(s)];
    const auto& p = m_tri[f].p;
    return (p[0] - x).squaredNorm() < r2 && (p[1] - x).squaredNorm() < r2 && (p[2] - x).squaredNorm() < r2;
  }
  int walk_start(std::size_t, int previous) const { return previous; }  // the triangles are in Morton order
  const Eigen::Vector2d& walk_target(std::size_t f) const { return m_tri[f].g; }  // inside T: see the kernel
  double distance(int s, const Eigen::Vector2d& y) const { return (m_sites[std::size_t(s)] - y).squaredNorm(); }
  Bisector bisector(std::size_t, int s, int n, Eigen::Vector2d& a, double& b) const
  {
    const Eigen::Vector2d &pn = m_sites[std::size_t(n)], &ps = m_sites[std::size_t(s)];
    a = 2.0 * (pn - ps);
    b = pn.squaredNorm() - ps.squaredNorm();
    return Bisector::untested;
  }
  void add_piece(std::size_t f, int s, const Small_polygon& poly, Accumulator& acc) const
  {
    integrate_polygon(poly.p, std::size_t(poly.n), m_tri[f].r0, m_tri[f].rg, m_sites[std::size_t(s)], acc);
  }
  void add_whole(std::size_t f, int s, Accumulator& acc) const { acc += whole_triangle_moments(m_tri[f], m_sites[std::size_t(s)]); }

private:
  const std::vector<Background_triangle>& m_tri;
  const std::vector<Eigen::Vector2d>& m_sites;
  std::vector<double> m_safe;  // per site: squared radius of the disk inside its cell (0: none known)
};

// out[i]: mass, first moment and energy (about sites[i]) of the part of the triangles `tri` (in Morton
// order) nearer to sites[i] than to any other site (Delaunay neighbours in CSR form); see
// integrate_restricted_voronoi(policy, ...)
inline void integrate_restricted_voronoi(const std::vector<Background_triangle>& tri, const std::vector<Eigen::Vector2d>& sites,
                                         const std::vector<int>& start, const std::vector<int>& nbr, unsigned threads,
                                         std::vector<Cell_accumulator>& out)
{
  integrate_restricted_voronoi(Euclidean_cell_geometry(tri, sites, start, nbr), sites.size(), start, nbr, first_connected_site(start), threads,
                               out);
}

// The weight of a background triangle when initial sites are drawn: the integral of rho^(1/2), the
// sites' density at the optimum of a CVT of density rho in two dimensions (a cell's area goes as
// rho^(-1/2): Gersho's conjecture; Du, Faber and Gunzburger 1999, SIAM Review 41(4), section 2.3), here
// |area| times the mean of the corners' rho^(1/2). Drawn by rho itself, the sites start crowded where rho
// is large (rho = cf^2: by the square of the area ratio) and the CVT spends its iterations moving them
// out, slowly (the energy still fell 2 % per 5 L-BFGS iterations after 100 on CGAL's bear).
inline double optimal_sampling_weight(const Background_triangle& T)
{
  return std::abs(T.area) * (std::sqrt(std::max(0.0, T.rho[0])) + std::sqrt(std::max(0.0, T.rho[1])) +
                             std::sqrt(std::max(0.0, T.rho[2]))) / 3;
}

// m points spread over the triangles `tri` (in Morton order) by the sites' optimal density:
// stratified_samples() weighted by optimal_sampling_weight()
inline std::vector<Eigen::Vector2d> optimally_stratified_samples(const std::vector<Background_triangle>& tri, std::size_t m,
                                                                 std::mt19937_64& rng)
{
  return stratified_samples(
      tri.size(), [&](std::size_t f) { return optimal_sampling_weight(tri[f]); },
      [&](std::size_t f) -> const std::array<Eigen::Vector2d, 3>& { return tri[f].p; }, m, rng);
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
