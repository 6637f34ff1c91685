// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_MESH_QUALITY_H
#define ANISO_CONFORMAL_MESH_QUALITY_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/internal/parallel_for.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

/// \file mesh_quality.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalQuality
 * the quality of a triangle mesh measured in a metric (paper 3.6, Frey and Borouchaki): each triangle
 * is transformed by `Q_T`, the mean of the metric square roots at its corners, then measured.
 */
struct Quality_report {
  std::size_t number_of_vertices = 0;   ///< vertices of the mesh
  std::size_t number_of_triangles = 0;  ///< triangles of the mesh
  double G_min = 0;                     ///< smallest `G = 2 sqrt(3) S / (p h)` (1 for equilateral)
  double G_avg = 0;                     ///< mean `G`
  double theta_min = 0;                 ///< smallest angle anywhere, degrees
  double theta_avg = 0;                 ///< mean over triangles of their smallest angle, degrees
  double percent_below_30 = 0;          ///< percentage of triangles whose smallest angle is below 30 degrees
  double theta_max = 0;                 ///< largest angle anywhere, degrees
  double bin_width = 5;                 ///< width of the histogram bins, degrees
  std::vector<double> angle_histogram;  ///< counts of all angles in bins of `bin_width` over [0, 180)
  std::vector<double> triangle_G;       ///< `G` of each triangle, in the order of the faces
  /// metric conformity: edge lengths in the metric (edge `Q` = mean of its ends), divided by their mean
  double edge_length_mean = 0;          ///< mean metric edge length (before normalisation)
  double edge_length_stddev = 0;        ///< standard deviation of the normalised lengths
  double edge_length_min = 0;           ///< smallest normalised length
  double edge_length_max = 0;           ///< largest normalised length
  /// realised anisotropy: the stretch ratio `sqrt(lambda_max / lambda_min)` of the metric restricted to
  /// the mesh's tangent plane at each vertex (the plane orthogonal to the area-weighted normal of its
  /// triangles), in the order of the points; 0 for a vertex of no triangle, +infinity where the metric is
  /// singular on that plane
  std::vector<double> vertex_stretch;
  double stretch_min = 0;               ///< smallest stretch ratio over the vertices of triangles (>= 1)
  double stretch_median = 0;            ///< median (nearest rank) stretch ratio
  double stretch_p95 = 0;               ///< 95th percentile (nearest rank) stretch ratio
  double stretch_max = 0;               ///< largest stretch ratio
};

/*!
 * \ingroup PkgAnisoConformalQuality
 * measures the quality of the mesh (`points`, `faces`) in the metric whose square roots at the
 * vertices are `Q` (DESIGN.md 3 "Quality"), and the anisotropy the mesh realises: the stretch ratio of the
 * metric at its vertices (`Quality_report::vertex_stretch` and its min, median, 95th percentile, max).
 * `points`: n positions (any unit); `faces`: indices into `points`, counter-clockwise seen from outside;
 * `Q`: n symmetric 3x3 square roots `M^{1/2}` of the metric (`M` is in 1 / unit^2). Time linear in the size of the mesh (plus sorting its edges);
 * the per-triangle and per-edge work runs on `number_of_threads` threads (0 = every core), the sums in
 * face and edge order, so the report does not depend on the number of threads.
 * \throws Invalid_input if the sizes disagree or the mesh is empty
 */
