// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Surfaces with long limbs through the cone domain (issue 16): the sphere refuses CGAL's cow (a conformal
// map to the sphere shrinks its legs and tail exponentially); a flat metric with cone singularities bounds
// the area distortion, and the CVT runs on the cone surface. Prints the sphere's refusal, the cones (their
// number, angles and positions on the input) and the quality, and writes the mesh.
// Usage: limbs_through_cones [mesh.off [number_of_vertices]]
//   without a mesh: the bundled cow (data/meshes/cow.off), 2000 vertices.

#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/remesh.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

namespace AC = Aniso_conformal;

int main(int argc, char** argv)
{
  try {
    const std::string input = argc > 1 ? argv[1] : std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/cow.off";
    const std::size_t n = argc > 2 ? std::size_t(std::atol(argv[2])) : 2000;
    const AC::Input_surface surface = AC::IO::read_triangle_mesh(input);
    const AC::Uniform_metric metric;

    // 1. the sphere, the domain of a closed genus-0 surface: refused for long limbs
    try {
      AC::Remeshing_result r;
      AC::remesh(surface, metric, r,
                 AC::parameters::number_of_vertices(n).parametric_domain(AC::Parametric_domain::SPHERE).feature_angle(180.0));
      std::cout << "the sphere remeshes this surface: G_avg " << r.quality.G_avg << "\n";
    } catch(const AC::Convergence_failure& e) {
      std::cout << "the sphere refuses: " << e.what() << "\n";
    }

    // 2. the cone domain (what the automatic choice falls back to; here asked for), creases not followed
    AC::Remeshing_result r;
    const AC::Remeshed_surface out =
      AC::remesh(surface, metric, r, AC::parameters::number_of_vertices(n).parametric_domain(AC::Parametric_domain::CONE).feature_angle(180.0));
    const AC::Domain_diagnostics& d = r.domain_diagnostics;
    std::cout << "cones: " << d.summary << "\n";
    const std::size_t cones = std::size_t(d.value("cones"));
    for(std::size_t c = 0; c < std::min<std::size_t>(cones, 5); ++c)  // one row per cone: x, y, z, angle (degrees)
      std::cout << "  cone " << c << " at (" << d.value("cone_table", 4 * c) << ", " << d.value("cone_table", 4 * c + 1) << ", "
                << d.value("cone_table", 4 * c + 2) << "), angle " << d.value("cone_table", 4 * c + 3) << " degrees\n";
    if(cones > 5) std::cout << "  ... (" << cones - 5 << " more)\n";

    // 3. the output: exactly n vertices, genus 0; the surface optimisation ran (the cone domain's default)
    std::cout << "output: " << out.points.size() << " vertices, " << out.faces.size() << " triangles; G_avg " << r.quality.G_avg
              << ", theta_min " << r.quality.theta_min << " degrees, " << r.quality.percent_below_30
              << " % below 30 degrees; Hausdorff " << r.hausdorff_distance_relative << " of the diagonal; surface optimisation "
              << (r.surface_optimization.ran ? "ran" : "did not run") << "; " << r.total_seconds() << " s\n";
    AC::IO::write_polygon_soup("limbs_through_cones.off", out.points, out.faces);
    std::cout << "wrote limbs_through_cones.off\n";
  } catch(const AC::Error& e) {
    std::cerr << "limbs_through_cones: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
