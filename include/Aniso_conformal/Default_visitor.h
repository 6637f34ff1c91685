// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_DEFAULT_VISITOR_H
#define ANISO_CONFORMAL_DEFAULT_VISITOR_H

#include <Aniso_conformal/Stage.h>

#include <cstddef>

/// \file Default_visitor.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalVisitors
 * a visitor whose callbacks do nothing; derive from it and override what you need.
 * The visitor is copied by `remesh()`: pass `std::ref(v)` to keep state or a cancellation flag.
 *
 * \cgalModels `AnisoConformalVisitor`
 */
struct Default_visitor {
  /// called when stage `s` starts
  void on_stage_started(Stage /*s*/) {}
  /// called when stage `s` ends, after `seconds` of wall time
  void on_stage_finished(Stage /*s*/, double /*seconds*/) {}
  /*!
   * called after each iteration of an iterative stage (`EDGE_LENGTHS`: adjustment round,
   * `EMBEDDING`: Newton step, `CVT`: optimiser iteration, `SURFACE_OPTIMIZATION`: round) with the
   * iteration number, the bound on iterations and the stage's current value (invalid triangles, gradient
   * norm, CVT energy, flips and moves of the round).
   * Returning `false` cancels: the algorithm throws `Cancelled` and leaves the output unchanged.
   */
  bool on_iteration(Stage /*s*/, std::size_t /*iteration*/, std::size_t /*bound*/, double /*value*/) { return true; }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_DEFAULT_VISITOR_H
