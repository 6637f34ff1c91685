// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_WEIGHTED_CENTROIDAL_VORONOI_TESSELLATION_H
#define ANISO_CONFORMAL_WEIGHTED_CENTROIDAL_VORONOI_TESSELLATION_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>

#include <cmath>
#include <deque>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

/// \file weighted_centroidal_Voronoi_tessellation.h

namespace Aniso_conformal {
namespace internal {

// Optional hooks of a curved domain (ParametricDomainTraits): `project_to_domain(p)` maps a trial point
// taken in the ambient coordinates back onto the domain, `project_to_tangent_plane(x, v)` keeps the
// component of v tangent to the domain at x. Without them (flat domains) the code below is unchanged.
template <typename D, typename = void>
struct Has_project_to_domain : std::false_type {};
template <typename D>
struct Has_project_to_domain<D, std::void_t<decltype(std::declval<const D&>().project_to_domain(
                                    std::declval<const typename D::Point&>()))>> : std::true_type {};
template <typename D, typename = void>
struct Has_project_to_tangent_plane : std::false_type {};
template <typename D>
struct Has_project_to_tangent_plane<D, std::void_t<decltype(std::declval<const D&>().project_to_tangent_plane(
                                           std::declval<const typename D::Point&>(), std::declval<const typename D::Point&>()))>>
    : std::true_type {};

// Optional member of a domain's Cell: `gradient`, the exact derivative of the cell's energy with respect
// to the site's coordinates, for domains whose coordinates are not those in which the distance is
// measured (the hyperboloid); without it the gradient is 2 m (x - c), exact in flat coordinates.
template <typename C, typename = void>
struct Has_cell_gradient : std::false_type {};
template <typename C>
struct Has_cell_gradient<C, std::void_t<decltype(std::declval<const C&>().gradient)>> : std::true_type {};

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * what `weighted_centroidal_Voronoi_tessellation()` did
 */
struct Cvt_report {
  std::vector<double> energy;        ///< CVT energy before the first and after every iteration
  std::size_t iterations = 0;        ///< iterations done
  std::size_t energy_evaluations = 0; ///< integrations of the restricted Voronoi diagram
  std::size_t lloyd_fallbacks = 0;   ///< L-BFGS iterations that fell back to a Lloyd step
  double gradient_norm = 0;          ///< norm of the energy gradient at the end, relative to the total mass
  Cvt_method method = Cvt_method::LBFGS;  ///< the optimiser used
};

/*!
 * \ingroup PkgAnisoConformalStages
 * optimises `sites` into a weighted centroidal Voronoi tessellation of `domain` (stage 4): minimises
 * `E(X) = sum_i integral_{V_i} rho(y) |y - x_i|^2 dy` over the free sites, whose gradient is
 * `2 m_i (x_i - c_i)` (mass `m_i`, centroid `c_i`).
 *
 * `Cvt_method::LLOYD` moves every free site to its centroid (as far as the domain allows);
 * `Cvt_method::LBFGS` (default) runs L-BFGS (memory 7) preconditioned by the cell masses, so that its
 * first step is a Lloyd step, with an Armijo backtracking line search that also rejects steps leaving
 * the domain; a failed line search falls back to a Lloyd step.
 *
 * On a curved domain that provides the optional hooks of `ParametricDomainTraits` (the sphere), the
 * optimisation is constrained to the domain: gradients and L-BFGS directions are projected on the
 * tangent planes at the sites (`project_to_tangent_plane()`), and every trial point is mapped back onto
 * the domain (`project_to_domain()`) before it is integrated (a retraction; the differences of points and
 * of projected gradients serve as the L-BFGS pairs).
 *
 * \tparam DomainTraits a model of `ParametricDomainTraits` (`Planar_domain_traits`,
 *         `Euclidean_periodic_domain_traits`, `Spherical_domain_traits`)
 * \param domain the domain
 * \param sites the sites, optimised in place
 * \param number_of_fixed_sites the first sites stay where they are (boundary sites)
 * \param np optional named parameters: `number_of_iterations` (default 100), `cvt_method`
 *        (default `Cvt_method::LBFGS`), `visitor` (`on_iteration(Stage::CVT, it, bound, energy)`)
 * \throws Cancelled if the visitor asks to stop
 */
template <typename DomainTraits, typename NamedParameters = parameters::Default_named_parameters>
Cvt_report weighted_centroidal_Voronoi_tessellation(const DomainTraits& domain,
                                                    std::vector<typename DomainTraits::Point>& sites,
                                                    std::size_t number_of_fixed_sites,
                                                    const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  typedef typename DomainTraits::Point Point;
  typedef typename DomainTraits::Cell Cell;
  const std::size_t max_it = choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), 100u);
  const Cvt_method method = choose_parameter(get_parameter(np, internal_np::cvt_method), Cvt_method::LBFGS);
  typename internal::Visitor_reference<NamedParameters>::type vis = internal::get_visitor(np);

