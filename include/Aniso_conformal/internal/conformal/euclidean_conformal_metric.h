// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_EUCLIDEAN_CONFORMAL_METRIC_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_EUCLIDEAN_CONFORMAL_METRIC_H

#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/conformal/newton_solver.h>
#include <Aniso_conformal/internal/visitor_helper.h>

#include <string>
#include <utility>
#include <vector>

namespace Aniso_conformal {
namespace internal {

/*
 * The flat discrete conformal metric of the Euclidean domains (plane, sphere's planar map, flat torus):
 * `itri` is first flipped to its intrinsic Delaunay triangulation for its own lengths (the conformal
 * class is defined there), then solve_conformal_metric() in the Euclidean vertex-scaling geometry with
 * u fixed where `fixed` is set (to `fixed_u`, or 0) and angle sum 2 pi elsewhere (or
 * `target_angle_sums[v]`, when given), starting from `fixed_u` (or 0). Bounds and visitor from the named parameters (`max_conformal_iterations`,
 * `conformal_tolerance`, `max_flips_per_edge`, `visitor`); the figures are copied into `emb` (any
 * embedding struct with u, iterations, residual, degenerate_triangles and flips).
 */
template <typename Embedding, typename NamedParameters>
void solve_euclidean_conformal_metric(Intrinsic_triangulation& itri, const std::vector<char>& fixed, const NamedParameters& np,
                                      const std::string& who, Embedding& emb, const std::vector<char>* keep_star = nullptr,
                                      const std::vector<double>* fixed_u = nullptr,
                                      const std::vector<double>* target_angle_sums = nullptr)
{
  const Newton_bounds bounds = Newton_bounds::from(np);
  typename Visitor_reference<NamedParameters>::type vis = get_visitor(np);
  const std::size_t first_pass = make_intrinsic_delaunay(itri, bounds.flips_per_edge, who, keep_star);
  std::vector<double> u0 = fixed_u ? *fixed_u : std::vector<double>(itri.number_of_vertices(), 0.0);
  Conformal_solution sol =
      solve_conformal_metric(itri, Euclidean_vertex_scaling(), fixed, std::move(u0), bounds, vis, who, keep_star, target_angle_sums);
  emb.u = std::move(sol.u);
  emb.iterations = sol.iterations;
  emb.residual = sol.residual;
  emb.degenerate_triangles = sol.degenerate;
  emb.flips = first_pass + sol.flips;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_EUCLIDEAN_CONFORMAL_METRIC_H
