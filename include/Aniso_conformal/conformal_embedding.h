// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_CONFORMAL_EMBEDDING_H
#define ANISO_CONFORMAL_CONFORMAL_EMBEDDING_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/internal/conformal/euclidean_conformal_metric.h>
#include <Aniso_conformal/internal/conformal/layout.h>
#include <Aniso_conformal/internal/conformal/planar_boundary.h>
#include <Aniso_conformal/internal/domains/simple_polygon_2.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

/// \file conformal_embedding.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * a conformal embedding of a disk-topology `Intrinsic_triangulation` into the plane (stage 3)
 */
struct Planar_embedding {
  std::vector<Eigen::Vector2d> uv;         ///< domain position of each vertex
  /// log scale factor of each vertex: 0 on the boundary with `Planar_boundary::KEEP_LENGTHS`; with
  /// `KEEP_SHAPE` shifted by a constant so that the layout's area is the adjusted (metric) area
  std::vector<double> u;
  std::vector<double> conformal_factor;    ///< `cf(v)`: adjusted area around v over domain area around v (paper eq. 6)
  std::size_t iterations = 0;              ///< Newton iterations (of the solve that was kept)
  /// max |target - angle sum| over the vertices solved for at the end (radians): interior vertices
  /// (target `2 pi`), and with `KEEP_SHAPE` the boundary vertices (target `pi` minus the turning angle)
  double residual = 0;
  std::size_t degenerate_triangles = 0;    ///< triangles treated as flat at the end of the solve (0 normally)
  std::size_t flips = 0;                   ///< intrinsic Delaunay flips made during the solve
  /// what the boundary kept: `KEEP_LENGTHS` or `KEEP_SHAPE` (`AUTOMATIC` resolves to one of them)
  Planar_boundary boundary = Planar_boundary::KEEP_SHAPE;
  /// `KEEP_SHAPE` only: `true` if the input's outline would have touched or crossed itself in the
  /// layout (a boundary that touches itself), so reflex turns were dropped and the layout is convex
  bool convex_boundary = false;
  /// `KEEP_SHAPE` only: `2 pi` minus the sum of the input's boundary turning angles (radians): the
  /// total Gaussian curvature of a curved patch, rounding on a planar input; spread over the boundary
  double turning_defect = 0;
  /// the turning angle of the layout's boundary at each boundary vertex (`pi` minus its angle sum in
  /// the layout; 0 elsewhere), radians: with `KEEP_SHAPE` the prescribed one, within the tolerance
  std::vector<double> boundary_turning;
  /// boundary edges split because an interior vertex encroached on them, after a first attempt whose
  /// layout inverted (0 normally; see `conformal_embedding()`)
  std::size_t boundary_splits = 0;
};


