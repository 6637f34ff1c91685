// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// aniso_remesh: the command-line front end of Aniso_conformal (see --help and the manual).

#include "batch_memory.h"
#include "command_line.h"

#include <Aniso_conformal/Analytic_metric_2.h>
#include <Aniso_conformal/Curvature_metric.h>
#include <Aniso_conformal/Image_metric.h>
#include <Aniso_conformal/IO/read_feature_file.h>
#include <Aniso_conformal/IO/read_image.h>
#include <Aniso_conformal/IO/read_metric_file.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/IO/write_report.h>
#include <Aniso_conformal/IO/write_svg.h>
#include <Aniso_conformal/Paper_metrics.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/make_image_background.h>
#include <Aniso_conformal/make_square_background.h>
#include <Aniso_conformal/internal/printable.h>
#include <Aniso_conformal/remesh.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <iostream>
#include <new>
#include <string>
#include <unistd.h>
#include <vector>

namespace AC = Aniso_conformal;

namespace {

// A progress bar on stderr for the iterative stages, only when stderr is a terminal.
struct Progress_visitor : AC::Default_visitor {
  bool enabled = false;
  void on_stage_started(AC::Stage s)
  {
    if(enabled) std::fprintf(stderr, "\r%-14s ...%40s", AC::stage_name(s), "");
  }
  void on_stage_finished(AC::Stage s, double seconds)
  {
    if(enabled) std::fprintf(stderr, "\r%-14s %8.3f s%40s\n", AC::stage_name(s), seconds, "");
  }
  bool on_iteration(AC::Stage s, std::size_t it, std::size_t bound, double value)
  {
    if(!enabled) return true;
    const int width = 30, filled = bound ? int(width * std::min<std::size_t>(it, bound) / bound) : width;
    std::fprintf(stderr, "\r%-14s [%s%s] %zu/%zu  %.4g   ", AC::stage_name(s), std::string(std::size_t(filled), '#').c_str(),
                 std::string(std::size_t(width - filled), ' ').c_str(), it, bound, value);
    return true;
  }
};

// Writes through a temporary file in the same folder and renames it: no partial file on failure.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& writer)
{
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  const std::string ext = (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ? path.substr(dot) : "";
  const std::string tmp = path + ".partial-" + std::to_string(::getpid()) + ext;
  try {
    writer(tmp);
  } catch(...) {
    std::remove(tmp.c_str());
    throw;
  }
  if(std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw AC::Invalid_input("cannot write " + path);
  }
}

// `repairs`: what was repaired in --input on reading (null for the square and images); `marked`: the
// features of --features, read with the mesh (before the metric is built) and mapped through the repairs
template <typename Metric>
int run(const aniso_remesh::Options& o, const AC::Input_surface& surface, const Metric& metric, double background_seconds,
        const std::string& input_name, const AC::Repair_report* repairs = nullptr, const AC::IO::Marked_features& marked = {})
{
  Progress_visitor progress;
  progress.enabled = ::isatty(2) && !o.quiet;
  AC::Remeshing_result result;
  const auto np = AC::parameters::number_of_vertices(std::size_t(o.vertices))
                    .number_of_iterations(unsigned(o.iterations))
                    .random_seed(o.seed)
                    .cvt_method(o.cvt == "lloyd" ? AC::Cvt_method::LLOYD : AC::Cvt_method::LBFGS)
                    .corner_angle(o.corner_angle)
                    .feature_angle(aniso_remesh::feature_angle(o))
                    .drop_ragged_creases(!o.keep_ragged_creases)
                    .feature_sizing(!o.no_feature_sizing)
                    .curvature_sizing(o.curvature_sizing == "off"      ? AC::Curvature_sizing::OFF
                                      : o.curvature_sizing == "always" ? AC::Curvature_sizing::ALWAYS
                                                                       : AC::Curvature_sizing::CONES)
                    .feature_edges(marked.edges)
                    .feature_vertices(marked.vertices)
                    .planar_boundary(o.planar_boundary == "lengths" ? AC::Planar_boundary::KEEP_LENGTHS
                                     : o.planar_boundary == "shape" ? AC::Planar_boundary::KEEP_SHAPE
                                                                     : AC::Planar_boundary::AUTOMATIC)
                    .surface_optimization(o.surface_optimization == "off"      ? AC::Surface_optimization::OFF
                                          : o.surface_optimization == "always" ? AC::Surface_optimization::ALWAYS
                                                                               : AC::Surface_optimization::REPAIR)
                    .number_of_threads(o.threads)
                    .parametric_domain(o.parametric_domain)
                    .visitor(std::ref(progress));
  AC::Remeshed_surface out = AC::remesh(surface, metric, result, np);
  if(repairs) {
    result.repairs = *repairs;
    AC::IO::restore_input_orientation(out.faces, *repairs);  // a clockwise planar input gets a clockwise output
  }

  if(!o.output.empty())
    write_atomically(o.output, [&](const std::string& p) { AC::IO::write_polygon_soup(p, out.points, out.faces); });
  if(!o.report.empty())
    write_atomically(o.report, [&](const std::string& p) {
      std::ofstream f(p);
      if(!f) throw AC::Invalid_input("cannot write " + o.report);
      AC::IO::write_report_json(f, result,
                                {{"input_name", input_name},
                                 {"requested_vertices", o.vertices},
                                 {"seed", o.seed},
                                 {"background_seconds", AC::IO::internal::report_number(background_seconds)}});
      if(!f) throw AC::Invalid_input("cannot write " + o.report);
    });
  if(!o.svg.empty())
    write_atomically(o.svg, [&](const std::string& p) {
      const std::string title =
        AC::internal::printable(input_name) + ": " + std::to_string(out.points.size()) + " vertices, quality G in the metric";
      if(surface.is_planar())
        AC::IO::write_svg(p, out.points, out.faces, result.quality.triangle_G, 0.5, 1.0, title);
      else  // a curved surface: shaded, seen from an oblique direction
        AC::IO::write_surface_svg(p, out.points, out.faces, result.quality.triangle_G, 0.5, 1.0, title,
                                  Eigen::Vector3d(0.3, -0.5, 1.0));
    });
  if(!o.histogram.empty())
    write_atomically(o.histogram, [&](const std::string& p) {
      AC::IO::write_histogram_svg(p, result.quality.angle_histogram, result.quality.bin_width,
                                  AC::internal::printable(input_name) + ": angles in the metric");
    });

  if(!o.quiet) {
    const AC::Quality_report& q = result.quality;
    std::printf("input        %s: %zu vertices, %zu faces (background %zu vertices", AC::internal::printable(input_name).c_str(),
                result.input_vertices, result.input_faces, result.background_vertices);
    if(result.refinement.splits > 0)
      std::printf(", refined from %zu by %zu edge splits", result.refinement.vertices_before, result.refinement.splits);
    std::printf(")\n");
    if(result.repairs.any()) std::printf("repairs      %s\n", result.repairs.summary().c_str());
    if(!result.domain_choice.empty()) std::printf("domain       %s\n", result.domain_choice.c_str());
    if(!result.reseeded.empty()) std::printf("reseeded     the CVT ran again with the next seed (holes whose loop passes twice through a point closed lobe by lobe): %s\n", result.reseeded.c_str());
    if(result.stretch_limit.applied) {
      const AC::Stretch_limit_report& l = result.stretch_limit;
      std::printf("stretch cap  the metric's stretch (up to %.3g) was lowered at %zu input vertices to what straight edges can "
                  "follow where its long axis turns (bounds from %.3g, median %.3g): the run in the metric as given failed (%s); "
                  "the quality below is in the bounded metric, in the metric as given G_min %.4f  G_avg %.4f  theta_min %.2f  "
                  "%%<30 %.3f\n",
                  l.stretch_asked_max, l.vertices_limited, l.bound_min, l.bound_median, l.reason.c_str(), l.given_G_min,
                  l.given_G_avg, l.given_theta_min, l.given_percent_below_30);
    }
    std::printf("output       %zu vertices, %zu triangles, %zu on the boundary, %zu boundary corners, %zu inverted (domain %s)\n",
                q.number_of_vertices, q.number_of_triangles, result.boundary_sites, result.corners, result.inverted_triangles,
                AC::domain_name(result.domain));
    if(result.loop_edges_recovered > 0)
      std::printf("boundary     %zu edges between consecutive sites of a boundary loop recovered by flips\n", result.loop_edges_recovered);
    if(result.collared_loops > 0)
      std::printf("boundary     %zu loops along both faces of a part thinner than an output edge closed by a collar first\n",
                  result.collared_loops);
    if(result.patch_sites_moved > 0)
      std::printf("boundary     %zu free sites cut off into a hole's patch moved onto the longest edge\n", result.patch_sites_moved);
    std::printf("distance     Hausdorff distance to the input %.3g (%.3g of the bounding-box diagonal)\n",
                result.hausdorff_distance, result.hausdorff_distance_relative);
    const AC::Feature_report& ft = result.features;
    if(ft.crease_edges > 0 || ft.corners > 0)
      std::printf("features     input %zu curves (crease length %.4g), %zu corners; output keeps %zu of the corners and covers "
                  "%.1f %% of the crease length\n",
                  ft.curves, ft.crease_length, ft.corners, ft.corners_kept, 100.0 * ft.covered_share);
    const AC::Feature_sizing_report& fs = result.feature_sizing;
    if(!fs.applied && fs.narrow_points > 0)
      std::printf("features     sizing: crease curves run as close as %.3g output edges at %zu points; not refined there: "
                  "that would take more than half of the output's vertices, or the gap is below 1/7.8 of an edge (more "
                  "vertices would let the output resolve it)\n",
                  fs.gap_min, fs.narrow_points);
    if(fs.applied && fs.narrow_points > fs.gaps_left) {
      std::printf("features     sizing: crease curves run as close as %.3g output edges; the metric scaled up there (up to %.3g "
                  "times, at %zu input vertices; metric area x %.3g, the rest coarser; %zu of %zu narrow points left as they "
                  "are); --no-feature-sizing turns it off\n",
                  fs.gap_min, fs.scale_max, fs.vertices_scaled, fs.area_factor, fs.gaps_left, fs.narrow_points);
    }
    if(fs.curved_points > 0)
      std::printf("metric       curvature sizing: the surface bends with a radius down to %.3g output edges at %zu input vertices; %s\n",
                  fs.radius_min, fs.curved_points,
                  fs.curvature_applied ? "the metric scaled up there so that edges are about 1.25 times the radius, the rest coarser; "
                                         "--curvature-sizing off turns it off"
                                       : "not refined there: that would take more than 5/6 of the output's vertices, or the "
                                         "run with it failed");
    if(ft.ragged_components_dropped > 0)
      std::printf("features     %zu ragged crease components left out (length %.4g): their triangles bend at other edges too "
                  "(noise or a staircase, not a sharp crease)%s\n",
                  ft.ragged_components_dropped, ft.ragged_length_dropped,
                  ft.rough_surface ? "; the surface is rough (ragged creases are a quarter of its crease length or more): every "
                                     "detected crease left out; --keep-ragged-creases keeps them"
                                   : "; --keep-ragged-creases keeps them");
    if(ft.short_components_dropped > 0)
      std::printf("features     %zu crease components shorter than an output edge left out (length %.4g): no output edge can follow them\n",
                  ft.short_components_dropped, ft.short_length_dropped);
    if(result.crease_run == AC::Crease_run::REFINED)
      std::printf("features     crease run %s: the crease sites on the crease pieces refined\n", AC::crease_run_name(result.crease_run));
    else if(result.crease_run == AC::Crease_run::INPUT_VERTICES)
      std::printf("features     crease run %s: the run on refined crease pieces failed (%s); the crease sites on the input's own "
                  "crease vertices\n",
                  AC::crease_run_name(result.crease_run), result.crease_refinement_failed.c_str());
    if(!result.creases_not_followed.empty())
      std::printf("features     crease run %s: creases not followed: the run with crease sites failed (%s); this output is the run "
                  "without them\n",
                  AC::crease_run_name(result.crease_run), result.creases_not_followed.c_str());
    if(!result.corners_not_kept.empty())
      std::printf("features     crease run %s: corners not kept either: the run with the corners as fixed sites failed (%s); this "
                  "output is the run without any feature site, as with --no-features\n",
                  AC::crease_run_name(result.crease_run), result.corners_not_kept.c_str());
    std::printf("quality      G_min %.4f  G_avg %.4f  theta_min %.2f  theta_avg %.2f  %%<30 %.3f\n", q.G_min, q.G_avg,
                q.theta_min, q.theta_avg, q.percent_below_30);
    std::printf("metric edge  mean length %.4g, normalised length stddev %.3f, min %.3f, max %.3f\n",
                q.edge_length_mean, q.edge_length_stddev, q.edge_length_min, q.edge_length_max);
    std::printf("stretch      metric stretch at the vertices min %.2f, median %.2f, 95%% %.2f, max %.2f\n",
                q.stretch_min, q.stretch_median, q.stretch_p95, q.stretch_max);
    std::printf("stages       flips %zu, splits %zu, repaired %zu, Newton %zu (residual %.2g, %zu intrinsic flips%s), "
                "CVT %zu iterations (%s)\n",
                result.adjustment.flips, result.adjustment.splits, result.adjustment.repaired_triangles,
                result.conformal_iterations, result.conformal_residual, result.conformal_flips,
                result.embedding_reused ? "; the embedding of an earlier run on this background" : "", result.cvt.iterations,
                o.cvt.c_str());
    const AC::Surface_optimization_report& so = result.surface_optimization;
    if(so.ran)
      std::printf("optimised    on the surface%s: %zu rounds, %zu flips, %zu vertex moves%s%s; inverted %zu -> %zu, G_min %.4f -> "
                  "%.4f, G_avg %.4f -> %.4f, theta_min %.2f -> %.2f, %%<30 %.3f -> %.3f\n",
                  so.second_phase ? " (both phases)" : "", so.rounds, so.flips, so.relocations,
                  so.sliding_vertices ? (" (" + std::to_string(so.sliding_vertices) + " boundary vertices free to slide)").c_str() : "",
                  so.crowded_vertices ? (", " + std::to_string(so.crowded_vertices) + " crowded vertices moved to split edges").c_str() : "",
                  so.inverted_before, so.inverted_after, so.G_min_before, so.G_min_after,
                  so.G_avg_before, so.G_avg_after, so.theta_min_before, so.theta_min_after, so.percent_below_30_before,
                  so.percent_below_30_after);
    if(!result.domain_diagnostics.summary.empty())
      std::printf("%-12s %s\n", AC::domain_name(result.domain), result.domain_diagnostics.summary.c_str());
    std::printf("time         background %.3f s, total %.3f s (", background_seconds, background_seconds + result.total_seconds());
    for(int s = 0; s < AC::number_of_stages; ++s)
      std::printf("%s%s %.3f", s ? ", " : "", AC::stage_name(AC::Stage(s)), result.seconds[s]);
    if(result.discarded_seconds > 0) std::printf("; runs thrown away %.3f", result.discarded_seconds);
    std::printf(")\n");
  }
  return 0;
}

int main_impl(int argc, char** argv)
{
  std::vector<std::string> args(argv + 1, argv + argc);
  const aniso_remesh::Options o = aniso_remesh::parse_command_line(args);
  if(o.help) { std::fputs(aniso_remesh::usage().c_str(), stdout); return 0; }
  if(o.version) { std::puts(aniso_remesh::version_line()); return 0; }

  if(!o.features_file.empty() && o.input.empty())
    throw AC::Invalid_input("--features marks vertices of an --input mesh; it does not apply to --image or --domain");
  const auto t0 = std::chrono::steady_clock::now();
  auto since = [&]() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  if(!o.image.empty()) {
    const AC::IO::Image img = AC::IO::read_image(o.image);
    const double s = o.anisotropy > 0 ? o.anisotropy : (img.channels == 1 ? 0.2 : 0.1);  // grey: see the manual, Fig. 9
    const AC::Image_metric metric(img, s);
    const AC::Input_surface bg = AC::make_image_background(img);
    return run(o, bg, metric, since(), o.image);
  }
  if(!o.domain.empty()) {
    auto square = [&](const auto& metric) {
      const AC::Input_surface bg = AC::make_square_background(metric, std::size_t(o.vertices), std::size_t(o.background_vertices));
      return run(o, bg, metric, since(), "square");
    };
    if(o.metric == "fig6") return square(AC::make_analytic_metric_2(AC::Fig6_metric()));
    if(o.metric == "fig7") return square(AC::make_analytic_metric_2(AC::Circular_metric()));
    return square(AC::Uniform_metric());
  }
  AC::Repair_report repairs;
  const AC::Input_surface surface =
    AC::IO::read_triangle_mesh(o.input, repairs, o.no_repair ? AC::Repair_options::none() : AC::Repair_options());
  // the user's features, indices of the mesh file's vertices mapped through the repairs: read before any
  // metric is built, so that a wrong file is reported at once
  const AC::IO::Marked_features marked =
    o.features_file.empty() ? AC::IO::Marked_features() : AC::IO::read_feature_file(o.features_file, repairs);
  // the metric file has a row per vertex of --input: those of the vertices kept by the repairs are used
  if(!o.metric_file.empty())
    return run(o, surface, AC::IO::read_metric_file(o.metric_file, repairs), 0.0, o.input, &repairs, marked);
  if(o.metric == "curvature") {
    const AC::Curvature_metric_options co = aniso_remesh::curvature_metric_options(o);
    return run(o, surface, AC::Curvature_metric(surface, co), 0.0, o.input, &repairs, marked);
  }
  if(o.metric == "fig6" || o.metric == "fig7") {
    if(!surface.is_planar())
      throw AC::Invalid_input("--metric " + o.metric + " is a planar metric; " + o.input + " is not in the plane z = 0");
    if(o.metric == "fig6") return run(o, surface, AC::make_analytic_metric_2(AC::Fig6_metric()), 0.0, o.input, &repairs, marked);
    return run(o, surface, AC::make_analytic_metric_2(AC::Circular_metric()), 0.0, o.input, &repairs, marked);
  }
  return run(o, surface, AC::Uniform_metric(), 0.0, o.input, &repairs, marked);
}

// Every message goes through printable(): a path or a token quoted from a file may hold any byte.
void print_error(const char* kind, const std::string& message)
{
  std::fprintf(stderr, "aniso_remesh: %s: %s\n", kind, AC::internal::printable(message).c_str());
}

} // namespace

// The exit status (documented in --help, the README and the manual, "Errors"): 0 success; 2 the input is
// wrong; 3 a valid input this version cannot remesh; 1 anything else (a bug, cancelled, out of memory).
int main(int argc, char** argv)
{
  aniso_remesh::keep_freed_memory();
  try {
    return main_impl(argc, argv);
  } catch(const AC::Invalid_input& e) {
    print_error("error", e.what());
    return 2;
  } catch(const AC::Remeshing_failure& e) {  // and its Convergence_failure
    print_error("cannot remesh", e.what());
    return 3;
  } catch(const AC::Internal_error& e) {
    print_error("internal error (please report it)", e.what());
    return 1;
  } catch(const AC::Cancelled& e) {
    print_error("cancelled", e.what());
    return 1;
  } catch(const std::bad_alloc&) {
    print_error("error", "out of memory");
    return 1;
  } catch(const std::exception& e) {
    print_error("internal error (please report it)", e.what());
    return 1;
  } catch(...) {
    print_error("internal error (please report it)", "an exception of unknown type");
    return 1;
  }
}
