// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_PLANAR_DOMAIN_H
#define ANISO_CONFORMAL_PLANAR_DOMAIN_H

#include <Aniso_conformal/Domain_diagnostics.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Planar_domain_traits.h>
#include <Aniso_conformal/conformal_embedding.h>
#include <Aniso_conformal/internal/domains/domain_policy_base.h>
#include <Aniso_conformal/parameters.h>

#include <cstddef>
#include <string>

/// \file Planar_domain.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the plane, for topological disks (2D domains, images, open curved patches): stage 3 is
 * `conformal_embedding()` (by default, `Planar_boundary::AUTOMATIC`, the paper's `u = 0` on the
 * boundary, and where that layout is not embedded one that keeps the input's outline, its turning
 * angles prescribed and its lengths free; the named parameter `planar_boundary` forces either), stages
 * 4 and 5 run in `Planar_domain_traits` (the boundary is a 1D CVT in metric length, corners are fixed
 * sites). Paper sections 3.3-3.5.
 *
 * \cgalModels `ParametricDomain`
 */
struct Planar_domain : internal::Domain_policy_base<Planar_embedding, Planar_domain_traits> {
  static constexpr Parametric_domain kind = Parametric_domain::PLANE;  ///< its tag

  /// the topologies it takes, in words
  static const char* topology() { return "topological disks"; }
  /// `true` for a topological disk
  static bool fits(const Input_surface& s) { return s.is_disk(); }
  /*!
   * \throws Invalid_input below 3 vertices (a triangle); the corners, which must all be output vertices,
   *         are counted by `Planar_domain_traits::initial_sites()`, which checks them
   */
  static void check_number_of_vertices(const Input_surface& s, std::size_t n) { require_vertices(s, n, 3, "a triangle"); }
  /// stage 3: `conformal_embedding()`
  template <typename NamedParameters>
  static Embedding embed(Intrinsic_triangulation& itri, const NamedParameters& np)
  {
    return conformal_embedding(itri, np);
  }
  /*!
   * what the boundary kept: `boundary_keeps_shape` (1: the input's outline, `Planar_boundary::KEEP_SHAPE`;
   * 0: the metric lengths), `convex_boundary` (1 if the outline touched or crossed itself in the layout
   * and was made convex), `turning_defect` (radians: `2 pi` minus the input's total boundary turning, the
   * Gaussian curvature of a curved patch, spread over the boundary), `added_boundary_sites` (sites added
   * to keep the polygon of the boundary sites simple)
   */
  static Domain_diagnostics diagnostics(const Embedding& emb, const Traits& traits)
  {
    Domain_diagnostics d;
    const bool shape = emb.boundary == Planar_boundary::KEEP_SHAPE;
    d.add("boundary_keeps_shape", shape ? 1.0 : 0.0, "1 if the layout keeps the input's outline (turning angles), 0 if the boundary's metric lengths", true);
    if(shape) {
      d.add("convex_boundary", emb.convex_boundary ? 1.0 : 0.0,
            "1 if the input's outline touched or crossed itself in the layout and was made convex", true);
      d.add("turning_defect", emb.turning_defect, "2 pi minus the input's total boundary turning (radians), spread over the boundary");
    }
    d.add("added_boundary_sites", double(traits.number_of_added_boundary_sites()),
          "boundary sites added so that their polygon does not touch or cross itself", true);
    d.summary = !shape ? "boundary: metric lengths kept (u = 0)"
                : emb.convex_boundary ? "boundary: made convex (the input's outline touches or crosses itself in the layout)"
                                      : "boundary: the input's outline kept";
    if(traits.number_of_added_boundary_sites() > 0)
      d.summary += ", " + std::to_string(traits.number_of_added_boundary_sites()) + " boundary sites added";
    return d;
  }
  /// the point of the domain of background vertex `v` (a corner of `face`): its layout position, the same in
  /// every face around it (used for the fixed sites of the input's interior corners and creases)
  static Traits::Point corner_site(const Embedding& emb, int /*face*/, int /*corner*/, int v) { return emb.uv[std::size_t(v)]; }
  /// what an inverted output triangle most likely means here
  static const char* inverted_triangles_hint() { return "the metric is too strong for this background near its boundary"; }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_PLANAR_DOMAIN_H
