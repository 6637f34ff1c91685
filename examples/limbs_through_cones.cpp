// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Surfaces with long limbs through the cone domain (issue 16): the sphere refuses CGAL's cow (a conformal
// map to the sphere shrinks its legs and tail exponentially); a flat metric with cone singularities bounds
// the area distortion, and the CVT runs on the cone surface. Prints the sphere's refusal, the cones (their
// number, angles and positions on the input) and the quality, and writes the mesh and two pictures:
// limbs_through_cones_mesh.svg (the output, triangles coloured by their quality G) and
// limbs_through_cones_cvt.svg (the weighted CVT on the cone surface, chart by chart, with the cones).
// Usage: limbs_through_cones [mesh.off [number_of_vertices]]
//   without a mesh: the bundled cow (data/meshes/cow.off), 2000 vertices.

#include <Aniso_conformal/Cone_domain.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/IO/write_cone_cvt_svg.h>
#include <Aniso_conformal/IO/write_svg.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/adjust_edge_lengths.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/refine_background.h>
#include <Aniso_conformal/remesh.h>
#include <Aniso_conformal/weighted_centroidal_Voronoi_tessellation.h>

#include <algorithm>
#include <cmath>
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

    // 2. the cone domain (what the automatic choice falls back to; here asked for), creases not followed,
    // and the metric as given (without the cone domain's default curvature sizing, which scales it at
    // the tips: the CVT of step 4, run again from the stages, is then the run's)
    AC::Remeshing_result r;
    const AC::Remeshed_surface out =
      AC::remesh(surface, metric, r,
                 AC::parameters::number_of_vertices(n).parametric_domain(AC::Parametric_domain::CONE).feature_angle(180.0).curvature_sizing(
                   AC::Curvature_sizing::OFF));
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
    AC::IO::write_surface_svg("limbs_through_cones_mesh.svg", out.points, out.faces, r.quality.triangle_G, 0.5, 1.0,
                              "through cones: " + std::to_string(out.points.size()) + " vertices, colour = quality G",
                              Eigen::Vector3d(0.25, 0.2, 1.0));

    // 4. the CVT on the cone surface. remesh() keeps its sites to itself: its stages run again here with the
    // same parameters (no crease; the background refined for n sites, the lengths adjusted, the cones placed,
    // the widest cones of negative curvature, at most n / 8, fixed sites at their vertices)
    const auto np = AC::parameters::number_of_vertices(n).feature_angle(180.0);
    AC::Intrinsic_triangulation itri(surface, AC::compute_metric_square_roots(surface, metric));
    AC::refine_background(itri, surface, metric, n);
    AC::adjust_edge_lengths(itri, surface, np);
    const AC::Cone_embedding emb = AC::Cone_domain::embed(itri, np);
    AC::Cone_domain_traits traits(itri, emb);
    std::vector<std::pair<int, int>> fixed;  // (face, corner) of each fixed site
    for(std::size_t v : AC::Cone_domain::vertices_kept(emb)) {
      if(fixed.size() >= n / 8) break;
      const int h = itri.outgoing_halfedges(int(v)).front();
      fixed.emplace_back(h / 3, h % 3);
    }
    std::vector<AC::Cone_domain_traits::Point> sites = traits.initial_sites_after(fixed, n, 0u);
    AC::weighted_centroidal_Voronoi_tessellation(traits, sites, fixed.size(), np);
    const std::vector<AC::Cone_domain_traits::Chart_cells> charts = traits.voronoi_cells(sites);
    std::vector<AC::Cone_domain_traits::Cell> cells;
    traits.integrate(sites, cells);
    std::vector<double> mass(sites.size());  // log2 of the cell's mass over the mean
    for(std::size_t i = 0; i < sites.size(); ++i)
      mass[i] = std::log2(std::max(1e-300, cells[i].mass / (traits.total_mass() / double(sites.size()))));
    std::cout << "CVT picture: " << emb.cones.size() << " cones (the run: " << cones << "), " << fixed.size()
              << " fixed sites (the run: " << out.released_vertices.size() << "), " << charts.size() << " charts\n";
    AC::IO::write_cone_cvt_svg("limbs_through_cones_cvt.svg", charts, mass,
                               "weighted CVT on the cone surface, " + std::to_string(n) + " sites; colour = log2(cell mass / mean)");
    std::cout << "wrote limbs_through_cones.off, limbs_through_cones_mesh.svg, limbs_through_cones_cvt.svg\n";
  } catch(const AC::Error& e) {
    std::cerr << "limbs_through_cones: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
