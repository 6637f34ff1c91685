// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_HYPERBOLIC_VERTEX_SCALING_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_HYPERBOLIC_VERTEX_SCALING_H

#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/hyperbolic_geometry.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

// The hyperbolic vertex-scaling geometry of the discrete conformal solve (Bobenko, Pinkall and Springborn
// 2015): hyperbolic lengths sinh(l_ij / 2) = exp((u_i + u_j) / 2) s L_ij, L_ij the lengths stored in the
// Intrinsic_triangulation and s one global scale, as a policy of solve_conformal_metric(): lengths,
// angles by the half-angle formulas, the exact Hessian (the negated Jacobian of the angle sums, from the
// hyperbolic law of cosines) and the Delaunay flips that keep the current hyperbolic metric (Gu, Guo,
// Luo, Sun and Wu 2018).

namespace Aniso_conformal {
namespace internal {

// the hyperbolic length of the edge of h at scales u
inline double hyperbolic_length(const Intrinsic_triangulation& itri, int h, double s, const std::vector<double>& u)
{
  return 2 * std::asinh(s * itri.length(h) * std::exp(0.5 * (u[std::size_t(itri.tail(h))] + u[std::size_t(itri.head(h))])));
}

inline std::array<double, 3> hyperbolic_face_lengths(const Intrinsic_triangulation& itri, int f, double s, const std::vector<double>& u)
{
  return {{hyperbolic_length(itri, 3 * f, s, u), hyperbolic_length(itri, 3 * f + 1, s, u), hyperbolic_length(itri, 3 * f + 2, s, u)}};
}

// Flip when the angles facing the edge sum to more than the four others (the hyperbolic Delaunay
// condition); the new edge gets the distance between the opposite corners in the unfolded quad (law of
// cosines), stored back as a base length through the scales. No flip creates a double edge.
struct Hyperbolic_delaunay_flip_rule {
  const std::vector<double>& u;
  double s;

  // the angles of h's face, rotated to start at h's tail
  std::array<double, 3> angles_from(const Intrinsic_triangulation& itri, int h) const
  {
    bool deg;
    const std::array<double, 3> a = hyperbolic_corner_angles(hyperbolic_face_lengths(itri, Intrinsic_triangulation::face(h), s, u), deg);
    const int k = h % 3;
    return std::array<double, 3>{{a[std::size_t(k)], a[std::size_t((k + 1) % 3)], a[std::size_t((k + 2) % 3)]}};
  }
  bool wants_flip(const Intrinsic_triangulation& itri, int h) const
  {
    const int t = itri.twin(h);
    // face of h: corners a = tail(h), b = head(h), c; face of t: b, a, d
    const std::array<double, 3> A = angles_from(itri, h), B = angles_from(itri, t);
    if(A[2] + B[2] <= A[0] + A[1] + B[0] + B[1] + 1e-10) return false;
    const int c = itri.opposite_vertex(h), d = itri.opposite_vertex(t);
    return c != d && !itri.has_edge(c, d);  // no double edge
  }
  double flipped_length(const Intrinsic_triangulation& itri, int h) const
  {
    const int t = itri.twin(h), c = itri.opposite_vertex(h), d = itri.opposite_vertex(t);
    const std::array<double, 3> A = angles_from(itri, h), B = angles_from(itri, t);
    const double l_ca = hyperbolic_length(itri, Intrinsic_triangulation::prev(h), s, u);
    const double l_ad = hyperbolic_length(itri, Intrinsic_triangulation::next(t), s, u);
    const double theta = A[0] + B[1];  // angle at a between c and d
    // the law of cosines without its cancellation on short edges: cosh l - 1 = 2 sinh^2 (l / 2), so
    // sinh^2 (l_cd / 2) = sinh^2 ((l_ca - l_ad) / 2) + sinh l_ca sinh l_ad sin^2 (theta / 2) (through
    // acosh(cosh a cosh b - sinh a sinh b cos theta) an edge of 1e-6 kept 4 digits, and the flips of
    // the femur's sub-degree triangles made flat ones)
    const double sh = std::sinh(0.5 * (l_ca - l_ad)), st = std::sin(0.5 * theta);
    const double sinh_half = std::sqrt(sh * sh + std::sinh(l_ca) * std::sinh(l_ad) * st * st);
    return sinh_half * std::exp(-0.5 * (u[std::size_t(c)] + u[std::size_t(d)])) / s;
  }
};

// The hyperbolic vertex-scaling geometry for solve_conformal_metric(). Its Jacobian is symmetric only up
// to rounding, so the solver symmetrises it before the Cholesky factorisation.
struct Hyperbolic_vertex_scaling {
  static constexpr bool symmetrize_hessian = true;
  static constexpr bool l2_merit = true;  // the line search is Armijo's on the squared angle-sum errors
  double s = 1;  // the global scale
  static const char* name() { return "hyperbolic"; }
  std::array<double, 3> face_lengths(const Intrinsic_triangulation& itri, int f, const std::vector<double>& u) const
  {
    return hyperbolic_face_lengths(itri, f, s, u);
  }
  std::array<double, 3> angles(const std::array<double, 3>& l, bool& degenerate) const
  {
    return hyperbolic_corner_angles(l, degenerate);
  }
  // J[k][m] = d angle_k / d u_m = sum over sides e of d angle_k / d l_e * d l_e / d u_m, with
  // d angle_k / d l_opp = sinh l_opp / (sinh l_b sinh l_c sin angle_k) =: D_k, the adjacent sides
  // -D_k cos(angle at their other end), and d l_e / d u_m = tanh(l_e / 2) at either end of e; the
  // Hessian block is -J on the unknowns. A flat triangle contributes nothing.
  void add_hessian(const std::array<int, 3>& c, const std::array<double, 3>& l, const std::array<double, 3>& a, bool degenerate,
                   const std::vector<int>& index, std::vector<Eigen::Triplet<double>>& triplets) const
  {
    if(degenerate) return;
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for(int k = 0; k < 3; ++k) {
      const int opp = (k + 1) % 3, s1 = k, s2 = (k + 2) % 3;
      const double den = std::sinh(l[std::size_t(s1)]) * std::sinh(l[std::size_t(s2)]) * std::sin(a[std::size_t(k)]);
      if(!(den > 0)) continue;
      const double D = std::sinh(l[std::size_t(opp)]) / den;
      std::array<double, 3> dl;  // d angle_k / d l_e, e = side index
      dl[std::size_t(opp)] = D;
      dl[std::size_t(s1)] = -D * std::cos(a[std::size_t((k + 1) % 3)]);
      dl[std::size_t(s2)] = -D * std::cos(a[std::size_t((k + 2) % 3)]);
      for(int e = 0; e < 3; ++e) {
        const double w = dl[std::size_t(e)] * std::tanh(0.5 * l[std::size_t(e)]);
        J(k, e) += w;            // side e runs from corner e ...
        J(k, (e + 1) % 3) += w;  // ... to corner e + 1
      }
    }
    for(int k = 0; k < 3; ++k)
      for(int m = 0; m < 3; ++m) {
        const int i = index[std::size_t(c[k])], j = index[std::size_t(c[m])];
        if(i >= 0 && j >= 0) triplets.emplace_back(i, j, -J(k, m));
      }
  }
  Hyperbolic_delaunay_flip_rule flip_rule(const std::vector<double>& u, const std::vector<char>* /*keep_star*/) const
  {
    return Hyperbolic_delaunay_flip_rule{u, s};
  }
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_HYPERBOLIC_VERTEX_SCALING_H
