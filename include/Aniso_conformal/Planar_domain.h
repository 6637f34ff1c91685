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
 * `conformal_embedding()` (`u = 0` on the boundary, which keeps the boundary's metric length), stages
 * 4 and 5 run in `Planar_domain_traits` (the boundary is a 1D CVT, corners are fixed sites). Paper
 * sections 3.3-3.5.
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
  /// nothing beyond the figures every domain reports
  static Domain_diagnostics diagnostics(const Embedding&, const Traits&) { return Domain_diagnostics(); }
  /// what an inverted output triangle most likely means here
  static const char* inverted_triangles_hint() { return "the metric is too strong for this background near its boundary"; }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_PLANAR_DOMAIN_H
