// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A curved open surface with the curvature metric of the paper's eq. 4: reads a disk-topology mesh
// (default: the bundled face mask data/meshes/nefertiti.off), builds the metric with a stretch bound and
// smoothing, remeshes it keeping its boundary, and writes the result.
// Usage: curvature_metric_surface [mesh.off [number_of_vertices [stretch_max [output.off]]]]

#include <Aniso_conformal/Curvature_metric.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/remesh.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

namespace AC = Aniso_conformal;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/nefertiti.off";
  const std::size_t n = argc > 2 ? std::size_t(std::atol(argv[2])) : 250;
  const std::string output = argc > 4 ? argv[4] : "nefertiti_remeshed.off";
  try {
    const AC::Input_surface surface = AC::IO::read_triangle_mesh(input);
    std::cout << input << ": " << surface.number_of_vertices() << " vertices, " << surface.topology_description() << "\n";

    AC::Curvature_metric_options options;
    options.stretch_max = argc > 3 ? std::atof(argv[3]) : 5.0;  // edges at most 5x longer along than across
    options.smoothing_iterations = 2;        // a coarse scan: little smoothing keeps its anisotropy
    options.scale_smoothing_iterations = 2;  // (directions and scales)
    const AC::Curvature_metric metric(surface, options);
    const auto& ratios = metric.stretch_ratios();
    std::cout << "curvature metric: stretch ratios in [" << *std::min_element(ratios.begin(), ratios.end()) << ", "
              << *std::max_element(ratios.begin(), ratios.end()) << "]\n";

    // at most as many output vertices as the background (the input after the edge-length adjustment) has
    AC::Remeshing_result r;
    const AC::Remeshed_surface out = AC::remesh(surface, metric, r, AC::parameters::number_of_vertices(n));
    const AC::Quality_report& q = r.quality;
    std::cout << "output: " << q.number_of_vertices << " vertices (" << r.boundary_sites << " on the boundary, "
              << r.corners << " corners), G_avg " << q.G_avg << ", theta_min " << q.theta_min << " degrees, "
              << q.percent_below_30 << " % below 30 degrees, " << r.total_seconds() << " s\n";
    AC::IO::write_polygon_soup(output, out.points, out.faces);
    std::cout << "wrote " << output << "\n";
  } catch(const AC::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
