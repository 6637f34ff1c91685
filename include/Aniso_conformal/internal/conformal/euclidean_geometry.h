// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_EUCLIDEAN_GEOMETRY_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_EUCLIDEAN_GEOMETRY_H

#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/flat_triangle.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

// Euclidean triangles from their side lengths, and the Euclidean vertex-scaling geometry of the discrete
// conformal solve (Springborn, Schroeder and Pinkall 2008: l'_ij = exp((u_i + u_j) / 2) l_ij) as a
// policy of solve_conformal_metric(): scaled lengths, angles, the cotangent Hessian, and the intrinsic
// Delaunay flip rules (Gillespie, Springborn and Crane 2021).

namespace Aniso_conformal {
namespace internal {

inline double heron_area(double a, double b, double c)
{
  const double s = (a + b + c) / 2;
  return std::sqrt(std::max(0.0, s * (s - a) * (s - b) * (s - c)));
}

// Angles of a triangle with side lengths l[k] (l[k] = length of halfedge k, from corner k to k+1);
// the angle at corner k is opposite halfedge k+1. A triangle that violates the triangle inequality gets
// the angles of the flat triangle (0, 0, pi): the convex extension of the energy of Bobenko, Pinkall
// and Springborn, which keeps Newton's method well defined.
inline std::array<double, 3> corner_angles(const std::array<double, 3>& l, bool& degenerate)
{
  std::array<double, 3> angle;
  if((degenerate = flat_triangle_angles(l, angle))) return angle;
  for(int k = 0; k < 3; ++k) {
    const double opp = l[(k + 1) % 3], a = l[k], b = l[(k + 2) % 3];
    double c = (a * a + b * b - opp * opp) / (2 * a * b);
    angle[k] = std::acos(std::max(-1.0, std::min(1.0, c)));
  }
  return angle;
}

// the lengths of face f scaled by u
inline std::array<double, 3> scaled_face_lengths(const Intrinsic_triangulation& itri, int f, const std::vector<double>& u)
{
  const auto& c = itri.face_vertices(std::size_t(f));
  std::array<double, 3> l;
  for(int k = 0; k < 3; ++k) l[k] = itri.length(3 * f + k) * std::exp(0.5 * (u[c[k]] + u[c[(k + 1) % 3]]));
  return l;
}

// the point r to the left of p->q with |pr| = lpr and |qr| = lqr (unfolding one triangle)
inline Eigen::Vector2d third_point(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double lpr, double lqr)
{
  const Eigen::Vector2d e = q - p;
  const double d = e.norm();
  const double x = (lpr * lpr - lqr * lqr + d * d) / (2 * d);
  const double y = std::sqrt(std::max(0.0, lpr * lpr - x * x));
  const Eigen::Vector2d ex = e / d, ey(-ex.y(), ex.x());
  return p + x * ex + y * ey;
}

// The intrinsic Delaunay flip rule of the Euclidean metric scaled by u: flip when the two angles facing
// the edge sum to more than pi. The new edge's length is Ptolemy's relation on the quad, which commutes
// with the scaling, so the flipped triangulation stays in the same discrete conformal class and no
// triangle degenerates (Gillespie, Springborn and Crane 2021); or, for the first pass on the input's own
// lengths (u = 0), the distance in the unfolded quad (law of cosines), which keeps the input metric.
// No flip touches the star of a vertex marked in `keep_star`, nor creates a double edge unless
// `allow_double_edges` (the cone metrics: cone_metric_geometry()), in which case a flip is still refused
// where the quad's two faces are glued along another edge too (no loop edge either way).
struct Euclidean_delaunay_flip_rule {
  const std::vector<double>& u;
  const std::vector<char>* keep_star;
  bool keep_metric;  // true: law of cosines (first pass); false: Ptolemy
  bool allow_double_edges = false;

