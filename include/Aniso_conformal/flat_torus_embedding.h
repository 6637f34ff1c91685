// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_FLAT_TORUS_EMBEDDING_H
#define ANISO_CONFORMAL_FLAT_TORUS_EMBEDDING_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/euclidean_conformal_metric.h>
#include <Aniso_conformal/internal/conformal/layout.h>
#include <Aniso_conformal/internal/conformal/tree_cotree.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

/// \file flat_torus_embedding.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * a conformal embedding of a closed genus-1 `Intrinsic_triangulation` onto a flat torus `R^2 / L`
 * (stage 3): the fundamental domain unfolded in the plane and the lattice `L`.
 */
struct Flat_torus_embedding {
  /// per face of the triangulation, the positions of its three corners in the unfolded fundamental
  /// domain (counterclockwise); a vertex on the cut has one position per face around it, which
  /// differ by lattice vectors
  std::vector<std::array<Eigen::Vector2d, 3>> corner_uv;
  /// a reduced basis of the lattice (Lagrange-Gauss: `|a| <= |b|`, `|a.b| <= |a|^2 / 2`,
  /// `det(a, b) > 0`); the torus is the plane modulo integer combinations of `lattice[0]` and `lattice[1]`
  std::array<Eigen::Vector2d, 2> lattice;
  std::vector<double> u;                 ///< log scale factor of each vertex (0 at vertex 0)
  std::vector<double> conformal_factor;  ///< `cf(v)`: adjusted area around v over domain area around v (paper eq. 6)
  /// two closed vertex loops forming a homology basis (tree-cotree); their translations span the lattice
  std::array<std::vector<int>, 2> homology_basis;
  std::size_t iterations = 0;            ///< Newton iterations
  double residual = 0;                   ///< max |2 pi - angle sum| over the vertices at the end
  std::size_t degenerate_triangles = 0;  ///< triangles treated as flat at the end of the solve (0 normally)
  std::size_t flips = 0;                 ///< intrinsic Delaunay flips made during the solve
  /// largest distance (in lattice coordinates) of a cut edge's translation to the lattice: the layout
  /// error, of the order of the Newton tolerance
  double lattice_error = 0;
};

