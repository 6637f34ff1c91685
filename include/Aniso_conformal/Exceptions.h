// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_EXCEPTIONS_H
#define ANISO_CONFORMAL_EXCEPTIONS_H

#include <stdexcept>
#include <string>

/// \file Exceptions.h
/// The exception types thrown by the library (DESIGN.md 4).

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalErrors
 * base class of every exception the library throws; `what()` names the problem and where
 * (file, line, vertex or face index).
 */
class Error : public std::runtime_error {
public:
  /// constructs the exception with the message `what`
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/*!
 * \ingroup PkgAnisoConformalErrors
 * thrown for input the library cannot work on: a non-manifold or degenerate mesh, a topology the
 * chosen domain does not fit, a metric that is not finite or not positive definite on the tangent
 * plane, an unreadable file, an impossible vertex count. The input is left unchanged.
 */
class Invalid_input : public Error {
public:
  /// constructs the exception with the message `what`
  explicit Invalid_input(const std::string& what) : Error(what) {}
};

/*!
 * \ingroup PkgAnisoConformalErrors
 * thrown when an iterative stage (edge-length adjustment, conformal Newton solve, CVT) reaches its
 * documented iteration bound or breaks down numerically; `residual()` is the residual it reached.
 */
class Convergence_failure : public Error {
public:
  /// constructs the exception with the message `what` and the residual reached
  Convergence_failure(const std::string& what, double residual) : Error(what), m_residual(residual) {}
  /// the residual (stage-specific: gradient norm, number of invalid triangles, ...) when it stopped
  double residual() const { return m_residual; }

private:
  double m_residual;
};

/*!
 * \ingroup PkgAnisoConformalErrors
 * thrown when a visitor asked to stop; the output mesh is left unchanged.
 */
class Cancelled : public Error {
public:
  /// constructs the exception with the message `what`
  explicit Cancelled(const std::string& what) : Error(what) {}
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_EXCEPTIONS_H
