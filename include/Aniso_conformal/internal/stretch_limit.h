// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_STRETCH_LIMIT_H
#define ANISO_CONFORMAL_INTERNAL_STRETCH_LIMIT_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Remeshing_result.h>
#include <Aniso_conformal/Surface_point.h>
#include <Aniso_conformal/internal/directed_edges.h>
#include <Aniso_conformal/internal/printable.h>
#include <Aniso_conformal/internal/remesh/canonical_parameters.h>
#include <Aniso_conformal/internal/remesh/pipeline_steps.h>
#include <Aniso_conformal/mesh_quality.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

// The stretch a mesh of straight-edged triangles can realise (issue 17, "a metric whose stretch cannot be
// realised"). An element of the metric is an ellipse of length L along the metric's long axis and width
// w = L / r (r the stretch). Where the long axis turns within the tangent plane (its integral lines have a
// geodesic curvature kappa_g: the lines along a tube at the top of a torus or a cyclide, which bend around
// the axis while the surface does not bend along them), a straight edge of length L leaves the line by the
// sagitta kappa_g L^2 / 8; once that exceeds a fraction of the width, the next row's vertex lies on the
// wrong side of the edge and the triangle folds over on the surface, whatever the CVT does. Keeping
// kappa_g L^2 / 8 <= c w with L = r w bounds the stretch by r <= sqrt(8 c / (kappa_g w)); the width w is
// the short axis of an element at the requested number of vertices, so the bound loosens as the output
// grows (w ~ 1 / sqrt(N)). c = 1/4 keeps the sagitta at a quarter of the width: on the Table 2 cyclide with
// a field of stretch [2, 29] at 8000 vertices (make_dupin_cyclide_stretch_field()), a prototype of the
// bound (analytic curvatures, Surface_optimization::ALWAYS) gave with c = 1/4 G_avg 0.948 and theta_min
// 32.0, c = 1/2 0.943 and 26.4, c = 1 0.943 and 18.6, each output valid (the field unbounded: 3 folded
// triangles); this code with the defaults: 0.932 and 30.0 (doc/manual.md, "the stretch a mesh can realise").

