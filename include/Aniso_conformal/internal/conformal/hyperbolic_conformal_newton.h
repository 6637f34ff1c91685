// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_HYPERBOLIC_CONFORMAL_NEWTON_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_HYPERBOLIC_CONFORMAL_NEWTON_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/internal/conformal/hyperbolic_geometry.h>
#include <Aniso_conformal/internal/visitor_helper.h>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <string>
#include <vector>

// The hyperbolic discrete conformal solve (Bobenko, Pinkall and Springborn 2015): per-vertex log scales
// u with hyperbolic lengths sinh(l_ij / 2) = exp((u_i + u_j) / 2) s L_ij, where L_ij are the edge lengths
// stored in the Intrinsic_triangulation and s one global scale, and angle sum 2 pi at every vertex.
// The energy is strictly convex (no gauge: the hyperbolic metric fixes the scale); Newton's method with
// its Hessian, the negated Jacobian of the angle sums, and intrinsic Delaunay flips that keep the
// current hyperbolic metric (Gu, Guo, Luo, Sun and Wu 2018) before every evaluation.

namespace Aniso_conformal {
namespace internal {

struct Hyperbolic_conformal_solution {
  std::vector<double> u;       // log scale per vertex
  double scale = 1;            // s
  std::size_t iterations = 0;  // Newton iterations
  double residual = 0;         // max |2 pi - angle sum|
  std::size_t degenerate = 0;  // triangles treated as flat at the end
  std::size_t flips = 0;       // intrinsic Delaunay flips
};

// the hyperbolic length of the edge of h at scales u
inline double hyperbolic_length(const Intrinsic_triangulation& itri, int h, double s, const std::vector<double>& u)
{
  return 2 * std::asinh(s * itri.length(h) * std::exp(0.5 * (u[std::size_t(itri.tail(h))] + u[std::size_t(itri.head(h))])));
}

inline std::array<double, 3> hyperbolic_face_lengths(const Intrinsic_triangulation& itri, int f, double s, const std::vector<double>& u)
{
  return {{hyperbolic_length(itri, 3 * f, s, u), hyperbolic_length(itri, 3 * f + 1, s, u), hyperbolic_length(itri, 3 * f + 2, s, u)}};
}

/*
 * Solves for u on the closed triangulation `itri` of genus >= 2. The global scale s makes the input's
 * Euclidean area equal to the hyperbolic area 4 pi (g - 1), so that u = 0 is a good start. Bounded:
 * `max_it` Newton iterations, 40 halvings per line search (on the residual), `flips_per_halfedge` x
 * (halfedges) + 100 flips per evaluation; Convergence_failure with the residual reached otherwise.
 */
template <typename Visitor>
Hyperbolic_conformal_solution solve_hyperbolic_conformal_metric(Intrinsic_triangulation& itri, int genus, std::size_t max_it,
                                                                double tol, Visitor& vis, std::size_t flips_per_halfedge = 50)
{
  const double pi = 3.14159265358979323846, two_pi = 2 * pi;
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces()), nh = int(itri.number_of_halfedges());
  Hyperbolic_conformal_solution sol;
  sol.u.assign(std::size_t(nv), 0.0);
  double euclidean_area = 0;
  for(int f = 0; f < nf; ++f) {
    const double a = itri.length(3 * f), b = itri.length(3 * f + 1), c = itri.length(3 * f + 2), p = (a + b + c) / 2;
    euclidean_area += std::sqrt(std::max(0.0, p * (p - a) * (p - b) * (p - c)));
  }
  sol.scale = std::sqrt(4 * pi * (genus - 1) / euclidean_area);
  const double s = sol.scale;
  double residual = std::numeric_limits<double>::infinity();
  std::size_t it = 0;

  auto opposite_angles = [&](int h, const std::vector<double>& u) {  // angles of h's face, rotated to start at h's tail
    const int f = Intrinsic_triangulation::face(h);
    bool deg;
    const std::array<double, 3> a = hyperbolic_corner_angles(hyperbolic_face_lengths(itri, f, s, u), deg);
    const int k = h % 3;
    return std::array<double, 3>{{a[std::size_t(k)], a[std::size_t((k + 1) % 3)], a[std::size_t((k + 2) % 3)]}};
  };
  // Delaunay flips that keep the hyperbolic metric: the new edge gets the distance between the opposite
  // corners in the unfolded quad (law of cosines), stored back as a base length through the scales
  auto make_delaunay = [&](const std::vector<double>& u) {
    std::size_t flips = 0;
    std::deque<int> queue;
    std::vector<char> queued(std::size_t(nh), 0);
    auto enqueue = [&](int h) {
      const int r = itri.is_edge_representative(h) ? h : itri.twin(h);
      if(!queued[std::size_t(r)]) { queued[std::size_t(r)] = 1; queue.push_back(r); }
    };
    for(int h = 0; h < nh; ++h) enqueue(h);
    const std::size_t budget = flips_per_halfedge * std::size_t(nh) + 100;
    while(!queue.empty() && flips < budget) {
      const int h = queue.front();
      queue.pop_front();
      queued[std::size_t(h)] = 0;
      const int t = itri.twin(h);
      // face of h: corners a = tail(h), b = head(h), c; face of t: b, a, d
      const std::array<double, 3> A = opposite_angles(h, u), B = opposite_angles(t, u);
      // hyperbolic Delaunay condition: the angles facing the edge sum to at most the four others
      if(A[2] + B[2] <= A[0] + A[1] + B[0] + B[1] + 1e-10) continue;
      const int c = itri.opposite_vertex(h), d = itri.opposite_vertex(t);
      if(c == d || itri.find_halfedge(c, d) >= 0) continue;  // would create a double edge
      const double l_ca = hyperbolic_length(itri, Intrinsic_triangulation::prev(h), s, u);
      const double l_ad = hyperbolic_length(itri, Intrinsic_triangulation::next(t), s, u);
      const double theta = A[0] + B[1];  // angle at a between c and d
      const double ch = std::cosh(l_ca) * std::cosh(l_ad) - std::sinh(l_ca) * std::sinh(l_ad) * std::cos(theta);
      const double l_cd = std::acosh(std::max(1.0, ch));
      const int g = itri.flip(h);
      itri.set_length(g, std::sinh(0.5 * l_cd) * std::exp(-0.5 * (u[std::size_t(c)] + u[std::size_t(d)])) / s);
      ++flips;
      for(int e : {Intrinsic_triangulation::next(g), Intrinsic_triangulation::prev(g),
                   Intrinsic_triangulation::next(itri.twin(g)), Intrinsic_triangulation::prev(itri.twin(g))})
        enqueue(e);
    }
    sol.flips += flips;
    if(!queue.empty())
      throw Convergence_failure("hyperbolic embedding: the intrinsic Delaunay flips did not terminate within " +
                                    std::to_string(budget) + " flips at Newton iteration " + std::to_string(it) +
                                    (std::isfinite(residual) ? " (angle-sum error " + std::to_string(residual) + ")" : std::string()),
                                residual);
    return flips;
  };

