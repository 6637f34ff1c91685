// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_SPHERICAL_EMBEDDING_H
#define ANISO_CONFORMAL_SPHERICAL_EMBEDDING_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/euclidean_conformal_metric.h>
#include <Aniso_conformal/internal/conformal/layout.h>
#include <Aniso_conformal/internal/conformal/spherical_map.h>
#include <Aniso_conformal/internal/intrinsic/midpoint_split.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
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
  /// triangles of the disk (the surface minus the star of the puncture) flat in the planar metric at the
  /// end of the solve (0 normally; the star's own triangles hold the point at infinity, have no planar
  /// shape, and are judged on the sphere instead)
  std::size_t degenerate_triangles = 0;
  std::size_t flips = 0;                  ///< intrinsic Delaunay flips (the first pass on the whole surface, then the solve)
  /// seam edges (between a hole's patch and the surface) split at their midpoints after an attempt whose
  /// planar metric flattened a triangle onto them (0 when the first attempt embeds)
  std::size_t seam_splits = 0;
  /// `true` if the first attempt failed and the puncture was then chosen far from the holes' patches
  bool puncture_away_from_patches = false;
  std::size_t centring_iterations = 0;    ///< iterations of the Moebius normalisation
  double centre_offset = 0;               ///< norm of the area centroid after the Moebius normalisation
  /// angle distortion of the map: |corner angle of the chordal triangle - corner angle with the adjusted
  /// lengths|, in degrees, mean over all corners
  double angle_distortion_mean = 0;
  double angle_distortion_max = 0;  ///< the same, maximum over all corners (degrees)
};


