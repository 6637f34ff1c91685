// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The paper's Fig. 11 and Table 2: a Dupin ring cyclide (the 180 x 144 grid, 25920 vertices; a closed
// genus-1 surface, so remesh() goes through the flat torus) with the curvature metric, stretch ratio at
// most 29, remeshed into 8000 vertices (100 CVT iterations, seed 0). Prints the quality in the metric
// next to the paper's Table 2 and checks the bar; writes <folder>/fig11_mesh.off,
// fig11_mesh.svg (the surface coloured by the quality G of each triangle in the metric),
// fig11_histogram.svg (the angles in the metric) and fig11_cvt.svg (the weighted CVT on the flat
// torus: the fundamental cell with the sites and their Voronoi cells, the paper's Fig. 11 (a)). Then the
// same cyclide in a field whose stretch spans the paper's [2, 29] exactly (make_dupin_cyclide_stretch_field()),
// with the stretch bound remesh_in_domain() applies where straight edges cannot follow it
// (Stretch_limit_report); writes <folder>/fig11_paper_stretch_mesh.off.
// Usage: fig11_cyclide [output_folder [number_of_vertices]]

#include "figure_common.h"

#include <Aniso_conformal/Curvature_metric.h>
#include <Aniso_conformal/Euclidean_periodic_domain_traits.h>
#include <Aniso_conformal/Flat_torus_domain.h>
#include <Aniso_conformal/flat_torus_embedding.h>
#include <Aniso_conformal/make_dupin_cyclide.h>

#include <algorithm>
#include <cmath>
#include <iostream>