  const int D = int(Point::RowsAtCompileTime);
  const std::size_t ns = sites.size(), nfree = ns - number_of_fixed_sites;
  const Eigen::Index nvar = Eigen::Index(nfree) * D;
  Cvt_report report;
  report.method = method;
  std::vector<Cell> cells;
  auto energy_of = [&](const std::vector<Point>& x, std::vector<Cell>& c) {
    domain.integrate(x, c);
    ++report.energy_evaluations;
    double e = 0;
    for(const Cell& cell : c) e += cell.energy;
    return e;
  };
  constexpr bool tangent_hook = internal::Has_project_to_tangent_plane<DomainTraits>::value;
  constexpr bool domain_hook = internal::Has_project_to_domain<DomainTraits>::value;
  auto gradient_of = [&](const std::vector<Point>& x, const std::vector<Cell>& c, Eigen::VectorXd& g) {
    g.resize(nvar);
    for(std::size_t i = 0; i < nfree; ++i) {
      const std::size_t s = number_of_fixed_sites + i;
      Point gs;
      if constexpr(internal::Has_cell_gradient<Cell>::value)
        gs = c[s].gradient;
      else
        gs = 2.0 * c[s].mass * (x[s] - c[s].centroid);
      // fixed-size segments: GCC 12 misreads a dynamic one assigned from a Vector2d (-Wstringop-overread)
      if constexpr(tangent_hook)
        g.template segment<Point::RowsAtCompileTime>(Eigen::Index(i) * D) = domain.project_to_tangent_plane(x[s], gs);
      else
        g.template segment<Point::RowsAtCompileTime>(Eigen::Index(i) * D) = gs;
    }
  };
  auto lloyd_step = [&](std::vector<Point>& x, const std::vector<Cell>& c) {
    for(std::size_t s = number_of_fixed_sites; s < ns; ++s)
      if(c[s].mass > 0) x[s] = domain.move_towards(x[s], c[s].centroid);
  };

  double E = energy_of(sites, cells);
  report.energy.push_back(E);
  const double total_mass = [&] { double m = 0; for(const Cell& c : cells) m += c.mass; return m; }();
  Eigen::VectorXd g, g_new;
  gradient_of(sites, cells, g);
  std::deque<Eigen::VectorXd> S, Y;
  std::deque<double> RHO;
  const std::size_t memory = 7;

