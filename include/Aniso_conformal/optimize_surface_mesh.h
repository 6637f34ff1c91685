// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_OPTIMIZE_SURFACE_MESH_H
#define ANISO_CONFORMAL_OPTIMIZE_SURFACE_MESH_H

#include <Aniso_conformal/Default_visitor.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/extract_dual_mesh.h>
#include <Aniso_conformal/internal/optimize/crowded_vertices.h>
#include <Aniso_conformal/internal/optimize/surface_optimizer.h>
#include <Aniso_conformal/mesh_quality.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <string>

/// \file optimize_surface_mesh.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * what the surface optimisation (`optimize_surface_mesh()`, stage `Stage::SURFACE_OPTIMIZATION`) did,
 * with the quality in the metric before and after it (the "after" figures are those of the final report)
 */
struct Surface_optimization_report {
  bool ran = false;                   ///< `false` when the stage was off or had nothing to repair
  bool second_phase = false;          ///< the second phase ran (its moves toward each vertex's ideal point in the metric: `Surface_optimization::ALWAYS`, and `REPAIR` where it runs as `ALWAYS`, see `remesh()`)
  std::size_t rounds = 0;             ///< rounds made (flip passes then one relocation pass, and the max-min angle pass, each)
  std::size_t flips = 0;              ///< metric-Delaunay (or repairing) edge flips
  std::size_t relocations = 0;        ///< accepted vertex moves along the input (both relocation passes)
  std::size_t fixed_vertices = 0;     ///< boundary vertices and the mesh's fixed sites (`Remeshed_surface::fixed_vertices`: boundary sites, kept corners), never moved (less the sliding ones)
  std::size_t sliding_vertices = 0;   ///< boundary vertices free to slide along a straight piece of the input's boundary (with `angle_pass_everywhere` only)
  std::size_t crowded_vertices = 0;   ///< free vertices removed where the mesh is densest and reinserted on a thin triangle's split edge (see `optimize_surface_mesh()`)
  std::size_t inverted_before = 0;    ///< inverted or degenerate triangles before the stage
  std::size_t inverted_after = 0;     ///< the same after it
  double G_min_before = 0;            ///< quality in the metric before the stage (see `Quality_report`)
  double G_avg_before = 0;            ///< mean G before
  double theta_min_before = 0;        ///< smallest angle before, degrees
  double percent_below_30_before = 0; ///< %<30 before
  double G_min_after = 0;             ///< the same after the stage
  double G_avg_after = 0;             ///< mean G after
  double theta_min_after = 0;         ///< smallest angle after, degrees
  double percent_below_30_after = 0;  ///< %<30 after
};

