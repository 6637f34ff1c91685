// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_MAKE_SQUARE_BACKGROUND_H
#define ANISO_CONFORMAL_MAKE_SQUARE_BACKGROUND_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/adjust_edge_lengths.h>
#include <Aniso_conformal/internal/intrinsic/longest_edge_queue.h>
#include <Aniso_conformal/internal/tensor.h>

#include <Eigen/Core>

#include <cmath>
#include <queue>
#include <string>
#include <tuple>
#include <vector>

/// \file make_square_background.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * builds a background triangulation of the unit square `[0,1]^2` (z = 0) fine enough to resolve
 * `metric` for an output of `output_vertices` vertices.
 *
 * Starting from a 17 x 17 grid, it splits the longest edge *measured in the metric* (at its midpoint,
 * both neighbouring triangles in two) and restores the metric-Delaunay property around the new vertex,
 * until every edge is shorter than `h / 1.5`, with `h = sqrt(2 A / (sqrt(3) n))` the expected output edge
 * length and `A` the area of the square in the metric. The background is graded and stretched like the
 * metric; for the paper's Fig. 6 and Fig. 7 it has 5154 and 19861 vertices (the paper used 5112 and
 * 25717). With
 * `background_vertices > 0` it instead refines, longest edge first, until it has that many vertices.
 *
 * \tparam AnisotropicMetric a model of `AnisotropicMetric` that can be evaluated from a position alone
 *         (`Analytic_metric_2`, `Image_metric`, `Uniform_metric`)
 * \throws Invalid_input if `output_vertices < 4`, if the metric is not finite and positive definite
 *         somewhere, or if the refinement would need more than `max_vertices` vertices (default 50 n + 10000)
 */
template <typename AnisotropicMetric>
Input_surface make_square_background(const AnisotropicMetric& metric, std::size_t output_vertices,
                                     std::size_t background_vertices = 0, std::size_t max_vertices = 0)
{
  if(output_vertices < 4)
    throw Invalid_input("the unit square needs at least 4 output vertices (its corners), " +
                        std::to_string(output_vertices) + " were requested");
  if(max_vertices == 0) max_vertices = 50 * output_vertices + 10000;
  if(background_vertices > max_vertices) max_vertices = background_vertices;
  auto Q_at = [&](const Eigen::Vector3d& x) {
    Surface_point p;
    p.position = x;
    const Eigen::Matrix3d M = metric.tensor(p);
    if(!internal::all_finite(M) || !(internal::tangent_positivity(M, Eigen::Vector3d(0, 0, 1)) > 1e-12))
      throw Invalid_input("the metric is not finite and positive definite at (" + std::to_string(x.x()) + ", " +
                          std::to_string(x.y()) + ")");
    return internal::symmetric_sqrt(M);
  };
  // area of the square in the metric, by a 200 x 200 midpoint rule on sqrt(det M)
  double area = 0;
  const int S = 200;
  for(int i = 0; i < S; ++i)
    for(int j = 0; j < S; ++j) {
      const Eigen::Matrix3d Q = Q_at(Eigen::Vector3d((i + 0.5) / S, (j + 0.5) / S, 0));
      area += std::abs(Q.topLeftCorner<2, 2>().determinant()) / (double(S) * S);
    }
  const double h_out = std::sqrt(2 * area / (std::sqrt(3.0) * double(output_vertices)));
  const double h_bg = background_vertices > 0 ? 0.0 : h_out / 1.5;

  const int g = 17;
  std::vector<Eigen::Vector3d> pts;
  std::vector<Input_surface::Face> faces;
  for(int j = 0; j < g; ++j)
    for(int i = 0; i < g; ++i) pts.emplace_back(double(i) / (g - 1), double(j) / (g - 1), 0.0);
  for(int j = 0; j + 1 < g; ++j)
    for(int i = 0; i + 1 < g; ++i) {
      const std::size_t a = j * g + i, b = a + 1, c = a + g + 1, d = a + g;
      if((i + j) % 2 == 0) { faces.push_back({{a, b, c}}); faces.push_back({{a, c, d}}); }
      else { faces.push_back({{a, b, d}}); faces.push_back({{b, c, d}}); }
    }
  Input_surface grid(pts, faces);
  std::vector<Eigen::Matrix3d> Qs;
  for(const auto& p : grid.points()) Qs.push_back(Q_at(p));
  Intrinsic_triangulation tri(grid, Qs);
  auto metric_length = [&](int a, int b) {
    const Eigen::Vector3d pa = tri.position(a), pb = tri.position(b), e = pb - pa;
    Surface_point mid;
    mid.position = 0.5 * (pa + pb);
    return std::sqrt(std::max(0.0, e.dot(metric.tensor(mid) * e)));  // |Q e| without the square root of M
  };
  internal::Longest_edge_queue queue = internal::longest_edge_queue(tri, metric_length);
  while(!queue.empty()) {
    const internal::Edge_key e = queue.top();
    if(background_vertices > 0 ? tri.number_of_vertices() >= background_vertices : std::get<0>(e) <= h_bg) break;
    queue.pop();
    const int h = tri.find_halfedge(std::get<1>(e), std::get<2>(e));
    if(h < 0) continue;  // split already
    if(tri.number_of_vertices() >= max_vertices)
      throw Invalid_input("the metric needs a background of more than " + std::to_string(max_vertices) +
                          " vertices to be resolved; it varies too fast for " + std::to_string(output_vertices) +
                          " output vertices");
    Surface_point mid;
    mid.position = 0.5 * (tri.position(tri.tail(h)) + tri.position(tri.head(h)));
    const int m = tri.split(h, mid, Q_at(mid.position));
    // metric-Delaunay flips around the new vertex make the refinement anisotropic: triangles stretch
    // along the metric instead of being bisected isotropically
    std::vector<int> opposite;
    for(int o : tri.outgoing_halfedges(m)) opposite.push_back(Intrinsic_triangulation::next(o));
    for(int flips = 0; !opposite.empty() && flips < 200;) {
      const int e = opposite.back();
      opposite.pop_back();
      if(tri.twin(e) < 0 || tri.opposite_vertex(e) != m) continue;
      if(!internal::Metric_delaunay_flip_rule().wants_flip(tri, e)) continue;
      const int g = tri.flip(e);  // g = d -> m in face (m, x, d); twin(g) = m -> d in face (d, y, m)
      ++flips;
      opposite.push_back(Intrinsic_triangulation::prev(g));            // x -> d, opposite m
      opposite.push_back(Intrinsic_triangulation::next(tri.twin(g)));  // d -> y, opposite m
    }
    // queue the edges of the new vertex's star and their opposite edges (flips changed them)
    for(int o : tri.outgoing_halfedges(m))
      for(int e : {o, Intrinsic_triangulation::next(o), Intrinsic_triangulation::prev(o)}) {
        const int r = tri.is_edge_representative(e) ? e : tri.twin(e);
        queue.emplace(metric_length(tri.tail(r), tri.head(r)), tri.tail(r), tri.head(r));
      }
  }
  std::vector<Eigen::Vector3d> out_pts(tri.number_of_vertices());
  for(int v = 0; v < int(out_pts.size()); ++v) out_pts[v] = tri.position(v);
  std::vector<Input_surface::Face> out_faces(tri.number_of_faces());
  for(std::size_t f = 0; f < out_faces.size(); ++f) {
    const auto& c = tri.face_vertices(f);
    out_faces[f] = {{std::size_t(c[0]), std::size_t(c[1]), std::size_t(c[2])}};
  }
  return Input_surface(std::move(out_pts), std::move(out_faces));
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_MAKE_SQUARE_BACKGROUND_H
