// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_FLAT_TORUS_DOMAIN_H
#define ANISO_CONFORMAL_FLAT_TORUS_DOMAIN_H

#include <Aniso_conformal/Domain_diagnostics.h>
#include <Aniso_conformal/Euclidean_periodic_domain_traits.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/domains/domain_policy_base.h>
#include <Aniso_conformal/flat_torus_embedding.h>
#include <Aniso_conformal/parameters.h>

#include <cstddef>
#include <cstdio>
#include <string>

/// \file Flat_torus_domain.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the flat torus `R^2 / L`, for closed surfaces of genus 1: stage 3 is `flat_torus_embedding()`
 * (flat metric, tree-cotree cut, lattice reduced by Lagrange-Gauss), stages 4 and 5 run in
 * `Euclidean_periodic_domain_traits`. Reports the lattice and its layout error. `fits()` a closed
 * surface of genus 1; `check_number_of_vertices()` throws `Invalid_input` below 7 (the smallest torus
 * triangulation, Moebius' torus).
 *
 * \cgalModels `ParametricDomain`
 */
struct Flat_torus_domain : internal::Closed_domain_policy_base<Flat_torus_embedding, Euclidean_periodic_domain_traits, 1, 1> {
  static constexpr Parametric_domain kind = Parametric_domain::FLAT_TORUS;  ///< its tag

  /// the topologies it takes, in words
  static const char* topology() { return "closed surfaces of genus 1"; }
  /// stage 3: `flat_torus_embedding()`
  template <typename NamedParameters>
  static Embedding embed(Intrinsic_triangulation& itri, const NamedParameters& np)
  {
    return flat_torus_embedding(itri, np);
  }
  /// the site of background vertex `v` (a corner of the feature graph, fixed in the CVT): its image in the
  /// layout, as corner `corner` of background face `face` (a point of the plane standing for its class)
  static Traits::Point corner_site(const Embedding& emb, int face, int corner, int /*v*/)
  {
    return emb.corner_uv[std::size_t(face)][std::size_t(corner)];
  }
  /// the reduced lattice basis (by rows) and the layout's error
  static Domain_diagnostics diagnostics(const Embedding& emb, const Traits&)
  {
    Domain_diagnostics d;
    d.add("lattice", {emb.lattice[0].x(), emb.lattice[0].y(), emb.lattice[1].x(), emb.lattice[1].y()}, 2,
          "reduced lattice basis a, b by rows (units of the flat metric)");
    d.add("lattice_error", emb.lattice_error, "largest distance of a cut edge's translation to the lattice, lattice coordinates");
    char text[160];
    std::snprintf(text, sizeof(text), "lattice a = (%.4f, %.4f), b = (%.4f, %.4f), layout error %.1e", emb.lattice[0].x(),
                  emb.lattice[0].y(), emb.lattice[1].x(), emb.lattice[1].y(), emb.lattice_error);
    d.summary = text;
    return d;
  }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_FLAT_TORUS_DOMAIN_H