namespace internal {

// one attempt of spherical_embedding() (its documentation gives the method); when it fails on triangles
// flat in the planar metric and `obtuse_seams` is given, the seam edges facing an angle of at least 90
// degrees in that metric (ends: tail, head) are put there first
// (`away_from_patches`: the puncture far from the holes' patches, choose_puncture())
template <typename NamedParameters>
Spherical_embedding spherical_embedding_once(Intrinsic_triangulation& itri, const NamedParameters& np,
                                             std::vector<std::pair<int, int>>* obtuse_seams, bool away_from_patches = false)
{
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  internal::require_closed_surface(itri, "spherical_embedding()", "the sphere", [](int g) { return g == 0; }, "genus 0");

  // ---- 1. intrinsic Delaunay flips on the whole surface (the solver's first pass, with every vertex
  // fixed: no Newton step), so that some star is Delaunay with a margin; they keep the metric
  Spherical_embedding emb;
  {
    Spherical_embedding delaunay;
    internal::solve_euclidean_conformal_metric(itri, std::vector<char>(std::size_t(nv), 1), np, "spherical embedding", delaunay);
    emb.flips = delaunay.flips;
  }
  emb.puncture = internal::choose_puncture(itri, away_from_patches);
  const int p = emb.puncture;

  // ---- 2. the flat metric of the disk (the surface minus the open star of p), the inversion's data on p's link
  std::vector<char> fixed(std::size_t(nv), 0), keep(std::size_t(nv), 0);
  keep[std::size_t(p)] = 1;
  const std::vector<double> fixed_u = internal::inversion_data(itri, p, fixed);
  const std::size_t delaunay_flips = emb.flips;
  internal::solve_euclidean_conformal_metric(itri, fixed, np, "spherical embedding", emb, &keep, &fixed_u);
  emb.flips += delaunay_flips;
  auto in_star = [&](int f) {
    const auto& c = itri.face_vertices(std::size_t(f));
    return c[0] == p || c[1] == p || c[2] == p;
  };
  // the solver counts every face; the star's (all corners fixed, in no angle sum that is solved) has
  // lengths scaled by the inversion's data, which give it no shape in the plane: judged on the sphere
  emb.degenerate_triangles = 0;
  for(int f = 0; f < nf; ++f)
    if(!in_star(f)) {
      bool deg;
      internal::corner_angles(internal::scaled_face_lengths(itri, f, emb.u), deg);
      if(deg) ++emb.degenerate_triangles;
    }
  if(emb.degenerate_triangles > 0 && obtuse_seams)
    for(int f = 0; f < nf; ++f) {
      if(in_star(f)) continue;
      const std::array<double, 3> l = internal::scaled_face_lengths(itri, f, emb.u);
      for(int k = 0; k < 3; ++k)
        if(itri.is_seam_edge(3 * f + k) && !(l[k] * l[k] < l[(k + 1) % 3] * l[(k + 1) % 3] + l[(k + 2) % 3] * l[(k + 2) % 3]))
          obtuse_seams->emplace_back(itri.tail(3 * f + k), itri.head(3 * f + k));
    }
  if(emb.degenerate_triangles > 0)
    throw Convergence_failure("spherical embedding: " + std::to_string(emb.degenerate_triangles) +
                                  " triangles are flat in the planar metric (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)",
                              double(emb.degenerate_triangles));
  // unfold the disk breadth-first (every face but the star of p), each vertex once
  std::vector<std::array<double, 3>> L(static_cast<std::size_t>(nf));
  for(int f = 0; f < nf; ++f) L[std::size_t(f)] = internal::scaled_face_lengths(itri, f, emb.u);
  int f0 = 0;
  while(in_star(f0)) ++f0;  // the star is not everything: the link is a simple cycle of length >= 3
  std::vector<Eigen::Vector2d> uv(std::size_t(nv), Eigen::Vector2d::Zero());
  std::vector<char> placed(std::size_t(nv), 0), done;
  internal::unfold_breadth_first(itri, L, f0, Eigen::Vector2d(0, 0), Eigen::Vector2d(L[std::size_t(f0)][0], 0),
                                 [&](int h) { return !in_star(Intrinsic_triangulation::face(itri.twin(h))); }, internal::third_point,
                                 done, &uv, &placed);

  // ---- 3. inverse stereographic projection, 4. Moebius normalisation
  emb.position = internal::inverse_stereographic_projection(uv, p);
  internal::centre_by_moebius_map(itri, emb);

  // ---- checks, conformal factor and angle distortion
  internal::check_spherical_layout_and_measure(itri, emb);
  return emb;
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
 * Seams (the loops between the surface and the patches that close its holes, `remesh()`; issue 15) never
 * flip, and the planar metric can flatten a triangle onto one (CGAL's ChineseDragon-10kv and lion,
 * isotropic, at 2000 vertices: a vertex of a thin triangle along a loop scaled onto the seam edge). When
 * the first attempt on a triangulation with seams fails (any `Convergence_failure`), all of the above is
 * done again on the triangulation as it was given with the puncture chosen far from the patches: among
 * the vertices whose distance along the edges to the nearest vertex of a patch face is at least half the
 * largest such distance (`Spherical_embedding::puncture_away_from_patches`; a puncture on a seam or in a
 * patch puts the inversion's log singularity next to seam edges). If that fails with triangles flat
 * in the planar metric, the seam edges that face an angle of 90 degrees or more in that attempt's planar
 * metric are split at their midpoints in the triangulation as it was given (the halves and the medians of
 * its two triangles, the new vertex on the seam, `Spherical_embedding::seam_splits`) and it is solved
 * again (the puncture still far from the patches), at most 3 more times; `itri` then has these new
 * vertices. A triangulation without seams, or one that embeds at the first attempt, is not touched.
 *
 * `Spherical_embedding::angle_distortion_mean` and `angle_distortion_max` compare every corner angle of
 * the chordal triangles, those of the star of `p` included, with the one of `itri`'s lengths. Where the
 * Newton solve flipped an edge, `itri` holds its Ptolemy length, which keeps the conformal class but is
 * not a length of the metric (the triangle may even be flat with it): near such flips the figure
 * overstates the distortion.
 *
 * \param itri a closed genus-0 triangulation with valid edge lengths (after `adjust_edge_lengths()`);
 *        its edges may be flipped (those of the puncture's star only by the first, metric-preserving,
 *        Delaunay pass); its vertices are not changed, but seam edges may be split (above)
 * \param np optional named parameters: `max_conformal_iterations` (default 100), `conformal_tolerance`
 *        (default `1e-9`), `max_flips_per_edge` (default 50), `visitor`
 *        (`on_iteration(Stage::EMBEDDING, it, bound, residual)`)
 * \throws Invalid_input if `itri` has a boundary, is not of genus 0, no vertex has a simple link, or its
 *         edge lengths are not set (`Intrinsic_triangulation::has_edge_lengths()`)
 * \throws Convergence_failure if Newton's method or the normalisation does not converge within its bound
 *         (with the angle-sum error or the centroid offset reached), or a triangle is flat in the planar
 *         metric, or a chordal triangle is inverted or flat, or the triangles cover the sphere more than
 *         once (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Spherical_embedding spherical_embedding(Intrinsic_triangulation& itri, const NamedParameters& np = parameters::default_values())
{
  internal::require_edge_lengths(itri, "spherical_embedding()");
  bool seams = false;
  for(int v = 0; v < int(itri.number_of_vertices()) && !seams; ++v) seams = itri.seam(v) >= 0;
  if(!seams) return internal::spherical_embedding_once(itri, np, nullptr);
  // a seam edge never flips, and the planar metric can flatten the triangle on it: then the puncture is
  // chosen far from the patches and it is solved again; if that fails too, its seam edges facing an
  // obtuse angle in that metric are split in the triangulation as it was given, and it is solved again
  // (at most 3 more attempts, the puncture still far from the patches)
  Intrinsic_triangulation entry = itri;  // the triangulation as given: each attempt flips `itri`
  std::size_t splits = 0;
  try {
    return internal::spherical_embedding_once(itri, np, nullptr);
  } catch(const Convergence_failure&) {
    itri = entry;
  }
  for(int attempt = 0;; ++attempt) {
    std::vector<std::pair<int, int>> obtuse;
    try {
      Spherical_embedding emb = internal::spherical_embedding_once(itri, np, &obtuse, true);
      emb.seam_splits = splits;
      emb.puncture_away_from_patches = true;
      return emb;
    } catch(const Convergence_failure& e) {
      std::size_t made = 0;
      if(attempt < 3) {
        std::sort(obtuse.begin(), obtuse.end());
        obtuse.erase(std::unique(obtuse.begin(), obtuse.end()), obtuse.end());
        made = internal::split_edges_at_midpoints(entry, obtuse, [&](int h) { return entry.is_seam_edge(h); });
      }
      if(made == 0)
        throw Convergence_failure(std::string(e.what()) + " (also with the puncture far from the holes' patches" +
                                      (splits > 0 ? ", after " + std::to_string(splits) + " seam edges of the holes' loops were split in " +
                                                        std::to_string(attempt) + " more attempts"
                                                  : std::string()) +
                                      ")",
                                  e.residual());
      splits += made;
      itri = entry;
    }
  }
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_SPHERICAL_EMBEDDING_H