namespace internal {

// conformal_embedding() on `itri` as it is (no boundary split)
template <typename NamedParameters>
Planar_embedding conformal_embedding_once(Intrinsic_triangulation& itri, const NamedParameters& np)
{
  const double pi = 3.14159265358979323846;
  const int nv = int(itri.number_of_vertices());
  std::vector<char> boundary(std::size_t(nv), 0);
  for(int v = 0; v < nv; ++v) boundary[std::size_t(v)] = itri.is_boundary_vertex(v);
  if(std::find(boundary.begin(), boundary.end(), 1) == boundary.end())
    throw Invalid_input("conformal_embedding(): the triangulation has no boundary (not a disk)");
  // the boundary loop as halfedges, found again after every solve: a flip renumbers the halfedges of its two faces
  auto boundary_loop = [&] { return internal::boundary_halfedge_loop(itri, "conformal_embedding()"); };

  Planar_embedding emb;
  const Planar_boundary requested = internal::planar_boundary(np);
  if(requested != Planar_boundary::KEEP_SHAPE) {  // KEEP_LENGTHS, or AUTOMATIC's first choice
    emb.boundary = Planar_boundary::KEEP_LENGTHS;
    try {
      internal::solve_euclidean_conformal_metric(itri, boundary, np, "conformal embedding", emb);
      const std::vector<int> loop = boundary_loop();
      internal::lay_out_planar_embedding(itri, loop, emb);
      if(internal::planar_boundary_is_embedded(emb.uv, itri, loop, 0.0)) return emb;
    } catch(const Convergence_failure&) {
      if(requested == Planar_boundary::KEEP_LENGTHS) throw;
    }
    if(requested == Planar_boundary::KEEP_LENGTHS)
      throw Remeshing_failure("conformal embedding: with the boundary's metric lengths kept (Planar_boundary::KEEP_LENGTHS), "
                              "the layout's boundary crosses itself (the metric bends it too much); "
                              "Planar_boundary::KEEP_SHAPE (or the default, AUTOMATIC) keeps the input's outline instead");
    emb = Planar_embedding();  // AUTOMATIC: the input's outline instead (itri keeps its flips: the same surface)
  }
  emb.boundary = Planar_boundary::KEEP_SHAPE;

  // the input's outline first, a convex one if that is not embedded
  std::vector<char> gauge(std::size_t(nv), 0);
  gauge[std::size_t(itri.tail(boundary_loop()[0]))] = 1;  // u is defined up to a constant: fixed at one vertex, shifted after
  for(const bool convex : {false, true}) {
    std::vector<double> target(std::size_t(nv), 2 * pi);
    std::vector<int> loop = boundary_loop();
    const std::vector<double> turn = internal::boundary_turning_angles(itri, loop, convex, emb.turning_defect);
    for(std::size_t i = 0; i < loop.size(); ++i) target[std::size_t(itri.tail(loop[i]))] = pi - turn[i];
    emb.convex_boundary = convex;
    try {
      internal::solve_euclidean_conformal_metric(itri, gauge, np, "conformal embedding", emb, nullptr, nullptr, &target);
      internal::scale_to_adjusted_area(itri, emb.u);
      loop = boundary_loop();
      internal::lay_out_planar_embedding(itri, loop, emb);
    } catch(const Convergence_failure&) {
      if(convex) throw;
      continue;  // the input's outline could not be laid out: try the convex one
    }
    if(internal::planar_boundary_is_embedded(emb.uv, itri, loop, 1e-9)) return emb;
  }
  throw Remeshing_failure("conformal embedding: the layout's boundary touches or crosses itself even with a convex outline "
                          "(rounding on a background whose boundary is nearly flat everywhere?)");
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * computes a conformal embedding of the disk `itri` into the plane (stage 3, DESIGN.md 3): discrete
 * conformal equivalence (Springborn, Schroeder, Pinkall 2008) with per-vertex log scales `u` and scaled
 * lengths `l'_ij = exp((u_i + u_j) / 2) l_ij`, angle sum `2 pi` at interior vertices, solved by Newton's
 * method with the cotangent Laplacian as Hessian (CHOLMOD's sparse Cholesky when the build found it and the system is large, else Eigen's SimplicialLDLT) and a backtracking line
 * search; then laid out by unfolding triangles breadth-first, and the conformal factor computed per
 * vertex (paper eq.\ 6). What the boundary keeps is the named parameter `planar_boundary`:
 *
 * - `Planar_boundary::AUTOMATIC` (the default): `KEEP_LENGTHS` when its layout is embedded, else
 *   `KEEP_SHAPE` (measured on the regression set: the paper's map gives the better meshes on images and
 *   on the paper's figures, e.g. the CT slice to 1500 vertices G_avg 0.845 against 0.828 and theta_min
 *   6.9 against 0.5 degrees; the outline-keeping map is the one that exists on a swirling field at a
 *   re-entrant corner or a boundary that touches itself).
 * - `Planar_boundary::KEEP_SHAPE`: at each boundary vertex the angle sum is prescribed,
 *   `pi` minus the input's turning angle there (`pi - Intrinsic_triangulation::input_angle_sum()`: the
 *   geodesic curvature of the input's boundary, measured on the input, not in the metric), the sum made
 *   `2 pi` by Gauss-Bonnet (on a curved patch the difference, its total Gaussian curvature, is spread
 *   over the non-corner boundary vertices); `u` is free on the boundary too (fixed at one vertex for the
 *   scale, then shifted so that the layout's area is the adjusted area). This is the prescribed
 *   geodesic curvature boundary condition of Springborn, Schroeder and Pinkall (2008, section 4) with
 *   the input's own curvature, as in boundary first flattening (Sawhney and Crane 2017): the layout has
 *   the input's outline (straight runs stay straight, corners keep their angle: an L stays an L, a
 *   square becomes a rectangle) and the boundary's lengths adapt, so the conformal factor stays bounded
 *   where `u = 0` makes it explode (a strong image metric near the border). If that outline touches or
 *   crosses itself in the layout (checked exactly, with a margin of `1e-9` of the layout's diameter: a
 *   boundary that touches itself, as a ring cut open along a zero-width slit), or the solve fails, it is
 *   solved again with a convex outline (reflex turns dropped, the others scaled to `2 pi`), which is
 *   always embedded (`Planar_embedding::convex_boundary`).
 * - `Planar_boundary::KEEP_LENGTHS` (the paper's): `u = 0` on the boundary, which keeps the boundary's
 *   metric lengths and bends it as the metric demands; its layout is not guaranteed to be embedded
 *   (then a `Remeshing_failure`).
 *
 * Before every evaluation the triangulation is made intrinsically Delaunay for the scaled lengths
 * (Gillespie, Springborn and Crane 2021): interior edges are flipped, the new edge's length given by
 * Ptolemy's relation, which is invariant under the scaling. This keeps every triangle valid during the
 * solve, so metrics the paper had to tame (strong images, high stretch) embed without inverted
 * triangles. `itri` is modified by these flips (its vertices, boundary and corners are not).
 *
 * A triangle whose long edge is on the boundary cannot be flipped: where an interior vertex encroaches
 * on a boundary edge (an obtuse angle there) the scaling can flatten the triangle onto the boundary and
 * the layout inverts (CGAL's cylinder_locally_refined.off, isotropic, at 2000 vertices: three such
 * triangles flat at the end of every solve). When an attempt fails so (a `Convergence_failure`), the
 * encroached boundary edges of the triangulation as it was given are split at their midpoints until none
 * is left (`internal::split_encroached_boundary_edges()`, Ruppert's rule for the boundary, the lengths
 * kept: halves and medians of the flat triangles) and everything above is done again on it
 * (`Planar_embedding::boundary_splits`); `itri` then has these new boundary vertices. An input that
 * embeds at the first attempt is not touched.
 *
 * \param itri a disk-topology triangulation with valid edge lengths (after `adjust_edge_lengths()`);
 *        interior edges may be flipped, boundary edges split
 * \param np optional named parameters: `planar_boundary` (default `Planar_boundary::AUTOMATIC`),
 *        `max_conformal_iterations` (default 100), `conformal_tolerance` (default `1e-9`, on the max
 *        angle-sum error in radians), `max_flips_per_edge` (default 50: the intrinsic Delaunay flips of
 *        one evaluation are at most that many per interior edge, plus 100), `visitor`
 *        (`on_iteration(Stage::EMBEDDING, it, bound, residual)`).
 * \returns the layout `uv` (in the units of the metric lengths: with `KEEP_SHAPE` its area is the adjusted
 *          area), `u`, the conformal factor per vertex, the solver's figures
 * \throws Invalid_input if `itri` has no boundary, or its edge lengths are not set (`Intrinsic_triangulation::has_edge_lengths()`)
 * \throws Convergence_failure if Newton's method does not reach the tolerance within the bound, if the
 *         factorisation fails, or if the layout has inverted triangles (with the residual reached)
 * \throws Remeshing_failure if the layout's boundary touches or crosses itself: with `KEEP_LENGTHS`
 *         (the message suggests `KEEP_SHAPE`), or with `KEEP_SHAPE` even once made convex (not met)
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Planar_embedding conformal_embedding(Intrinsic_triangulation& itri,
                                     const NamedParameters& np = parameters::default_values())
{
  internal::require_edge_lengths(itri, "conformal_embedding()");
  Intrinsic_triangulation entry = itri;  // kept for a second attempt: the first one flips `itri`
  std::size_t splits = 0;
  try {
    return internal::conformal_embedding_once(itri, np);
  } catch(const Convergence_failure&) {
    const internal::Newton_bounds bounds = internal::Newton_bounds::from(np);
    internal::make_intrinsic_delaunay(entry, bounds.flips_per_edge, "conformal embedding");
    splits = internal::split_encroached_boundary_edges(entry, bounds.flips_per_edge, "conformal embedding");
    if(splits == 0) throw;
    itri = std::move(entry);
  }
  Planar_embedding emb = internal::conformal_embedding_once(itri, np);
  emb.boundary_splits = splits;
  return emb;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_CONFORMAL_EMBEDDING_H
