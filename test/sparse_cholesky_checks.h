// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The checks of the Newton solves' sparse factorisation (internal/conformal/sparse_cholesky.h), written
// once and compiled twice: by test_sparse_cholesky.cpp with the build's choice (CHOLMOD when found) and by
// test_sparse_cholesky_ldlt.cpp with ANISO_CONFORMAL_DISABLE_CHOLMOD (Eigen's SimplicialLDLT only).

#include <Aniso_conformal/Default_visitor.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/internal/conformal/euclidean_conformal_metric.h>
#include <Aniso_conformal/internal/conformal/sparse_cholesky.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cmath>
#include <string>
#include <vector>

namespace AC = Aniso_conformal;
namespace ACI = Aniso_conformal::internal;

namespace {

#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
const std::string expected_backend = "CHOLMOD";
#else
const std::string expected_backend = "Eigen SimplicialLDLT";
#endif

// the graph Laplacian of an n x n grid plus `shift` on the diagonal (SPD for shift > 0)
Eigen::SparseMatrix<double> grid_laplacian(int n, double shift, double weight = 1)
{
  std::vector<Eigen::Triplet<double>> t;
  auto id = [n](int i, int j) { return i * n + j; };
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j) {
      t.emplace_back(id(i, j), id(i, j), shift);
      for(auto [di, dj] : {std::pair<int, int>(1, 0), std::pair<int, int>(0, 1)}) {
        if(i + di >= n || j + dj >= n) continue;
        const int a = id(i, j), b = id(i + di, j + dj);
        t.emplace_back(a, a, weight);
        t.emplace_back(b, b, weight);
        t.emplace_back(a, b, -weight);
        t.emplace_back(b, a, -weight);
      }
    }
  Eigen::SparseMatrix<double> A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

double relative_residual(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& x, const Eigen::VectorXd& b)
{
  return (A * x - b).norm() / b.norm();
}

// a spherical cap as a grid disk, with the Euclidean lengths of its edges
AC::Input_surface spherical_cap(int n)
{
  std::vector<Eigen::Vector3d> pts;
  std::vector<AC::Input_surface::Face> faces;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i) {
      const double x = 2.0 * i / n - 1, y = 2.0 * j / n - 1;
      pts.emplace_back(x, y, std::sqrt(9 - x * x - y * y));
    }
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i) {
      const std::size_t a = std::size_t(j * (n + 1) + i), b = a + 1, c = b + std::size_t(n + 1), d = a + std::size_t(n + 1);
      faces.push_back({{a, b, c}});
      faces.push_back({{a, c, d}});
    }
  return AC::Input_surface(pts, faces);
}

// the Euclidean vertex-scaling geometry with a Hessian that no factorisation takes: one diagonal entry
// -1e-12 per unknown, which the solver's 1e-12 shift makes exactly zero
struct Singular_hessian_geometry : ACI::Euclidean_vertex_scaling {
  mutable std::vector<char> emitted;
  void add_hessian(const std::array<int, 3>& c, const std::array<double, 3>&, const std::array<double, 3>&, bool,
                   const std::vector<int>& index, std::vector<Eigen::Triplet<double>>& triplets) const
  {
    for(int k = 0; k < 3; ++k) {
      const int i = index[std::size_t(c[k])];
      if(i < 0) continue;
      if(emitted.size() <= std::size_t(i)) emitted.resize(std::size_t(i) + 1, 0);
      if(!emitted[std::size_t(i)]) triplets.emplace_back(i, i, -1e-12);
      emitted[std::size_t(i)] = 1;
    }
  }
};

} // namespace

BOOST_AUTO_TEST_CASE(factorises_and_solves_an_spd_system)
{
  const Eigen::SparseMatrix<double> A = grid_laplacian(30, 1e-3);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1, 2);
  ACI::Sparse_factor f;
  std::string failure;
  BOOST_TEST(f.factorize(A, true, failure));
  BOOST_TEST(failure.empty());
  BOOST_TEST(f.backend() == expected_backend);
  BOOST_TEST(f.fallback_reason.empty());
  Eigen::VectorXd x;
  BOOST_TEST(f.solve(b, x));
  BOOST_TEST(relative_residual(A, x, b) < 1e-12);
  // the same pattern, new values: no new analysis needed
  const Eigen::SparseMatrix<double> B = grid_laplacian(30, 2e-3, 1.5);
  BOOST_TEST(f.factorize(B, false, failure));
  BOOST_TEST(f.solve(b, x));
  BOOST_TEST(relative_residual(B, x, b) < 1e-12);
}

BOOST_AUTO_TEST_CASE(a_singular_system_is_refused_with_every_backends_reason)
{
  Eigen::SparseMatrix<double> A = grid_laplacian(5, 0.0);  // singular: constants are in its kernel
  A.coeffRef(0, 0) -= 2;                                   // and not semi-definite either
  A.coeffRef(0, 0) = 0;                                    // a zero first pivot: no LDLT without pivoting
  ACI::Sparse_factor f;
  std::string failure;
  BOOST_TEST(!f.factorize(A, true, failure));
  BOOST_TEST(failure.find("Eigen's SimplicialLDLT: zero pivot") != std::string::npos, failure);
#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
  BOOST_TEST(failure.find("CHOLMOD factorisation: matrix not positive definite") != std::string::npos, failure);
#endif
}

