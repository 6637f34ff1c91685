// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_SPHERICAL_EMBEDDING_H
#define ANISO_CONFORMAL_SPHERICAL_EMBEDDING_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/flat_conformal_newton.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <deque>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>
#include <vector>

/// \file spherical_embedding.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * a conformal embedding of a closed genus-0 `Intrinsic_triangulation` onto the unit sphere (stage 3):
 * one point of the sphere per vertex. The background triangles in the domain are the chordal (flat)
 * triangles between these points, counterclockwise seen from outside the sphere.
 */
struct Spherical_embedding {
  std::vector<Eigen::Vector3d> position;  ///< per vertex of the triangulation, a unit vector
  /// log scale factor of each vertex in the planar solve (on the link of the puncture, the Dirichlet data
  /// `-2 log(l_pv / mean)`; 0 at the puncture, which is not part of the planar solve)
  std::vector<double> u;
  /// `cf(v)`: adjusted (Heron) area of the triangles around v over their chordal area on the sphere
  /// (paper eq. 6); the CVT density is `cf^2`, linear over each chordal triangle
  std::vector<double> conformal_factor;
  int puncture = -1;                      ///< the vertex sent to infinity by the planar map (then to a pole)
  std::size_t iterations = 0;             ///< Newton iterations of the planar solve
  double residual = 0;                    ///< max |2 pi - angle sum| over the free vertices at the end
  std::size_t degenerate_triangles = 0;   ///< triangles treated as flat at the end of the solve (0 normally)
  std::size_t flips = 0;                  ///< intrinsic Delaunay flips (the first pass on the whole surface, then the solve)
  std::size_t centring_iterations = 0;    ///< iterations of the Moebius normalisation
  double centre_offset = 0;               ///< norm of the area centroid after the Moebius normalisation
  /// angle distortion of the map: |corner angle of the chordal triangle - corner angle with the adjusted
  /// lengths|, in degrees, mean and maximum over all corners
  double angle_distortion_mean = 0, angle_distortion_max = 0;
};

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

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * computes a discrete conformal map of the closed genus-0 surface `itri` onto the unit sphere (stage 3
 * for genus 0, DESIGN.md 3), the image of each triangle being the chordal triangle of its corners:
 * 1. *puncture*: `itri` is first made intrinsically Delaunay (edge flips, which keep the metric); `p` is
 *    the vertex whose link edges are the most strictly Delaunay: the largest smallest margin
 *    `pi - (sum of the two angles facing the edge)` over its link edges, among the vertices whose link is
 *    a simple cycle; ties (within `1e-12`) go to the angle sum nearest `2 pi`, then to the smallest
 *    index. The star of `p` is then kept as it is (never flipped). The margin matters because of step 2:
 *    the inversion from `p` flattens the triangle beyond a link edge if its circumcircle passes through
 *    `p` (margin 0: on a grid of squares cut by diagonals, every vertex has such a link edge) and turns
 *    it over if the circle holds `p`;
 * 2. *planar map*: the surface minus the open star of `p` is a disk whose boundary is the link of `p`.
 *    Its flat discrete conformal metric (vertex scaling, Springborn, Schroeder and Pinkall 2008) with
 *    angle sum `2 pi` at every vertex off the closed star is solved by Newton's method with intrinsic
 *    Delaunay flips that never touch the star (as `conformal_embedding()`), with the Dirichlet data
 *    `u_v = -2 log(l_pv / mean)` on the link (`l_pv` the length of the edge `pv`, `mean` their geometric
 *    mean), starting from `u_v = -log(d_v / mean)` at the free vertices (`d_v` the shortest-path
 *    distance from `p` along the edges: 4 Newton iterations where `u = 0` takes 13 to 32); the disk is
 *    unfolded in the plane breadth-first;
 * 3. *inverse stereographic projection*: the plane, centred on the mean of the vertices and scaled so that
 *    their median distance to the centre is 1, to the unit sphere, `p` at the north pole (the outside of
 *    the link polygon, which holds infinity, is the cap of the star of `p`);
 * 4. *Moebius normalisation*: the hyperbolic translation of the ball that takes the centroid of the
 *    surface's area to the centre. Each vertex carries a third of the adjusted (Heron) area of its
 *    triangles, at its position on the sphere; the translation is the minimiser of the sum of Busemann
 *    functions `F(z) = sum_v w_v log(|x_v - z|^2 / (1 - |z|^2))`, which is convex along hyperbolic
 *    geodesics and whose gradient at `0` is `-2` times the centroid (the conformal barycentre of Douady
 *    and Earle 1986; cf. the Moebius centring of Baden, Crane and Kazhdan 2018). It is found by Newton's
 *    method (Hessian `4 (I - sum_v w_v x_v x_v^T)` at `0`, the points moved after every step so that the
 *    current estimate is the centre), backtracking on the centroid's norm, until that is at most `1e-9`
 *    (at most 100 iterations; 0 to 5 in the tests). Without it most of the sphere is taken by a small part
 *    of the surface, and the CVT density `cf^2` spans many orders of magnitude.
 *
 * Why the Dirichlet data on the link: the stereographic projection from `p` is an inversion centred at
 * `p`, which changes the distance of two points `a`, `b` to `|ab| / (|pa| |pb|)` (times a constant); the
 * data above does exactly this to the link edges. With it, every chord on the sphere, the star's
 * included, is the adjusted (or, after a flip, Ptolemy) length of its edge times `exp((U_a + U_b) / 2)`
 * for per-vertex factors `U`: the map is discretely conformal on the whole closed surface. Moebius maps
 * of the sphere also scale chords by per-vertex factors, so the normalisation keeps this.
 *
 * Why this route rather than the paper's spherical harmonic map (a heat flow of the Gauss map under
 * area constraints): that flow converges slowly, drifts tangentially, and can fold triangles under a
 * strong metric, with no guarantee of a bijection. Here the work is the convex, flip-robust Newton
 * solve of the plane shared with the disk and the torus, exact up to its tolerance, and the only
 * spherical step, the Moebius centring, is a 3-dimensional convex problem.
 *
 * Checks: every chordal triangle is positively oriented seen from outside (`det(a, b, c) > 0`) and not
 * flat, and their spherical areas add up to `4 pi` (the map covers the sphere once).
 *
 * `Spherical_embedding::angle_distortion_mean` and `angle_distortion_max` compare every corner angle of
 * the chordal triangles, those of the star of `p` included, with the one of `itri`'s lengths. Where the
 * Newton solve flipped an edge, `itri` holds its Ptolemy length, which keeps the conformal class but is
 * not a length of the metric (the triangle may even be flat with it): near such flips the figure
 * overstates the distortion.
 *
 * \param itri a closed genus-0 triangulation with valid edge lengths (after `adjust_edge_lengths()`);
 *        its edges may be flipped (those of the puncture's star only by the first, metric-preserving,
 *        Delaunay pass); its vertices are not changed
 * \param np optional named parameters: `max_conformal_iterations` (default 100), `conformal_tolerance`
 *        (default `1e-9`), `max_flips_per_edge` (default 50), `visitor`
 *        (`on_iteration(Stage::EMBEDDING, it, bound, residual)`)
 * \throws Invalid_input if `itri` has a boundary, is not of genus 0, or no vertex has a simple link
 * \throws Convergence_failure if Newton's method or the normalisation does not converge within its bound
 *         (with the angle-sum error or the centroid offset reached), or a triangle is flat in the planar
 *         metric, or a chordal triangle is inverted or flat, or the triangles cover the sphere more than
 *         once (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Spherical_embedding spherical_embedding(Intrinsic_triangulation& itri, const NamedParameters& np = parameters::default_values())
{
  const double pi = 3.14159265358979323846;
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces()), nh = int(itri.number_of_halfedges());
  for(int h = 0; h < nh; ++h)
    if(itri.is_boundary_edge(h))
      throw Invalid_input("spherical_embedding(): the triangulation has a boundary; the sphere needs a closed surface");
  const int chi = nv - nh / 2 + nf;
  if(chi != 2)
    throw Invalid_input("spherical_embedding(): the surface has genus " + std::to_string((2 - chi) / 2) +
                        "; the sphere needs a closed surface of genus 0");

  // ---- 1. intrinsic Delaunay flips on the whole surface (the solver's first pass, with every vertex
  // fixed: no Newton step), so that some star is Delaunay with a margin; they keep the metric
  Spherical_embedding emb;
  {
    Spherical_embedding delaunay;
    internal::solve_flat_conformal_metric(itri, std::vector<char>(std::size_t(nv), 1), np, "spherical embedding", delaunay);
    emb.flips = delaunay.flips;
  }

  // the puncture: the vertex whose link edges are the most strictly Delaunay (the Delaunay margin
  // pi - (sum of the two angles facing an edge), smallest over the link edges), among those whose link
  // is a simple cycle (otherwise the rest is no disk); then the flattest (angle sum nearest 2 pi), then
  // the smallest index. A link edge whose margin is 0 is cocircular with p: the inversion from p makes
  // the triangle beyond it flat, which the planar metric cannot hold. (A spoke of margin 0 only makes
  // the link polygon straight at a vertex, which is harmless.)
  std::vector<std::array<double, 3>> angle(static_cast<std::size_t>(nf));  // angle[f][k] at corner k
  std::vector<double> angle_sum(std::size_t(nv), 0.0);
  for(int f = 0; f < nf; ++f) {
    bool deg;
    angle[std::size_t(f)] = internal::corner_angles({{itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2)}}, deg);
    const auto& c = itri.face_vertices(std::size_t(f));
    for(int k = 0; k < 3; ++k) angle_sum[std::size_t(c[k])] += angle[std::size_t(f)][std::size_t(k)];
  }
  auto facing = [&](int h) { return angle[std::size_t(h / 3)][std::size_t((h % 3 + 2) % 3)]; };  // the angle facing h
  auto margin = [&](int h) { return pi - facing(h) - facing(itri.twin(h)); };
  double best_margin = -std::numeric_limits<double>::infinity();
  for(int v = 0; v < nv; ++v) {
    const std::vector<int> out = itri.outgoing_halfedges(v);
    std::vector<int> link;
    double m = std::numeric_limits<double>::infinity();
    for(int h : out) {
      link.push_back(itri.head(h));
      m = std::min(m, margin(Intrinsic_triangulation::next(h)));  // the link edge facing p in h's face
    }
    std::sort(link.begin(), link.end());
    if(link.size() < 3 || std::adjacent_find(link.begin(), link.end()) != link.end()) continue;
    const bool better = emb.puncture < 0 || m > best_margin + 1e-12 ||
                        (m >= best_margin - 1e-12 && std::abs(angle_sum[std::size_t(v)] - 2 * pi) <
                                                         std::abs(angle_sum[std::size_t(emb.puncture)] - 2 * pi));
    if(better) {
      emb.puncture = v;
      best_margin = std::max(best_margin, m);
    }
  }
  if(emb.puncture < 0)
    throw Invalid_input("spherical_embedding(): no vertex has a simple link (the triangulation has multiple edges everywhere)");
  const int p = emb.puncture;

  // ---- 2. the flat metric of the disk (the surface minus the open star of p), the inversion's data on p's link
  std::vector<char> fixed(std::size_t(nv), 0), keep(std::size_t(nv), 0);
  std::vector<double> fixed_u(std::size_t(nv), 0.0);
  keep[std::size_t(p)] = 1;
  fixed[std::size_t(p)] = 1;
  const std::vector<int> spokes = itri.outgoing_halfedges(p);
  double mean_log = 0;
  for(int h : spokes) mean_log += std::log(itri.length(h)) / double(spokes.size());
  for(int h : spokes) {
    fixed[std::size_t(itri.head(h))] = 1;
    fixed_u[std::size_t(itri.head(h))] = -2 * (std::log(itri.length(h)) - mean_log);
  }
  // the initial guess at the free vertices: half the inversion's factor, -log(d(p, v) / mean), d the
  // shortest-path distance from p along the edges. From u = 0 the far side of the surface is off by
  // about 2 log(diameter / link edge) and Newton spends its iterations in damped steps: measured, 13
  // iterations on the Fig. 10 ellipsoid, 16 at level 6, 32 on a round sphere; 4 on all three from this
  // guess, and never more elsewhere (bear, needles). The full factor (-2 log) overshoots: 6 everywhere.
  {
    std::vector<double> d(std::size_t(nv), std::numeric_limits<double>::infinity());
    typedef std::pair<double, int> Item;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
    d[std::size_t(p)] = 0;
    heap.push({0.0, p});
    while(!heap.empty()) {
      const Item top = heap.top();
      heap.pop();
      if(top.first > d[std::size_t(top.second)]) continue;
      for(int h : itri.outgoing_halfedges(top.second)) {
        const double dh = top.first + itri.length(h);
        if(dh < d[std::size_t(itri.head(h))]) {
          d[std::size_t(itri.head(h))] = dh;
          heap.push({dh, itri.head(h)});
        }
      }
    }
    for(int v = 0; v < nv; ++v)
      if(!fixed[std::size_t(v)] && std::isfinite(d[std::size_t(v)]) && d[std::size_t(v)] > 0)
        fixed_u[std::size_t(v)] = -(std::log(d[std::size_t(v)]) - mean_log);
  }
  const std::size_t delaunay_flips = emb.flips;
  internal::solve_flat_conformal_metric(itri, fixed, np, "spherical embedding", emb, &keep, &fixed_u);
  emb.flips += delaunay_flips;
  if(emb.degenerate_triangles > 0)
    throw Convergence_failure("spherical embedding: " + std::to_string(emb.degenerate_triangles) +
                                  " triangles are flat in the planar metric (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)",
                              double(emb.degenerate_triangles));

  // unfold the disk breadth-first (every face but the star of p), each vertex once
  std::vector<std::array<double, 3>> L(static_cast<std::size_t>(nf));
  for(int f = 0; f < nf; ++f) L[std::size_t(f)] = internal::scaled_face_lengths(itri, f, emb.u);
  auto in_star = [&](int f) {
    const auto& c = itri.face_vertices(std::size_t(f));
    return c[0] == p || c[1] == p || c[2] == p;
  };
  std::vector<Eigen::Vector2d> uv(std::size_t(nv), Eigen::Vector2d::Zero());
  std::vector<char> placed(std::size_t(nv), 0), done(std::size_t(nf), 0);
  std::deque<int> queue;
  int f0 = 0;
  while(in_star(f0)) ++f0;  // the star is not everything: the link is a simple cycle of length >= 3
  {
    const auto& c = itri.face_vertices(std::size_t(f0));
    uv[std::size_t(c[1])] = Eigen::Vector2d(L[std::size_t(f0)][0], 0);
    placed[std::size_t(c[0])] = placed[std::size_t(c[1])] = 1;
    queue.push_back(3 * f0);
  }
  while(!queue.empty()) {
    const int h = queue.front();
    queue.pop_front();
    const int f = Intrinsic_triangulation::face(h);
    if(done[std::size_t(f)] || in_star(f)) continue;
    done[std::size_t(f)] = 1;
    const int a = itri.tail(h), b = itri.head(h), c = itri.opposite_vertex(h), k = h % 3;
    if(!placed[std::size_t(c)]) {
      // corner k+2 = c; |ac| is halfedge k+2 (c->a), |bc| is halfedge k+1 (b->c)
      uv[std::size_t(c)] = internal::third_point(uv[std::size_t(a)], uv[std::size_t(b)], L[std::size_t(f)][std::size_t((k + 2) % 3)],
                                                  L[std::size_t(f)][std::size_t((k + 1) % 3)]);
      placed[std::size_t(c)] = 1;
    }
    for(int j = 0; j < 3; ++j) {
      const int t = itri.twin(3 * f + j);
      if(!done[std::size_t(Intrinsic_triangulation::face(t))]) queue.push_back(t);
    }
  }

  // ---- 3. inverse stereographic projection, centred on the mean and scaled to a median radius of 1 (a
  // first guess for step 4); y is mirrored because the projection from the north pole reverses the
  // orientation seen from outside
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for(int v = 0; v < nv; ++v)
    if(v != p) centre += uv[std::size_t(v)] / double(nv - 1);
  std::vector<double> radius;
  for(int v = 0; v < nv; ++v)
    if(v != p) radius.push_back((uv[std::size_t(v)] - centre).norm());
  std::nth_element(radius.begin(), radius.begin() + std::ptrdiff_t(radius.size() / 2), radius.end());
  const double scale = radius[radius.size() / 2] > 0 ? 1.0 / radius[radius.size() / 2] : 1.0;
  emb.position.assign(std::size_t(nv), Eigen::Vector3d(0, 0, 1));
  for(int v = 0; v < nv; ++v) {
    if(v == p) continue;
    const Eigen::Vector2d q = (uv[std::size_t(v)] - centre) * scale;
    const double r2 = q.squaredNorm();
    emb.position[std::size_t(v)] = Eigen::Vector3d(2 * q.x(), -2 * q.y(), r2 - 1) / (r2 + 1);
  }

  // ---- 4. Moebius normalisation: Newton's method on the sum of Busemann functions, in the frame where
  // the current estimate is the centre (there the gradient is -2 c and the Hessian 4 (I - M))
  std::vector<double> weight(std::size_t(nv), 0.0);
  double total = 0;
  for(int f = 0; f < nf; ++f) {
    const double a = internal::heron_area(itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2));
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
      for(int v = 0; v < nv; ++v) trial[std::size_t(v)] = internal::ball_translation(emb.position[std::size_t(v)], z);
      const Eigen::Vector3d ct = centroid(trial);
      if(ct.norm() < emb.centre_offset || k == 39) {
        mean_point = ct;
        break;
      }
    }
    emb.position.swap(trial);
  }

  // ---- checks, conformal factor and angle distortion
  std::size_t inverted = 0, tiny = 0;
  std::vector<double> adjusted(std::size_t(nv), 0.0), chordal(std::size_t(nv), 0.0);
  double sum_distortion = 0, covered = 0;
  emb.angle_distortion_max = 0;
  for(int f = 0; f < nf; ++f) {
    const auto& c = itri.face_vertices(std::size_t(f));
    const Eigen::Vector3d& A = emb.position[std::size_t(c[0])];
    const Eigen::Vector3d& B = emb.position[std::size_t(c[1])];
    const Eigen::Vector3d& C = emb.position[std::size_t(c[2])];
    const double area = 0.5 * (B - A).cross(C - A).norm();
    if(!(area > 1e-14))
      ++tiny;
    else if(!(A.dot(B.cross(C)) > 0))
      ++inverted;
    covered += internal::spherical_triangle_area(A, B, C);
    const double a_adj = internal::heron_area(itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2));
    bool d1, d2;
    const auto in = internal::corner_angles({{itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2)}}, d1);
    const auto out = internal::corner_angles({{(B - A).norm(), (C - B).norm(), (A - C).norm()}}, d2);
    for(int k = 0; k < 3; ++k) {
      adjusted[std::size_t(c[k])] += a_adj;
      chordal[std::size_t(c[k])] += area;
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
  emb.conformal_factor.resize(std::size_t(nv));
  for(int v = 0; v < nv; ++v) emb.conformal_factor[std::size_t(v)] = adjusted[std::size_t(v)] / chordal[std::size_t(v)];
  return emb;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_SPHERICAL_EMBEDDING_H