  for(std::size_t it = 0; it < max_it && nfree > 0; ++it) {
    if(method == Cvt_method::LLOYD) {
      lloyd_step(sites, cells);
      E = energy_of(sites, cells);
    } else {
      // two-loop recursion with the mass preconditioner H0 = diag(1 / (2 m_i))
      Eigen::VectorXd q = g, alpha(S.size());
      for(int k = int(S.size()) - 1; k >= 0; --k) {
        alpha[k] = RHO[k] * S[k].dot(q);
        q -= alpha[k] * Y[k];
      }
      for(std::size_t i = 0; i < nfree; ++i) {
        const double m = cells[number_of_fixed_sites + i].mass;
        q.segment(Eigen::Index(i) * D, D) *= (m > 0 ? 0.5 / m : 0.0);
      }
      for(std::size_t k = 0; k < S.size(); ++k) {
        const double beta = RHO[k] * Y[k].dot(q);
        q += (alpha[k] - beta) * S[k];
      }
      Eigen::VectorXd d = -q;
      if constexpr(tangent_hook)
        for(std::size_t i = 0; i < nfree; ++i) {
          const Point di = d.segment(Eigen::Index(i) * D, D);
          d.segment(Eigen::Index(i) * D, D) = domain.project_to_tangent_plane(sites[number_of_fixed_sites + i], di);
        }
      double slope = g.dot(d);
      if(!(slope < 0)) {  // not a descent direction: restart from the preconditioned gradient
        S.clear(); Y.clear(); RHO.clear();
        for(std::size_t i = 0; i < nfree; ++i) {
          const double m = cells[number_of_fixed_sites + i].mass;
          d.segment(Eigen::Index(i) * D, D) = -g.segment(Eigen::Index(i) * D, D) * (m > 0 ? 0.5 / m : 0.0);
        }
        slope = g.dot(d);
      }
      std::vector<Point> trial = sites;
      std::vector<Cell> trial_cells;
      double step = 1.0, E_trial = E;
      bool accepted = false;
      for(int k = 0; k < 12 && !accepted; ++k, step *= 0.5) {
        bool inside = true;
        for(std::size_t i = 0; i < nfree && inside; ++i) {
          const std::size_t s = number_of_fixed_sites + i;
          if constexpr(domain_hook)
            trial[s] = domain.project_to_domain(Point(sites[s] + step * d.segment(Eigen::Index(i) * D, D)));
          else
            trial[s] = sites[s] + step * d.segment(Eigen::Index(i) * D, D);
          inside = domain.contains(trial[s]);
        }
        if(!inside) continue;
        E_trial = energy_of(trial, trial_cells);
        accepted = E_trial <= E + 1e-4 * step * slope;
      }
      if(accepted) {
        gradient_of(trial, trial_cells, g_new);
        Eigen::VectorXd s_vec(nvar), y_vec = g_new - g;
        for(std::size_t i = 0; i < nfree; ++i)
          s_vec.segment(Eigen::Index(i) * D, D) = trial[number_of_fixed_sites + i] - sites[number_of_fixed_sites + i];
        const double sy = s_vec.dot(y_vec);
        if(sy > 1e-16 * s_vec.squaredNorm()) {
          S.push_back(s_vec); Y.push_back(y_vec); RHO.push_back(1.0 / sy);
          if(S.size() > memory) { S.pop_front(); Y.pop_front(); RHO.pop_front(); }
        }
        sites.swap(trial);
        cells.swap(trial_cells);
        E = E_trial;
        g.swap(g_new);
        report.energy.push_back(E);
        report.iterations = it + 1;
        if(!vis.on_iteration(Stage::CVT, it + 1, max_it, E)) throw Cancelled("cancelled by the visitor during the CVT");
        continue;
      }
      ++report.lloyd_fallbacks;
      S.clear(); Y.clear(); RHO.clear();
      lloyd_step(sites, cells);
      E = energy_of(sites, cells);
    }
    gradient_of(sites, cells, g);
    report.energy.push_back(E);
    report.iterations = it + 1;
    if(!vis.on_iteration(Stage::CVT, it + 1, max_it, E)) throw Cancelled("cancelled by the visitor during the CVT");
  }
  report.gradient_norm = total_mass > 0 ? g.norm() / total_mass : 0;
  return report;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_WEIGHTED_CENTROIDAL_VORONOI_TESSELLATION_H
