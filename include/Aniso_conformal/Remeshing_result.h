// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_REMESHING_RESULT_H
#define ANISO_CONFORMAL_REMESHING_RESULT_H

#include <Aniso_conformal/Domain_diagnostics.h>
#include <Aniso_conformal/IO/Repair_report.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/adjust_edge_lengths.h>
#include <Aniso_conformal/measure_features.h>
#include <Aniso_conformal/mesh_quality.h>
#include <Aniso_conformal/optimize_surface_mesh.h>
#include <Aniso_conformal/parameters.h>
#include <Aniso_conformal/refine_background.h>
#include <Aniso_conformal/weighted_centroidal_Voronoi_tessellation.h>

#include <array>
#include <string>
#include <vector>

/// \file Remeshing_result.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMain
 * the stretch bound of `remesh_in_domain()` and `remesh()` (issue 17; doc/manual.md, "The paper's [2, 29] as a field, and the stretch a mesh can realise"): when the run
 * in the metric as given leaves folded (inverted) triangles because straight edges cannot follow the
 * metric's long axis where it turns within the tangent plane (an element of length `L`, width `w` and
 * stretch `r = L / w` along a line of geodesic curvature `kappa_g` folds once the sagitta
 * `kappa_g L^2 / 8` nears `w`), it runs again with the stretch at each input vertex lowered to
 * `sqrt(8 c / (kappa_g w))` (`c` = 1/4, `w` the element's width at the requested number of vertices)
 * where it asked for more, and reports it here. The output's `Remeshing_result::quality` is then
 * measured in the bounded metric, the one the output realises; the `given_*` figures measure it in the
 * metric as given.
 */
struct Stretch_limit_report {
  bool applied = false;              ///< `true` if the output is that of the run with the stretch bounded
  std::size_t vertices_limited = 0;  ///< input vertices whose stretch was lowered
  double stretch_asked_max = 0;      ///< the largest stretch asked for at those vertices
  double bound_min = 0;              ///< the smallest bound there (where the output's stretch is bounded most)
  double bound_median = 0;           ///< the median bound there
  std::string reason;                ///< why the run in the metric as given failed
  double given_G_min = 0;            ///< the output's `G_min` in the metric as given
  double given_G_avg = 0;            ///< the output's `G_avg` in the metric as given
  double given_theta_min = 0;        ///< the output's smallest angle in the metric as given (degrees)
  double given_percent_below_30 = 0; ///< the share of its triangles below 30 degrees there (percent)
};

/*!
 * \ingroup PkgAnisoConformalMain
 * the feature sizing of `remesh()` (`feature_sizing`, default on; issue 15): where two crease curves run closer than an output triangle's height, the metric's lengths are multiplied
 * by a scale so that the output's edges there are about as long as the gap is wide (1.3 times), graded
 * away from it by at most a factor 1.2 per output edge (Borouchaki, Hecht and Frey 1998, isotropic
 * form), at most 6; the number of output vertices stays the one asked for, so the rest is a little coarser.
 * `Remeshing_result::quality` is measured in the scaled metric (the same angles and `G` where the scale
 * is constant over a triangle: the scale is isotropic). The curvature sizing (`curvature_sizing`, by
 * default in the cone domain) shares the field: where the largest principal curvature's radius is shorter than an output edge,
 * edges of about 1.25 times the radius, graded by 1.8 per edge, at most 3 times shorter
 * (`internal/features/curvature_size.h`; manual, "Thin parts and tips").
 */
struct Feature_sizing_report {
  bool applied = false;             ///< `true` if the metric was scaled (the other figures are filled when `narrow_points > 0`)
  std::size_t narrow_points = 0;    ///< samples of the crease curves (a quarter of an output edge apart) across a narrow gap
  std::size_t vertices_scaled = 0;  ///< input vertices where the scale is above 1
  double gap_min = 0;               ///< the narrowest gap in the metric, over the output edge length of the unscaled metric
  double scale_max = 1;             ///< the largest scale (at most 6)
  double area_factor = 1;           ///< the metric's area after the scaling over before (at most 2): the unscaled parts' edges grow by its square root
  std::size_t gaps_left = 0;        ///< narrow points left as they are: a gap below 1 / 7.8 output edges, or past the area budget (narrowest first)
  /// input vertices where the surface bends more tightly than an output edge (`curvature_sizing`): the
  /// largest principal curvature's radius, in the metric, shorter than the refined parts' largest edge
  std::size_t curved_points = 0;
  double radius_min = 0;            ///< the smallest such radius over the output edge length of the unscaled metric (0: none measured)
  bool curvature_applied = false;   ///< `true` if the field holds the curvature's sizes (within the area budget)
};

/*!
 * \ingroup PkgAnisoConformalMain
 * which of the runs of `remesh()` that follow the input's creases (issue 15) gave the output: up to four
 * runs from the background after stage 2's refinement (doc/manual.md, "Sharp features");
 * `crease_run_name()` spells each value as the JSON report and the tool's summary write it
 */
enum class Crease_run {
  NONE,            ///< "none": no crease curve to follow (none found, or `feature_angle(180)` without marked edges)
  REFINED,         ///< "refined": the first run, the crease sites on the crease pieces refined to a third of an output edge
  INPUT_VERTICES,  ///< "input-vertices": the first run failed; the crease sites on the background's own crease vertices, nothing split
  NOT_FOLLOWED,    ///< "not-followed": both runs with crease sites failed; the run without them (`Remeshing_result::creases_not_followed` says why)
  FEATURES_DROPPED ///< "features-dropped": in a closed domain the run without crease sites failed too, with the corners as fixed sites; the run without any feature site, as `feature_angle(180)` (`Remeshing_result::corners_not_kept` says why)
};

/*!
 * \ingroup PkgAnisoConformalMain
 * the name of a crease run, as the JSON report (`features.crease_run`) and the tool's summary spell it
 */
inline const char* crease_run_name(Crease_run r)
{
  switch(r) {
  case Crease_run::REFINED: return "refined";
  case Crease_run::INPUT_VERTICES: return "input-vertices";
  case Crease_run::NOT_FOLLOWED: return "not-followed";
  case Crease_run::FEATURES_DROPPED: return "features-dropped";
  default: return "none";
  }
}

/*!
 * \ingroup PkgAnisoConformalMain
 * the diagnostics of a `remesh()` call: per-stage wall times and counts, solver figures, quality.
 * Failures are exceptions, not fields of this struct.
 */
struct Remeshing_result {
  std::array<double, number_of_stages> seconds{};  ///< wall time of each stage, indexed by `Stage`
  /// the parametric domain used (`domain_name()` spells it: "plane", "sphere", "flat-torus", "hyperbolic")
  Parametric_domain domain = Parametric_domain::AUTOMATIC;
  std::size_t input_vertices = 0;                  ///< vertices of the input
  std::size_t input_faces = 0;                     ///< faces of the input
  std::size_t background_vertices = 0;             ///< vertices of the background after adjustment
  std::size_t background_faces = 0;                ///< faces of the background after adjustment
  std::size_t corners = 0;                         ///< input corners kept as output vertices
  /// what was repaired in the input before it became an `Input_surface` (`IO::repair_polygon_soup()`).
  /// `remesh()` takes a valid surface and repairs nothing: it leaves this empty, and a caller that read
  /// its input with repairs (`IO::read_triangle_mesh(path, report)`, as the tool does) stores the report
  /// here after `remesh()`, so that `IO::write_report_json()` writes it
  Repair_report repairs;
  Refinement_report refinement;                    ///< the background refined for the requested size (stage 2)
  Edge_adjustment_report adjustment;               ///< flips and splits of stage 2
  std::size_t conformal_iterations = 0;            ///< Newton iterations of stage 3
  double conformal_residual = 0;                   ///< max angle-sum error at the end of stage 3 (radians)
  /// `true` if stage 3 was not solved in this run: an earlier run of the same call (one that followed
  /// the creases, or the first run at a boundary loop) had embedded the same background, edge lengths and
  /// all, and its embedding was taken; the figures above are its (internal/remesh/embedding_memo.h)
  bool embedding_reused = false;
  std::size_t conformal_flips = 0;                 ///< intrinsic Delaunay flips made during stage 3
  double conformal_factor_min = 0;                 ///< smallest conformal factor
  double conformal_factor_max = 0;                 ///< largest conformal factor
  Cvt_report cvt;                                  ///< energies and iterations of stage 4
  std::size_t boundary_sites = 0;                  ///< output vertices on the boundary
  /// the final optimisation on the surface (`Stage::SURFACE_OPTIMIZATION`): what it did, quality before and after
  Surface_optimization_report surface_optimization;
  /// output triangles whose orientation disagrees with the input (after the surface optimisation; an
  /// output with any is refused, so this is 0 in a returned result)
  std::size_t inverted_triangles = 0;
  Quality_report quality;                          ///< quality of the output in the metric
  /// symmetric Hausdorff distance between the output and the input, approximated by closest-point
  /// queries from the output's vertices, edge midpoints and face centroids to the input and from the
  /// input's vertices to the output
  double hausdorff_distance = 0;
  double hausdorff_distance_relative = 0;          ///< `hausdorff_distance` over the input's bounding-box diagonal
  /// the input's sharp features (`detect_features()` with `feature_angle`, `corner_angle` and the user's
  /// `feature_edges` and `feature_vertices`) and how many
  /// of them the output keeps (`measure_features()`); all zero when the input has none
  Feature_report features;
  /// fixed sites placed along the input's crease curves (issue 15, item 2, every domain; the curves'
  /// corners not counted); 0 without a crease
  std::size_t crease_sites = 0;
  /// pairs of consecutive crease sites (or corners) the dual did not join, joined by one output edge flip
  /// or a sequence of flips (internal/features/edge_recovery_by_flips.h, recover_edge_by_flips())
  std::size_t crease_edges_recovered = 0;
  /// pairs of consecutive crease sites (or corners) left without an output edge between them (the crease
  /// coverage of `features` then misses that piece)
  std::size_t crease_edges_missing = 0;
  /// pairs of consecutive sites of a boundary loop (a surface with holes in a closed domain, issue 15 item
  /// 3) the dual did not join, joined by a sequence of output edge flips (the loop's edges are checked
  /// after; 0 when the dual joined them all, the output then as without the recovery)
  std::size_t loop_edges_recovered = 0;
  /// boundary loops that run along both faces of a part thinner than an output edge (two loop vertices
  /// closer than the output's edge length, with normals facing away, more than three times that apart
  /// along the loop), whose patch begins with a collar along the surface's normals, two output edges
  /// high (internal/remesh/patch_collars.h); 0 when none
  std::size_t collared_loops = 0;
  /// free sites the dual left on the patch side of a loop's chain of sites (cut off with the tip of a spike
  /// of the surface narrower than the spacing), moved onto the midpoint of the longest output edge between
  /// two free sites, which they split (internal/remesh/hole_patches.h, remove_patch_triangles())
  std::size_t patch_sites_moved = 0;
  /// empty, or why the creases were not followed: the runs with crease sites (their pieces refined, then,
  /// if pieces were split or their refinement failed, the sites on the input's own crease vertices) failed, the first with this
  /// message (`Remeshing_failure`), and the output is that of the run without them (corners kept, creases not)
  std::string creases_not_followed;
  /// empty, or, when the run with the crease sites on the input's own crease vertices stood
  /// (`Crease_run::INPUT_VERTICES`), why the run on the refined crease pieces before it failed (the
  /// message of its `Remeshing_failure`)
  std::string crease_refinement_failed;
  /// empty, or why no corner was kept either (`Crease_run::FEATURES_DROPPED`): the run with the corners as
  /// fixed sites and no crease site failed with this message, and the output is that of the run without
  /// any feature site
  std::string corners_not_kept;
  /// empty, or why the first run of an input with boundary loops and no crease failed (a free site left on
  /// a loop's chain of sites, which then has no output edge): the output is that of a second run whose
  /// CVT starts from initial sites drawn with `random_seed + 1`; if a loop passes twice through one point,
  /// any failure of the first run (its message here) leads to that run, which starts from the metric with
  /// such holes closed lobe by lobe and those points no corners
  /// (remesh_in_domain.h, run_pipeline(); manual, "A hole whose loop passes twice through one point")
  std::string reseeded;
  /// how the domain was chosen when the automatic choice left the topology's own: "cones, because the
  /// sphere failed: <its reason>" (issue 16, item 5); empty otherwise
  std::string domain_choice;
  /// the run whose output this is (`Crease_run`): crease sites on refined pieces, on the input's own crease
  /// vertices, or none (`NONE` without a crease curve; `NOT_FOLLOWED` with `creases_not_followed`)
  Crease_run crease_run = Crease_run::NONE;
  /// what the domain measured (flat torus: the lattice; sphere: the angle distortion; hyperbolic disk:
  /// the group's relation error and the tiles reached), written by the report writers as they are
  Domain_diagnostics domain_diagnostics;
  /// the stretch bound, when the run in the metric as given folded triangles (`Stretch_limit_report`)
  Stretch_limit_report stretch_limit;
  /// the feature sizing, when two crease curves run close (`Feature_sizing_report`)
  Feature_sizing_report feature_sizing;
  /// wall time (s) of the runs whose output was thrown away: the runs with crease sites that failed
  /// (`creases_not_followed`, `crease_run`), under the automatic choice, the topology's own domain
  /// before the cone domain took over (`domain_choice`), and the run in the metric as given before the
  /// stretch was bounded (`stretch_limit`); `seconds` holds the stages of the run that stood
  double discarded_seconds = 0;
  /// total wall time (s): the stages of the run that stood plus `discarded_seconds`
  double total_seconds() const
  {
    double s = discarded_seconds;
    for(double x : seconds) s += x;
    return s;
  }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_REMESHING_RESULT_H
