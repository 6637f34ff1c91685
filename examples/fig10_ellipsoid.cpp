// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The paper's Fig. 10: an ellipsoid (semi-axes 1, 0.6, 0.4; the level-5 icosphere, 10242 vertices, the
// paper's count; a closed genus-0 surface, so remesh() goes through the sphere) with the curvature
// metric, stretch ratio at most 10, remeshed into 1000 vertices (100 CVT iterations, seed 0). Prints the
// quality in the metric and checks the bar; writes <folder>/fig10_mesh.off, fig10_mesh.svg (the
// surface coloured by the quality G of each triangle in the metric), fig10_histogram.svg (the angles in
// the metric) and fig10_cvt.svg (the weighted CVT on the unit sphere, the paper's Fig. 10 (a)).
// Usage: fig10_ellipsoid [output_folder [number_of_vertices]]

#include "figure_common.h"

#include <Aniso_conformal/Curvature_metric.h>
#include <Aniso_conformal/Spherical_domain.h>
#include <Aniso_conformal/Spherical_domain_traits.h>
#include <Aniso_conformal/make_ellipsoid.h>
#include <Aniso_conformal/spherical_embedding.h>

#include <algorithm>
#include <cmath>
#include <iostream>

int main(int argc, char** argv)
{
  namespace AC = Aniso_conformal;
  const figure::Arguments a(argc, argv, 1000);
  const std::string caption = "Fig. 10, ellipsoid";
  try {
    const AC::Input_surface ellipsoid = AC::make_ellipsoid(5);
    AC::Curvature_metric_options options;
    options.stretch_max = 10;
    const AC::Curvature_metric metric(ellipsoid, options);
    const auto& ratios = metric.stretch_ratios();
    std::printf("input: %zu vertices, %s; stretch ratios in [%.2f, %.2f]\n", ellipsoid.number_of_vertices(),
                ellipsoid.topology_description().c_str(), *std::min_element(ratios.begin(), ratios.end()),
                *std::max_element(ratios.begin(), ratios.end()));

    const auto np = figure::figure_parameters(a.vertices);
    AC::Remeshing_result r;
    const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(ellipsoid, metric, r, np);
    const AC::Quality_report& q = r.quality;
    figure::print_report(caption, r);
    std::printf("domain %s; conformal factor in [%.3g, %.3g]; %s\n", AC::domain_name(r.domain), r.conformal_factor_min,
                r.conformal_factor_max, r.domain_diagnostics.summary.c_str());
    std::printf("Hausdorff distance to the input: %.3g of the bounding-box diagonal\n", r.hausdorff_distance_relative);
    const bool ok = q.G_avg >= 0.90 && q.theta_min >= 20 && q.percent_below_30 <= 0.5;
    std::printf("quality bar (G_avg >= 0.90, theta_min >= 20, %%<30 <= 0.5): %s\n", ok ? "met" : "NOT met");

    // The CVT picture needs the sites and the domain, which remesh() keeps to itself: run its stages
    // 1 to 4 again, with the same parameters (deterministic, so the same sites).
    AC::Intrinsic_triangulation itri(ellipsoid, AC::compute_metric_square_roots(ellipsoid, metric));
    AC::adjust_edge_lengths(itri, ellipsoid, np);
    const AC::Spherical_embedding emb = AC::spherical_embedding(itri, np);
    AC::Spherical_domain_traits sphere(itri, emb);
    std::vector<AC::Spherical_domain_traits::Point> sites = sphere.initial_sites(a.vertices, 0u);
    AC::weighted_centroidal_Voronoi_tessellation(sphere, sites, sphere.number_of_fixed_sites(), np);
    const bool same = AC::extract_dual_mesh(ellipsoid, itri, sphere, sites).points == out.points;
    std::printf("CVT picture from the sites of the mesh: %s\n", same ? "yes" : "NO (the stages differ from remesh())");

    std::vector<AC::Spherical_domain_traits::Cell> integrals;
    sphere.integrate(sites, integrals);
    std::vector<double> mass(sites.size());  // log2 of the cell's mass over the mean
    for(std::size_t i = 0; i < sites.size(); ++i)
      mass[i] = std::log2(std::max(1e-300, integrals[i].mass / (sphere.total_mass() / double(sites.size()))));

    const std::string base = a.folder + "/fig10";
    AC::IO::write_polygon_soup(base + "_mesh.off", out.points, out.faces);
    AC::IO::write_surface_svg(base + "_mesh.svg", out.points, out.faces, q.triangle_G, 0.5, 1.0,
                              caption + ": " + std::to_string(q.number_of_vertices) + " vertices, colour = quality G in the metric",
                              Eigen::Vector3d(0.3, -1.0, 0.75));
    AC::IO::write_histogram_svg(base + "_histogram.svg", q.angle_histogram, q.bin_width, caption + ": angles in the metric");
    AC::IO::write_spherical_cvt_svg(base + "_cvt.svg", sites, sphere.voronoi_cells(sites), mass,
                                    caption + ": weighted CVT on the sphere, colour = log2(cell mass / mean)");
    std::printf("wrote %s_mesh.off, %s_mesh.svg, %s_histogram.svg, %s_cvt.svg\n", base.c_str(), base.c_str(), base.c_str(),
                base.c_str());
  } catch(const AC::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  return EXIT_SUCCESS;
}
