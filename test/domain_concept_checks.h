// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// One test of the ParametricDomain and ParametricDomainTraits concepts, written once and run by each
// domain's test module on its own model (so that a module compiles only the domain it exercises):
// the policy's topology checks and stage 3, then every member of the traits that stages 4 and 5 use,
// with the invariants every model must keep.

#ifndef ANISO_CONFORMAL_TEST_DOMAIN_CONCEPT_CHECKS_H
#define ANISO_CONFORMAL_TEST_DOMAIN_CONCEPT_CHECKS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/adjust_edge_lengths.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/parameters.h>
#include <Aniso_conformal/weighted_centroidal_Voronoi_tessellation.h>

#include <boost/test/unit_test.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace test {

// The contract of `Domain` (a model of ParametricDomain) and of its `Traits` on `surface`, a surface the
// domain takes, with `n` sites. `other` is a surface it does not take.
template <typename Domain>
void check_domain_concept(const Aniso_conformal::Input_surface& surface, const Aniso_conformal::Input_surface& other, std::size_t n,
                          double mass_tolerance = 1e-6)
{
  namespace AC = Aniso_conformal;
  typedef typename Domain::Traits Traits;
  typedef typename Traits::Point Point;
  static_assert(Point::RowsAtCompileTime >= 2, "a domain point has at least two coordinates");
  const std::string name = AC::domain_name(Domain::kind);

  // the policy: topology, vertex counts, stage 3
  BOOST_TEST(Domain::fits(surface), name << " takes its test surface");
  BOOST_TEST(!Domain::fits(other), name << " refuses a surface of another topology");
  BOOST_TEST(std::string(Domain::topology()).size() > 0u);
  BOOST_CHECK_NO_THROW(Domain::check_number_of_vertices(surface, n));
  BOOST_CHECK_THROW(Domain::check_number_of_vertices(surface, 2), AC::Invalid_input);
  AC::Intrinsic_triangulation itri(surface, AC::compute_metric_square_roots(surface, AC::Uniform_metric()));
  AC::adjust_edge_lengths(itri, surface);
  const typename Domain::Embedding emb = Domain::embed(itri, AC::parameters::max_conformal_iterations(100u));
  itri.validate(true);
  BOOST_TEST(emb.conformal_factor.size() == itri.number_of_vertices());
  for(double cf : emb.conformal_factor) BOOST_TEST((std::isfinite(cf) && cf > 0), name << ": conformal factor " << cf);
  BOOST_TEST(emb.residual <= 1e-9);

  // the traits: sites
  Traits traits = Domain::make_traits(itri, emb, 1);
  std::vector<Point> sites = traits.initial_sites(n, 3u);
  BOOST_TEST(sites.size() == n);
  BOOST_TEST(traits.number_of_fixed_sites() <= n);
  // the free sites lie in the domain (the fixed ones lie on its boundary, where contains() may say either)
  for(std::size_t i = traits.number_of_fixed_sites(); i < n; ++i)
    BOOST_TEST(traits.contains(sites[i]), name << ": initial site " << i << " lies outside the domain");
  Traits again = Domain::make_traits(itri, emb, 2);
  const std::vector<Point> same = again.initial_sites(n, 3u);
  bool identical = same.size() == sites.size();
  for(std::size_t i = 0; identical && i < sites.size(); ++i) identical = (same[i] - sites[i]).norm() == 0;
  BOOST_TEST(identical, name << ": the same seed must give the same sites");

  // integration: the cells share the total mass, masses and energies are non-negative, whatever the
  // number of threads (the chunks are summed in a fixed order)
  std::vector<typename Traits::Cell> cells, cells2;
  traits.integrate(sites, cells);
  again.integrate(sites, cells2);
  BOOST_TEST(cells.size() == n);
  double mass = 0;
  for(std::size_t i = 0; i < cells.size(); ++i) {
    BOOST_TEST(cells[i].mass >= 0);
    BOOST_TEST(cells[i].energy >= 0);
    BOOST_TEST(cells[i].mass == cells2[i].mass, name << ": the integration depends on the number of threads");
    mass += cells[i].mass;
  }
  BOOST_TEST(std::abs(mass - traits.total_mass()) <= mass_tolerance * traits.total_mass(), name << ": cells hold " << mass << " of "
                                                                                      << traits.total_mass());
  // a Lloyd move stays in the domain
  for(std::size_t i = traits.number_of_fixed_sites(); i < n; ++i)
    BOOST_TEST(traits.contains(traits.move_towards(sites[i], cells[i].centroid)));

  // a few CVT iterations lower the energy (the dual of random sites need not be a triangulation of the
  // surface: on a thin torus two translates of a site can share a Delaunay triangle)
  double before = 0;
  for(const auto& c : cells) before += c.energy;
  const AC::Cvt_report cvt = AC::weighted_centroidal_Voronoi_tessellation(traits, sites, traits.number_of_fixed_sites(),
                                                                          AC::parameters::number_of_iterations(30u));
  BOOST_TEST(cvt.energy.back() < before, name << ": the CVT did not lower the energy");

  // the dual: every site a vertex, indices in range; every site located on the background
  const std::vector<std::array<std::size_t, 3>> tris = traits.dual_triangles(sites);
  std::vector<char> used(n, 0);
  for(const auto& t : tris)
    for(std::size_t k : t) {
      BOOST_REQUIRE(k < n);
      used[k] = 1;
    }
  for(std::size_t i = 0; i < n; ++i) BOOST_TEST(used[i] != 0, name << ": site " << i << " is not a vertex of the dual");
  for(std::size_t i = 0; i < n; ++i) {
    int face = -1;
    Eigen::Vector3d bary;
    BOOST_TEST(traits.background_location(i, sites[i], face, bary), name << ": site " << i << " not located");
    BOOST_TEST((face >= 0 && std::size_t(face) < itri.number_of_faces()));
    BOOST_TEST((bary.minCoeff() >= 0 && std::abs(bary.sum() - 1) < 1e-12));
  }

  // diagnostics: every figure named and described, with values
  const AC::Domain_diagnostics d = Domain::diagnostics(emb, traits);
  for(const AC::Domain_figure& f : d.figures) {
    BOOST_TEST(!f.key.empty());
    BOOST_TEST(!f.description.empty());
    BOOST_TEST(!f.values.empty());
    BOOST_TEST((f.columns == 0 || f.values.size() % f.columns == 0));
  }
  BOOST_TEST(std::string(Domain::inverted_triangles_hint()).size() > 0u);
}

} // namespace test

#endif // ANISO_CONFORMAL_TEST_DOMAIN_CONCEPT_CHECKS_H
