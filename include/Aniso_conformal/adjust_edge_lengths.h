// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_ADJUST_EDGE_LENGTHS_H
#define ANISO_CONFORMAL_ADJUST_EDGE_LENGTHS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/internal/edge_lengths/adjustment.h>
#include <Aniso_conformal/internal/intrinsic/flip_to_delaunay.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

/// \file adjust_edge_lengths.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * what `adjust_edge_lengths()` did
 */
struct Edge_adjustment_report {
  std::size_t invalid_triangles_before = 0;  ///< triangles violating the triangle inequality before any flip
  std::size_t flips = 0;                     ///< metric-Delaunay flips
  std::size_t splits = 0;                    ///< longest-edge splits
  std::size_t rounds = 0;                    ///< flip-then-split rounds
  /// the length added to every edge by the final mollification, relative to the median edge length
  /// (0 if the splits sufficed)
  double mollification = 0;
  /// triangles repaired by changing an edge length locally when splits stalled
  std::size_t repaired_triangles = 0;
  /// rounds whose flip pass stopped at its budget (`max_flips_per_edge`) with edges still to flip
  std::size_t flip_budget_hits = 0;
  /// flips refused because the edge's two vertices had already been joined and flipped apart twice in
  /// the same pass: the metric-Delaunay test cycling on a quad whose metric varies across it
  std::size_t cycling_flips_refused = 0;
};


/*!
 * \ingroup PkgAnisoConformalStages
 * makes the metric edge lengths of `itri` a valid triangulation (paper 3.2): computes the lengths
 * (`compute_metric_edge_lengths()`), makes the triangulation metric-Delaunay by edge flips (paper
 * Fig.\ 3), and while some triangle still violates the triangle inequality splits its longest edge at
 * the midpoint (projected onto `surface`; its `Q` is the mean of the edge's ends), then repeats.
 *
 * A boundary edge facing an angle above 120 degrees is split too (Ruppert's encroached segments):
 * boundary edges cannot be flipped, and the conformal scaling would flatten such a triangle.
 *
 * \param itri the triangulation, modified in place
 * \param surface the input surface the vertices of `itri` lie on
 * \param np optional named parameters:
 *   - `max_adjustment_rounds` (unsigned, default 50): bound on flip-then-split rounds;
 *   - `max_flips_per_edge` (unsigned, default 50): bound on the flips of one round, per edge it examines;
 *   - `visitor`: `on_iteration(Stage::EDGE_LENGTHS, round, bound, invalid_triangles)`.
 *
 * When three rounds of splits in a row do not reduce the number of invalid triangles (a metric that
 * jumps between neighbouring triangles, like the colour edges of an image), the remaining triangles are
 * repaired locally: the longest edge of such a triangle is shortened to just below the sum of the other
 * two when that keeps its other triangle valid, else the two others are lengthened
 * (`Edge_adjustment_report::repaired_triangles`, a few passes). If triangles remain, intrinsic
 * mollification (Sharp, Soliman, Crane 2019) lengthens every edge by the smallest `epsilon` that makes
 * every triangle valid, accepted if `epsilon` is at most a tenth of the median edge length
 * (`Edge_adjustment_report::mollification`).
 *
 * The first round examines every edge, later rounds only the edges around the vertices the splits
 * inserted. The number of flips of a round is bounded by `max_flips_per_edge` times the number of edges
 * it examines, plus 100 (a metric that varies across a quad can make Lawson's algorithm cycle); flipping
 * then stops for that round (`Edge_adjustment_report::flip_budget_hits`) and the splits go on: the
 * round bound still applies. Before that bound, such a cycle is stopped where it happens: within one
 * pass, an edge whose two vertices have already been joined and flipped apart twice is kept
 * (`Edge_adjustment_report::cycling_flips_refused`), so one cycling quad no longer spends the budget
 * of the whole pass and leaves every other edge unflipped (the CT slice at the paper's s = 0.5).
 * \throws Convergence_failure if invalid triangles remain after `max_adjustment_rounds` rounds, or when
 *         the splits stall and mollification would need more than a tenth of the median edge length
 *         (the residual is their number): the metric varies too fast for the input's resolution.
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Edge_adjustment_report adjust_edge_lengths(Intrinsic_triangulation& itri, const Input_surface& surface,
                                           const NamedParameters& np = parameters::default_values())
{
  const std::size_t max_rounds = internal::max_adjustment_rounds(np);
  const std::size_t flips_per_edge = internal::max_flips_per_edge(np);
  typename internal::Visitor_reference<NamedParameters>::type vis = internal::get_visitor(np);

  Edge_adjustment_report report;
  compute_metric_edge_lengths(itri);
  report.invalid_triangles_before = internal::count_invalid_triangles(itri);
  std::vector<int> seeds = internal::all_halfedges(itri);  // every edge in the first round
  std::size_t best = std::size_t(-1), stalled = 0;  // progress of the splits

  for(report.rounds = 1;; ++report.rounds) {
    // 1. metric-Delaunay flips (Lawson's queue): every edge in the first round, then only the edges
    //    around the vertices the last splits inserted (Lawson's incremental insertion): elsewhere nothing changed
    const internal::Flip_pass pass = internal::flip_to_delaunay(itri, internal::Metric_delaunay_flip_rule(), seeds, flips_per_edge,
                                                                internal::defaults::metric_flips_per_vertex_pair);
    report.flips += pass.flips;
    report.cycling_flips_refused += pass.capped;
    if(pass.budget_hit) ++report.flip_budget_hits;
    compute_metric_edge_lengths(itri);

    // 2. the edges to split
    const std::vector<int> to_split = internal::edges_to_split(itri);
    if(to_split.empty()) break;
    if(to_split.size() < best) {
      best = to_split.size();
      stalled = 0;
    } else if(++stalled >= 3) {
      // splitting no longer helps (a metric that jumps between neighbouring triangles): repair the few
      // triangles left by shortening or lengthening their edges, or mollify
      if(internal::repair_lengths(itri, report) || internal::mollify(itri, report)) break;
      throw Convergence_failure("edge-length adjustment: " + std::to_string(to_split.size()) +
                                    " triangles still violate the triangle inequality and splitting no longer helps"
                                    " (mollification would lengthen every edge by " +
                                    std::to_string(report.mollification) +
                                    " of the median edge length); smooth the metric or refine the input",
                                double(to_split.size()));
    }
    if(report.rounds >= max_rounds)
      throw Convergence_failure("edge-length adjustment: " + std::to_string(to_split.size()) +
                                    " triangles still violate the triangle inequality after " +
                                    std::to_string(max_rounds) +
                                    " rounds of flips and splits; smooth the metric or refine the input",
                                double(to_split.size()));
    const std::vector<int> inserted = internal::split_edges(itri, surface, to_split);
    report.splits += inserted.size();
    seeds.clear();
    for(int v : inserted)
      for(int h : itri.outgoing_halfedges(v)) {
        seeds.push_back(h);
        seeds.push_back(Intrinsic_triangulation::next(h));
      }
    compute_metric_edge_lengths(itri);
    if(!vis.on_iteration(Stage::EDGE_LENGTHS, report.rounds, max_rounds, double(internal::count_invalid_triangles(itri))))
      throw Cancelled("cancelled by the visitor during the edge-length adjustment");
  }
  return report;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_ADJUST_EDGE_LENGTHS_H
