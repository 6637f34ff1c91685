// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_FLAT_CONFORMAL_NEWTON_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_FLAT_CONFORMAL_NEWTON_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/parameters.h>

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

// The discrete conformal solve shared by every Euclidean domain (plane, flat torus): per-vertex log
// scales u with scaled lengths exp((u_i + u_j) / 2) l_ij, angle sums 2 pi at the free vertices, Newton's
// method on the convex energy of Springborn, Schroeder and Pinkall with intrinsic Delaunay flips
// (Gillespie, Springborn and Crane 2021) before every evaluation.

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
  degenerate = false;
  for(int k = 0; k < 3; ++k) {
    const double opp = l[(k + 1) % 3], a = l[k], b = l[(k + 2) % 3];
    if(opp >= a + b) { degenerate = true; angle = {{0, 0, 0}}; angle[k] = 3.14159265358979323846; return angle; }
  }
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

// what the solve did
struct Flat_conformal_solution {
  std::vector<double> u;           // log scale per vertex (0, or fixed_u, at the fixed vertices)
  std::size_t iterations = 0;      // Newton iterations
  double residual = 0;             // max |2 pi - angle sum| over the free vertices
  std::size_t degenerate = 0;      // triangles treated as flat at the end
  std::size_t flips = 0;           // intrinsic Delaunay flips
};

/*
 * Solves for u with u = 0 at the vertices where `fixed` is set and angle sum 2 pi at the others.
 * Interior edges of `itri` are flipped (Ptolemy lengths) to keep it intrinsically Delaunay for the
 * current scales. `who` names the caller in messages. At least one vertex must be fixed (on a closed
 * surface the energy is invariant under a constant shift of u; one fixed vertex removes that).
 * Bounded: `max_it` Newton iterations, 40 halvings per line search, `flips_per_halfedge` x (halfedges)
 * + 100 flips per evaluation; throws Convergence_failure with the residual reached when the Newton or the
 * flip bound is hit (Delaunay flips terminate in exact arithmetic, so hitting that bound means rounding
 * made them cycle). Where `keep_star` is given, no flip touches the star of a vertex it marks (no edge
 * at that vertex nor opposite it is flipped), so that star stays as it is (the puncture of the sphere).
 * Where `fixed_u` is given, every vertex starts from its value instead of 0: Dirichlet data at the fixed
 * vertices, the initial guess at the free ones; the first flip pass still uses u = 0, so that the
 * conformal class is that of the input metric.
 */