int main(int argc, char** argv)
{
  namespace AC = Aniso_conformal;
  const figure::Arguments a(argc, argv, 8000);
  const std::string caption = "Fig. 11, Dupin cyclide";
  try {
    const AC::Input_surface cyclide = AC::make_dupin_cyclide(180, 144);
    AC::Curvature_metric_options options;
    options.stretch_max = 29;
    const AC::Curvature_metric metric(cyclide, options);
    const auto& ratios = metric.stretch_ratios();
    std::printf("input: %zu vertices, %s; stretch ratios in [%.2f, %.2f]\n", cyclide.number_of_vertices(),
                cyclide.topology_description().c_str(), *std::min_element(ratios.begin(), ratios.end()),
                *std::max_element(ratios.begin(), ratios.end()));

    // the mesh and its report
    const auto np = figure::figure_parameters(a.vertices);
    AC::Remeshing_result r;
    const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Flat_torus_domain>(cyclide, metric, r, np);
    const AC::Quality_report& q = r.quality;
    figure::print_report(caption, r);
    std::printf("domain %s; %s; conformal factor in [%.3g, %.3g]\n", AC::domain_name(r.domain),
                r.domain_diagnostics.summary.c_str(), r.conformal_factor_min, r.conformal_factor_max);
    std::printf("Hausdorff distance to the input: %.3g of the bounding-box diagonal\n", r.hausdorff_distance_relative);
    figure::print_paper_comparison(q, figure::Paper_quality{0.3771, 0.9068, 22.57, 52.48, 0.0187});  // Table 2
    const bool ok = q.G_avg >= 0.90 && q.theta_min >= 20 && q.percent_below_30 <= 0.5;
    std::printf("quality bar (G_avg >= 0.90, theta_min >= 20, %%<30 <= 0.5): %s\n", ok ? "met" : "NOT met");

    // The CVT picture needs the sites and the domain, which remesh() keeps to itself: run its stages
    // 1 to 4 again, with the same parameters (deterministic, so the same sites).
    AC::Intrinsic_triangulation itri(cyclide, AC::compute_metric_square_roots(cyclide, metric));
    AC::adjust_edge_lengths(itri, cyclide, np);
    const AC::Flat_torus_embedding emb = AC::flat_torus_embedding(itri, np);
    AC::Euclidean_periodic_domain_traits torus(itri, emb);
    std::vector<AC::Euclidean_periodic_domain_traits::Point> sites = torus.initial_sites(a.vertices, 0u);
    AC::weighted_centroidal_Voronoi_tessellation(torus, sites, torus.number_of_fixed_sites(), np);
    const bool same = AC::extract_dual_mesh(cyclide, itri, torus, sites).points == out.points;
    std::printf("CVT picture from the sites of the mesh: %s\n", same ? "yes" : "NO (the stages differ from remesh())");

    for(auto& p : sites) p = torus.wrap(p);
    std::vector<AC::Euclidean_periodic_domain_traits::Cell> integrals;
    torus.integrate(sites, integrals);
    std::vector<double> mass(sites.size());  // log2 of the cell's mass over the mean
    for(std::size_t i = 0; i < sites.size(); ++i)
      mass[i] = std::log2(std::max(1e-300, integrals[i].mass / (torus.total_mass() / double(sites.size()))));

    const std::string base = a.folder + "/fig11";
    AC::IO::write_polygon_soup(base + "_mesh.off", out.points, out.faces);
    AC::IO::write_surface_svg(base + "_mesh.svg", out.points, out.faces, q.triangle_G, 0.5, 1.0,
                              caption + ": " + std::to_string(q.number_of_vertices) + " vertices, colour = quality G in the metric",
                              Eigen::Vector3d(0.3, -1.0, 0.75));
    AC::IO::write_histogram_svg(base + "_histogram.svg", q.angle_histogram, q.bin_width, caption + ": angles in the metric");
    AC::IO::write_periodic_cvt_svg(base + "_cvt.svg", torus.lattice(), sites, torus.voronoi_cells(sites), mass,
                                   caption + ": weighted CVT on the flat torus, colour = log2(cell mass / mean)");
    std::printf("wrote %s_mesh.off, %s_mesh.svg, %s_histogram.svg, %s_cvt.svg\n", base.c_str(), base.c_str(), base.c_str(),
                base.c_str());

    // The paper's stated stretch, [2, 29], as a field that spans it exactly (make_dupin_cyclide_stretch_field():
    // the long axis along the tube). At this size straight edges cannot follow the long axis where it turns
    // along the tube: remesh_in_domain() bounds the stretch there and says so (Stretch_limit_report).
    const AC::Tensor_field_metric paper_field = AC::make_dupin_cyclide_stretch_field(180, 144, 2, 29);
    AC::Remeshing_result rp;
    const AC::Remeshed_surface outp = AC::remesh_in_domain<AC::Flat_torus_domain>(cyclide, paper_field, rp, np);
    const AC::Quality_report& qp = rp.quality;
    std::printf("\nthe field of stretch [2, 29]: %zu vertices, stretch at the output vertices [%.2f, %.2f] (median %.2f, 95%% %.2f)\n",
                qp.number_of_vertices, qp.stretch_min, qp.stretch_max, qp.stretch_median, qp.stretch_p95);
    if(rp.stretch_limit.applied)
      std::printf("stretch bounded at %zu input vertices (bounds from %.3g, median %.3g) where straight edges cannot follow the "
                  "long axis; in the field as given: G_min %.4f  G_avg %.4f  theta_min %.2f  %%<30 %.3f\n",
                  rp.stretch_limit.vertices_limited, rp.stretch_limit.bound_min, rp.stretch_limit.bound_median,
                  rp.stretch_limit.given_G_min, rp.stretch_limit.given_G_avg, rp.stretch_limit.given_theta_min,
                  rp.stretch_limit.given_percent_below_30);
    figure::print_paper_comparison(qp, figure::Paper_quality{0.3771, 0.9068, 22.57, 52.48, 0.0187});
    AC::IO::write_polygon_soup(base + "_paper_stretch_mesh.off", outp.points, outp.faces);
    std::printf("wrote %s_paper_stretch_mesh.off\n", base.c_str());
  } catch(const AC::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  return EXIT_SUCCESS;
}
