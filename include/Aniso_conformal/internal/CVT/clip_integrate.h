// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_CLIP_INTEGRATE_H
#define ANISO_CONFORMAL_INTERNAL_CVT_CLIP_INTEGRATE_H

#include <Eigen/Core>

#include <array>
#include <vector>

namespace Aniso_conformal {
namespace internal {

// Mass, first moment and CVT energy of a linear density over a region, accumulated exactly.
struct Cell_accumulator {
  double mass = 0, mx = 0, my = 0, energy = 0;
  void operator+=(const Cell_accumulator& o) { mass += o.mass; mx += o.mx; my += o.my; energy += o.energy; }
};

// A convex polygon with a fixed capacity: clipping a triangle by the half-planes of one Voronoi cell adds
// at most one vertex per half-plane, and cells have far fewer than 120 Delaunay neighbours. Each edge
// carries a label: e[i] for the edge from p[i] to p[i + 1] (cyclically), -1 for the triangle's own edges
// and the label given to clip_half_plane() for the edges its half-plane made (the Voronoi neighbour whose
// bisector it lies on).
struct Small_polygon {
  static constexpr int capacity = 128;
  std::array<Eigen::Vector2d, capacity> p;
  std::array<int, capacity> e;
  int n = 0;
  void assign(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c)
  {
    p[0] = a;
    p[1] = b;
    p[2] = c;
    e[0] = e[1] = e[2] = -1;
    n = 3;
  }
};

// Sutherland-Hodgman clip of the convex polygon `in` by the half-plane a.p <= b, into `out`; the edges
// along the half-plane's line get the label `label`, the others keep theirs. Returns false (and leaves
// `out` unspecified) if the half-plane does not cut `in`.
inline bool clip_half_plane(const Small_polygon& in, const Eigen::Vector2d& a, double b, Small_polygon& out, int label = -1)
{
  double f[Small_polygon::capacity];
  bool cuts = false;
  for(int i = 0; i < in.n; ++i) {
    f[i] = a.x() * in.p[i].x() + a.y() * in.p[i].y() - b;
    cuts = cuts || f[i] > 0;
  }
  if(!cuts) return false;
  out.n = 0;
  for(int i = 0; i < in.n && out.n + 1 < Small_polygon::capacity; ++i) {
    const int j = (i + 1 == in.n) ? 0 : i + 1;
    const double fp = f[i], fq = f[j];
    if(fp <= 0) {  // p[i] kept; its edge leaves along the line when p[i] is on it and p[j] outside
      out.e[out.n] = (fp == 0 && fq > 0) ? label : in.e[i];
      out.p[out.n++] = in.p[i];
    }
    if((fp < 0 && fq > 0) || (fp > 0 && fq < 0)) {  // the edge crosses the line: leaving, then along it
      out.e[out.n] = fp < 0 ? label : in.e[i];
      out.p[out.n++] = in.p[i] + (fp / (fp - fq)) * (in.p[j] - in.p[i]);
    }
  }
  return true;
}

// Adds the integrals over the convex polygon `poly` of rho, rho*y and rho*|y - s|^2, with rho the affine
// function rho(y) = r0 + rg.y. Fan triangulation; each piece integrated in closed form from
// int_T l_i l_j l_k = 2A i!j!k!/(i+j+k+2)! (exact: rho is linear, |y - s|^2 quadratic). With q_k the
// corners relative to s and S = q_0 + q_1 + q_2 this gives
//   int_T rho |y - s|^2 = A/60 sum_i rho_i (2|S|^2 + 4|q_i|^2 - 2 q_j.q_k),   {i, j, k} = {0, 1, 2}.
template <typename Points>
void integrate_polygon(const Points& poly, std::size_t n, double r0, const Eigen::Vector2d& rg, const Eigen::Vector2d& s,
                       Cell_accumulator& acc)
{
  if(n < 3) return;
  const double x0 = poly[0].x(), y0 = poly[0].y();
  const double rho0 = r0 + rg.x() * x0 + rg.y() * y0;
  const double qx0 = x0 - s.x(), qy0 = y0 - s.y();
  double x1 = poly[1].x(), y1 = poly[1].y(), rho1 = r0 + rg.x() * x1 + rg.y() * y1;
  for(std::size_t i = 2; i < n; ++i) {
    const double x2 = poly[i].x(), y2 = poly[i].y(), rho2 = r0 + rg.x() * x2 + rg.y() * y2;
    const double A = 0.5 * ((x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0));
    if(A > 0) {
      const double rs = rho0 + rho1 + rho2;
      acc.mass += A * rs / 3.0;
      const double c = A / 12.0;
      acc.mx += c * ((rs + rho0) * x0 + (rs + rho1) * x1 + (rs + rho2) * x2);
      acc.my += c * ((rs + rho0) * y0 + (rs + rho1) * y1 + (rs + rho2) * y2);
      const double qx1 = x1 - s.x(), qy1 = y1 - s.y(), qx2 = x2 - s.x(), qy2 = y2 - s.y();
      const double Sx = qx0 + qx1 + qx2, Sy = qy0 + qy1 + qy2, SS2 = 2 * (Sx * Sx + Sy * Sy);
      const double g00 = qx0 * qx0 + qy0 * qy0, g11 = qx1 * qx1 + qy1 * qy1, g22 = qx2 * qx2 + qy2 * qy2;
      const double g01 = qx0 * qx1 + qy0 * qy1, g02 = qx0 * qx2 + qy0 * qy2, g12 = qx1 * qx2 + qy1 * qy2;
      acc.energy += (A / 60.0) * (rho0 * (SS2 + 4 * g00 - 2 * g12) + rho1 * (SS2 + 4 * g11 - 2 * g02) +
                                  rho2 * (SS2 + 4 * g22 - 2 * g01));
    }
    x1 = x2;
    y1 = y2;
    rho1 = rho2;
  }
}

// std::vector forms of the two functions above (convenient in tests; the CVT uses the fixed-size ones)
inline void clip_half_plane(const std::vector<Eigen::Vector2d>& in, const Eigen::Vector2d& a, double b,
                            std::vector<Eigen::Vector2d>& out)
{
  Small_polygon p, q;
  p.n = int(std::min<std::size_t>(in.size(), Small_polygon::capacity));
  for(int i = 0; i < p.n; ++i) {
    p.p[i] = in[i];
    p.e[i] = -1;
  }
  const Small_polygon& r = clip_half_plane(p, a, b, q) ? q : p;
  out.assign(r.p.begin(), r.p.begin() + r.n);
}

inline void integrate_polygon(const std::vector<Eigen::Vector2d>& poly, double r0, const Eigen::Vector2d& rg,
                              const Eigen::Vector2d& s, Cell_accumulator& acc)
{
  integrate_polygon(poly, poly.size(), r0, rg, s, acc);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_CLIP_INTEGRATE_H
