// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The paper's Fig. 13: closed surfaces of genus above 1 through the hyperbolic disk. The Eight (a
// 9734-vertex genus-2 surface) with the curvature metric, stretch ratio at most 5, remeshed into 1000
// vertices; then a genus-3 surface (CGAL's 3torus.off, triangulated and refined by 4 Loop subdivisions
// into 5884 vertices) into 2000 vertices (100 CVT iterations, seed 0). Prints the quality in the metric
// and checks the bar on the Eight; writes <folder>/fig13_mesh.off, fig13_mesh.svg (the surface
// coloured by the quality G of each triangle in the metric), fig13_histogram.svg (the angles in the
// metric), fig13_cvt.svg (the weighted CVT in the Klein disk: the fundamental domain's cut, the sites
// and their hyperbolic Voronoi cells, the paper's Fig. 13 (a)), and the same four files for
// fig13_genus3.
// Usage: fig13_eight [output_folder [number_of_vertices_of_the_eight]]

#include "figure_common.h"

#include <Aniso_conformal/Curvature_metric.h>
#include <Aniso_conformal/Hyperbolic_domain.h>
#include <Aniso_conformal/Hyperbolic_klein_domain_traits.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/hyperbolic_embedding.h>
#include <Aniso_conformal/make_subdivided_surface.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace AC = Aniso_conformal;

// remeshes `surface` (curvature metric, stretch at most 5), reports, and writes the four pictures
static AC::Quality_report run(const AC::Input_surface& surface, const std::string& caption, const std::string& base, std::size_t n)
{
  AC::Curvature_metric_options options;
  options.stretch_max = 5;
  const AC::Curvature_metric metric(surface, options);
  const auto& ratios = metric.stretch_ratios();
  std::printf("%s: %zu vertices, %s; stretch ratios in [%.2f, %.2f]\n", caption.c_str(), surface.number_of_vertices(),
              surface.topology_description().c_str(), *std::min_element(ratios.begin(), ratios.end()),
              *std::max_element(ratios.begin(), ratios.end()));
  const auto np = figure::figure_parameters(n);
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Hyperbolic_domain>(surface, metric, r, np);
  const AC::Quality_report& q = r.quality;
  figure::print_report(caption, r);
  std::printf("domain %s; conformal factor in [%.3g, %.3g]; %s; Hausdorff distance %.3g of the bounding-box diagonal\n",
              AC::domain_name(r.domain), r.conformal_factor_min, r.conformal_factor_max, r.domain_diagnostics.summary.c_str(),
              r.hausdorff_distance_relative);

  // The CVT picture needs the sites and the domain, which remesh() keeps to itself: run its stages
  // 1 to 4 again, with the same parameters (deterministic, so the same sites).
  AC::Intrinsic_triangulation itri(surface, AC::compute_metric_square_roots(surface, metric));
  AC::adjust_edge_lengths(itri, surface, np);
  const AC::Hyperbolic_embedding emb = AC::hyperbolic_embedding(itri, np);
  AC::Hyperbolic_klein_domain_traits disk(itri, emb);
  std::vector<AC::Hyperbolic_klein_domain_traits::Point> sites = disk.initial_sites(n, 0u);
  AC::weighted_centroidal_Voronoi_tessellation(disk, sites, disk.number_of_fixed_sites(), np);
  const bool same = AC::extract_dual_mesh(surface, itri, disk, sites).points == out.points;
  std::printf("CVT picture from the sites of the mesh: %s\n", same ? "yes" : "NO (the stages differ from remesh())");
  std::vector<AC::Hyperbolic_klein_domain_traits::Cell> integrals;
  disk.integrate(sites, integrals);
  std::vector<double> mass(sites.size());  // log2 of the cell's mass over the mean
  for(std::size_t i = 0; i < sites.size(); ++i)
    mass[i] = std::log2(std::max(1e-300, integrals[i].mass / (disk.total_mass() / double(sites.size()))));

  AC::IO::write_polygon_soup(base + "_mesh.off", out.points, out.faces);
  AC::IO::write_surface_svg(base + "_mesh.svg", out.points, out.faces, q.triangle_G, 0.5, 1.0,
                            caption + ": " + std::to_string(q.number_of_vertices) + " vertices, colour = quality G in the metric",
                            Eigen::Vector3d(0.3, -1.0, 0.75));
  AC::IO::write_histogram_svg(base + "_histogram.svg", q.angle_histogram, q.bin_width, caption + ": angles in the metric");
  AC::IO::write_hyperbolic_cvt_svg(base + "_cvt.svg", disk.klein_sites(sites), disk.voronoi_cells(sites),
                                   disk.fundamental_domain_boundary(), mass,
                                   caption + ": weighted CVT in the Klein disk, colour = log2(cell mass / mean)");
  std::printf("wrote %s_mesh.off, %s_mesh.svg, %s_histogram.svg, %s_cvt.svg\n", base.c_str(), base.c_str(), base.c_str(),
              base.c_str());
  return q;
}

int main(int argc, char** argv)
{
  const figure::Arguments a(argc, argv, 1000);
  try {
    const AC::Input_surface eight = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/eight_10k.off");
    const AC::Quality_report q = run(eight, "Fig. 13, Eight", a.folder + "/fig13", a.vertices);
    const bool ok = q.G_avg >= 0.88 && q.theta_min >= 15 && q.percent_below_30 <= 1;
    std::printf("quality bar (G_avg >= 0.88, theta_min >= 15, %%<30 <= 1): %s\n\n", ok ? "met" : "NOT met");

    const AC::Input_surface genus3 = AC::make_subdivided_surface(std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/3torus.off", 4);
    run(genus3, "Fig. 13, genus 3", a.folder + "/fig13_genus3", 2 * a.vertices);
  } catch(const AC::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  return EXIT_SUCCESS;
}