inline Quality_report compute_mesh_quality(const std::vector<Eigen::Vector3d>& points,
                                           const std::vector<std::array<std::size_t, 3>>& faces,
                                           const std::vector<Eigen::Matrix3d>& Q, unsigned number_of_threads = 0)
{
  if(points.size() != Q.size()) throw Invalid_input("compute_mesh_quality(): one metric per vertex is needed");
  if(faces.empty()) throw Invalid_input("compute_mesh_quality(): the mesh has no triangle");
  for(const auto& f : faces)
    for(std::size_t k = 0; k < 3; ++k)
      if(f[k] >= points.size()) throw Invalid_input("compute_mesh_quality(): face index out of range");
  const double rad = 180.0 / 3.14159265358979323846;
  const std::size_t nf = faces.size();
  Quality_report r;
  r.number_of_vertices = points.size();
  r.number_of_triangles = nf;
  r.angle_histogram.assign(36, 0.0);
  r.triangle_G.resize(nf);
  std::vector<std::array<double, 3>> angle(nf);  // degrees, at the corners
  internal::parallel_for(nf, number_of_threads, [&](std::size_t t) {
    const auto& f = faces[t];
    const Eigen::Matrix3d QT = (Q[f[0]] + Q[f[1]] + Q[f[2]]) / 3.0;
    std::array<Eigen::Vector3d, 3> p = {{QT * points[f[0]], QT * points[f[1]], QT * points[f[2]]}};
    std::array<double, 3> l;
    for(int k = 0; k < 3; ++k) l[k] = (p[(k + 1) % 3] - p[k]).norm();
    const double S = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const double half_perimeter = 0.5 * (l[0] + l[1] + l[2]);
    const double h = std::max({l[0], l[1], l[2]});
    r.triangle_G[t] = (half_perimeter > 0 && h > 0) ? 2 * std::sqrt(3.0) * S / (half_perimeter * h) : 0.0;
    for(int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
      angle[t][k] = std::atan2(u.cross(v).norm(), u.dot(v)) * rad;
    }
  }, 1024);
  r.G_min = 1e300;
  r.theta_min = 1e300;
  std::size_t below = 0;
  for(std::size_t t = 0; t < nf; ++t) {
    const double G = r.triangle_G[t];
    r.G_min = std::min(r.G_min, G);
    r.G_avg += G;
    double smallest = 1e300;
    for(int k = 0; k < 3; ++k) {
      const double a = angle[t][k];
      smallest = std::min(smallest, a);
      r.theta_max = std::max(r.theta_max, a);
      r.angle_histogram[std::min<std::size_t>(35, std::size_t(std::max(0.0, a) / r.bin_width))] += 1;
    }
    r.theta_min = std::min(r.theta_min, smallest);
    r.theta_avg += smallest;
    if(smallest < 30) ++below;
  }
  r.G_avg /= double(nf);
  r.theta_avg /= double(nf);
  r.percent_below_30 = 100.0 * double(below) / double(nf);

  // every edge once, ordered by its (smaller, larger) end
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  edges.reserve(3 * nf);
  for(const auto& f : faces)
    for(int k = 0; k < 3; ++k) edges.push_back(std::minmax(f[k], f[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> length(edges.size());
  internal::parallel_for(edges.size(), number_of_threads, [&](std::size_t e) {
    const std::size_t a = edges[e].first, b = edges[e].second;
    length[e] = (0.5 * (Q[a] + Q[b]) * (points[b] - points[a])).norm();
  });
  double sum = 0;
  for(double x : length) sum += x;
  r.edge_length_mean = sum / double(edges.size());
  double var = 0;
  r.edge_length_min = 1e300;
  r.edge_length_max = 0;
  for(double e : length) {
    const double x = e / r.edge_length_mean;
    var += (x - 1) * (x - 1);
    r.edge_length_min = std::min(r.edge_length_min, x);
    r.edge_length_max = std::max(r.edge_length_max, x);
  }
  r.edge_length_stddev = std::sqrt(var / double(edges.size()));

  // the stretch of the metric at the vertices, on the plane orthogonal to the mesh's vertex normal
  std::vector<Eigen::Vector3d> normal(points.size(), Eigen::Vector3d::Zero());
  for(const auto& f : faces) {
    const Eigen::Vector3d c = (points[f[1]] - points[f[0]]).cross(points[f[2]] - points[f[0]]);
    for(int k = 0; k < 3; ++k) normal[f[k]] += c;
  }
  r.vertex_stretch.assign(points.size(), 0.0);
  internal::parallel_for(points.size(), number_of_threads, [&](std::size_t v) {
    const double len = normal[v].norm();
    if(!(len > 0)) return;  // a vertex of no (or only of degenerate) triangles: no tangent plane
    const Eigen::Vector3d n = normal[v] / len, t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    Eigen::Matrix<double, 3, 2> B;
    B.col(0) = t1;
    B.col(1) = t2;
    const Eigen::Matrix<double, 3, 2> A = Q[v] * B;  // M restricted to the plane is A^T A
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(A.transpose() * A, Eigen::EigenvaluesOnly);
    const double lo = es.eigenvalues()[0], hi = es.eigenvalues()[1];
    r.vertex_stretch[v] = lo > 0 ? std::max(1.0, std::sqrt(hi / lo)) : std::numeric_limits<double>::infinity();
  }, 2048);
  std::vector<double> sorted;
  sorted.reserve(points.size());
  for(std::size_t v = 0; v < points.size(); ++v)
    if(normal[v].norm() > 0) sorted.push_back(r.vertex_stretch[v]);
  if(!sorted.empty()) {
    std::sort(sorted.begin(), sorted.end());
    const auto rank = [&](double p) {  // nearest rank: the smallest value with at least p of the values <= it
      const std::size_t k = std::size_t(std::ceil(p * double(sorted.size())));
      return sorted[std::min(sorted.size() - 1, k > 0 ? k - 1 : 0)];
    };
    r.stretch_min = sorted.front();
    r.stretch_median = rank(0.5);
    r.stretch_p95 = rank(0.95);
    r.stretch_max = sorted.back();
  }
  return r;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_MESH_QUALITY_H
