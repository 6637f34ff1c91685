// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_DOMAIN_POLICY_BASE_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_DOMAIN_POLICY_BASE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>

#include <cstddef>
#include <string>

// What the models of ParametricDomain share: the types, the traits built from the background and the
// embedding, the topology test of the closed domains, the refusal of too few vertices, and the hint for
// inverted triangles on a closed surface.

namespace Aniso_conformal {
namespace internal {

template <typename Embedding_, typename Traits_>
struct Domain_policy_base {
  typedef Embedding_ Embedding;  // result of stage 3
  typedef Traits_ Traits;        // the domain of stages 4 and 5

  // the domain traits of stages 4 and 5, `threads` workers (0: all cores)
  static Traits make_traits(const Intrinsic_triangulation& itri, const Embedding& emb, unsigned threads)
  {
    return Traits(itri, emb, threads);
  }
  // `true` if the default surface optimisation (Surface_optimization::REPAIR) runs always in this domain,
  // as Surface_optimization::ALWAYS (the cone domain, whose Voronoi cells next to cones are approximate)
  static constexpr bool optimizes_on_the_surface_by_default = false;
  // the likely reason for an inverted output triangle on a closed surface
  static const char* inverted_triangles_hint()
  {
    return "the output is too coarse for thin or strongly curved parts of the surface, or the metric too strong for the "
           "background (more vertices or a finer input may help)";
  }

protected:
  static bool is_closed_of_genus(const Input_surface& s, int least, int most)
  {
    return s.boundary_loops().empty() && s.genus() >= least && s.genus() <= most;
  }
  // Invalid_input if `n` is below `least`, the smallest triangulation (`what`) of the surface's topology
  static void require_vertices(const Input_surface& s, std::size_t n, std::size_t least, const std::string& what)
  {
    if(n < least)
      throw Invalid_input("remesh(): " + s.topology_description() + " needs at least " + std::to_string(least) +
                          " output vertices (" + what + "), " + std::to_string(n) + " were requested");
  }
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_DOMAIN_POLICY_BASE_H
