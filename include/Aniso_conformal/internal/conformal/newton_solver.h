// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_NEWTON_SOLVER_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_NEWTON_SOLVER_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/conformal/sparse_cholesky.h>
#include <Aniso_conformal/internal/intrinsic/flip_to_delaunay.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/internal/printable.h>
#include <Aniso_conformal/internal/visitor_helper.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

// The discrete conformal solve, written once for every domain (DESIGN.md 3): per-vertex log scales u,
// angle sum 2 pi at the free vertices, Newton's method on the convex energy of the vertex-scaling
// geometry (Springborn, Schroeder and Pinkall 2008 for the Euclidean, Bobenko, Pinkall and Springborn
// 2015 for the hyperbolic one), sparse Cholesky factorisation of its Hessian (CHOLMOD or Eigen's LDLT,
// sparse_cholesky.h), a backtracking line search
// on the angle-sum error, and intrinsic Delaunay flips before every evaluation (Gillespie, Springborn
// and Crane 2021), which keep every triangle valid during the solve. The geometry is a policy
// (Euclidean_vertex_scaling, Hyperbolic_vertex_scaling) giving the face lengths at scales u, their
// angles, the face's Hessian block and the flip rule.

namespace Aniso_conformal {
namespace internal {

// what the solve did
struct Conformal_solution {
  std::vector<double> u;       // log scale per vertex (the given start at the fixed vertices)
  std::size_t iterations = 0;  // Newton iterations
  double residual = 0;         // max |target - angle sum| over the free vertices
  std::size_t degenerate = 0;  // triangles treated as flat at the end
  std::size_t flips = 0;       // intrinsic Delaunay flips
  std::size_t factorisations = 0;         // numerical factorisations of the Hessian
  std::size_t preconditioned_solves = 0;  // Newton systems solved by CG preconditioned with an earlier factor
  std::size_t cg_iterations = 0;          // the iterations of those CG solves
  std::size_t analyses = 0;               // symbolic analyses (CHOLMOD)
  double analysis_seconds = 0, factorisation_seconds = 0, cg_seconds = 0;  // where the solve's time went
  std::string backend;                    // the factorisation of the last system ("CHOLMOD", "Eigen SimplicialLDLT")
  std::string fallback_reason;            // why CHOLMOD was abandoned for LDLT (empty if it was not)
};

// the bounds of the solve, from the named parameters
struct Newton_bounds {
  std::size_t max_iterations = defaults::max_conformal_iterations;
  double tolerance = defaults::conformal_tolerance;
  std::size_t flips_per_edge = defaults::max_flips_per_edge;
  std::size_t cholmod_min_unknowns = 50000;  // smaller systems go to Eigen's LDLT (Sparse_spd_solver)
  bool reuse_ldlt_factor = true;             // LDLT's factor preconditions later systems (Sparse_spd_solver)

