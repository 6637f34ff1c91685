// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_HYPERBOLIC_DOMAIN_H
#define ANISO_CONFORMAL_HYPERBOLIC_DOMAIN_H

#include <Aniso_conformal/Domain_diagnostics.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Hyperbolic_klein_domain_traits.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/domains/domain_policy_base.h>
#include <Aniso_conformal/hyperbolic_embedding.h>
#include <Aniso_conformal/parameters.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <string>

/// \file Hyperbolic_domain.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the hyperbolic disk modulo a Fuchsian group, for closed surfaces of genus 2 or more: stage 3 is
 * `hyperbolic_embedding()` (hyperbolic discrete conformal metric, fundamental domain and deck
 * transformations), stages 4 and 5 run in `Hyperbolic_klein_domain_traits`. Reports how well the group's
 * relations hold and how many tiles the CVT's band of images reached.
 *
 * \cgalModels `ParametricDomain`
 */
struct Hyperbolic_domain : internal::Domain_policy_base<Hyperbolic_embedding, Hyperbolic_klein_domain_traits> {
  static constexpr Parametric_domain kind = Parametric_domain::HYPERBOLIC;  ///< its tag

  /// the topologies it takes, in words
  static const char* topology() { return "closed surfaces of genus 2 or more"; }
  /// `true` for a closed surface of genus 2 or more
  static bool fits(const Input_surface& s) { return is_closed_of_genus(s, 2, std::numeric_limits<int>::max()); }
  /*!
   * the fewest vertices of a triangulation of the closed surface of genus `g >= 1` (Ringel and
   * Jungerman: Heawood's bound `ceil((7 + sqrt(1 + 48 g)) / 2)`, except 10 for genus 2)
   */
  static std::size_t minimum_number_of_vertices(int g)
  {
    if(g == 2) return 10;
    return std::size_t(std::ceil((7 + std::sqrt(1.0 + 48.0 * g)) / 2 - 1e-9));
  }
  /// \throws Invalid_input below `minimum_number_of_vertices(genus)`
  static void check_number_of_vertices(const Input_surface& s, std::size_t n)
  {
    require_vertices(s, n, minimum_number_of_vertices(s.genus()), "the smallest triangulation of that genus");
  }
  /// stage 3: `hyperbolic_embedding()`
  template <typename NamedParameters>
  static Embedding embed(Intrinsic_triangulation& itri, const NamedParameters& np)
  {
    return hyperbolic_embedding(itri, np);
  }
  /// the site of background vertex `v` (a corner of the feature graph, fixed in the CVT): its image in the
  /// fundamental domain's layout, as corner `corner` of background face `face` (a point of the hyperboloid)
  static Traits::Point corner_site(const Embedding& emb, int face, int corner, int /*v*/)
  {
    return emb.corner_hyperboloid[std::size_t(face)][std::size_t(corner)];
  }
  /// the relations' error and the tiles reached (called after the CVT, which grows the band)
  static Domain_diagnostics diagnostics(const Embedding& emb, const Traits& traits)
  {
    Domain_diagnostics d;
    d.add("group_relation_error", emb.relation_error, "largest entry of (product of the side pairings around a vertex) - I");
    d.add("group_elements", double(traits.number_of_group_elements()), "group elements whose tiles the CVT's band of images reached",
          true);
    char text[160];
    std::snprintf(text, sizeof(text), "group relations hold to %.1e; %zu group elements near the fundamental domain", emb.relation_error,
                  traits.number_of_group_elements());
    d.summary = text;
    return d;
  }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_HYPERBOLIC_DOMAIN_H
