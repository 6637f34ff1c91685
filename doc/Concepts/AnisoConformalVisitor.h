// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
// Concept documentation (Doxygen only).

/*!
 * \ingroup PkgAnisoConformalConcepts
 * \cgalConcept
 *
 * Receives the progress of `remesh()` and of the iterative stages, and may cancel them. Passed with the
 * named parameter `visitor`; it is copied, so pass `std::ref(v)` to keep its state. When
 * `on_iteration()` returns `false` the running stage throws `Aniso_conformal::Cancelled` and the output
 * mesh of `remesh()` is left unchanged.
 *
 * \cgalHasModel `Aniso_conformal::Default_visitor` (callbacks that do nothing; derive from it)
 */
class AnisoConformalVisitor {
public:
  /// called when stage `s` starts
  void on_stage_started(Aniso_conformal::Stage s);
  /// called when stage `s` ends, after `seconds` of wall time
  void on_stage_finished(Aniso_conformal::Stage s, double seconds);
  /// called after each iteration of an iterative stage (`EDGE_LENGTHS`: round, value = invalid
  /// triangles; `EMBEDDING`: Newton step, value = angle-sum error; `CVT`: iteration, value = energy),
  /// with the iteration's bound; returns `false` to cancel
  bool on_iteration(Aniso_conformal::Stage s, std::size_t iteration, std::size_t bound, double value);
};