  template <typename NamedParameters>
  static Newton_bounds from(const NamedParameters& np)
  {
    Newton_bounds b;
    b.max_iterations = max_conformal_iterations(np);
    b.tolerance = conformal_tolerance(np);
    b.flips_per_edge = max_flips_per_edge(np);
    return b;
  }
};

/*
 * Solves for u with u fixed at the vertices where `fixed` is set (to their value in `u0`) and angle sum
 * 2 pi at the others (or `(*target_angle_sums)[v]`, when given: a disk whose boundary angles are
 * prescribed), starting from `u0` (the initial guess at the free vertices). At least one vertex
 * must be fixed in the Euclidean geometry (its energy is invariant under a constant shift of u); the
 * hyperbolic one has no gauge. Interior edges of `itri` are flipped by the geometry's flip rule before
 * every evaluation; no flip touches the star of a vertex marked in `keep_star`. `who` names the caller in
 * messages. Bounded: `max_iterations` Newton iterations (fewer when the error stalls below 1e-5: 8 iterations
 * without halving it), 40 halvings per line search, the flip passes by
 * `flips_per_edge`; Convergence_failure with the residual reached when a bound is hit (Delaunay flips
 * terminate in exact arithmetic, so hitting theirs means rounding made them cycle) or the factorisation
 * fails (CHOLMOD and then Eigen's LDLT: the message gives both reasons).
 */
// size: one Newton loop whose evaluation, step and two line searches (Euclidean: on the residual;
// hyperbolic: Armijo on the squared errors, undoing a rejected step's flips) share its state; 132 lines
template <typename Geometry, typename Visitor>
Conformal_solution solve_conformal_metric(Intrinsic_triangulation& itri, const Geometry& geometry, const std::vector<char>& fixed,
                                          std::vector<double> u0, const Newton_bounds& bounds, Visitor& vis, const std::string& who,
                                          const std::vector<char>* keep_star = nullptr,
                                          const std::vector<double>* target_angle_sums = nullptr)
{
  const double two_pi = 2 * 3.14159265358979323846;
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  std::vector<int> index(std::size_t(nv), -1);  // free vertex -> unknown
  int n = 0;
  for(int v = 0; v < nv; ++v)
    if(!fixed[std::size_t(v)]) index[std::size_t(v)] = n++;
  auto target = [&](int v) { return target_angle_sums ? (*target_angle_sums)[std::size_t(v)] : two_pi; };

  Conformal_solution sol;
  sol.u = std::move(u0);
  std::vector<double> angle_sum(static_cast<std::size_t>(nv));
  std::vector<Eigen::Triplet<double>> triplets;
  double residual = std::numeric_limits<double>::infinity();  // the angle-sum error, for the messages
  std::size_t it = 0;
  bool connectivity_changed = false;
  double squared_error = 0;  // sum of the squared angle-sum errors at the last evaluation
  // angle sums and (optionally) the Hessian at scales u, after the Delaunay flips; returns the residual
  auto evaluate = [&](const std::vector<double>& u, bool with_hessian, std::size_t& degenerate) {
    const Flip_pass pass = flip_to_delaunay(itri, geometry.flip_rule(u, keep_star), bounds.flips_per_edge);
    sol.flips += pass.flips;
    if(pass.budget_hit)
      throw Convergence_failure(who + ": the intrinsic Delaunay flips did not terminate within " + std::to_string(pass.budget) +
                                    " flips at Newton iteration " + std::to_string(it) +
                                    (std::isfinite(residual) ? " (angle-sum error " + short_number(residual) + ")" : std::string()),
                                residual);
    if(pass.flips > 0) connectivity_changed = true;
    std::fill(angle_sum.begin(), angle_sum.end(), 0.0);
    triplets.clear();
    if(with_hessian) triplets.reserve(12 * std::size_t(nf));  // at most 12 entries per face
    degenerate = 0;
    for(int f = 0; f < nf; ++f) {
      const auto& c = itri.face_vertices(std::size_t(f));
      bool deg;
      const std::array<double, 3> l = geometry.face_lengths(itri, f, u);
      const std::array<double, 3> a = geometry.angles(l, deg);
      if(deg) ++degenerate;
      for(int k = 0; k < 3; ++k) angle_sum[std::size_t(c[k])] += a[std::size_t(k)];
      if(with_hessian) geometry.add_hessian(c, l, a, deg, index, triplets);
    }
    double r = 0;
    squared_error = 0;
    for(int v = 0; v < nv; ++v)
      if(index[std::size_t(v)] >= 0) {
        const double e = target(v) - angle_sum[std::size_t(v)];
        r = std::max(r, std::abs(e));
        squared_error += e * e;
      }
    return r;
  };

  Eigen::SparseMatrix<double> H(n, n);
  Sparse_spd_solver solver;
  solver.cholmod_min_unknowns = bounds.cholmod_min_unknowns;
  solver.reuse_ldlt_factor = bounds.reuse_ldlt_factor;
  std::size_t degenerate = 0;
  residual = evaluate(sol.u, true, degenerate);
  // the rounding floor: below 1e-5 Newton's method about squares its error at each iteration, so 8
  // iterations in a row that do not halve the best error reached mean the error sits at the floor that
  // rounding leaves, above the tolerance; stop there rather than at the bound (CGAL's blade through the
  // sphere at 500 sites: 2.35e-7 from the 5th to the 100th iteration, twice, 38 s of a 41 s run)
  double best = residual;
  std::size_t without_halving = 0;
  bool stalled = false;
  for(; it < bounds.max_iterations && residual > bounds.tolerance; ++it) {
    H.setFromTriplets(triplets.begin(), triplets.end());
    std::vector<Eigen::Triplet<double>>().swap(triplets);  // ~400 bytes per vertex: not kept through the factorisation
    if constexpr(Geometry::symmetrize_hessian) {  // symmetric up to rounding: LDLT must see one matrix
      Eigen::SparseMatrix<double> Ht = H.transpose();
      H = 0.5 * (H + Ht);
    }
    // a tiny diagonal shift keeps the factorisation definite where degenerate triangles zero a row
    for(int i = 0; i < n; ++i) H.coeffRef(i, i) += 1e-12;
    H.makeCompressed();
    Eigen::VectorXd g(n);
    for(int v = 0; v < nv; ++v)
      if(index[std::size_t(v)] >= 0) g[index[std::size_t(v)]] = angle_sum[std::size_t(v)] - target(v);
    Eigen::VectorXd du;
    std::string failure;
    // flips change the sparsity pattern: the factorisation is analysed again (with the first ordering)
    if(!solver.solve(H, g, connectivity_changed, du, failure))
      throw Convergence_failure(who + ": the sparse Cholesky factorisation failed at Newton iteration " + std::to_string(it) + " (" +
                                    failure + ")",
                                residual);
    connectivity_changed = false;
    std::vector<double> trial(static_cast<std::size_t>(nv));
    double step = 1.0;
    std::size_t deg_new = 0;
    if constexpr(Geometry::l2_merit) {
      // Armijo backtracking on the sum of the squared angle-sum errors, a merit function the Newton
      // direction provably decreases (its derivative along du is -2 times its value), so that a start
      // far from the solution (sub-degree angles, thin parts) is globalised: halvings until the sum
      // drops by the fraction 1e-4 of its predicted decrease; a failure after 40 halvings is reported
      // every trial flips from the triangulation of the current iterate (a rejected step's flips are undone)
      const double merit = squared_error;
      const Intrinsic_triangulation base = itri;
      bool accepted = false;
      for(int k = 0; k < 40 && !accepted; ++k, step *= 0.5) {
        if(k > 0) itri = base;
        for(int v = 0; v < nv; ++v)
          trial[std::size_t(v)] = index[std::size_t(v)] >= 0 ? sol.u[std::size_t(v)] + step * du[index[std::size_t(v)]] : sol.u[std::size_t(v)];
        evaluate(trial, false, deg_new);
        accepted = squared_error <= (1 - 2e-4 * step) * merit;
        if(accepted) break;
      }
      if(!accepted)
        throw Convergence_failure(who + ": the line search of Newton's method found no decrease of the angle-sum error at iteration " +
                                      std::to_string(it) + " (angle-sum error " + short_number(residual) + ")",
                                  residual);
    } else {
      // backtracking on the residual: the energy is convex, so a full step is nearly always taken
      for(int k = 0; k < 40; ++k, step *= 0.5) {
        for(int v = 0; v < nv; ++v)
          trial[std::size_t(v)] = index[std::size_t(v)] >= 0 ? sol.u[std::size_t(v)] + step * du[index[std::size_t(v)]] : sol.u[std::size_t(v)];
        if(evaluate(trial, false, deg_new) < residual || k == 39) break;
      }
    }
    sol.u.swap(trial);
    residual = evaluate(sol.u, true, degenerate);
    if(!vis.on_iteration(Stage::EMBEDDING, it + 1, bounds.max_iterations, residual))
      throw Cancelled("cancelled by the visitor during the conformal embedding");
    if(residual <= 0.5 * best) {
      best = residual;
      without_halving = 0;
    } else if(best < 1e-5 && residual > bounds.tolerance && ++without_halving >= 8) {
      stalled = true;
      ++it;
      break;
    }
  }
  sol.iterations = it;
  sol.residual = residual;
  sol.degenerate = degenerate;
  sol.factorisations = solver.factorisations;
  sol.preconditioned_solves = solver.preconditioned_solves;
  sol.cg_iterations = solver.cg_iterations_total;
  sol.analyses = solver.factor().analyses;
  sol.analysis_seconds = solver.factor().analysis_seconds;
  sol.factorisation_seconds = solver.factor().factorisation_seconds;
  sol.cg_seconds = solver.cg_seconds;
  sol.backend = solver.factor().backend();
  sol.fallback_reason = solver.factor().fallback_reason;
  if(!(residual <= bounds.tolerance))
    throw Convergence_failure(who + ": Newton's method " + (stalled ? "stalled at" : "reached") + " angle-sum error " +
                                  short_number(residual) + " after " + std::to_string(it) + " iterations" +
                                  (stalled ? ", the last 8 without halving it" : "") + " (tolerance " + short_number(bounds.tolerance) + ")",
                              residual);
  return sol;
}

// Flips `itri` to its intrinsic Delaunay triangulation for its own (unscaled) Euclidean lengths: the
// distance in the unfolded quad, so the metric is kept. The discrete conformal class is defined on that
// triangulation. Returns the number of flips; Convergence_failure if rounding makes the flips cycle.
inline std::size_t make_intrinsic_delaunay(Intrinsic_triangulation& itri, std::size_t flips_per_edge, const std::string& who,
                                           const std::vector<char>* keep_star = nullptr)
{
  const std::vector<double> zero(itri.number_of_vertices(), 0.0);
  const Flip_pass pass = flip_to_delaunay(itri, Euclidean_delaunay_flip_rule{zero, keep_star, true}, flips_per_edge);
  if(pass.budget_hit)
    throw Convergence_failure(who + ": the intrinsic Delaunay flips did not terminate within " + std::to_string(pass.budget) +
                                  " flips of the first pass, before Newton's method",
                              std::numeric_limits<double>::infinity());
  return pass.flips;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_NEWTON_SOLVER_H
