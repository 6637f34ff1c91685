// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_SPHERICAL_MAP_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_SPHERICAL_MAP_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/conformal/layout.h>
#include <Aniso_conformal/internal/intrinsic/shortest_paths.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>
#include <vector>

// The steps of spherical_embedding() (its documentation gives the method): the puncture, the inversion's
// Dirichlet data, the inverse stereographic projection, the Moebius centring, the checks and measures.

namespace Aniso_conformal {
namespace internal {

// The Moebius map of the unit sphere that is the hyperbolic translation of the unit ball taking z
// (|z| < 1) to the centre (Ahlfors' formula); it keeps the sphere and maps circles to circles.
inline Eigen::Vector3d ball_translation(const Eigen::Vector3d& x, const Eigen::Vector3d& z)
{
  const Eigen::Vector3d d = x - z;
  const double z2 = z.squaredNorm();
  // for |x| = 1 the denominator is |x - z|^2 > 0
  return (((1 - z2) * d - d.squaredNorm() * z) / (1 - 2 * z.dot(x) + z2 * x.squaredNorm())).normalized();
}

// The solid angle of the spherical triangle (a, b, c) of unit vectors, signed (Van Oosterom and
// Strackee 1983); atan2 keeps it accurate for tiny and for large triangles.
inline double spherical_triangle_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  return 2 * std::atan2(a.dot(b.cross(c)), 1 + a.dot(b) + b.dot(c) + c.dot(a));
}

// The puncture: the vertex whose link edges are the most strictly Delaunay (the Delaunay margin
// pi - (sum of the two angles facing an edge), smallest over the link edges), among those whose link
// is a simple cycle (otherwise the rest is no disk); then the flattest (angle sum nearest 2 pi), then
// the smallest index. A link edge whose margin is 0 is cocircular with p: the inversion from p makes
// the triangle beyond it flat, which the planar metric cannot hold. (A spoke of margin 0 only makes
// the link polygon straight at a vertex, which is harmless.) Invalid_input if no link is simple.
// With `away_from_patches` (spherical_embedding()'s retry on a surface whose holes are closed by patches),
// only the vertices at least half as far from the patches as the farthest one (shortest paths along the
// edges, from every vertex of a patch face) are candidates: a puncture on a seam or in a patch put the
// log singularity of the inversion's factor next to seam edges, which cannot flip (CGAL's lion.off: a
// patch vertex one edge from a seam; a plate with a U-shaped hole at 600 vertices: a seam vertex, its
// flat triangles two and three edges from it).
inline int choose_puncture(const Intrinsic_triangulation& itri, bool away_from_patches = false)
{
  const double pi = 3.14159265358979323846;
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  std::vector<std::array<double, 3>> angle(static_cast<std::size_t>(nf));  // angle[f][k] at corner k
  std::vector<double> angle_sum(std::size_t(nv), 0.0);
  for(int f = 0; f < nf; ++f) {
    bool deg;
    angle[std::size_t(f)] = corner_angles({{itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2)}}, deg);
    const auto& c = itri.face_vertices(std::size_t(f));
    for(int k = 0; k < 3; ++k) angle_sum[std::size_t(c[k])] += angle[std::size_t(f)][std::size_t(k)];
  }
  auto facing = [&](int h) { return angle[std::size_t(h / 3)][std::size_t((h % 3 + 2) % 3)]; };  // the angle facing h
  auto margin = [&](int h) { return pi - facing(h) - facing(itri.twin(h)); };
  std::vector<char> candidate(std::size_t(nv), 1);
  if(away_from_patches && itri.has_patches()) {
    // Dijkstra from the patches' vertices
    std::vector<double> d(std::size_t(nv), std::numeric_limits<double>::infinity());
    typedef std::pair<double, int> Item;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
    for(int f = 0; f < nf; ++f)
      if(itri.is_patch_face(std::size_t(f)))
        for(int v : itri.face_vertices(std::size_t(f)))
          if(d[std::size_t(v)] > 0) d[std::size_t(v)] = 0, heap.push({0.0, v});
    while(!heap.empty()) {
      const Item top = heap.top();
      heap.pop();
      if(top.first > d[std::size_t(top.second)]) continue;
      for(int h : itri.outgoing_halfedges(top.second)) {
        const double dh = top.first + itri.length(h);
        if(dh < d[std::size_t(itri.head(h))]) d[std::size_t(itri.head(h))] = dh, heap.push({dh, itri.head(h)});
      }
    }
    double farthest = 0;
    for(double x : d)
      if(std::isfinite(x)) farthest = std::max(farthest, x);
    if(farthest > 0)
      for(int v = 0; v < nv; ++v) candidate[std::size_t(v)] = d[std::size_t(v)] >= 0.5 * farthest;
  }
  int puncture = -1;
  double best_margin = -std::numeric_limits<double>::infinity();
  for(int v = 0; v < nv; ++v) {
    if(!candidate[std::size_t(v)]) continue;
    std::vector<int> link;
    double m = std::numeric_limits<double>::infinity();
    for(int h : itri.outgoing_halfedges(v)) {
      link.push_back(itri.head(h));
      m = std::min(m, margin(Intrinsic_triangulation::next(h)));  // the link edge facing v in h's face
    }
    std::sort(link.begin(), link.end());
    if(link.size() < 3 || std::adjacent_find(link.begin(), link.end()) != link.end()) continue;
    const bool better = puncture < 0 || m > best_margin + 1e-12 ||
                        (m >= best_margin - 1e-12 && std::abs(angle_sum[std::size_t(v)] - 2 * pi) <
                                                         std::abs(angle_sum[std::size_t(puncture)] - 2 * pi));
    if(better) {
      puncture = v;
      best_margin = std::max(best_margin, m);
    }
  }
  if(puncture < 0)
    throw Invalid_input("spherical_embedding(): no vertex has a simple link (the triangulation has multiple edges everywhere)");
  return puncture;
}

