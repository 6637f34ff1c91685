// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Calls the five stages one by one on the paper's Fig. 6 square, printing what each produced.
// Usage: pipeline_step_by_step [number_of_vertices]

#include <Aniso_conformal/Analytic_metric_2.h>
#include <Aniso_conformal/Paper_metrics.h>
#include <Aniso_conformal/remesh.h>
#include <Aniso_conformal/make_square_background.h>

#include <cstdlib>
#include <iostream>

namespace AC = Aniso_conformal;

int main(int argc, char** argv)
{
  const std::size_t n = argc > 1 ? std::size_t(std::atol(argv[1])) : 1000;
  const auto metric = AC::make_analytic_metric_2(AC::Fig6_metric());
  try {
    // a background triangulation of the unit square that resolves the metric
    const AC::Input_surface square = AC::make_square_background(metric, n);
    std::cout << "background: " << square.number_of_vertices() << " vertices\n";

    // 1. the metric at the vertices, as symmetric square roots Q = M^(1/2)
    AC::Intrinsic_triangulation itri(square, AC::compute_metric_square_roots(square, metric));

    // 2. edge lengths in the metric, made valid by metric-Delaunay flips and longest-edge splits
    const AC::Edge_adjustment_report adj = AC::adjust_edge_lengths(itri, square);
    std::cout << "edge lengths: " << adj.flips << " flips, " << adj.splits << " splits\n";

    // 3. conformal embedding into the plane (u = 0 on the boundary)
    const AC::Planar_embedding emb = AC::conformal_embedding(itri);
    std::cout << "embedding: " << emb.iterations << " Newton iterations, residual " << emb.residual << "\n";

    // 4. weighted CVT with density cf^2, boundary sites fixed between the corners
    AC::Planar_domain_traits domain(itri, emb);
    std::vector<AC::Planar_domain_traits::Point> sites = domain.initial_sites(n, 0);
    const AC::Cvt_report cvt = AC::weighted_centroidal_Voronoi_tessellation(
        domain, sites, domain.number_of_fixed_sites(), AC::parameters::number_of_iterations(100u));
    std::cout << "CVT: energy " << cvt.energy.front() << " -> " << cvt.energy.back() << " in " << cvt.iterations
              << " iterations\n";

    // 5. the Delaunay dual, mapped back onto the square
    const AC::Remeshed_surface out = AC::extract_dual_mesh(square, itri, domain, sites);
    std::vector<Eigen::Matrix3d> Q;
    for(const auto& p : out.surface_points) Q.push_back(AC::internal::symmetric_sqrt(metric.tensor(p)));
    const AC::Quality_report q = AC::compute_mesh_quality(out.points, out.faces, Q);
    std::cout << "output: " << out.points.size() << " vertices, G_avg " << q.G_avg << ", theta_min " << q.theta_min << "\n";
  } catch(const AC::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
