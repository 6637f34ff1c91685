// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_SPARSE_CHOLESKY_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_SPARSE_CHOLESKY_H

#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <chrono>
#include <limits>
#include <memory>
#include <string>
#include <vector>

// The sparse factorisation of the conformal Newton solves (newton_solver.h): CHOLMOD's supernodal
// Cholesky (SuiteSparse, Chen, Davis, Hager and Rajamanickam 2008) through Eigen's CholmodSupport when the
// build found it (CMake option ANISO_CONFORMAL_WITH_CHOLMOD defines ANISO_CONFORMAL_USE_CHOLMOD on the
// target) for systems of at least 50000 unknowns, Eigen's SimplicialLDLT for smaller ones, without
// CHOLMOD, and whenever CHOLMOD fails (not positive definite, out of memory). Defining ANISO_CONFORMAL_DISABLE_CHOLMOD before the first include forces the LDLT path in
// that translation unit (the tests use it).
//
// Reuse: the fill-reducing ordering of the first analysis (AMD) is kept for the whole solve, so an
// intrinsic flip, which changes a few entries of the pattern, costs a symbolic analysis with that
// ordering instead of a new ordering; and a factor, CHOLMOD's or LDLT's, serves as the preconditioner of
// conjugate gradients on the next Newton systems (Hessians of nearby u), so that most Newton iterations
// cost a few triangular solves instead of a factorisation. (A pattern kept fixed across flips, e.g. the union of every edge
// met, would save only that symbolic analysis, a small part of a factorisation, at the price of fill.)

#if defined(ANISO_CONFORMAL_USE_CHOLMOD) && !defined(ANISO_CONFORMAL_DISABLE_CHOLMOD)
#define ANISO_CONFORMAL_HAS_CHOLMOD 1
#include <Eigen/CholmodSupport>
#endif

namespace Aniso_conformal {
namespace internal {

#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
// the text of a CHOLMOD status (cholmod_core.h)
inline std::string cholmod_status_text(int status)
{
  switch(status) {
  case CHOLMOD_OK: return "ok";
  case CHOLMOD_NOT_INSTALLED: return "method not installed";
  case CHOLMOD_OUT_OF_MEMORY: return "out of memory";
  case CHOLMOD_TOO_LARGE: return "problem too large";
  case CHOLMOD_INVALID: return "invalid input";
  case CHOLMOD_GPU_PROBLEM: return "GPU failure";
  case CHOLMOD_NOT_POSDEF: return "matrix not positive definite";
  case CHOLMOD_DSMALL: return "diagonal entry tiny";
  default: return "status " + std::to_string(status);
  }
}

// CHOLMOD's supernodal or simplicial LL^T (its own choice by the flop count), silent, with the ordering of
// the first analysis kept for the later ones
class Cholmod_factor : public Eigen::CholmodBase<Eigen::SparseMatrix<double>, Eigen::Lower, Cholmod_factor> {
  typedef Eigen::CholmodBase<Eigen::SparseMatrix<double>, Eigen::Lower, Cholmod_factor> Base;

public:
  Cholmod_factor()
  {
    m_cholmod.final_asis = 1;  // as CholmodDecomposition's automatic mode: CHOLMOD picks supernodal or simplicial
    m_cholmod.supernodal = CHOLMOD_AUTO;
    // AMD only: CHOLMOD's default also tries METIS on large matrices, whose nested dissection halves the
    // factor's flops but took 9x AMD's time to compute (1.66M unknowns: 18.8 s against 2.1 s, the
    // factorisation 13.3 s against 19.9 s with OpenBLAS); a solve factorises once or twice
    m_cholmod.nmethods = 1;
    m_cholmod.method[0].ordering = CHOLMOD_AMD;
    m_cholmod.postorder = 1;
    // never print (the default level 3 prints warnings such as "not positive definite" on stdout) and
    // no handler: failures are read from the status and reported by the caller
    m_cholmod.print = 0;
    m_cholmod.error_handler = nullptr;
  }
  // the symbolic analysis of the pattern of `A` (its lower triangle); returns false with the reason
  bool analyze(const Eigen::SparseMatrix<double>& A, std::string& reason)
  {
    if(m_cholmodFactor) {
      cholmod_free_factor(&m_cholmodFactor, &m_cholmod);
      m_cholmodFactor = nullptr;
    }
    m_analysisIsOk = m_factorizationIsOk = false;
    cholmod_sparse a = Eigen::viewAsCholmod(A.selfadjointView<Eigen::Lower>());
    if(m_permutation.size() == std::size_t(A.rows())) {
      m_cholmod.method[0].ordering = CHOLMOD_GIVEN;
      m_cholmodFactor = cholmod_analyze_p(&a, m_permutation.data(), nullptr, 0, &m_cholmod);
      m_cholmod.method[0].ordering = CHOLMOD_AMD;
    } else {
      m_cholmodFactor = cholmod_analyze(&a, &m_cholmod);
    }
    if(!m_cholmodFactor || m_cholmod.status < CHOLMOD_OK) {
      reason = "CHOLMOD analysis: " + cholmod_status_text(m_cholmod.status);
      return false;
    }
    if(m_permutation.size() != std::size_t(A.rows())) {
      const int* perm = static_cast<const int*>(m_cholmodFactor->Perm);
      m_permutation.assign(perm, perm + A.rows());
    }
    m_isInitialized = true;
    m_analysisIsOk = true;
    m_info = Eigen::Success;
    return true;
  }
  // the numerical factorisation of `A` (same pattern as analysed); returns false with the reason
  bool factorize(const Eigen::SparseMatrix<double>& A, std::string& reason)
  {
    Base::factorize(A);
    if(m_cholmod.status < CHOLMOD_OK) {  // out of memory, too large
      reason = "CHOLMOD factorisation: " + cholmod_status_text(m_cholmod.status);
      m_factorizationIsOk = false;
      return false;
    }
    if(info() != Eigen::Success) {  // minor < n: the leading minor of that order is not positive definite
      reason = "CHOLMOD factorisation: matrix not positive definite (leading minor " + std::to_string(m_cholmodFactor->minor + 1) +
               " of " + std::to_string(A.rows()) + ")";
      m_factorizationIsOk = false;
      return false;
    }
    return true;
  }
  // x = A^-1 b; false if CHOLMOD failed (out of memory)
  bool solve_into(const Eigen::VectorXd& b, Eigen::VectorXd& x) const
  {
    x = Base::solve(b);
    return info() == Eigen::Success && m_cholmod.status >= CHOLMOD_OK;
  }
  // CHOLMOD's own estimate of the factor's memory and flops, after an analysis
  double factor_nonzeros() const { return m_cholmod.lnz; }

private:
  std::vector<int> m_permutation;  // the ordering of the first analysis
};
#endif

/*
 * The factorisation behind Sparse_spd_solver: CHOLMOD when available, with Eigen's SimplicialLDLT as the
 * fallback. `factorize()` analyses when told the pattern changed (or on the first call), then factorises;
 * on a CHOLMOD failure it factorises the same matrix with LDLT and records the reason in `fallback_reason`.
 * Returns false, with both reasons in `failure`, when no backend could factorise.
 */
class Sparse_factor {
public:
  typedef Eigen::SparseMatrix<double> Matrix;