  std::vector<double> angle_sum(static_cast<std::size_t>(nv));
  std::vector<Eigen::Triplet<double>> triplets;
  bool connectivity_changed = false;
  auto evaluate = [&](const std::vector<double>& u, bool with_hessian, std::size_t& degenerate) {
    if(make_delaunay(u) > 0) connectivity_changed = true;
    std::fill(angle_sum.begin(), angle_sum.end(), 0.0);
    triplets.clear();
    degenerate = 0;
    for(int f = 0; f < nf; ++f) {
      const auto& c = itri.face_vertices(std::size_t(f));
      const std::array<double, 3> l = hyperbolic_face_lengths(itri, f, s, u);
      bool deg;
      const std::array<double, 3> a = hyperbolic_corner_angles(l, deg);
      if(deg) ++degenerate;
      for(int k = 0; k < 3; ++k) angle_sum[std::size_t(c[k])] += a[std::size_t(k)];
      if(!with_hessian || deg) continue;
      // J[k][m] = d angle_k / d u_m = sum over sides e of d angle_k / d l_e * d l_e / d u_m, with
      // d angle_k / d l_opp = sinh l_opp / (sinh l_b sinh l_c sin angle_k) =: D_k, the adjacent sides
      // -D_k cos(angle at their other end), and d l_e / d u_m = tanh(l_e / 2) at either end of e
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
        for(int m = 0; m < 3; ++m) triplets.emplace_back(c[k], c[m], -J(k, m));
    }
    double r = 0;
    for(int v = 0; v < nv; ++v) r = std::max(r, std::abs(two_pi - angle_sum[std::size_t(v)]));
    return r;
  };

  Eigen::SparseMatrix<double> H(nv, nv);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  bool analysed = false;
  std::size_t degenerate = 0;
  residual = evaluate(sol.u, true, degenerate);
  for(; it < max_it && residual > tol; ++it) {
    H.setFromTriplets(triplets.begin(), triplets.end());
    // the Jacobian is symmetric up to rounding; symmetrise so that LDLT sees one matrix
    Eigen::SparseMatrix<double> Ht = H.transpose();
    H = 0.5 * (H + Ht);
    for(int i = 0; i < nv; ++i) H.coeffRef(i, i) += 1e-12;
    if(!analysed || connectivity_changed) {
      solver.analyzePattern(H);
      analysed = true;
      connectivity_changed = false;
    }
    solver.factorize(H);
    if(solver.info() != Eigen::Success)
      throw Convergence_failure("hyperbolic embedding: the sparse Cholesky factorisation failed at Newton iteration " +
                                    std::to_string(it),
                                residual);
    Eigen::VectorXd g(nv);
    for(int v = 0; v < nv; ++v) g[v] = angle_sum[std::size_t(v)] - two_pi;
    const Eigen::VectorXd du = solver.solve(g);
    std::vector<double> trial(static_cast<std::size_t>(nv));
    double step = 1.0;
    std::size_t deg_new = 0;
    for(int k = 0; k < 40; ++k, step *= 0.5) {
      for(int v = 0; v < nv; ++v) trial[std::size_t(v)] = sol.u[std::size_t(v)] + step * du[v];
      if(evaluate(trial, false, deg_new) < residual || k == 39) break;
    }
    sol.u.swap(trial);
    residual = evaluate(sol.u, true, degenerate);
    if(!vis.on_iteration(Stage::EMBEDDING, it + 1, max_it, residual))
      throw Cancelled("cancelled by the visitor during the conformal embedding");
  }
  sol.iterations = it;
  sol.residual = residual;
  sol.degenerate = degenerate;
  if(!(residual <= tol))
    throw Convergence_failure("hyperbolic embedding: Newton's method reached angle-sum error " + std::to_string(residual) +
                                  " after " + std::to_string(it) + " iterations (tolerance " + std::to_string(tol) + ")",
                              residual);
  return sol;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_HYPERBOLIC_CONFORMAL_NEWTON_H
