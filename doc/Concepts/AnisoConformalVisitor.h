// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Concept documentation (read by Doxygen only; not a header to include).

/*!
 * \ingroup PkgAnisoConformalConcepts
 * Receives the progress of `remesh()` and of its iterative stages, and may cancel them.
 *
 * \cgalConcept
 *
 * A visitor is passed with the named parameter `visitor` (`Aniso_conformal::parameters::visitor(v)`);
 * without it the functions use a `Default_visitor`. The named-parameter pack stores a copy, so pass
 * `std::ref(v)` to keep the visitor's state (counters, a cancellation flag) in `v` itself. The callbacks
 * are called on a non-const visitor, from the calling thread.
 *
 * - `remesh()` calls `on_stage_started()` and `on_stage_finished()` around each of its stages, in the
 *   order of `Aniso_conformal::Stage`.
 * - `adjust_edge_lengths()`, `conformal_embedding()` and `weighted_centroidal_Voronoi_tessellation()`
 *   call `on_iteration()` after each of their iterations (also when called on their own).
 *
 * When `on_iteration()` returns `false`, the running stage throws `Aniso_conformal::Cancelled`; the
 * output mesh of `remesh()` is then left unchanged.
 *
 * \cgalHasModel `Aniso_conformal::Default_visitor` (callbacks that do nothing; derive from it and
 * redefine what you need)
 *
 * \sa `examples/progress_visitor.cpp`, which prints the stage times and the CVT energy and cancels
 * the run beyond a time budget.
 */
class AnisoConformalVisitor {
public:
  /// \name Callbacks
  /// @{

  /// called when stage `s` starts
  void on_stage_started(Aniso_conformal::Stage s);

  /// called when stage `s` ends, after `seconds` of wall time
  void on_stage_finished(Aniso_conformal::Stage s, double seconds);

  /*!
   * called after iteration `iteration` (counted from 1) of the iterative stage `s`, whose iterations
   * are bounded by `bound`, with the stage's current `value`:
   * - `Stage::EDGE_LENGTHS`: a flip-then-split round; `value` is the number of invalid triangles;
   * - `Stage::EMBEDDING`: a Newton step; `value` is the largest angle-sum error (radians);
   * - `Stage::CVT`: an optimiser iteration; `value` is the CVT energy.
   *
   * \returns `true` to continue, `false` to cancel (the stage throws `Aniso_conformal::Cancelled`)
   */
  bool on_iteration(Aniso_conformal::Stage s, std::size_t iteration, std::size_t bound, double value);

  /// @}
};
