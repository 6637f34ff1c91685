// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_EXCEPTIONS_H
#define ANISO_CONFORMAL_EXCEPTIONS_H

#include <stdexcept>
#include <string>

/// \file Exceptions.h
/// The exception types thrown by the library (DESIGN.md 4). Three kinds of failure are kept apart,
/// because a user acts differently on each: the input is wrong (`Invalid_input`: fix the input), the
/// input is valid but this version cannot remesh it (`Remeshing_failure` and its `Convergence_failure`:
/// change a parameter, or report it), or the library broke one of its own invariants (`Internal_error`:
/// a bug, please report it). The command-line tool maps them to the exit codes 2, 3 and 1.

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
 * thrown for input that is wrong: a non-manifold or degenerate mesh, several connected components, a
 * metric that is not finite or not positive definite on the tangent plane, an unreadable file, a
 * parametric domain that does not fit the topology, an impossible vertex count. The input is left
 * unchanged. The tool exits with status 2.
 */
struct Invalid_input : Error {
  using Error::Error;  ///< constructs the exception with the message `what` (explicit, as `Error`'s)
};

/*!
 * \ingroup PkgAnisoConformalErrors
 * thrown when the input is valid but this version cannot remesh it: a topology without a domain yet,
 * a surface whose conformal map cannot be represented in double precision, an output that would have
 * inverted triangles. The message says what was reached and, where one exists, what may help. The
 * input is left unchanged. The tool exits with status 3.
 */
struct Remeshing_failure : Error {
  using Error::Error;  ///< constructs the exception with the message `what` (explicit, as `Error`'s)
};

/*!
 * \ingroup PkgAnisoConformalErrors
 * a `Remeshing_failure` of an iterative stage (edge-length adjustment, conformal Newton solve, CVT,
 * band of images): it reached its documented bound or broke down numerically; `residual()` is what
 * it reached.
 */
class Convergence_failure : public Remeshing_failure {
public:
  /// constructs the exception with the message `what` and the residual reached
  Convergence_failure(const std::string& what, double residual) : Remeshing_failure(what), m_residual(residual) {}
  /// the residual (stage-specific: gradient norm, number of invalid triangles, ...) when it stopped
  double residual() const { return m_residual; }

private:
  double m_residual;
};

/*!
 * \ingroup PkgAnisoConformalErrors
 * thrown when the library finds one of its own invariants broken (an intrinsic triangulation whose
 * twins disagree, a homology basis of the wrong size): a bug, not a property of the input. The tool
 * exits with status 1.
 */
struct Internal_error : Error {
  using Error::Error;  ///< constructs the exception with the message `what` (explicit, as `Error`'s)
};

/*!
 * \ingroup PkgAnisoConformalErrors
 * thrown when a visitor asked to stop; the output mesh is left unchanged.
 */
struct Cancelled : Error {
  using Error::Error;  ///< constructs the exception with the message `what` (explicit, as `Error`'s)
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_EXCEPTIONS_H