/*!
 * \ingroup PkgAnisoConformalStages
 * improves the remeshed surface `mesh` on the input `surface`, in `metric` (the pipeline's stage
 * `Stage::SURFACE_OPTIMIZATION`, between the dual mesh and the quality measure): `max_rounds` rounds,
 * then, while inverted triangles are left and a round still changes something, up to `3 max_rounds`
 * more, each of
 * - passes (at most 4) of *metric-Delaunay edge flips*: an interior edge is flipped when the two angles
 *   opposite to it, measured in the mean metric of the four corners, sum to more than pi (the Delaunay
 *   criterion in the metric, as in anisotropic Delaunay meshing, e.g. Labelle and Shewchuk 2003), the flip
 *   makes the two triangles no worse (below) and neither folds (their normals agree with the input's, as
 *   `remesh()`'s output check measures them, and with each other) nor leaves the input (the new
 *   diagonal's midpoint stays within 5 % of its length, or twice the old diagonal's distance, of the
 *   input; this last test is waived for a flip that repairs an inverted triangle);
 * - one pass of *vertex relocation along the surface*: each interior vertex moves toward the centroid of
 *   its one-ring's triangles weighted by their area in the metric (steps 1, 1/2, 1/4 of the way, then
 *   the plain mean of its neighbours; a vertex of an inverted triangle also tries half way to that mean
 *   and 1/2 and 1/4 of the way to each neighbour), projected back onto the input with its AABB tree
 *   (`Input_surface::project()`, CGAL's `AABB_tree`);
 * - one pass of *max-min angle relocation* (optimisation-based smoothing, Freitag and
 *   Plassmann 2000): each free vertex whose one-ring has an angle below 30 degrees in the metric tries the
 *   apex of the triangle equilateral on the edge opposite it in its worst triangles, in space and in the
 *   metric (the triangle's mean square root `Q`; the same point for an isotropic metric), and 1/2, 1/4,
 *   1/8 and 1/16 of the way to each, and steps of 1/2 to 1/32 of its mean edge length along the steepest
 *   ascent of the ring's smallest angle (central differences in its tangent plane: what turns a vertex
 *   around a tip of the surface, where the apexes ask for angles the tip does not have; CGAL's camel
 *   through cones at 3000 vertices, theta_min 19.6 -> 29.6), projected onto the input, and takes the target that raises the ring's smallest angle
 *   most without an inverted triangle, a lower G_min or more triangles below 30 degrees (a free vertex
 *   across a short edge between two fixed sites is otherwise left thin: CGAL's three_peaks at 2000
 *   vertices, theta_min 20.6 -> 30.6 degrees; the image metric of paper eq. 9, whose thin triangles sit
 *   where the metric changes by 40-100 % between a triangle's corners, across colour edges: chelsea at
 *   s = 0.1, 3000 vertices, theta_min 24.1 -> 29.4 degrees and %<30 0.19 -> 0.02 after the other
 *   passes, G_avg unchanged to 1e-4; issue 17 item 4; CGAL's bear at 2000, isotropic: 17.1 -> 30.4).
 *
 * Then, on an output with fixed vertices inside and no inverted triangle, *crowded vertices* are moved
 * (internal/optimize/crowded_vertices.h): next to the fixed sites the CVT can leave a gap that no move of
 * one vertex fills (a band between two crease chains with a single free vertex in it, joined to both
 * by long edges: CGAL's spool at 2000 vertices, theta_min 14 degrees), so a free vertex is taken from
 * where the mesh is densest (its star retriangulated without it, with the largest smallest angle) to the
 * midpoint, on the input, of the longest edge of a thin triangle, followed by max-min angle flips
 * around it (vertex removal, edge split and flips of local remeshing, as one move that keeps the vertex
 * count); a move is made only if, over all the triangles it replaces, none is inverted, the smallest
 * angle rises, G_min does not drop and no more are below 30 degrees; at most 1 % of the vertices move,
 * each once (`Surface_optimization_report::crowded_vertices`), and the rounds above run again after
 * them. At 2000 vertices: spool theta_min 14.0 -> 16.6 and %<30 1.73 -> 0.95, pinion 18.6 -> 23.1 and
 * 0.65 -> 0.35; part.off at 1000: 25.8 -> 28.5 and 0.30 -> 0.10 (G_avg rose on each).
 *
 * Then, when `angle_pass_everywhere` (`Surface_optimization::ALWAYS`) and no triangle is inverted, a
 * *second phase* of up to `max_rounds` rounds of vertex relocation and the max-min angle pass, in which
 * each free vertex first tries its *ideal point in the metric*: the mean, over the triangles of its
 * one-ring, of the apex of the triangle equilateral in that triangle's mean metric on the edge opposite
 * the vertex (as GETMe smoothing, Vartziotis and Wipper 2009, averages the nodes of regularised elements;
 * here in the metric), and 1/2 and 1/4 of the way to it, before the targets above; and a move is accepted
 * if it raises the one-ring's sum of G with no more triangles below 30 degrees and no inverted one, and
 * keeps the ring's G_min and smallest angle at least at min(what they were, F_G) and min(what they were,
 * F_theta) (`improves_above_floors()`), with the floors `F_G = max(0.6, G_min)` and `F_theta = max(35
 * degrees, theta_min)` of the mesh at the start of the phase: a ring's best triangle may give a little so
 * that the others gain. This phase lifts G where the first one stalls at a local optimum of its stricter test (circular
 * field of Fig. 7 at 4000 vertices: G_avg 0.900 -> 0.923, theta_avg 52.2 -> 53.5, theta_min 30.2 -> 33.3;
 * Fig. 8: 0.879 -> 0.909; the torus with its exact stretch-30 metric: 0.922 -> 0.939; issue 17). It never
 * lowers the report's G_min or theta_min (the floors are at least the mesh's), nor adds a triangle below
 * 30 degrees, and raises G_avg; it may lower theta_avg (not measured lower on any case of
 * benchmark/results.md).
 *
 * An operation is accepted only if it lowers the number of inverted triangles among those it changes,
 * or keeps it and makes none of their G_min, theta_min, theta_avg, %<30 worse while raising their sum of
 * G (the quality of `compute_mesh_quality()`, computed the same way); the max-min angle moves above
 * instead raise theta_min with G_min and %<30 no worse, and may lower G_avg a little (at 2000 vertices
 * three_peaks by 1e-4, blob by 5e-3). So on an output without inverted triangles the stage never makes the report's G_min, theta_min
 * or %<30 worse, nor, without a triangle below 30 degrees, its G_avg or theta_avg (up to rounding in the
 * report's sums); on one with inverted triangles it repairs them where a flip or a move can, and a repair
 * may lower those figures. A round that changes nothing ends the first phase. (The second phase's
 * acceptance is the looser one above.)
 *
 * With `angle_pass_everywhere` (as `ALWAYS` asks) a boundary vertex whose two boundary
 * neighbours are on one straight line with it (to 1e-12 relative: not a corner, not a curved boundary)
 * and that lies on an edge of the input's boundary *slides*: its targets are projected onto that line
 * and kept within 90 % of the way to each neighbour, and a move is taken only if it lands on an input
 * boundary edge within 1e-9 of the diagonal of that line; the output's boundary as a set, so its area in
 * the plane, does not change (images at 3000 vertices: 189 boundary vertices, 185 sliding; CT slice at
 * s = 0.2: theta_min 22.9 -> 29.4, G_avg 0.924 -> 0.926; Fig. 8: G_avg 0.909 -> 0.911; circular field at 4000:
 * 0.923 -> 0.924).
 *
 * *Tips* are kept: a free vertex with an angle deficit above 1 radian in space and no fixed neighbour (the
 * one vertex the CVT leaves at the tip of a horn, a tail, a finger) moves only while its one-ring stays
 * within a tenth of its edge length of where it started (unless the move repairs an inverted triangle),
 * and is never a crowded-vertex donor: moved toward its ring's centroid a little at each round it would
 * cut the tip off (CGAL's cow through cones at 3000 vertices: Hausdorff distance 1.3 -> 2.5 % of the
 * diagonal without this rule, 1.45 % with it).
 *
 * Kept: the number of vertices, the topology (flips keep the genus and the boundary; an edge already
 * present is never created), the boundary vertices (but the sliding ones above, which stay on the
 * input's boundary) and the first `mesh.fixed_vertices` vertices (the CVT's fixed sites: the input's corners
 * and crease sites; fixed) but those of `mesh.released_vertices` (the cone domain's cones, moved like any
 * other vertex), the edges of `mesh.kept_edges` (the creases' output edges: never flipped), every vertex on the input (moved vertices get
 * their new `Surface_point`, planar ones keep z = 0). Faces are rewritten only if an edge was flipped
 * (the same triangles in the same order otherwise), or a crowded vertex moved. Time O(rounds * (E + V log F)), serial (a user's
 * metric model need not be safe for concurrent calls); after the first round a pass visits only the
 * vertices whose one-ring changed since it last left them in place, and tests only the edges whose quad
 * changed since it last kept them (the same output as visiting all: each visit and test depends on
 * those alone; internal/optimize/settled_marks.h), which halves the stage on CGAL's meshes at 2000 vertices.
 *
 * \tparam AnisotropicMetric a model of `AnisotropicMetric`
 * \tparam Visitor a model of `AnisoConformalVisitor`: `on_iteration(Stage::SURFACE_OPTIMIZATION, round,
 *         4 max_rounds, operations made in the round)`
 * \param surface the input surface the output lies on (never modified)
 * \param metric the metric
 * \param mesh the output of stage 5 (`extract_dual_mesh()`): positions, triangles, points on the input;
 *        modified in place
 * \param max_rounds bound on the rounds (0: nothing is done)
 * \param vis the visitor: told of each round, may cancel
 * \param angle_pass_everywhere the second phase, and boundary vertices sliding along straight pieces of
 *        the input's boundary (`Surface_optimization::ALWAYS`; the max-min angle pass runs either way)
 * \returns what was done, with the quality before and after
 * \throws Internal_error if `mesh` is inconsistent (a face index out of range, fewer surface points than
 *         vertices); a `mesh` whose triangles are not a 2-manifold is left unchanged (`ran` is `false`)
 * \throws Cancelled if the visitor asked to stop (`mesh` is then partly optimised, still valid)
 */