  double scaled(const Intrinsic_triangulation& itri, int h) const
  {
    return itri.length(h) * std::exp(0.5 * (u[itri.tail(h)] + u[itri.head(h)]));
  }
  // the angle at the corner facing h, with the flat-triangle rule of corner_angles() for one angle
  double opposite_angle(const Intrinsic_triangulation& itri, int h) const
  {
    const double pi = 3.14159265358979323846;
    const double o = scaled(itri, h), a = scaled(itri, Intrinsic_triangulation::next(h)),
                 b = scaled(itri, Intrinsic_triangulation::prev(h));
    if(o >= a + b) return pi;
    if(a >= o + b || b >= o + a) return 0.0;
    return std::acos(std::max(-1.0, std::min(1.0, (a * a + b * b - o * o) / (2 * a * b))));
  }
  bool wants_flip(const Intrinsic_triangulation& itri, int h) const
  {
    const int t = itri.twin(h);
    if(opposite_angle(itri, h) + opposite_angle(itri, t) <= 3.14159265358979323846 + 1e-10) return false;
    const int c = itri.opposite_vertex(h), d = itri.opposite_vertex(t);
    if(c == d) return false;
    typedef Intrinsic_triangulation T;
    if(allow_double_edges) {  // two distinct faces, glued along this edge only
      for(int e : {T::next(h), T::prev(h), T::next(t), T::prev(t)}) {
        const int o = itri.twin(e);
        if(o < 0 || T::face(o) == T::face(h) || T::face(o) == T::face(t)) return false;
      }
    } else if(itri.has_edge(c, d)) {
      return false;  // would create a double edge
    }
    if(keep_star && ((*keep_star)[std::size_t(c)] || (*keep_star)[std::size_t(d)] || (*keep_star)[std::size_t(itri.tail(h))] ||
                     (*keep_star)[std::size_t(itri.head(h))]))
      return false;
    return true;
  }
  double flipped_length(const Intrinsic_triangulation& itri, int h) const
  {
    const int t = itri.twin(h);
    const double l_ab = itri.length(h), l_bc = itri.length(Intrinsic_triangulation::next(h)),
                 l_ca = itri.length(Intrinsic_triangulation::prev(h)), l_ad = itri.length(Intrinsic_triangulation::next(t)),
                 l_db = itri.length(Intrinsic_triangulation::prev(t));
    if(!keep_metric) return (l_ad * l_bc + l_db * l_ca) / l_ab;  // Ptolemy on the quad a, d, b, c
    const double a1 = std::acos(std::max(-1.0, std::min(1.0, (l_ab * l_ab + l_ca * l_ca - l_bc * l_bc) / (2 * l_ab * l_ca))));
    const double a2 = std::acos(std::max(-1.0, std::min(1.0, (l_ab * l_ab + l_ad * l_ad - l_db * l_db) / (2 * l_ab * l_ad))));
    return std::sqrt(std::max(0.0, l_ca * l_ca + l_ad * l_ad - 2 * l_ca * l_ad * std::cos(a1 + a2)));
  }
};

// The Euclidean vertex-scaling geometry for solve_conformal_metric(): the energy's Hessian is the
// cotangent Laplacian (exactly symmetric, so no symmetrisation).
struct Euclidean_vertex_scaling {
  bool allow_double_edges = false;  // passed to the flip rule (Euclidean_delaunay_flip_rule)
  static constexpr bool symmetrize_hessian = false;
  static constexpr bool l2_merit = false;  // the line search backtracks on the largest angle-sum error
  static const char* name() { return "Euclidean"; }
  std::array<double, 3> face_lengths(const Intrinsic_triangulation& itri, int f, const std::vector<double>& u) const
  {
    return scaled_face_lengths(itri, f, u);
  }
  std::array<double, 3> angles(const std::array<double, 3>& l, bool& degenerate) const { return corner_angles(l, degenerate); }
  // the face's cotangent weights on the unknowns (index >= 0); a flat triangle contributes nothing
  void add_hessian(const std::array<int, 3>& c, const std::array<double, 3>& /*l*/, const std::array<double, 3>& a, bool degenerate,
                   const std::vector<int>& index, std::vector<Eigen::Triplet<double>>& triplets) const
  {
    for(int k = 0; k < 3; ++k) {
      // the edge opposite corner k is halfedge k+1, between corners k+1 and k+2
      const double w = degenerate ? 0.0 : 0.5 / std::tan(a[k]);
      const int i = index[c[(k + 1) % 3]], j = index[c[(k + 2) % 3]];
      if(i >= 0) triplets.emplace_back(i, i, w);
      if(j >= 0) triplets.emplace_back(j, j, w);
      if(i >= 0 && j >= 0) {
        triplets.emplace_back(i, j, -w);
        triplets.emplace_back(j, i, -w);
      }
    }
  }
  Euclidean_delaunay_flip_rule flip_rule(const std::vector<double>& u, const std::vector<char>* keep_star) const
  {
    return Euclidean_delaunay_flip_rule{u, keep_star, false, allow_double_edges};
  }
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_EUCLIDEAN_GEOMETRY_H