BOOST_AUTO_TEST_CASE(an_indefinite_system_falls_back_to_ldlt)
{
  // symmetric, nonsingular, indefinite: CHOLMOD's supernodal LL^T (its choice for a matrix this size)
  // refuses it, LDLT (negative pivots) solves it
  Eigen::SparseMatrix<double> A = grid_laplacian(100, 1.0);
  A.coeffRef(10, 10) = -3;
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  ACI::Sparse_factor f;
  std::string failure;
  BOOST_TEST(f.factorize(A, true, failure));
  BOOST_TEST(f.backend() == std::string("Eigen SimplicialLDLT"));
#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
  BOOST_TEST(f.fallback_reason.find("CHOLMOD factorisation: matrix not positive definite") == 0u, f.fallback_reason);
#else
  BOOST_TEST(f.fallback_reason.empty());
#endif
  Eigen::VectorXd x;
  BOOST_TEST(f.solve(b, x));
  BOOST_TEST(relative_residual(A, x, b) < 1e-10);
  // CHOLMOD is not tried again on the next systems of this factorisation
  BOOST_TEST(f.factorize(grid_laplacian(100, 1.0), false, failure));
  BOOST_TEST(f.backend() == std::string("Eigen SimplicialLDLT"));
}

#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
namespace {
void* failing_malloc(std::size_t) { return nullptr; }
void* failing_calloc(std::size_t, std::size_t) { return nullptr; }
} // namespace

BOOST_AUTO_TEST_CASE(cholmod_out_of_memory_falls_back_to_ldlt)
{
  // SuiteSparse allocates through these hooks: make every allocation fail during the analysis
  const Eigen::SparseMatrix<double> A = grid_laplacian(20, 1e-3);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  ACI::Sparse_factor f;
  std::string failure;
  auto* const saved_malloc = SuiteSparse_config.malloc_func;
  auto* const saved_calloc = SuiteSparse_config.calloc_func;
  SuiteSparse_config.malloc_func = failing_malloc;
  SuiteSparse_config.calloc_func = failing_calloc;
  const bool ok = f.factorize(A, true, failure);
  SuiteSparse_config.malloc_func = saved_malloc;
  SuiteSparse_config.calloc_func = saved_calloc;
  BOOST_TEST(ok);
  BOOST_TEST(f.backend() == std::string("Eigen SimplicialLDLT"));
  BOOST_TEST(f.fallback_reason == std::string("CHOLMOD analysis: out of memory"));
  Eigen::VectorXd x;
  BOOST_TEST(f.solve(b, x));
  BOOST_TEST(relative_residual(A, x, b) < 1e-12);
}
#endif

BOOST_AUTO_TEST_CASE(later_systems_reuse_the_factor_or_refactorise)
{
  ACI::Sparse_spd_solver s;
  s.cholmod_min_unknowns = 0;  // CHOLMOD for this small system too
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(400, 1, 3);
  Eigen::VectorXd x;
  std::string failure;
  const Eigen::SparseMatrix<double> A = grid_laplacian(20, 1e-2);
  BOOST_TEST(s.solve(A, b, true, x, failure));
  BOOST_TEST(s.factorisations == 1u);
  // a nearby matrix: CG preconditioned by A's factor (CHOLMOD's or LDLT's), no new factorisation
  const Eigen::SparseMatrix<double> B = grid_laplacian(20, 1.01e-2, 1.001);
  BOOST_TEST(s.solve(B, b, false, x, failure));
  BOOST_TEST(relative_residual(B, x, b) < 1e-8);
  BOOST_TEST(s.factorisations == 1u);
  BOOST_TEST(s.preconditioned_solves == 1u);
  // a far one (edge weights spread over three orders of magnitude): the preconditioned CG does not
  // converge within its bound, so C is factorised
  std::vector<Eigen::Triplet<double>> tc;
  for(int i = 0; i < 20; ++i)
    for(int j = 0; j < 20; ++j) {
      const int a = i * 20 + j;
      tc.emplace_back(a, a, 1e-2);
      for(int d = 0; d < 2; ++d) {
        const int i2 = i + (d == 0), j2 = j + (d == 1);
        if(i2 >= 20 || j2 >= 20) continue;
        const int b2 = i2 * 20 + j2;
        const double w = std::pow(10.0, 3.0 * double((7 * i + 13 * j + 5 * d) % 10) / 10.0);
        tc.emplace_back(a, a, w);
        tc.emplace_back(b2, b2, w);
        tc.emplace_back(a, b2, -w);
        tc.emplace_back(b2, a, -w);
      }
    }
  Eigen::SparseMatrix<double> C(400, 400);
  C.setFromTriplets(tc.begin(), tc.end());
  const std::size_t before = s.factorisations;
  BOOST_TEST(s.solve(C, b, false, x, failure));
  BOOST_TEST(relative_residual(C, x, b) < 1e-10);
  BOOST_TEST(s.factorisations == before + 1);
  // a new pattern (an extra coupling, as a flip makes): analysed again, solved exactly
  std::vector<Eigen::Triplet<double>> t;
  for(int k = 0; k < A.outerSize(); ++k)
    for(Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) t.emplace_back(int(it.row()), int(it.col()), it.value());
  t.emplace_back(0, 399, -0.5);
  t.emplace_back(399, 0, -0.5);
  t.emplace_back(0, 0, 0.5);
  t.emplace_back(399, 399, 0.5);
  Eigen::SparseMatrix<double> D(400, 400);
  D.setFromTriplets(t.begin(), t.end());
  BOOST_TEST(s.solve(D, b, true, x, failure));
  BOOST_TEST(relative_residual(D, x, b) < 1e-8);
}