namespace Aniso_conformal {
namespace internal {

/// the share `c` of an element's width that the sagitta of its long edge may reach (above)
constexpr double stretch_limit_sagitta_share = 0.25;

// the metric restricted to the tangent plane of the unit normal `n`: its two scales (square roots of the
// eigenvalues, small <= big) and the unit tangent direction of the small one (the metric's long axis,
// where lengths are measured shortest, so elements are longest)
struct Tangent_scales {
  double small = 0, big = 0;
  Eigen::Vector3d long_axis = Eigen::Vector3d::Zero();
};

inline Tangent_scales tangent_scales(const Eigen::Matrix3d& M, const Eigen::Vector3d& n)
{
  const Eigen::Vector3d a = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = (a - a.dot(n) * n).normalized(), e2 = n.cross(e1);
  Eigen::Matrix2d T;
  T << e1.dot(M * e1), e1.dot(M * e2), e2.dot(M * e1), e2.dot(M * e2);
  T = 0.5 * (T + T.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(T);
  Tangent_scales s;
  s.small = std::sqrt(std::max(es.eigenvalues()[0], 0.0));
  s.big = std::sqrt(std::max(es.eigenvalues()[1], 0.0));
  s.long_axis = (es.eigenvectors()(0, 0) * e1 + es.eigenvectors()(1, 0) * e2).normalized();
  return s;
}

// `M` with its tangent stretch (for the unit normal `n`) lowered to at most `r_max` >= 1 by raising its
// small scale; the rest of `M` (the long axis' orthogonal complement, the normal part) is kept
inline Eigen::Matrix3d limit_stretch(const Eigen::Matrix3d& M, const Eigen::Vector3d& n, double r_max)
{
  const Tangent_scales s = tangent_scales(M, n);
  if(!(s.small > 0) || s.big <= r_max * s.small) return M;
  const double small = s.big / r_max;
  return M + (small * small - s.small * s.small) * s.long_axis * s.long_axis.transpose();
}

// The bound on the stretch at each vertex of `surface` for a remesh of `n` output vertices in `metric`
// (above): the geodesic curvature of the long axis at a vertex is fitted over its one-ring (the change of
// the axis, carried into the vertex's tangent plane and measured across it, as a linear function of the
// tangent displacement: least squares, then its rate along the axis); the width w follows from the
// metric's area with the stretch bounded, a fixed point of a few rounds. +infinity where the axis does not
// turn. `stretch[v]` receives the stretch asked for at each vertex.
template <typename AnisotropicMetric>
std::vector<double> stretch_bounds(const Input_surface& surface, const AnisotropicMetric& metric, std::size_t n,
                                   std::vector<double>& stretch, double share = stretch_limit_sagitta_share)
{
  const auto& P = surface.points();
  const auto& N = surface.vertex_normals();
  const std::size_t nv = P.size();
  std::vector<Tangent_scales> sc(nv);
  stretch.assign(nv, 1.0);
  for(std::size_t v = 0; v < nv; ++v) {
    const Eigen::Vector3d nrm = surface.is_planar() ? Eigen::Vector3d::UnitZ() : N[v];
    sc[v] = tangent_scales(Eigen::Matrix3d(metric.tensor(Surface_point::at_vertex(v, P[v]))), nrm);
    stretch[v] = sc[v].small > 0 ? sc[v].big / sc[v].small : 1.0;
  }
  std::vector<double> area(nv, 0.0);
  for(const auto& f : surface.faces()) {
    const double a = 0.5 * (P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]).norm();
    for(int k = 0; k < 3; ++k) area[f[k]] += a / 3;
  }
  std::vector<std::size_t> start, adj;  // the one-rings (directed_edges.h)
  vertex_neighbours(Directed_edges<std::size_t>(nv, surface.faces(), surface.number_of_faces()), nv, start, adj);
  std::vector<double> kappa_g(nv, 0.0);
  for(std::size_t v = 0; v < nv; ++v) {
    const Eigen::Vector3d nrm = surface.is_planar() ? Eigen::Vector3d::UnitZ() : N[v];
    const Eigen::Vector3d d = sc[v].long_axis, across = nrm.cross(d);
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Eigen::Vector2d b = Eigen::Vector2d::Zero();
    for(std::size_t i = start[v]; i < start[v + 1]; ++i) {
      const std::size_t w = adj[i];
      Eigen::Vector3d dw = sc[w].long_axis;
      if(dw.dot(d) < 0) dw = -dw;  // a line field: no orientation
      const Eigen::Vector3d e = P[w] - P[v];
      const Eigen::Vector2d x(e.dot(d), e.dot(across));
      const double turn = (dw - d).dot(across);
      A += x * x.transpose();
      b += turn * x;
    }
    if(std::abs(A.determinant()) > 1e-12 * A.squaredNorm()) kappa_g[v] = std::abs(A.ldlt().solve(b)[0]);
  }
  // the width of an element at `n` vertices: the metric's area with the stretch bounded, over the area of
  // n equilateral unit triangles' Voronoi cells (sqrt(3) / 2 h^2 each)
  std::vector<double> bound(nv, std::numeric_limits<double>::infinity());
  for(int round = 0; round < 8; ++round) {
    double metric_area = 0;
    for(std::size_t v = 0; v < nv; ++v) metric_area += area[v] * sc[v].big * sc[v].big / std::max(1.0, std::min(stretch[v], bound[v]));
    const double h = std::sqrt(2 * metric_area / (std::sqrt(3.0) * double(std::max<std::size_t>(n, 1))));
    for(std::size_t v = 0; v < nv; ++v) {
      const double w = sc[v].big > 0 ? h / sc[v].big : 0;
      bound[v] = kappa_g[v] > 0 && w > 0 ? std::max(1.0, std::sqrt(8 * share / (kappa_g[v] * w)))
                                         : std::numeric_limits<double>::infinity();
    }
  }
  return bound;
}

// A metric adjusted: its lengths multiplied by `scale` at the point (the feature sizing,
// features/feature_size.h; none when empty), then its stretch lowered to `bounds` per input vertex
// (stretch_bounds(); none when empty), interpolated linearly in the input's triangles (a model of AnisotropicMetric over the
// same input; a point whose vertex indices lie outside the input, a patch's, keeps the given tensor). The
// given metric is held through a function, so that the pipeline is compiled once for every metric type
// these adjustments wrap (remesh_in_domain()).
class Adjusted_metric {
public:
  typedef Eigen::Matrix3d Tensor;
  Adjusted_metric(const Input_surface& surface, std::function<Tensor(const Surface_point&)> given, std::vector<double> bounds,
                  std::function<double(const Surface_point&)> scale = {})
      : m_surface(surface), m_given(std::move(given)), m_bounds(std::move(bounds)), m_scale(std::move(scale))
  {
  }
  Tensor tensor(const Surface_point& p) const
  {
    Tensor M = m_given(p);
    for(int k = 0; k < 3; ++k)
      if(p.vertices[k] >= m_surface.number_of_vertices()) return M;
    if(m_scale) {
      const double s = m_scale(p);
      M *= s * s;
    }
    if(m_bounds.empty()) return M;
    Eigen::Vector3d nrm = Eigen::Vector3d::Zero();
    double r = 0;
    for(int k = 0; k < 3; ++k) {
      r += p.barycentric[k] * std::min(m_bounds[p.vertices[k]], 1e6);
      nrm += p.barycentric[k] * m_surface.vertex_normals()[p.vertices[k]];
    }
    if(m_surface.is_planar()) nrm = Eigen::Vector3d::UnitZ();
    if(!(nrm.norm() > 0) || r >= 1e6) return M;
    return limit_stretch(M, nrm.normalized(), std::max(1.0, r));
  }

private:
  const Input_surface& m_surface;
  std::function<Tensor(const Surface_point&)> m_given;
  std::vector<double> m_bounds;
  std::function<double(const Surface_point&)> m_scale;
};

// `run(metric)`, the pipeline; if it fails with Convergence_failure for folded (inverted) output triangles
// (`result.inverted_triangles`, set by the check before it throws) while `metric` asks somewhere for more
// stretch than straight-edged triangles of
// `options.number_of_vertices` vertices can follow (stretch_bounds(), Stretch_limit_report), `run` again
// in the metric with its stretch bounded there; the output of that run, with `result.stretch_limit`
// saying what was bounded and how the output measures in `metric`, or Convergence_failure with both reasons
template <typename AnisotropicMetric, typename Run>
Remeshed_surface run_with_stretch_bound(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                                        const Remeshing_options& options, const Run& run)
{
  const auto start = std::chrono::steady_clock::now();
  try {
    return run(metric);
  } catch(const Convergence_failure& e) {
    // only an output with folded triangles: a stage that did not converge is not the stretch's doing
    // (CGAL's cheese with the curvature metric: its hyperbolic Newton solve fails either way, 17 s -> 91 s
    // when it was run again)
    if(result.inverted_triangles == 0) throw;
    std::vector<double> asked;
    std::vector<double> bounds = stretch_bounds(surface, metric, options.number_of_vertices, asked);
    Stretch_limit_report limit;
    std::vector<double> limited;
    for(std::size_t v = 0; v < bounds.size(); ++v)
      if(asked[v] > bounds[v] * (1 + 1e-9)) {
        limit.stretch_asked_max = std::max(limit.stretch_asked_max, asked[v]);
        limited.push_back(bounds[v]);
      }
    if(limited.empty()) throw;  // the metric asks for no more than the output can realise: the failure stands
    std::sort(limited.begin(), limited.end());
    limit.applied = true;
    limit.vertices_limited = limited.size();
    limit.bound_min = limited.front();
    limit.bound_median = limited[limited.size() / 2];
    limit.reason = e.what();
    const double failed_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Adjusted_metric bounded(
        surface, [&metric](const Surface_point& p) { return Eigen::Matrix3d(metric.tensor(p)); }, std::move(bounds));
    result = Remeshing_result();
    Remeshed_surface out;
    try {
      out = run(bounded);
    } catch(const Convergence_failure& e2) {
      throw Convergence_failure(std::string(e.what()) + "; run again with the stretch bounded to what straight edges can follow (at " +
                                    std::to_string(limit.vertices_limited) + " input vertices, to at least " +
                                    short_number(limit.bound_min) + "), it failed too: " + e2.what(),
                                e.residual());
    }
    const Quality_report given = compute_mesh_quality(out.points, out.faces, metric_square_roots_at(metric, out), options.number_of_threads);
    limit.given_G_min = given.G_min;
    limit.given_G_avg = given.G_avg;
    limit.given_theta_min = given.theta_min;
    limit.given_percent_below_30 = given.percent_below_30;
    result.stretch_limit = limit;
    result.discarded_seconds += failed_seconds;
    return out;
  }
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_STRETCH_LIMIT_H
