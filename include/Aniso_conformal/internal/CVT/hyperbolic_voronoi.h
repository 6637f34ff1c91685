// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_HYPERBOLIC_VORONOI_H
#define ANISO_CONFORMAL_INTERNAL_CVT_HYPERBOLIC_VORONOI_H

#include <Aniso_conformal/internal/CVT/clip_integrate.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi_kernel.h>
#include <Aniso_conformal/internal/conformal/hyperbolic_geometry.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

// The restricted Voronoi diagram of points of the hyperboloid over background triangles laid out in the
// Klein disk. The hyperbolic Voronoi diagram is a power diagram in the Klein disk (Nielsen and Nock,
// "Hyperbolic Voronoi diagrams made easy", 2010): y is nearer to x_s than to x_n iff
// (x_n1 - x_s1, x_n2 - x_s2).k <= x_n0 - x_s0 at its Klein point k, a half-plane of the disk, so a Klein
// triangle is clipped as a planar one. The integrals are not polynomial there (the area element is
// (1 - |k|^2)^(-3/2)): a quadrature on each piece.

namespace Aniso_conformal {
namespace internal {

// mass, first moment on the hyperboloid (in R^3), energy int rho d(y, x)^2 and its gradient with respect
// to the site's coordinates in R^3, of one cell
struct Hyperbolic_cell_accumulator {
  double mass = 0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  double energy = 0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  void operator+=(const Hyperbolic_cell_accumulator& o)
  {
    mass += o.mass;
    moment += o.moment;
    energy += o.energy;
    gradient += o.gradient;
  }
};

// One node of the quadrature of integrate_hyperbolic_piece(): a point y of the hyperboloid and its weight
// (rule weight x Klein area x density x area element).
struct Hyperbolic_quadrature_node {
  Eigen::Vector3d y = Eigen::Vector3d::UnitX();
  double w = 0;
};

// Adds one node's integrals about the site x. With h = |y - x|_M / 2 (the Minkowski norm of the chord),
// d(y, x) = 2 asinh h and sinh d = 2 h sqrt(1 + h^2), so d / sinh d = (asinh h / h) / sqrt(1 + h^2) needs
// no sinh; asinh h / h by its Taylor series where h <= 1/8 (eight terms: remainder below 4e-17), by a
// logarithm beyond. The gradient uses
// d d(y, x) / dx = -J y / sinh d (J = diag(-1, 1, 1)) through d^2.
inline void add_hyperbolic_node(const Eigen::Vector3d& y, double w, const Eigen::Vector3d& x, Hyperbolic_cell_accumulator& acc)
{
  const Eigen::Vector3d e = y - x;
  const double h2 = 0.25 * std::max(0.0, minkowski_dot(e, e));
  double S;  // asinh(h) / h
  if(h2 <= 1.0 / 64)
    S = 1 + h2 * (-1.0 / 6 + h2 * (3.0 / 40 + h2 * (-5.0 / 112 + h2 * (35.0 / 1152 + h2 * (-63.0 / 2816 +
        h2 * (231.0 / 13312 + h2 * (-143.0 / 10240)))))));
  else {  // asinh h = log(h + sqrt(1 + h^2)): for h > 1/8 the rounding of the sum costs at most 1e-15 relative
    const double h = std::sqrt(h2);
    S = std::log(h + std::sqrt(1 + h2)) / h;
  }
  const double d2 = 4 * h2 * S * S;  // d = 2 h S
  const double f = S / std::sqrt(1 + h2);  // d / sinh d
  acc.mass += w;
  acc.moment += w * y;
  acc.energy += w * d2;
  acc.gradient += (2 * w * f) * Eigen::Vector3d(y.x(), -y.y(), -y.z());
}

// Calls node(y, w) for each quadrature node of the convex Klein polygon poly[0 .. n-1] (a part of
// background triangle T, with the density r0 + rg.k of T). The area element (1 - |k|^2)^(-3/2) is steep
// far out in the disk, so the polygon is first moved by the isometry F^-1 (F takes the centre to the
// triangle's centroid: a projective map of the Klein disk, polygons stay polygons), where the element is
// flat to second order; then a 6-point rule of degree 4 (Dunavant 1985) on a fan, the density evaluated
// at the node's place in the domain.
template <typename Points, typename Node>
void for_each_hyperbolic_node(const Background_triangle& T, const Eigen::Matrix3d& F, const Points& poly, int n, const Node& node)
{
  static const double w6[2] = {0.223381589678011, 0.109951743655322};
  static const double b6[2][3] = {{0.108103018168070, 0.445948490915965, 0.445948490915965},
                                  {0.816847572980459, 0.091576213509771, 0.091576213509771}};
  const Eigen::Matrix3d Finv = lorentz_inverse(F);
  Eigen::Vector2d local[Small_polygon::capacity];
  for(int i = 0; i < n; ++i) local[i] = to_klein(Finv * from_klein(poly[i]));
  for(int i = 2; i < n; ++i) {
    const Eigen::Vector2d &a = local[0], &b = local[i - 1], &c = local[i];
    const double A = 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
    if(!(A > 0)) continue;
    for(int q = 0; q < 6; ++q) {
      const double* l = b6[q / 3];
      const int r = q % 3;
      const Eigen::Vector2d k = l[r] * a + l[(r + 1) % 3] * b + l[(r + 2) % 3] * c;
      const double s = 1.0 / std::sqrt(std::max(1e-300, 1 - k.squaredNorm()));
      const Eigen::Vector3d y = F * Eigen::Vector3d(s, s * k.x(), s * k.y());  // the node in the domain
      const double rho = T.r0 + T.rg.dot(Eigen::Vector2d(y.y() / y.x(), y.z() / y.x()));
      node(y, A * w6[q / 3] * rho * s * s * s);  // area element (1 - |k|^2)^(-3/2)
    }
  }
}

// Adds the integrals over the convex Klein polygon poly[0 .. n-1] of background triangle T about the
// site x (hyperboloid): for_each_hyperbolic_node() and add_hyperbolic_node().
template <typename Points>
void integrate_hyperbolic_piece(const Background_triangle& T, const Eigen::Matrix3d& F, const Points& poly, int n,
                                const Eigen::Vector3d& x, Hyperbolic_cell_accumulator& acc)
{
  for_each_hyperbolic_node(T, F, poly, n, [&](const Eigen::Vector3d& y, double w) { add_hyperbolic_node(y, w, x, acc); });
}

// the six quadrature nodes of a whole background triangle (zero weights if it has no area): they do not
// depend on the sites, so they are computed once and serve every triangle that lies in one cell
inline std::array<Hyperbolic_quadrature_node, 6> hyperbolic_triangle_nodes(const Background_triangle& T, const Eigen::Matrix3d& F)
{
  std::array<Hyperbolic_quadrature_node, 6> nodes;
  int i = 0;
  for_each_hyperbolic_node(T, F, T.p, 3, [&](const Eigen::Vector3d& y, double w) { nodes[std::size_t(i++)] = {y, w}; });
  return nodes;
}

// The cell geometry of the Klein disk (integrate_restricted_voronoi()): the triangles are Klein
// triangles (with the density cf^2 and, per triangle, the isometry `frame` of
// integrate_hyperbolic_piece()), the walk orders the points by -<x, y> (cosh of the distance), the
// bisector is the power-diagram half-plane, and pieces and whole triangles are integrated by quadrature.
class Hyperbolic_cell_geometry {
public:
  typedef Hyperbolic_cell_accumulator Accumulator;
  Hyperbolic_cell_geometry(const std::vector<Background_triangle>& tri, const std::vector<Eigen::Matrix3d>& frame,
                           const std::vector<std::array<Hyperbolic_quadrature_node, 6>>& whole,
                           const std::vector<Eigen::Vector3d>& points)
    : m_tri(tri), m_frame(frame), m_whole(whole), m_points(points)
  {}
  std::size_t number_of_triangles() const { return m_tri.size(); }
  const Background_triangle& triangle(std::size_t f) const { return m_tri[f]; }
  bool in_one_cell(std::size_t, int&) const { return false; }
  bool in_cell_of(std::size_t, int) const { return false; }
  int walk_start(std::size_t, int previous) const { return previous; }  // the triangles are in Morton order
  Eigen::Vector3d walk_target(std::size_t f) const { return from_klein(m_tri[f].g); }  // inside T: see the kernel
  double distance(int s, const Eigen::Vector3d& y) const { return -minkowski_dot(m_points[std::size_t(s)], y); }
  Bisector bisector(std::size_t, int s, int n, Eigen::Vector2d& a, double& b) const
  {
    // closer to s than to n: (n1 - s1, n2 - s2) . k <= n0 - s0
    const Eigen::Vector3d &pn = m_points[std::size_t(n)], &ps = m_points[std::size_t(s)];
    a = Eigen::Vector2d(pn.y() - ps.y(), pn.z() - ps.z());
    b = pn.x() - ps.x();
    return Bisector::untested;
  }
  void add_piece(std::size_t f, int s, const Small_polygon& poly, Accumulator& acc) const
  {
    integrate_hyperbolic_piece(m_tri[f], m_frame[f], poly.p, poly.n, m_points[std::size_t(s)], acc);
  }
  void add_whole(std::size_t f, int s, Accumulator& acc) const
  {
    for(const Hyperbolic_quadrature_node& q : m_whole[f]) add_hyperbolic_node(q.y, q.w, m_points[std::size_t(s)], acc);
  }

private:
  const std::vector<Background_triangle>& m_tri;
  const std::vector<Eigen::Matrix3d>& m_frame;
  const std::vector<std::array<Hyperbolic_quadrature_node, 6>>& m_whole;  // hyperbolic_triangle_nodes() of each triangle
  const std::vector<Eigen::Vector3d>& m_points;
};

// per point of the hyperboloid (a site or an image), the integrals over the parts of the Klein triangles
// `tri` (in Morton order, with their `frame`s and the quadrature nodes `whole` of each whole triangle) in
// its cell; Delaunay neighbours of the power diagram in CSR form
inline void integrate_hyperbolic_restricted_voronoi(const std::vector<Background_triangle>& tri, const std::vector<Eigen::Matrix3d>& frame,
                                                    const std::vector<std::array<Hyperbolic_quadrature_node, 6>>& whole,
                                                    const std::vector<Eigen::Vector3d>& points, const std::vector<int>& start,
                                                    const std::vector<int>& nbr, unsigned threads,
                                                    std::vector<Hyperbolic_cell_accumulator>& out)
{
  integrate_restricted_voronoi(Hyperbolic_cell_geometry(tri, frame, whole, points), points.size(), start, nbr, first_connected_site(start),
                               threads, out);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_HYPERBOLIC_VORONOI_H