  bool factorize(const Matrix& A, bool pattern_changed, std::string& failure)
  {
    failure.clear();
#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
    if(cholmod_enabled && !m_cholmod_failed) {
      std::string reason;
      bool ok = true;
      if(!m_cholmod_analysed || pattern_changed) {
        const auto t0 = std::chrono::steady_clock::now();
        ok = m_cholmod.analyze(A, reason);
        m_cholmod_analysed = ok;
        ++analyses;
        analysis_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      }
      const auto t0 = std::chrono::steady_clock::now();
      if(ok) ok = m_cholmod.factorize(A, reason);
      factorisation_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if(ok) {
        m_use_ldlt = false;
        return true;
      }
      // fall back to LDLT from now on: a failure (indefinite Hessian, memory) would repeat on the next system
      m_cholmod_failed = true;
      fallback_reason = reason;
      pattern_changed = true;
    }
#endif
    if(!m_ldlt_analysed || pattern_changed) {
      m_ldlt.analyzePattern(A);
      m_ldlt_analysed = true;
    }
    m_ldlt.factorize(A);
    m_use_ldlt = true;
    if(m_ldlt.info() != Eigen::Success) {
      failure = (fallback_reason.empty() ? std::string() : fallback_reason + "; ") + "Eigen's SimplicialLDLT: " +
                (m_ldlt.info() == Eigen::NumericalIssue ? "zero pivot (singular matrix)" : "failed");
      m_ldlt_analysed = false;
      return false;
    }
    return true;
  }
  // x = A^-1 b with the last factorisation; false if the backend failed
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const
  {
#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
    if(!m_use_ldlt) return m_cholmod.solve_into(b, x);
#endif
    x = m_ldlt.solve(b);
    return m_ldlt.info() == Eigen::Success && x.allFinite();
  }
  // the backend of the last factorisation
  const char* backend() const { return m_use_ldlt ? "Eigen SimplicialLDLT" : "CHOLMOD"; }
  bool is_cholmod() const { return !m_use_ldlt; }

