// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_CONFORMAL_EMBEDDING_H
#define ANISO_CONFORMAL_CONFORMAL_EMBEDDING_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/internal/conformal/euclidean_conformal_metric.h>
#include <Aniso_conformal/internal/conformal/layout.h>
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
  std::vector<double> u;                   ///< log scale factor of each vertex (0 on the boundary)
  std::vector<double> conformal_factor;    ///< `cf(v)`: adjusted area around v over domain area around v (paper eq. 6)
  std::size_t iterations = 0;              ///< Newton iterations
  double residual = 0;                     ///< max |2 pi - angle sum| over interior vertices at the end
  std::size_t degenerate_triangles = 0;    ///< triangles treated as flat at the end of the solve (0 normally)
  std::size_t flips = 0;                   ///< intrinsic Delaunay flips made during the solve
};


/*!
 * \ingroup PkgAnisoConformalStages
 * computes a conformal embedding of the disk `itri` into the plane (stage 3, DESIGN.md 3): discrete
 * conformal equivalence (Springborn, Schroeder, Pinkall 2008) with per-vertex log scales `u`, scaled
 * lengths `l'_ij = exp((u_i + u_j) / 2) l_ij`, `u = 0` on the boundary (boundary lengths are kept) and
 * angle sum `2 pi` at interior vertices, solved by Newton's method with the cotangent Laplacian as
 * Hessian (CHOLMOD's sparse Cholesky when the build found it and the system is large, else Eigen's
 * SimplicialLDLT) and a backtracking line search; then laid out by unfolding triangles breadth-first, and the conformal factor
 * computed per vertex (paper eq.\ 6).
 *
 * Before every evaluation the triangulation is made intrinsically Delaunay for the scaled lengths
 * (Gillespie, Springborn and Crane 2021): interior edges are flipped, the new edge's length given by
 * Ptolemy's relation, which is invariant under the scaling. This keeps every triangle valid during the
 * solve, so metrics the paper had to tame (strong images, high stretch) embed without inverted
 * triangles. `itri` is modified by these flips (its vertices, boundary and corners are not).
 *
 * \param itri a disk-topology triangulation with valid edge lengths (after `adjust_edge_lengths()`);
 *        interior edges may be flipped
 * \param np optional named parameters: `max_conformal_iterations` (default 100), `conformal_tolerance`
 *        (default `1e-9`, on the max angle-sum error in radians), `max_flips_per_edge` (default 50: the
 *        intrinsic Delaunay flips of one evaluation are at most that many per interior edge, plus 100), `visitor`
 *        (`on_iteration(Stage::EMBEDDING, it, bound, residual)`).
 * \throws Invalid_input if `itri` has no boundary
 * \throws Convergence_failure if Newton's method does not reach the tolerance within the bound, if the
 *         factorisation fails, or if the layout has inverted triangles (with the residual reached)
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Planar_embedding conformal_embedding(Intrinsic_triangulation& itri,
                                     const NamedParameters& np = parameters::default_values())
{
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  std::vector<char> fixed(std::size_t(nv), 0);
  for(int v = 0; v < nv; ++v) fixed[v] = itri.is_boundary_vertex(v);
  if(std::find(fixed.begin(), fixed.end(), 1) == fixed.end())
    throw Invalid_input("conformal_embedding(): the triangulation has no boundary (not a disk)");

  Planar_embedding emb;
  internal::solve_euclidean_conformal_metric(itri, fixed, np, "conformal embedding", emb);

  // ---- layout: unfold breadth-first across the interior edges, each vertex placed once
  std::vector<std::array<double, 3>> L(nf);
  for(int f = 0; f < nf; ++f) L[f] = internal::scaled_face_lengths(itri, f, emb.u);
  emb.uv.assign(nv, Eigen::Vector2d::Zero());
  std::vector<char> placed(nv, 0), done;
  internal::unfold_breadth_first(itri, L, 0, Eigen::Vector2d(0, 0), Eigen::Vector2d(L[0][0], 0),
                                 [&](int h) { return itri.twin(h) >= 0; }, internal::third_point, done, &emb.uv, &placed);

  // ---- validity and conformal factor
  std::size_t inverted = 0;
  std::vector<double> domain_area(nf);
  for(int f = 0; f < nf; ++f) {
    const auto& c = itri.face_vertices(f);
    const Eigen::Vector2d e1 = emb.uv[c[1]] - emb.uv[c[0]], e2 = emb.uv[c[2]] - emb.uv[c[0]];
    const double a_dom = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    if(!(a_dom > 0)) ++inverted;
    domain_area[f] = std::max(a_dom, 0.0);
  }
  if(inverted > 0)
    throw Convergence_failure("conformal embedding: the layout has " + std::to_string(inverted) +
                                  " inverted or flat triangles (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)",
                              double(inverted));
  emb.conformal_factor = internal::vertex_conformal_factors(itri, domain_area);
  return emb;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_CONFORMAL_EMBEDDING_H