namespace internal {

// Lagrange-Gauss reduction of a 2D lattice basis, with det(a, b) > 0 at the end
inline void reduce_lattice_basis(Eigen::Vector2d& a, Eigen::Vector2d& b)
{
  for(int k = 0; k < 200; ++k) {  // converges in O(log) steps; the bound only guards against NaN
    if(b.squaredNorm() < a.squaredNorm()) std::swap(a, b);
    const double m = std::round(a.dot(b) / a.squaredNorm());
    if(m == 0) break;
    b -= m * a;
  }
  if(a.x() * b.y() - a.y() * b.x() < 0) b = -b;
}

// The lattice of the flat torus from the layout of the cut surface: the translation across each
// generator edge, reduced by Lagrange-Gauss; checks that the cell's area is the flat metric's `area` and
// that every cut edge's translation is a lattice vector (Convergence_failure otherwise: an inconsistent
// layout).
inline void read_lattice(const Intrinsic_triangulation& itri, const Tree_cotree& tc, double area, Flat_torus_embedding& emb)
{
  // the translation that takes face(t)'s copy of the edge of h onto face(h)'s copy
  auto translation = [&](int h) {
    const int t = itri.twin(h);
    return Eigen::Vector2d(emb.corner_uv[std::size_t(h / 3)][h % 3] - emb.corner_uv[std::size_t(t / 3)][(t % 3 + 1) % 3]);
  };
  Eigen::Vector2d a = translation(tc.generators[0]), b = translation(tc.generators[1]);
  emb.homology_basis[0] = generator_loop(itri, tc, tc.generators[0]);
  emb.homology_basis[1] = generator_loop(itri, tc, tc.generators[1]);
  reduce_lattice_basis(a, b);
  emb.lattice = {{a, b}};
  const double det = a.x() * b.y() - a.y() * b.x();
  if(!(std::abs(det - area) <= 1e-6 * area))
    throw Convergence_failure("flat torus embedding: the lattice cell has area " + std::to_string(det) +
                                  " but the flat metric has area " + std::to_string(area) + " (inconsistent layout)",
                              std::abs(det - area) / area);
  Eigen::Matrix2d B;
  B.col(0) = a;
  B.col(1) = b;
  const Eigen::Matrix2d Binv = B.inverse();
  for(int h = 0; h < int(itri.number_of_halfedges()); ++h) {
    if(!itri.is_edge_representative(h) || tc.in_cotree[std::size_t(h)]) continue;
    const int t = itri.twin(h);
    const Eigen::Vector2d c0 = Binv * translation(h), c1 = Binv * translation(t);  // both ends of the edge
    for(const Eigen::Vector2d& c : {c0, Eigen::Vector2d(-c1)})
      emb.lattice_error = std::max({emb.lattice_error, std::abs(c.x() - std::round(c.x())), std::abs(c.y() - std::round(c.y()))});
  }
  if(!(emb.lattice_error <= 1e-6))
    throw Convergence_failure("flat torus embedding: a cut edge's translation is " + std::to_string(emb.lattice_error) +
                                  " (lattice coordinates) away from the lattice (inconsistent layout)",
                              emb.lattice_error);
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * computes a flat conformal metric of the closed genus-1 surface `itri` and lays it out on the flat
 * torus (stage 3 for genus 1, DESIGN.md 3): per-vertex log scales `u` with `u = 0` at vertex 0 (the flat
 * metric is defined up to scale) and angle sum `2 pi` at every vertex, solved by Newton's method with
 * intrinsic Delaunay flips (as `conformal_embedding()`); a homology basis by tree-cotree; the surface
 * cut along the edges not in the cotree (a disk) is unfolded breadth-first through the cotree; the
 * translation across every cut edge is a lattice vector, and the two generator edges give a basis,
 * reduced by Lagrange-Gauss.
 *
 * Checks: every cut edge's translation is an integer combination of the basis (within `1e-6` in
 * lattice coordinates), and the area of the fundamental cell equals the area of the flat metric.
 *
 * \param itri a closed genus-1 triangulation with valid edge lengths (after `adjust_edge_lengths()`);
 *        its edges may be flipped
 * \param np optional named parameters: `max_conformal_iterations` (default 100), `conformal_tolerance`
 *        (default `1e-9`), `max_flips_per_edge` (default 50, as in `conformal_embedding()`), `visitor`
 *        (`on_iteration(Stage::EMBEDDING, it, bound, residual)`)
 * \throws Invalid_input if `itri` has a boundary, is not of genus 1, or its edge lengths are not set
 *         (`Intrinsic_triangulation::has_edge_lengths()`)
 * \throws Convergence_failure if Newton's method does not reach the tolerance within the bound, or the
 *         layout is inconsistent (with the error reached)
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Flat_torus_embedding flat_torus_embedding(Intrinsic_triangulation& itri,
                                          const NamedParameters& np = parameters::default_values())
{
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  internal::require_closed_surface(itri, "flat_torus_embedding()", "the flat torus", [](int g) { return g == 1; }, "genus 1");
  internal::require_edge_lengths(itri, "flat_torus_embedding()");

  Flat_torus_embedding emb;
  std::vector<char> fixed(std::size_t(nv), 0);
  fixed[0] = 1;  // the energy is invariant under a constant shift of u: fix the scale at one vertex
  internal::solve_euclidean_conformal_metric(itri, fixed, np, "flat torus embedding", emb);
  if(emb.degenerate_triangles > 0)
    throw Convergence_failure("flat torus embedding: " + std::to_string(emb.degenerate_triangles) +
                                  " triangles are flat in the solution (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)",
                              double(emb.degenerate_triangles));

  // ---- cut along the edges not in the cotree and unfold the disk through the cotree
  const internal::Tree_cotree tc = internal::tree_cotree(itri);
  if(tc.generators.size() != 2)
    throw Internal_error("flat torus embedding: the tree-cotree decomposition found " + std::to_string(tc.generators.size()) +
                         " generators instead of 2");
  std::vector<std::array<double, 3>> L(static_cast<std::size_t>(nf));
  std::vector<double> domain_area(static_cast<std::size_t>(nf));
  double area = 0;
  for(int f = 0; f < nf; ++f) {
    L[std::size_t(f)] = internal::scaled_face_lengths(itri, f, emb.u);
    domain_area[std::size_t(f)] = internal::heron_area(L[std::size_t(f)][0], L[std::size_t(f)][1], L[std::size_t(f)][2]);
    area += domain_area[std::size_t(f)];
  }
  std::vector<char> done;
  const int root = tc.root_face;
  emb.corner_uv = internal::unfold_breadth_first(itri, L, root, Eigen::Vector2d(0, 0), Eigen::Vector2d(L[std::size_t(root)][0], 0),
                                                 [&](int h) { return tc.in_cotree[std::size_t(h)] != 0; }, internal::third_point, done);
  internal::read_lattice(itri, tc, area, emb);
  emb.conformal_factor = internal::vertex_conformal_factors(itri, domain_area);
  return emb;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_FLAT_TORUS_EMBEDDING_H