  std::string fallback_reason;  // why CHOLMOD was abandoned, empty if it never failed
  bool cholmod_enabled = true;  // false: Eigen's LDLT only
  std::size_t analyses = 0;     // symbolic analyses (CHOLMOD)
  double analysis_seconds = 0, factorisation_seconds = 0;  // their wall time (CHOLMOD), for the profiles

private:
#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
  Cholmod_factor m_cholmod;
  bool m_cholmod_analysed = false, m_cholmod_failed = false;
#endif
  Eigen::SimplicialLDLT<Matrix> m_ldlt;
  bool m_ldlt_analysed = false, m_use_ldlt = true;
};

// Eigen's ConjugateGradient preconditioner interface over a Sparse_factor of a nearby matrix
class Factor_preconditioner {
public:
  typedef double Scalar;
  typedef Eigen::VectorXd Vector;
  Factor_preconditioner() {}
  template <typename M> explicit Factor_preconditioner(const M&) {}
  void set(const Sparse_factor* f) { m_factor = f; }
  template <typename M> Factor_preconditioner& analyzePattern(const M&) { return *this; }
  template <typename M> Factor_preconditioner& factorize(const M&) { return *this; }
  template <typename M> Factor_preconditioner& compute(const M&) { return *this; }
  template <typename Rhs> Vector solve(const Eigen::MatrixBase<Rhs>& b) const
  {
    Vector x;
    if(!m_factor->solve(b.eval(), x)) x = Vector::Constant(b.rows(), std::numeric_limits<double>::quiet_NaN());
    return x;
  }
  Eigen::ComputationInfo info() { return Eigen::Success; }

private:
  const Sparse_factor* m_factor = nullptr;
};

/*
 * Solves the Newton systems H du = g of one conformal solve (H symmetric positive definite, or nearly).
 * Each system after the first is tried by conjugate gradients preconditioned with the factorisation of an
 * earlier H (at most `cg_iterations` iterations, relative residual `cg_tolerance`), whichever backend made
 * it (LDLT's unless `reuse_ldlt_factor` is false); when that does not converge (the Hessian moved too far), H itself is factorised (Sparse_factor,
 * analysed again only when `pattern_changed`) and solved directly. Measured (bench_paper, one thread):
 * the 26k-vertex cyclide's flat-torus embedding 0.55 -> 0.30 s (3 LDLT factorisations -> 1 and 2 solves
 * of 4 CG iterations), the 10k ellipsoid's sphere 0.18 -> 0.12 s, the outputs' quality the same to the
 * printed digits (the Newton iterates differ at the CG tolerance). Until 2026-12-06 the LDLT path
 * factorised every system. Deterministic: the same sequence of systems gives the same answers whatever
 * the timing.
 */
class Sparse_spd_solver {
public:
  typedef Eigen::SparseMatrix<double> Matrix;

  std::size_t cg_iterations = 20;   // bound of one preconditioned CG attempt
  double cg_tolerance = 1e-10;      // its relative residual
  // Systems with fewer unknowns go to Eigen's LDLT: below ~50k unknowns it is about as fast or faster
  // (26k torus: 0.12 s against 0.08 s a factorisation; the 45k CT image background: 0.16 s against 0.33 s,
  // and its preconditioned CG iterations 5.6 ms against 19 ms); at 104k CHOLMOD is 5x faster, at 415k 18x.
  std::size_t cholmod_min_unknowns = 50000;
  // false: LDLT's factor is not reused, every system below cholmod_min_unknowns is factorised (the
  // hyperbolic embedding's choice, hyperbolic_embedding.h)
  bool reuse_ldlt_factor = true;

  // solves H x = b; `pattern_changed` tells that H's pattern differs from the last factorised one.
  // Returns false with the reason in `failure` when no factorisation of H succeeded.
  bool solve(const Matrix& H, const Eigen::VectorXd& b, bool pattern_changed, Eigen::VectorXd& x, std::string& failure)
  {
    m_pattern_changed = m_pattern_changed || pattern_changed;
    m_factor.cholmod_enabled = std::size_t(H.rows()) >= cholmod_min_unknowns;
    if(m_have_factor && cg_iterations > 0 && (m_factor.is_cholmod() || reuse_ldlt_factor)) {
      Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper, Factor_preconditioner> cg;
      cg.setMaxIterations(Eigen::Index(cg_iterations));
      cg.setTolerance(cg_tolerance);
      cg.preconditioner().set(&m_factor);
      cg.compute(H);
      const auto t0 = std::chrono::steady_clock::now();
      x = cg.solve(b);
      cg_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if(cg.info() == Eigen::Success && x.allFinite()) {
        ++preconditioned_solves;
        cg_iterations_total += std::size_t(cg.iterations());
        return true;
      }
    }
    m_have_factor = false;
    if(!m_factor.factorize(H, m_pattern_changed, failure)) return false;
    ++factorisations;
    m_pattern_changed = false;
    m_have_factor = true;
    if(!m_factor.solve(b, x)) {
      failure = std::string(m_factor.backend()) + ": the triangular solves failed";
      m_have_factor = false;
      return false;
    }
    return true;
  }
  const Sparse_factor& factor() const { return m_factor; }

  std::size_t factorisations = 0;        // numerical factorisations made
  std::size_t preconditioned_solves = 0; // systems solved by preconditioned CG
  std::size_t cg_iterations_total = 0;   // their iterations
  double cg_seconds = 0;                 // the wall time of the CG attempts

private:
  Sparse_factor m_factor;
  bool m_have_factor = false, m_pattern_changed = true;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_SPARSE_CHOLESKY_H