template <typename AnisotropicMetric, typename Visitor>
Surface_optimization_report optimize_surface_mesh(const Input_surface& surface, const AnisotropicMetric& metric,
                                                  Remeshed_surface& mesh, std::size_t max_rounds, Visitor& vis,
                                                  bool angle_pass_everywhere = false)
{
  Surface_optimization_report report;
  if(mesh.faces.empty() || max_rounds == 0) return report;
  typedef internal::Surface_optimizer<AnisotropicMetric> Optimizer;
  std::unique_ptr<Optimizer> optimizer(new Optimizer(surface, metric, mesh, angle_pass_everywhere));
  if(!optimizer->build()) return report;
  report.ran = true;
  report.fixed_vertices = optimizer->fixed_vertices();
  report.sliding_vertices = optimizer->sliding_vertices();
  auto count_inverted = [&]() {
    std::size_t n = 0;
    for(const auto& f : mesh.faces)
      n += internal::triangle_is_inverted(surface, mesh.points[f[0]], mesh.points[f[1]], mesh.points[f[2]],
                                          mesh.surface_points[f[0]], mesh.surface_points[f[1]], mesh.surface_points[f[2]],
                                          optimizer->side())
             ? 1
             : 0;
    return n;
  };
  // the quality figures and inverted triangles of `mesh` as it is, into the report's before or after fields
  auto measure = [&](std::size_t& inverted, double& G_min, double& G_avg, double& theta_min, double& percent_below_30) {
    const Quality_report q = compute_mesh_quality(mesh.points, mesh.faces, optimizer->metric_square_roots(), 1);
    inverted = count_inverted();
    G_min = q.G_min;
    G_avg = q.G_avg;
    theta_min = q.theta_min;
    percent_below_30 = q.percent_below_30;
  };
  measure(report.inverted_before, report.G_min_before, report.G_avg_before, report.theta_min_before, report.percent_below_30_before);
  // the rounds asked for, and while inverted triangles are left and the rounds still change something,
  // up to three times as many more
  const std::size_t bound = 4 * max_rounds;
  auto first_phase = [&]() {
    std::size_t inverted = count_inverted();
    for(std::size_t round = 1; round <= bound && (round <= max_rounds || inverted > 0); ++round) {
      std::size_t flips = 0;
      for(int pass = 0; pass < 4; ++pass) {
        const std::size_t f = optimizer->flip_pass();
        flips += f;
        if(f == 0) break;
      }
      const std::size_t moved = optimizer->relocation_pass() + optimizer->angle_pass();
      report.flips += flips;
      report.relocations += moved;
      report.rounds += 1;
      optimizer->write_faces();
      if(!vis.on_iteration(Stage::SURFACE_OPTIMIZATION, report.rounds, bound, double(flips + moved)))
        throw Cancelled("cancelled by the visitor during the surface optimisation");
      if(flips + moved == 0) break;
      if(round >= max_rounds) inverted = count_inverted();
    }
  };
  first_phase();
  // crowded vertices (crowded_vertices.h): on an output with fixed vertices inside and nothing inverted,
  // free vertices taken from where the mesh is densest (their star retriangulated without them) to the
  // split longest edge of a thin triangle, at most 1 % of the vertices; then the first phase again
  if(optimizer->has_interior_fixed_vertices() && count_inverted() == 0) {
    std::vector<Eigen::Matrix3d> Q = optimizer->metric_square_roots();
    const internal::Crowded_vertices_report crowded = internal::relocate_crowded_vertices(
        surface, metric, mesh, Q, optimizer->side(), std::max<std::size_t>(1, mesh.points.size() / 100));
    report.crowded_vertices = crowded.moved;
    if(crowded.moved > 0) {
      optimizer.reset(new Optimizer(surface, metric, mesh, angle_pass_everywhere));
      if(!optimizer->build()) throw Internal_error("surface optimisation: the crowded vertices' moves broke the 2-manifold");
      first_phase();
    }
  }
  // Surface_optimization::ALWAYS, second phase on a mesh without inverted triangles: the same rounds with
  // relocation_pass(true), which aims at each vertex's metric ideal point and may lower a one-ring's G_min
  // and smallest angle down to floors (0.6 and 35 degrees, or the mesh's G_min and theta_min where these
  // are higher: so neither of the report's figures gets worse) to raise its sum of G
  if(angle_pass_everywhere && count_inverted() == 0) {
    const Quality_report q = compute_mesh_quality(mesh.points, mesh.faces, optimizer->metric_square_roots(), 1);
    const double G_floor = std::max(internal::defaults::relaxed_G_floor, q.G_min);
    const double angle_floor = std::max(internal::defaults::relaxed_angle_floor, q.theta_min);
    report.second_phase = true;
    for(std::size_t round = 1; round <= max_rounds; ++round) {
      const std::size_t moved = optimizer->relocation_pass(true, G_floor, angle_floor) + optimizer->angle_pass();
      report.relocations += moved;
      report.rounds += 1;
      if(!vis.on_iteration(Stage::SURFACE_OPTIMIZATION, report.rounds, bound + max_rounds, double(moved)))
        throw Cancelled("cancelled by the visitor during the surface optimisation");
      if(moved == 0) break;
    }
  }
  measure(report.inverted_after, report.G_min_after, report.G_avg_after, report.theta_min_after, report.percent_below_30_after);
  return report;
}

/// `optimize_surface_mesh()` without a visitor
template <typename AnisotropicMetric>
Surface_optimization_report optimize_surface_mesh(const Input_surface& surface, const AnisotropicMetric& metric,
                                                  Remeshed_surface& mesh, std::size_t max_rounds = 5,
                                                  bool angle_pass_everywhere = false)
{
  Default_visitor vis;
  return optimize_surface_mesh(surface, metric, mesh, max_rounds, vis, angle_pass_everywhere);
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_OPTIMIZE_SURFACE_MESH_H