/*
 * The inversion's data for the planar map of the surface punctured at p: marks p and its link in
 * `fixed` and returns per vertex the log scale to start from: on the link the Dirichlet data
 * -2 (log l_pv - mean log), elsewhere the initial guess, half the inversion's factor, -(log d(p, v) -
 * mean log) with d the shortest-path distance from p along the edges. From u = 0 the far side of the
 * surface is off by about 2 log(diameter / link edge) and Newton spends its iterations in damped steps:
 * measured, 13 iterations on the Fig. 10 ellipsoid, 16 at level 6, 32 on a round sphere; 4 on all
 * three from this guess, and never more elsewhere (bear, needles). The full factor (-2 log) overshoots:
 * 6 everywhere.
 */
inline std::vector<double> inversion_data(const Intrinsic_triangulation& itri, int p, std::vector<char>& fixed)
{
  const int nv = int(itri.number_of_vertices());
  std::vector<double> fixed_u(std::size_t(nv), 0.0);
  fixed[std::size_t(p)] = 1;
  const std::vector<int> spokes = itri.outgoing_halfedges(p);
  double mean_log = 0;
  for(int h : spokes) mean_log += std::log(itri.length(h)) / double(spokes.size());
  for(int h : spokes) {
    fixed[std::size_t(itri.head(h))] = 1;
    fixed_u[std::size_t(itri.head(h))] = -2 * (std::log(itri.length(h)) - mean_log);
  }
  const std::vector<double> d = shortest_paths(
      std::size_t(nv), p,
      [&](int u, const auto& relax) {
        for(int h : itri.outgoing_halfedges(u)) relax(itri.head(h), itri.length(h), h);
      },
      [](int) {}, [](int, int) {});
  for(int v = 0; v < nv; ++v)
    if(!fixed[std::size_t(v)] && std::isfinite(d[std::size_t(v)]) && d[std::size_t(v)] > 0)
      fixed_u[std::size_t(v)] = -(std::log(d[std::size_t(v)]) - mean_log);
  return fixed_u;
}

// The inverse stereographic projection of the planar layout `uv` (every vertex but the puncture p),
// centred on the mean and scaled to a median radius of 1 (a first guess for the Moebius centring), p
// at the north pole; y is mirrored because the projection from the north pole reverses the orientation
// seen from outside.
inline std::vector<Eigen::Vector3d> inverse_stereographic_projection(const std::vector<Eigen::Vector2d>& uv, int p)
{
  const int nv = int(uv.size());
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for(int v = 0; v < nv; ++v)
    if(v != p) centre += uv[std::size_t(v)] / double(nv - 1);
  std::vector<double> radius;
  for(int v = 0; v < nv; ++v)
    if(v != p) radius.push_back((uv[std::size_t(v)] - centre).norm());
  std::nth_element(radius.begin(), radius.begin() + std::ptrdiff_t(radius.size() / 2), radius.end());
  const double scale = radius[radius.size() / 2] > 0 ? 1.0 / radius[radius.size() / 2] : 1.0;
  std::vector<Eigen::Vector3d> position(std::size_t(nv), Eigen::Vector3d(0, 0, 1));
  for(int v = 0; v < nv; ++v) {
    if(v == p) continue;
    const Eigen::Vector2d q = (uv[std::size_t(v)] - centre) * scale;
    const double r2 = q.squaredNorm();
    position[std::size_t(v)] = Eigen::Vector3d(2 * q.x(), -2 * q.y(), r2 - 1) / (r2 + 1);
  }
  return position;
}

