// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_DOMAIN_POLICY_BASE_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_DOMAIN_POLICY_BASE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

// What the models of ParametricDomain share: the types, the traits built from the background and the
// embedding, the refusal of too few vertices, and the hint for inverted triangles on a closed surface;
// for the closed domains also the topology test and the fewest vertices of the topology.

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
  // `true` if the default curvature sizing (Curvature_sizing::CONES) scales the metric in this domain
  static constexpr bool sizes_by_curvature_by_default = false;
  // the vertices of the background the domain needs as output vertices (fixed sites): none
  static std::vector<std::size_t> vertices_kept(const Embedding_&) { return {}; }
  // the likely reason for an inverted output triangle on a closed surface
  static const char* inverted_triangles_hint()
  {
    return "the output is too coarse for thin or strongly curved parts of the surface, or the metric too strong for the "
           "background (more vertices or a finer input may help)";
  }

protected:
  // Invalid_input if `n` is below `least`, the smallest triangulation (`what`) of the surface's topology
  static void require_vertices(const Input_surface& s, std::size_t n, std::size_t least, const std::string& what)
  {
    if(n < least)
      throw Invalid_input("remesh(): " + s.topology_description() + " needs at least " + std::to_string(least) +
                          " output vertices (" + what + "), " + std::to_string(n) + " were requested");
  }
};

// The fewest vertices of a triangulation of the closed surface of genus `g >= 0` (Ringel and Jungerman:
// Heawood's bound `ceil((7 + sqrt(1 + 48 g)) / 2)`, except 10 for genus 2): 4 (the tetrahedron) for the
// sphere, 7 (Moebius' torus) for the torus.
inline std::size_t minimum_vertices_of_closed_surface(int g)
{
  if(g == 2) return 10;
  return std::size_t(std::ceil((7 + std::sqrt(1.0 + 48.0 * g)) / 2 - 1e-9));
}

// The models of ParametricDomain for closed surfaces of genus `least_genus` to `most_genus`: their topology
// test and their refusal of fewer output vertices than the smallest triangulation of the input's genus.
template <typename Embedding_, typename Traits_, int least_genus, int most_genus>
struct Closed_domain_policy_base : Domain_policy_base<Embedding_, Traits_> {
  // `true` for a closed surface of genus `least_genus` to `most_genus`
  static bool fits(const Input_surface& s) { return s.boundary_loops().empty() && s.genus() >= least_genus && s.genus() <= most_genus; }
  // Invalid_input below minimum_vertices_of_closed_surface(genus)
  static void check_number_of_vertices(const Input_surface& s, std::size_t n)
  {
    const int g = s.genus();
    Domain_policy_base<Embedding_, Traits_>::require_vertices(
        s, n, minimum_vertices_of_closed_surface(g),
        g == 0 ? "the tetrahedron" : g == 1 ? "the smallest torus triangulation" : "the smallest triangulation of that genus");
  }
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_DOMAIN_POLICY_BASE_H
