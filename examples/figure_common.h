// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Shared by the examples that reproduce the paper's figures: remeshes a background with a metric,
// prints the quality report, and writes <folder>/<name>_mesh.off, <name>_mesh.svg (triangles coloured by
// their quality G in the metric) and <name>_histogram.svg (the angle histogram).

#ifndef ANISO_CONFORMAL_EXAMPLES_FIGURE_COMMON_H
#define ANISO_CONFORMAL_EXAMPLES_FIGURE_COMMON_H

#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/IO/write_svg.h>
#include <Aniso_conformal/remesh_in_domain.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace figure {

/// the arguments every figure example takes: [output_folder [number_of_vertices]]
struct Arguments {
  std::string folder = ".";
  std::size_t vertices = 0;
  Arguments(int argc, char** argv, std::size_t default_vertices) : vertices(default_vertices)
  {
    if(argc > 1) folder = argv[1];
    if(argc > 2) vertices = std::size_t(std::atol(argv[2]));
  }
};

/// the named parameters every figure uses: `n` output vertices, 100 CVT iterations, seed 0, and when the
/// surface optimisation runs (`REPAIR` by default; the images take `ALWAYS`)
inline auto figure_parameters(std::size_t n,
                              Aniso_conformal::Surface_optimization so = Aniso_conformal::Surface_optimization::REPAIR)
{
  return Aniso_conformal::parameters::number_of_vertices(n).number_of_iterations(100u).random_seed(0u).surface_optimization(so);
}

/// prints the sizes, the quality in the metric and the time of each stage
inline void print_report(const std::string& caption, const Aniso_conformal::Remeshing_result& r)
{
  namespace AC = Aniso_conformal;
  const AC::Quality_report& q = r.quality;
  std::printf("%s: %zu vertices, %zu triangles (background %zu vertices, %zu flips, %zu splits)\n", caption.c_str(),
              q.number_of_vertices, q.number_of_triangles, r.background_vertices, r.adjustment.flips, r.adjustment.splits);
  std::printf("quality in the metric: G_min %.4f  G_avg %.4f  theta_min %.2f  theta_avg %.2f  %%<30 %.3f  inverted %zu\n",
              q.G_min, q.G_avg, q.theta_min, q.theta_avg, q.percent_below_30, r.inverted_triangles);
  std::printf("seconds:");
  for(int s = 0; s < AC::number_of_stages; ++s) std::printf(" %s %.3f", AC::stage_name(AC::Stage(s)), r.seconds[s]);
  std::printf(" (total %.3f)\n", r.total_seconds());
}

/// the five quality figures of the paper's tables
struct Paper_quality {
  double G_min, G_avg, theta_min, theta_avg, percent_below_30;
};

/// prints ours next to the paper's
inline void print_paper_comparison(const Aniso_conformal::Quality_report& q, const Paper_quality& paper)
{
  std::printf("%-7s %8s %8s %10s %10s %8s\n", "", "G_min", "G_avg", "theta_min", "theta_avg", "%<30");
  std::printf("%-7s %8.4f %8.4f %10.2f %10.2f %8.4f\n", "ours", q.G_min, q.G_avg, q.theta_min, q.theta_avg, q.percent_below_30);
  std::printf("%-7s %8.4f %8.4f %10.2f %10.2f %8.4f\n", "paper", paper.G_min, paper.G_avg, paper.theta_min, paper.theta_avg,
              paper.percent_below_30);
}

/// remeshes in `Domain`, reports and writes the pictures; `bar` prints the quality bar check (Fig. 6
/// and 7); `so`: when the surface optimisation runs
template <typename Domain, typename Metric>
int reproduce(const std::string& name, const std::string& caption, const Aniso_conformal::Input_surface& background,
              const Metric& metric, const Arguments& a, bool bar,
              Aniso_conformal::Surface_optimization so = Aniso_conformal::Surface_optimization::REPAIR)
{
  namespace AC = Aniso_conformal;
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh_in_domain<Domain>(background, metric, r, figure_parameters(a.vertices, so));
  const AC::Quality_report& q = r.quality;
  print_report(caption, r);
  if(bar) {
    const bool ok = q.G_avg >= 0.85 && q.theta_min >= 10 && q.percent_below_30 <= 5 && r.inverted_triangles == 0;
    std::printf("quality bar (G_avg >= 0.85, theta_min >= 10, %%<30 <= 5, no inverted triangle): %s\n", ok ? "met" : "NOT met");
  }
  const std::string base = a.folder + "/" + name;
  AC::IO::write_polygon_soup(base + "_mesh.off", out.points, out.faces);
  AC::IO::write_svg(base + "_mesh.svg", out.points, out.faces, q.triangle_G, 0.5, 1.0,
                    caption + ": " + std::to_string(q.number_of_vertices) + " vertices, colour = quality G in the metric");
  AC::IO::write_histogram_svg(base + "_histogram.svg", q.angle_histogram, q.bin_width, caption + ": angles in the metric");
  std::printf("wrote %s_mesh.off, %s_mesh.svg, %s_histogram.svg\n", base.c_str(), base.c_str(), base.c_str());
  return EXIT_SUCCESS;
}

} // namespace figure

#endif // ANISO_CONFORMAL_EXAMPLES_FIGURE_COMMON_H
