// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_WRITE_REPORT_H
#define ANISO_CONFORMAL_IO_WRITE_REPORT_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Remeshing_result.h>
#include <Aniso_conformal/Stage.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>
#include <vector>

/// \file write_report.h
/// The JSON report of a `remesh()` call, built with nlohmann-json (Debian's nlohmann-json3-dev).

namespace Aniso_conformal {
namespace IO {

namespace internal {
// a real figure of the report: rounded to 10 significant digits, the precision the report has always had
// (so that reports compare equal across versions), or null if it is not finite
inline nlohmann::json report_number(double x)
{
  if(!std::isfinite(x)) return nullptr;
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.10g", x);
  return std::strtod(buf, nullptr);
}
inline nlohmann::json report_numbers(const std::vector<double>& v)
{
  nlohmann::json a = nlohmann::json::array();
  for(double x : v) a.push_back(report_number(x));
  return a;
}
// a figure of the domain, whatever the domain: a scalar, a vector, or a matrix as an array of rows
inline nlohmann::json domain_figure(const Domain_figure& f)
{
  auto number = [&](double x) -> nlohmann::json {
    if(f.integral && std::isfinite(x)) return static_cast<long long>(x);
    return report_number(x);
  };
  if(f.columns == 0 && f.values.size() == 1) return number(f.values[0]);
  nlohmann::json rows = nlohmann::json::array(), row = nlohmann::json::array();
  for(double x : f.values) {
    row.push_back(number(x));
    if(f.columns > 0 && row.size() == f.columns) {
      rows.push_back(row);
      row = nlohmann::json::array();
    }
  }
  if(f.columns == 0) return row;
  if(!row.empty()) rows.push_back(row);  // a last, incomplete row: written as it is
  return rows;
}
// the report's `features` object: the input's features, what the output keeps, what was left out, the run
inline nlohmann::json features_json(const Remeshing_result& r)
{
  nlohmann::json f = {{"crease_edges", r.features.crease_edges},
                      {"curves", r.features.curves},
                      {"corners", r.features.corners},
                      {"corners_kept", r.features.corners_kept},
                      {"crease_length", report_number(r.features.crease_length)},
                      {"covered_length", report_number(r.features.covered_length)},
                      {"covered_share", report_number(r.features.covered_share)}};
  if(r.features.short_components_dropped > 0) {  // creases the detection found, left out as shorter than an output edge
    f["short_components_dropped"] = r.features.short_components_dropped;
    f["short_length_dropped"] = report_number(r.features.short_length_dropped);
  }
  if(r.features.ragged_components_dropped > 0) {  // creases the detection found, left out as ragged (noise)
    f["ragged_components_dropped"] = r.features.ragged_components_dropped;
    f["ragged_length_dropped"] = report_number(r.features.ragged_length_dropped);
    f["rough_surface"] = r.features.rough_surface;
  }
  f["crease_run"] = crease_run_name(r.crease_run);  // which run stood
  if(!r.creases_not_followed.empty()) f["creases_not_followed"] = r.creases_not_followed;
  if(!r.crease_refinement_failed.empty()) f["crease_refinement_failed"] = r.crease_refinement_failed;
  if(!r.corners_not_kept.empty()) f["corners_not_kept"] = r.corners_not_kept;
  if(r.crease_sites > 0) {  // absent: no crease site placed (no crease curve, or curves too short for one)
    f["crease_sites"] = r.crease_sites;
    f["crease_edges_recovered"] = r.crease_edges_recovered;
    f["crease_edges_missing"] = r.crease_edges_missing;
  }
  return f;
}

// the report's `stretch_limit` and `feature_sizing` objects, when the metric was adjusted (or a gap measured)
inline void add_metric_adjustments(const Remeshing_result& r, nlohmann::json& j)
{
  if(r.stretch_limit.applied) {  // the run in the metric as given folded triangles: the stretch bounded (Stretch_limit_report)
    const Stretch_limit_report& l = r.stretch_limit;
    j["stretch_limit"] = {{"vertices_limited", l.vertices_limited},
                          {"stretch_asked_max", report_number(l.stretch_asked_max)},
                          {"bound_min", report_number(l.bound_min)},
                          {"bound_median", report_number(l.bound_median)},
                          {"reason", l.reason},
                          {"given_metric_quality",
                           {{"G_min", report_number(l.given_G_min)},
                            {"G_avg", report_number(l.given_G_avg)},
                            {"theta_min", report_number(l.given_theta_min)},
                            {"percent_below_30", report_number(l.given_percent_below_30)}}}};
  }
  // feature curves close together, or the surface bending more tightly than an edge: the metric scaled up there (Feature_sizing_report)
  if(r.feature_sizing.narrow_points > 0 || r.feature_sizing.curved_points > 0) {
    const Feature_sizing_report& s = r.feature_sizing;
    j["feature_sizing"] = {{"applied", s.applied},
                           {"narrow_points", s.narrow_points},
                           {"vertices_scaled", s.vertices_scaled},
                           {"gap_min", report_number(s.gap_min)},
                           {"scale_max", report_number(s.scale_max)},
                           {"area_factor", report_number(s.area_factor)},
                           {"gaps_left", s.gaps_left},
                           {"curved_points", s.curved_points},
                           {"radius_min", report_number(s.radius_min)},
                           {"curvature_applied", s.curvature_applied}};
  }
}
} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * the report of `r` as a JSON object: `domain` (and `domain_choice`, why the automatic choice went to cones, when it did; `reseeded`, why a first run at a boundary loop failed, when the output is that of the run with the next seed; `stretch_limit`, when the run in the metric as given failed and the output is that of the run with the stretch bounded (`Stretch_limit_report`: `vertices_limited`, `stretch_asked_max`, `bound_min`, `bound_median`, `reason`, and `given_metric_quality`, the output's `G_min`, `G_avg`, `theta_min`, `percent_below_30` in the metric as given)); `feature_sizing`, when two crease curves run closer than an output triangle's height or the surface bends more tightly than an output edge (`Feature_sizing_report`: `applied`, `narrow_points`, `vertices_scaled`, `gap_min`, `scale_max`, `area_factor`, `gaps_left`, `curved_points`, `radius_min`, `curvature_applied`); `input` and `background` (vertices, faces); `output`
 * (vertices, triangles, boundary vertices, corners, inverted triangles, Hausdorff distance absolute and
 * relative to the bounding-box diagonal); `quality` in the metric (G, angles in degrees, the angle
 * histogram; `metric_edge_length`: the mean edge length in the metric and the standard deviation, min and
 * max of the edge lengths divided by that mean, i.e. how well the edges conform to the metric;
 * `metric_stretch`: min, median, 95th percentile and max of the metric's stretch ratio at the output
 * vertices, i.e. the anisotropy the mesh realises); `features`, only if the input has sharp features
 * (`r.features`, `Feature_report`: crease edges, curves and corners of the input, corners kept, crease length,
 * the length and share of it covered by output edges; `short_components_dropped` and `short_length_dropped`,
 * `ragged_components_dropped`, `ragged_length_dropped` and `rough_surface` when crease components were
 * left out; `crease_run`, which run stood: `crease_run_name()` of
 * `r.crease_run`, "refined", "input-vertices" (with `crease_refinement_failed`), "not-followed" (with `creases_not_followed`), "features-dropped"
 * (with `creases_not_followed` and `corners_not_kept`) or "none"); `repairs`, only if the input was repaired on reading
 * (`r.repairs`, `Repair_report`: the file's vertex and face counts, polygons triangulated and the
 * triangles they became, points welded and points left unwelded, duplicated faces removed, vertices of no face dropped, faces
 * reoriented, whether a closed surface was turned outward, whether a planar input was clockwise);
 * `refinement` (the background refined for the requested
 * size: vertices before and after, splits, the output's and the longest edge length in the metric);
 * `edge_adjustment` (flips, splits, rounds, repairs); `surface_optimization`, only if that stage ran
 * (`Surface_optimization_report`: rounds, flips, relocations, fixed and sliding vertices, inverted triangles and
 * G_min, G_avg, theta_min, %<30 before and after it);
 * `conformal_embedding` (Newton iterations, residual in radians, intrinsic flips, conformal factor range, `reused` when an earlier run's embedding of the same background was taken,
 * and the domain's own figures from `r.domain_diagnostics`, written generically: a scalar, a vector or a
 * matrix as rows); `cvt` (method, iterations, energy per iteration); `seconds` (wall time per stage of the
 * run that stood, `discarded`: the runs thrown away, failed crease runs and the topology's own domain
 * before the cone domain, and `total`, their sum). Real numbers have 10 significant digits; a non-finite one is `null`.
 */
inline nlohmann::json report_json(const Remeshing_result& r)
{
  using internal::report_number;
  const Quality_report& q = r.quality;
  nlohmann::json j;
  j["domain"] = domain_name(r.domain);
  if(!r.domain_choice.empty()) j["domain_choice"] = r.domain_choice;  // why the automatic choice left the topology's own domain
  if(!r.reseeded.empty()) j["reseeded"] = r.reseeded;  // why the first run failed at a boundary loop (the output: seed + 1)
  internal::add_metric_adjustments(r, j);
  j["input"] = {{"vertices", r.input_vertices}, {"faces", r.input_faces}};
  j["background"] = {{"vertices", r.background_vertices}, {"faces", r.background_faces}};
  j["output"] = {{"vertices", q.number_of_vertices},
                 {"triangles", q.number_of_triangles},
                 {"boundary_vertices", r.boundary_sites},
                 {"corners", r.corners},
                 {"inverted_triangles", r.inverted_triangles},
                 {"hausdorff_distance", report_number(r.hausdorff_distance)},
                 {"hausdorff_distance_relative", report_number(r.hausdorff_distance_relative)}};
  if(r.loop_edges_recovered > 0) j["output"]["loop_edges_recovered"] = r.loop_edges_recovered;  // absent: none missing
  if(r.patch_sites_moved > 0) j["output"]["patch_sites_moved"] = r.patch_sites_moved;              // absent: none moved
  if(r.collared_loops > 0) j["output"]["collared_loops"] = r.collared_loops;                       // absent: none
  j["quality"] = {{"G_min", report_number(q.G_min)},
                  {"G_avg", report_number(q.G_avg)},
                  {"theta_min", report_number(q.theta_min)},
                  {"theta_avg", report_number(q.theta_avg)},
                  {"percent_below_30", report_number(q.percent_below_30)},
                  {"theta_max", report_number(q.theta_max)},
                  {"angle_histogram",
                   {{"bin_width_degrees", report_number(q.bin_width)}, {"counts", internal::report_numbers(q.angle_histogram)}}},
                  {"metric_edge_length",
                   {{"mean", report_number(q.edge_length_mean)},
                    {"normalized_stddev", report_number(q.edge_length_stddev)},
                    {"normalized_min", report_number(q.edge_length_min)},
                    {"normalized_max", report_number(q.edge_length_max)}}},
                  {"metric_stretch",
                   {{"min", report_number(q.stretch_min)},
                    {"median", report_number(q.stretch_median)},
                    {"p95", report_number(q.stretch_p95)},
                    {"max", report_number(q.stretch_max)}}}};
  // absent: the input has no sharp feature (none detected; all left out as short or ragged: only those counts)
  if(r.features.crease_edges > 0 || r.features.corners > 0 || r.features.short_components_dropped > 0 ||
     r.features.ragged_components_dropped > 0)
    j["features"] = internal::features_json(r);
  if(r.repairs.any())
    j["repairs"] = {{"input_vertices", r.repairs.input_points},
                    {"input_faces", r.repairs.input_polygons},
                    {"polygons_triangulated", r.repairs.polygons_triangulated},
                    {"triangles_from_polygons", r.repairs.triangles_from_polygons},
                    {"points_welded", r.repairs.points_welded},
                    {"points_left_unwelded", r.repairs.points_left_unwelded},
                    {"duplicate_faces_removed", r.repairs.duplicate_polygons_removed},
                    {"isolated_vertices_dropped", r.repairs.isolated_points_dropped},
                    {"faces_reoriented", r.repairs.faces_reoriented},
                    {"reversed_to_outward", r.repairs.reversed_to_outward},
                    {"planar_clockwise", r.repairs.planar_clockwise}};
  j["refinement"] = {{"vertices_before", r.refinement.vertices_before},
                     {"vertices_after", r.refinement.vertices_after},
                     {"splits", r.refinement.splits},
                     {"output_edge_length", report_number(r.refinement.output_edge_length)},
                     {"longest_edge", report_number(r.refinement.longest_edge)}};
  j["edge_adjustment"] = {{"invalid_triangles_before", r.adjustment.invalid_triangles_before},
                          {"flips", r.adjustment.flips},
                          {"splits", r.adjustment.splits},
                          {"rounds", r.adjustment.rounds},
                          {"repaired_triangles", r.adjustment.repaired_triangles},
                          {"mollification", report_number(r.adjustment.mollification)},
                          {"flip_budget_hits", r.adjustment.flip_budget_hits},
                          {"cycling_flips_refused", r.adjustment.cycling_flips_refused}};
  nlohmann::json& embedding = j["conformal_embedding"];
  embedding = {{"newton_iterations", r.conformal_iterations},
               {"residual", report_number(r.conformal_residual)},
               {"intrinsic_flips", r.conformal_flips},
               {"conformal_factor_min", report_number(r.conformal_factor_min)},
               {"conformal_factor_max", report_number(r.conformal_factor_max)}};
  if(r.embedding_reused) embedding["reused"] = true;  // solved by an earlier run on the same background
  for(const Domain_figure& f : r.domain_diagnostics.figures) embedding[f.key] = internal::domain_figure(f);
  j["cvt"] = {{"method", r.cvt.method == Cvt_method::LLOYD ? "lloyd" : "lbfgs"},
              {"iterations", r.cvt.iterations},
              {"energy_evaluations", r.cvt.energy_evaluations},
              {"lloyd_fallbacks", r.cvt.lloyd_fallbacks},
              {"relative_gradient_norm", report_number(r.cvt.gradient_norm)},
              {"energy", internal::report_numbers(r.cvt.energy)}};
  const Surface_optimization_report& so = r.surface_optimization;
  if(so.ran)
    j["surface_optimization"] = {{"ran", so.ran},
                               {"second_phase", so.second_phase},
                               {"rounds", so.rounds},
                               {"flips", so.flips},
                               {"relocations", so.relocations},
                               {"fixed_vertices", so.fixed_vertices},
                               {"sliding_vertices", so.sliding_vertices},
                               {"crowded_vertices", so.crowded_vertices},
                               {"inverted_before", so.inverted_before},
                               {"inverted_after", so.inverted_after},
                               {"G_min_before", report_number(so.G_min_before)},
                               {"G_avg_before", report_number(so.G_avg_before)},
                               {"theta_min_before", report_number(so.theta_min_before)},
                               {"percent_below_30_before", report_number(so.percent_below_30_before)},
                               {"G_min_after", report_number(so.G_min_after)},
                               {"G_avg_after", report_number(so.G_avg_after)},
                               {"theta_min_after", report_number(so.theta_min_after)},
                               {"percent_below_30_after", report_number(so.percent_below_30_after)}};
  nlohmann::json& seconds = j["seconds"];
  for(int s = 0; s < number_of_stages; ++s) seconds[stage_name(Stage(s))] = report_number(r.seconds[s]);
  seconds["discarded"] = report_number(r.discarded_seconds);
  seconds["total"] = report_number(r.total_seconds());
  return j;
}

/*!
 * \ingroup PkgAnisoConformalIO
 * writes `report_json(r)` to `os`, indented by 2, with the fields of `extra` added at the top level
 * (e.g. the command line's parameters or the time spent building a background). Strings that are not
 * valid UTF-8 (a file name, say) are written with U+FFFD in place of their invalid bytes.
 * \throws Invalid_input if `extra` is neither null nor a JSON object, or has a key the report already has
 */
inline void write_report_json(std::ostream& os, const Remeshing_result& r,
                              const nlohmann::json& extra = nlohmann::json::object())
{
  if(!extra.is_null() && !extra.is_object())
    throw Invalid_input("write_report_json(): the extra fields must be a JSON object, not " + std::string(extra.type_name()));
  nlohmann::json j = report_json(r);
  if(extra.is_object())
    for(const auto& e : extra.items()) {
      if(j.contains(e.key()))
        throw Invalid_input("write_report_json(): the extra field '" + e.key() + "' is a field of the report");
      j[e.key()] = e.value();
    }
  os << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_WRITE_REPORT_H
