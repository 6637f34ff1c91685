// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_SPHERICAL_DOMAIN_H
#define ANISO_CONFORMAL_SPHERICAL_DOMAIN_H

#include <Aniso_conformal/Domain_diagnostics.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/domains/domain_policy_base.h>
#include <Aniso_conformal/Spherical_domain_traits.h>
#include <Aniso_conformal/parameters.h>
#include <Aniso_conformal/spherical_embedding.h>

#include <cstddef>
#include <cstdio>
#include <string>

/// \file Spherical_domain.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the unit sphere, for closed surfaces of genus 0: stage 3 is `spherical_embedding()` (a planar
 * discrete conformal map of the punctured surface, inverse stereographic projection, Moebius
 * centring), stages 4 and 5 run in `Spherical_domain_traits`. Reports the angle distortion of the map.
 * `fits()` a closed surface of genus 0; `check_number_of_vertices()` throws `Invalid_input` below 4 (the
 * tetrahedron).
 *
 * \cgalModels `ParametricDomain`
 */
struct Spherical_domain : internal::Closed_domain_policy_base<Spherical_embedding, Spherical_domain_traits, 0, 0> {
  static constexpr Parametric_domain kind = Parametric_domain::SPHERE;  ///< its tag

  /// the topologies it takes, in words
  static const char* topology() { return "closed surfaces of genus 0"; }
  /// stage 3: `spherical_embedding()`
  template <typename NamedParameters>
  static Embedding embed(Intrinsic_triangulation& itri, const NamedParameters& np)
  {
    return spherical_embedding(itri, np);
  }
  /// the site of background vertex `v` (a corner of the feature graph, fixed in the CVT): its image on the
  /// sphere (`face`, `corner`: where it is a corner of the background; the sphere does not need them)
  static Traits::Point corner_site(const Embedding& emb, int /*face*/, int /*corner*/, int v) { return emb.position[std::size_t(v)]; }
  /// the angle distortion of the map (degrees), and the seam splits of `spherical_embedding()`
  static Domain_diagnostics diagnostics(const Embedding& emb, const Traits&)
  {
    Domain_diagnostics d;
    d.add("angle_distortion_mean_degrees", emb.angle_distortion_mean,
          "mean over the corners of |chordal angle - adjusted angle|, degrees");
    d.add("angle_distortion_max_degrees", emb.angle_distortion_max, "largest |chordal angle - adjusted angle| over the corners, degrees");
    d.add("seam_splits", double(emb.seam_splits), "seam edges of the holes' patches split after an attempt that flattened a triangle onto them", true);
    char text[200];
    std::snprintf(text, sizeof(text), "angle distortion of the conformal map: mean %.3f deg, max %.3f deg", emb.angle_distortion_mean,
                  emb.angle_distortion_max);
    d.summary = text;
    if(emb.seam_splits > 0) d.summary += "; " + std::to_string(emb.seam_splits) + " seam edges split (a triangle flattened onto a hole's loop)";
    return d;
  }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_SPHERICAL_DOMAIN_H