BOOST_AUTO_TEST_CASE(the_newton_solve_converges_with_this_backend)
{
  const AC::Input_surface cap = spherical_cap(16);
  AC::Intrinsic_triangulation t(cap, AC::compute_metric_square_roots(cap, AC::Uniform_metric()));
  AC::compute_metric_edge_lengths(t);
  std::vector<char> fixed(t.number_of_vertices(), 0);
  for(const auto& loop : cap.boundary_loops())
    for(std::size_t v : loop) fixed[v] = 1;
  AC::Default_visitor vis;
  ACI::Newton_bounds bounds;
  bounds.cholmod_min_unknowns = 0;  // CHOLMOD for this small solve too
  ACI::make_intrinsic_delaunay(t, bounds.flips_per_edge, "test");
  const ACI::Conformal_solution sol = ACI::solve_conformal_metric(t, ACI::Euclidean_vertex_scaling(), fixed,
                                                                  std::vector<double>(t.number_of_vertices(), 0.0), bounds,
                                                                  vis, "test");
  BOOST_TEST(sol.residual <= bounds.tolerance);
  BOOST_TEST(sol.iterations > 0u);
  BOOST_TEST(sol.backend == expected_backend);
  BOOST_TEST(sol.fallback_reason.empty());
  BOOST_TEST(sol.factorisations >= 1u);
  BOOST_TEST(sol.factorisations + sol.preconditioned_solves == sol.iterations);
  double u_min = 0;
  for(double u : sol.u) u_min = std::min(u_min, u);
  BOOST_TEST(u_min < -1e-3);  // the positive curvature inside shrinks the flat metric
}

BOOST_AUTO_TEST_CASE(a_failed_factorisation_is_a_typed_convergence_failure)
{
  const AC::Input_surface cap = spherical_cap(6);
  AC::Intrinsic_triangulation t(cap, AC::compute_metric_square_roots(cap, AC::Uniform_metric()));
  AC::compute_metric_edge_lengths(t);
  std::vector<char> fixed(t.number_of_vertices(), 0);
  for(const auto& loop : cap.boundary_loops())
    for(std::size_t v : loop) fixed[v] = 1;
  ACI::make_intrinsic_delaunay(t, ACI::Newton_bounds().flips_per_edge, "test");
  AC::Default_visitor vis;
  std::string message;
  ACI::Newton_bounds bounds;
  bounds.cholmod_min_unknowns = 0;
  try {
    ACI::solve_conformal_metric(t, Singular_hessian_geometry(), fixed, std::vector<double>(t.number_of_vertices(), 0.0), bounds,
                                vis, "test solve");
  } catch(const AC::Convergence_failure& e) {
    message = e.what();
    BOOST_TEST(e.residual() > 0);
  }
  BOOST_TEST(message.find("test solve: the sparse Cholesky factorisation failed at Newton iteration 0") == 0u, message);
  BOOST_TEST(message.find("SimplicialLDLT: zero pivot") != std::string::npos, message);
#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
  BOOST_TEST(message.find("CHOLMOD factorisation: matrix not positive definite") != std::string::npos, message);
#endif
}

BOOST_AUTO_TEST_CASE(small_systems_go_to_ldlt)
{
  // below cholmod_min_unknowns the solver factorises with Eigen's LDLT, as before CHOLMOD
  ACI::Sparse_spd_solver s;
  const Eigen::SparseMatrix<double> A = grid_laplacian(20, 1e-2);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  Eigen::VectorXd x;
  std::string failure;
  BOOST_TEST(s.solve(A, b, true, x, failure));
  BOOST_TEST(s.factor().backend() == std::string("Eigen SimplicialLDLT"));
  BOOST_TEST(relative_residual(A, x, b) < 1e-12);
  ACI::Sparse_spd_solver large;
  large.cholmod_min_unknowns = 400;  // this size and above: CHOLMOD, where the build has it
  BOOST_TEST(large.solve(A, b, true, x, failure));
  BOOST_TEST(large.factor().backend() == expected_backend);
}
