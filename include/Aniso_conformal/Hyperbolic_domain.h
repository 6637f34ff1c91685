// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_HYPERBOLIC_DOMAIN_H
#define ANISO_CONFORMAL_HYPERBOLIC_DOMAIN_H

#include <Aniso_conformal/Domain_diagnostics.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Hyperbolic_klein_domain_traits.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/domains/domain_policy_base.h>
#include <Aniso_conformal/hyperbolic_embedding.h>
#include <Aniso_conformal/parameters.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

/// \file Hyperbolic_domain.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the hyperbolic disk modulo a Fuchsian group, for closed surfaces of genus 2 or more: stage 3 is
 * `hyperbolic_embedding()` (hyperbolic discrete conformal metric, fundamental domain and deck
 * transformations), stages 4 and 5 run in `Hyperbolic_klein_domain_traits`. Reports how well the group's
 * relations hold and how many tiles the CVT's band of images reached. `fits()` a closed surface of genus 2
 * or more; `check_number_of_vertices()` throws `Invalid_input` below `minimum_number_of_vertices(genus)`.
 *
 * \cgalModels `ParametricDomain`
 */
struct Hyperbolic_domain
    : internal::Closed_domain_policy_base<Hyperbolic_embedding, Hyperbolic_klein_domain_traits, 2, std::numeric_limits<int>::max()> {
  static constexpr Parametric_domain kind = Parametric_domain::HYPERBOLIC;  ///< its tag

  /// the topologies it takes, in words
  static const char* topology() { return "closed surfaces of genus 2 or more"; }
  /*!
   * the fewest vertices of a triangulation of the closed surface of genus `g >= 1` (Ringel and
   * Jungerman: Heawood's bound `ceil((7 + sqrt(1 + 48 g)) / 2)`, except 10 for genus 2)
   */
  static std::size_t minimum_number_of_vertices(int g) { return internal::minimum_vertices_of_closed_surface(g); }
  /*!
   * the hyperbolic spacing `sqrt(A / n) 2 s exp(u*)` of `n` sites where the conformal metric shrinks the
   * surface most: `A` is the metric area of `itri` (Heron on its lengths), `s` and `u` the embedding's
   * scale and log scale factors (an edge of metric length `L` has hyperbolic length about
   * `2 s exp(u) L` when short), and `u*` the least `u` whose sublevel set holds one site's share `A / n`
   * of the area (a third of each face's area to each corner), so that a lone vertex does not decide it.
   * The patches closing a surface's holes hold no site and are left out.
   */
  static double smallest_site_spacing(const Intrinsic_triangulation& itri, const Embedding& emb, std::size_t n)
  {
    const std::size_t nv = itri.number_of_vertices();
    std::vector<double> area(nv, 0.0);
    double total = 0;
    for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
      if(itri.is_patch_face(f)) continue;  // a hole's patch holds no site
      const double af = internal::heron_area(itri.length(int(3 * f)), itri.length(int(3 * f + 1)), itri.length(int(3 * f + 2)));
      for(int v : itri.face_vertices(f)) area[std::size_t(v)] += af / 3;
      total += af;
    }
    if(!(total > 0) || n == 0 || emb.u.size() != nv) return 0;
    std::vector<std::size_t> order(nv);
    for(std::size_t v = 0; v < nv; ++v) order[v] = v;
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return emb.u[x] < emb.u[y]; });
    const double share = total / double(n);
    double below = 0, u_star = emb.u[order.back()];
    for(std::size_t v : order) {
      below += area[v];
      if(below >= share) {
        u_star = emb.u[v];
        break;
      }
    }
    return std::sqrt(share) * 2 * emb.scale * std::exp(u_star);
  }
  /// the spacing below which `embed()` refuses the surface: sites that close are not told apart in double
  /// precision on the hyperboloid (CGAL's femur: sites 1e-11 apart after 4 to 13 minutes of CVT)
  static constexpr double least_site_spacing = 1e-8;
  /*!
   * stage 3: `hyperbolic_embedding()`, then the spacing the requested sites would have where the metric
   * shrinks the surface most (`smallest_site_spacing()`, recorded in the embedding)
   * \throws Convergence_failure if that spacing is below `least_site_spacing`: the CVT would run for
   *         minutes and end with sites that coincide (cone singularities, issue 16, are the remedy)
   */
  template <typename NamedParameters>
  static Embedding embed(Intrinsic_triangulation& itri, const NamedParameters& np)
  {
    Embedding emb = hyperbolic_embedding(itri, np);
    const std::size_t n = internal::number_of_vertices(np);
    emb.smallest_site_spacing = smallest_site_spacing(itri, emb, n);
    if(emb.smallest_site_spacing > 0 && emb.smallest_site_spacing < least_site_spacing) {
      char text[320];
      std::snprintf(text, sizeof(text),
                    "hyperbolic embedding: the conformal metric shrinks part of the surface so much that %zu sites would lie "
                    "%.2g apart there in the hyperbolic plane, below what double precision resolves (%.0e); conformal maps "
                    "shrink long protrusions and thin handles exponentially",
                    n, emb.smallest_site_spacing, least_site_spacing);
      throw Convergence_failure(text, emb.smallest_site_spacing);
    }
    return emb;
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
    d.add("smallest_site_spacing", emb.smallest_site_spacing,
          "hyperbolic spacing of the sites where the conformal metric shrinks the surface most (estimate before the CVT)");
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