template <typename Visitor>
Flat_conformal_solution solve_flat_conformal_metric(Intrinsic_triangulation& itri, const std::vector<char>& fixed,
                                                    std::size_t max_it, double tol, Visitor& vis, const std::string& who,
                                                    std::size_t flips_per_halfedge = 50,
                                                    const std::vector<char>* keep_star = nullptr,
                                                    const std::vector<double>* fixed_u = nullptr)
{
  const double pi = 3.14159265358979323846, two_pi = 2 * pi;
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  std::vector<int> index(nv, -1);  // free vertex -> unknown
  int n = 0;
  for(int v = 0; v < nv; ++v)
    if(!fixed[v]) index[v] = n++;

  Flat_conformal_solution sol;
  sol.u.assign(nv, 0.0);
  const std::vector<double> zero = sol.u;  // the input metric, for the first flip pass
  if(fixed_u) sol.u = *fixed_u;
  std::vector<double> angle_sum(nv);
  std::vector<Eigen::Triplet<double>> triplets;
  auto scaled = [&](int h, const std::vector<double>& u) {
    return itri.length(h) * std::exp(0.5 * (u[itri.tail(h)] + u[itri.head(h)]));
  };
  // the angle at the corner facing h; the flat-triangle rule of corner_angles() for one angle, because
  // this runs in the flip loop where corner_angles() would compute all three
  auto opposite_angle = [&](int h, const std::vector<double>& u) {
    const double o = scaled(h, u), a = scaled(Intrinsic_triangulation::next(h), u), b = scaled(Intrinsic_triangulation::prev(h), u);
    if(o >= a + b) return pi;
    if(a >= o + b || b >= o + a) return 0.0;
    return std::acos(std::max(-1.0, std::min(1.0, (a * a + b * b - o * o) / (2 * a * b))));
  };
  // Intrinsic Delaunay flips for the lengths scaled by u. The first pass (u = 0) flips the input to its
  // intrinsic Delaunay triangulation with Euclidean lengths (law of cosines in the unfolded quad), which
  // keeps the input metric; the conformal class is defined on that triangulation. During the solve the
  // new edge gets its length by Ptolemy's relation, which commutes with the scaling, so the flipped
  // triangulation stays in the same discrete conformal class and no triangle degenerates (Gillespie,
  // Springborn and Crane 2021). Returns the number of flips.
  double residual = std::numeric_limits<double>::infinity();  // the angle-sum error, for the messages
  std::size_t it = 0;
  auto make_delaunay = [&](const std::vector<double>& u, bool euclidean) {
    std::size_t flips = 0;
    const int nh = int(itri.number_of_halfedges());
    std::deque<int> queue;
    std::vector<char> queued(std::size_t(nh), 0);
    auto enqueue = [&](int h) {
      const int r = itri.is_edge_representative(h) ? h : itri.twin(h);
      if(itri.twin(r) >= 0 && !queued[std::size_t(r)]) { queued[std::size_t(r)] = 1; queue.push_back(r); }
    };
    for(int h = 0; h < nh; ++h) enqueue(h);
    const std::size_t budget = flips_per_halfedge * std::size_t(nh) + 100;  // Delaunay flips terminate; a guard
    while(!queue.empty() && flips < budget) {
      const int h = queue.front();
      queue.pop_front();
      queued[std::size_t(h)] = 0;
      const int t = itri.twin(h);
      if(t < 0 || opposite_angle(h, u) + opposite_angle(t, u) <= pi + 1e-10) continue;
      const int c = itri.opposite_vertex(h), d = itri.opposite_vertex(t);
      if(c == d || itri.find_halfedge(c, d) >= 0) continue;  // would create a double edge
      if(keep_star && ((*keep_star)[std::size_t(c)] || (*keep_star)[std::size_t(d)] || (*keep_star)[std::size_t(itri.tail(h))] ||
                       (*keep_star)[std::size_t(itri.head(h))]))
        continue;
      const double l_ab = itri.length(h), l_bc = itri.length(Intrinsic_triangulation::next(h)),
                   l_ca = itri.length(Intrinsic_triangulation::prev(h)), l_ad = itri.length(Intrinsic_triangulation::next(t)),
                   l_db = itri.length(Intrinsic_triangulation::prev(t));
      const int g = itri.flip(h);
      if(euclidean) {
        const double a1 = std::acos(std::max(-1.0, std::min(1.0, (l_ab * l_ab + l_ca * l_ca - l_bc * l_bc) / (2 * l_ab * l_ca))));
        const double a2 = std::acos(std::max(-1.0, std::min(1.0, (l_ab * l_ab + l_ad * l_ad - l_db * l_db) / (2 * l_ab * l_ad))));
        itri.set_length(g, std::sqrt(std::max(0.0, l_ca * l_ca + l_ad * l_ad - 2 * l_ca * l_ad * std::cos(a1 + a2))));
      } else {
        itri.set_length(g, (l_ad * l_bc + l_db * l_ca) / l_ab);  // Ptolemy on the quad a, d, b, c
      }
      ++flips;
      for(int e : {Intrinsic_triangulation::next(g), Intrinsic_triangulation::prev(g),
                   Intrinsic_triangulation::next(itri.twin(g)), Intrinsic_triangulation::prev(itri.twin(g))})
        enqueue(e);
    }
    sol.flips += flips;
    if(!queue.empty())
      throw Convergence_failure(who + ": the intrinsic Delaunay flips did not terminate within " + std::to_string(budget) +
                                    (std::isfinite(residual) ? " flips at Newton iteration " + std::to_string(it) +
                                                                   " (angle-sum error " + std::to_string(residual) + ")"
                                                             : std::string(" flips of the first pass, before Newton's method")),
                                residual);
    return flips;
  };

  // angle sums and (optionally) the cotangent Laplacian at scales u, after the Delaunay flips
  bool connectivity_changed = false;
  auto evaluate = [&](const std::vector<double>& u, bool with_hessian, std::size_t& degenerate) {
    if(make_delaunay(u, false) > 0) connectivity_changed = true;
    std::fill(angle_sum.begin(), angle_sum.end(), 0.0);
    triplets.clear();
    degenerate = 0;
    for(int f = 0; f < nf; ++f) {
      const auto& c = itri.face_vertices(std::size_t(f));
      bool deg;
      const std::array<double, 3> a = corner_angles(scaled_face_lengths(itri, f, u), deg);
      if(deg) ++degenerate;
      for(int k = 0; k < 3; ++k) angle_sum[c[k]] += a[k];
      if(!with_hessian) continue;
      for(int k = 0; k < 3; ++k) {
        // the edge opposite corner k is halfedge k+1, between corners k+1 and k+2
        const double w = deg ? 0.0 : 0.5 / std::tan(a[k]);
        const int i = index[c[(k + 1) % 3]], j = index[c[(k + 2) % 3]];
        if(i >= 0) triplets.emplace_back(i, i, w);
        if(j >= 0) triplets.emplace_back(j, j, w);
        if(i >= 0 && j >= 0) {
          triplets.emplace_back(i, j, -w);
          triplets.emplace_back(j, i, -w);
        }
      }
    }
    double r = 0;
    for(int v = 0; v < nv; ++v)
      if(index[v] >= 0) r = std::max(r, std::abs(two_pi - angle_sum[v]));
    return r;
  };

  Eigen::SparseMatrix<double> H(n, n);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  bool analysed = false;
  std::size_t degenerate = 0;
  make_delaunay(zero, true);
  residual = evaluate(sol.u, true, degenerate);
  for(; it < max_it && residual > tol; ++it) {
    H.setFromTriplets(triplets.begin(), triplets.end());
    // a tiny diagonal shift keeps the factorisation definite where degenerate triangles zero a row
    for(int i = 0; i < n; ++i) H.coeffRef(i, i) += 1e-12;
    if(!analysed || connectivity_changed) {  // flips change the sparsity pattern
      solver.analyzePattern(H);
      analysed = true;
      connectivity_changed = false;
    }
    solver.factorize(H);
    if(solver.info() != Eigen::Success)
      throw Convergence_failure(who + ": the sparse Cholesky factorisation failed at Newton iteration " + std::to_string(it),
                                residual);
    Eigen::VectorXd g(n);
    for(int v = 0; v < nv; ++v)
      if(index[v] >= 0) g[index[v]] = angle_sum[v] - two_pi;
    Eigen::VectorXd du = solver.solve(g);
    // backtracking on the residual: the energy is convex, so a full step is nearly always taken
    std::vector<double> trial(nv);
    double step = 1.0;
    std::size_t deg_new = 0;
    for(int k = 0; k < 40; ++k, step *= 0.5) {
      for(int v = 0; v < nv; ++v) trial[v] = index[v] >= 0 ? sol.u[v] + step * du[index[v]] : sol.u[v];
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
  if(residual > tol)
    throw Convergence_failure(who + ": Newton's method reached angle-sum error " + std::to_string(residual) + " after " +
                                  std::to_string(it) + " iterations (tolerance " + std::to_string(tol) + ")",
                              residual);
  return sol;
}

// The same, with the bounds and the visitor from the named parameters (`max_conformal_iterations`,
// default 100; `conformal_tolerance`, default 1e-9; `max_flips_per_edge`, default 50; `visitor`), and the figures copied into `emb`
// (a Planar_embedding or a Flat_torus_embedding).
template <typename Embedding, typename NamedParameters>
void solve_flat_conformal_metric(Intrinsic_triangulation& itri, const std::vector<char>& fixed, const NamedParameters& np,
                                 const std::string& who, Embedding& emb, const std::vector<char>* keep_star = nullptr,
                                 const std::vector<double>* fixed_u = nullptr)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const std::size_t max_it = choose_parameter(get_parameter(np, internal_np::max_conformal_iterations), 100u);
  const double tol = choose_parameter(get_parameter(np, internal_np::conformal_tolerance), 1e-9);
  const std::size_t flips_per_halfedge = choose_parameter(get_parameter(np, internal_np::max_flips_per_edge), 50u);
  typename Visitor_reference<NamedParameters>::type vis = get_visitor(np);
  Flat_conformal_solution sol = solve_flat_conformal_metric(itri, fixed, max_it, tol, vis, who, flips_per_halfedge, keep_star, fixed_u);
  emb.u = std::move(sol.u);
  emb.iterations = sol.iterations;
  emb.residual = sol.residual;
  emb.degenerate_triangles = sol.degenerate;
  emb.flips = sol.flips;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_FLAT_CONFORMAL_NEWTON_H