// Moebius normalisation (spherical_embedding(), step 4): Newton's method on the sum of Busemann
// functions, in the frame where the current estimate is the centre (there the gradient is -2 c and the
// Hessian 4 (I - M)), backtracking on the centroid's norm; at most 100 iterations.
template <typename Embedding>
void centre_by_moebius_map(const Intrinsic_triangulation& itri, Embedding& emb)
{
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  std::vector<double> weight(std::size_t(nv), 0.0);
  double total = 0;
  for(int f = 0; f < nf; ++f) {
    const double a = heron_area(itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2));
    for(int v : itri.face_vertices(std::size_t(f))) weight[std::size_t(v)] += a / 3;
    total += a;
  }
  for(double& w : weight) w /= total;
  auto centroid = [&](const std::vector<Eigen::Vector3d>& x) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for(int v = 0; v < nv; ++v) c += weight[std::size_t(v)] * x[std::size_t(v)];
    return c;
  };
  const std::size_t max_centring = 100;
  Eigen::Vector3d mean_point = centroid(emb.position);
  std::vector<Eigen::Vector3d> trial(static_cast<std::size_t>(nv));
  for(;; ++emb.centring_iterations) {
    emb.centre_offset = mean_point.norm();
    if(emb.centre_offset <= 1e-9) break;
    if(!std::isfinite(emb.centre_offset))
      throw Convergence_failure("spherical embedding: the planar layout is not finite (the flat metric's scale factors "
                                "overflow: the surface has parts too thin or too long for a conformal map to the sphere)",
                                std::numeric_limits<double>::infinity());
    if(emb.centring_iterations >= max_centring)
      throw Convergence_failure("spherical embedding: the Moebius normalisation left the area centroid at " +
                                    std::to_string(emb.centre_offset) + " from the centre after " +
                                    std::to_string(max_centring) + " iterations",
                                emb.centre_offset);
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    for(int v = 0; v < nv; ++v) M += weight[std::size_t(v)] * emb.position[std::size_t(v)] * emb.position[std::size_t(v)].transpose();
    Eigen::Vector3d z = (2 * (Eigen::Matrix3d::Identity() - M)).fullPivLu().solve(mean_point);
    if(!z.allFinite()) z = mean_point;  // all the area on two antipodal points: no curvature to use
    if(z.norm() > 0.9) z *= 0.9 / z.norm();  // stay well inside the ball; the next steps go on
    // backtracking on |centroid| (the gradient's norm, which Newton's direction decreases)
    for(int k = 0; k < 40; ++k, z *= 0.5) {
      for(int v = 0; v < nv; ++v) trial[std::size_t(v)] = ball_translation(emb.position[std::size_t(v)], z);
      const Eigen::Vector3d ct = centroid(trial);
      if(ct.norm() < emb.centre_offset || k == 39) {
        mean_point = ct;
        break;
      }
    }
    emb.position.swap(trial);
  }
}

// The checks of the spherical layout (no chordal triangle below 1e-14 in area, none inverted, the sphere
// covered once) and its measures: the angle distortion and the conformal factor (paper eq. 6, with the
// chordal areas). Convergence_failure naming the reason otherwise.
template <typename Embedding>
void check_spherical_layout_and_measure(const Intrinsic_triangulation& itri, Embedding& emb)
{
  const double pi = 3.14159265358979323846;
  const int nf = int(itri.number_of_faces());
  std::size_t inverted = 0, tiny = 0;
  std::vector<double> chordal(std::size_t(nf), 0.0);
  double sum_distortion = 0, covered = 0;
  emb.angle_distortion_max = 0;
  for(int f = 0; f < nf; ++f) {
    const auto& c = itri.face_vertices(std::size_t(f));
    const Eigen::Vector3d& A = emb.position[std::size_t(c[0])];
    const Eigen::Vector3d& B = emb.position[std::size_t(c[1])];
    const Eigen::Vector3d& C = emb.position[std::size_t(c[2])];
    const double area = 0.5 * (B - A).cross(C - A).norm();
    chordal[std::size_t(f)] = area;
    if(!(area > 1e-14))
      ++tiny;
    else if(!(A.dot(B.cross(C)) > 0))
      ++inverted;
    covered += spherical_triangle_area(A, B, C);
    bool d1, d2;
    const auto in = corner_angles({{itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2)}}, d1);
    const auto out = corner_angles({{(B - A).norm(), (C - B).norm(), (A - C).norm()}}, d2);
    for(int k = 0; k < 3; ++k) {
      const double d = std::abs(in[k] - out[k]) * 180 / pi;
      sum_distortion += d;
      emb.angle_distortion_max = std::max(emb.angle_distortion_max, d);
    }
  }
  emb.angle_distortion_mean = sum_distortion / (3.0 * nf);
  if(tiny > 0)
    throw Convergence_failure("spherical embedding: " + std::to_string(tiny) +
                                  " triangles are too small on the sphere to be represented (area below 1e-14 of the unit "
                                  "sphere): conformal maps shrink long protrusions (legs, tails, thin handles) exponentially; "
                                  "such a surface cannot be remeshed through the sphere in double precision",
                              double(tiny));
  if(inverted > 0)
    throw Convergence_failure("spherical embedding: the layout has " + std::to_string(inverted) +
                                  " inverted or flat triangles on the sphere (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)",
                              double(inverted));
  // every triangle is positive, so the areas add up to 4 pi times the number of times the sphere is covered
  if(!(std::abs(covered - 4 * pi) <= 1e-6 * 4 * pi))
    throw Convergence_failure("spherical embedding: the triangles cover the sphere " + std::to_string(covered / (4 * pi)) +
                                  " times instead of once (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)",
                              std::abs(covered - 4 * pi));
  emb.conformal_factor = vertex_conformal_factors(itri, chordal);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_SPHERICAL_MAP_H
