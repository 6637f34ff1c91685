// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_WEIGHTED_CENTROIDAL_VORONOI_TESSELLATION_H
#define ANISO_CONFORMAL_WEIGHTED_CENTROIDAL_VORONOI_TESSELLATION_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
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
// Optional: `D::line_search_halvings` (an int constant), for a domain whose energy is continuous only up
// to a small jump (the cone surface: a band of copies is one sheet around a cone, so a site crossing a
// seam changes the energy by ~1e-8 where the gradient predicts ~1e-12): the line search stops after that
// many halvings instead of 12 (more find no descent: they only cost energy evaluations), the L-BFGS
// memory is forgotten after a backtracked step (its curvature pairs straddle the jump), and the line
// search is non-monotone (Grippo, Lampariello and Lucidi 1986) over the first four fifths of the
// iterations: a step is accepted against the largest of the last 10 energies, not the current one. With
// the monotone test a quarter of the iterations on the cone surface failed their line search within the
// jumps and fell back to a Lloyd step after four wasted evaluations (cow, 3000 sites: 26 of 100, 262
// evaluations; now 7 and 163, G_avg 0.9347 -> 0.9396). The last fifth stays monotone: its Lloyd
// fallbacks even out the worst triangles (CGAL's femur, 5 seeds: median theta_min 14.7 with the window
// to the end, 23.2 with the last fifth monotone; benchmark/cones.md).
template <typename D, typename = void>
struct Line_search_halvings : std::integral_constant<int, 12> {
  static constexpr bool forget_after_backtracking = false;
  static constexpr std::size_t nonmonotone_window = 1;
};
template <typename D>
struct Line_search_halvings<D, std::void_t<decltype(D::line_search_halvings)>> : std::integral_constant<int, D::line_search_halvings> {
  static constexpr bool forget_after_backtracking = true;
  static constexpr std::size_t nonmonotone_window = 10;
};
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


namespace internal {

// The state of the CVT optimisation of weighted_centroidal_Voronoi_tessellation(): the sites, their
// cells, the energy and its gradient over the free sites, and the L-BFGS memory (7 pairs).
template <typename DomainTraits>
class Cvt_optimizer {
public:
  typedef typename DomainTraits::Point Point;
  typedef typename DomainTraits::Cell Cell;
  static constexpr int D = int(Point::RowsAtCompileTime);

  Cvt_optimizer(const DomainTraits& domain, std::vector<Point>& sites, std::size_t fixed, Cvt_report& report)
    : m_domain(domain), m_sites(sites), m_fixed(fixed), m_free(sites.size() - fixed), m_report(report)
  {
    m_energy = energy_of(m_sites, m_cells);
    m_report.energy.push_back(m_energy);
    for(const Cell& c : m_cells) m_total_mass += c.mass;
    gradient_of(m_sites, m_cells, m_g);
  }
  std::size_t number_of_free_sites() const { return m_free; }
  // the line search accepts a step only below the current energy (the last iterations: see Line_search_halvings)
  void set_monotone(bool m) { m_monotone = m; }
  double energy() const { return m_energy; }
  double relative_gradient_norm() const { return m_total_mass > 0 ? m_g.norm() / m_total_mass : 0; }

  // moves every free site to its centroid, as far as the domain allows (forgets the L-BFGS memory)
  void lloyd_step()
  {
    m_S.clear(); m_Y.clear(); m_RHO.clear();
    for(std::size_t s = m_fixed; s < m_sites.size(); ++s)
      if(m_cells[s].mass > 0) m_sites[s] = m_domain.move_towards(m_sites[s], m_cells[s].centroid);
    m_energy = energy_of(m_sites, m_cells);
    gradient_of(m_sites, m_cells, m_g);
    m_report.energy.push_back(m_energy);
  }

  // One L-BFGS iteration: the preconditioned two-loop direction, an Armijo backtracking line search (12
  // halvings, or the domain's Line_search_halvings) that also rejects steps leaving the domain; returns
  // false, changing nothing, if it fails.
  bool lbfgs_step()
  {
    Eigen::VectorXd d = direction();
    double slope = m_g.dot(d);
    if(!(slope < 0)) {  // not a descent direction: restart from the preconditioned gradient
      m_S.clear(); m_Y.clear(); m_RHO.clear();
      for(std::size_t i = 0; i < m_free; ++i) {
        const double m = m_cells[m_fixed + i].mass;
        d.segment(Eigen::Index(i) * D, D) = -m_g.segment(Eigen::Index(i) * D, D) * (m > 0 ? 0.5 / m : 0.0);
      }
      slope = m_g.dot(d);
    }
    std::vector<Point> trial = m_sites;
    std::vector<Cell> trial_cells;
    double step = 1.0, E_trial = m_energy;
    bool accepted = false;
    int k = 0;
    for(; k < Line_search_halvings<DomainTraits>::value && !accepted; ++k, step *= 0.5) {
      bool inside = true;
      for(std::size_t i = 0; i < m_free && inside; ++i) {
        const std::size_t s = m_fixed + i;
        if constexpr(Has_project_to_domain<DomainTraits>::value)
          trial[s] = m_domain.project_to_domain(Point(m_sites[s] + step * d.segment(Eigen::Index(i) * D, D)));
        else
          trial[s] = m_sites[s] + step * d.segment(Eigen::Index(i) * D, D);
        inside = m_domain.contains(trial[s]);
      }
      if(!inside) continue;
      E_trial = energy_of(trial, trial_cells);
      double reference = m_energy;
      const std::size_t W = m_monotone ? 1 : Line_search_halvings<DomainTraits>::nonmonotone_window;
      for(std::size_t j = m_report.energy.size() > W ? m_report.energy.size() - W : 0; j < m_report.energy.size(); ++j)
        reference = std::max(reference, m_report.energy[j]);
      accepted = E_trial <= reference + 1e-4 * step * slope;
    }
    if(!accepted) return false;
    if(Line_search_halvings<DomainTraits>::forget_after_backtracking && k > 1) {
      m_S.clear(); m_Y.clear(); m_RHO.clear();
    }
    Eigen::VectorXd g_new;
    gradient_of(trial, trial_cells, g_new);
    Eigen::VectorXd s_vec(m_g.size()), y_vec = g_new - m_g;
    for(std::size_t i = 0; i < m_free; ++i)
      s_vec.segment(Eigen::Index(i) * D, D) = trial[m_fixed + i] - m_sites[m_fixed + i];
    const double sy = s_vec.dot(y_vec);
    if(sy > 1e-16 * s_vec.squaredNorm()) {
      m_S.push_back(s_vec); m_Y.push_back(y_vec); m_RHO.push_back(1.0 / sy);
      if(m_S.size() > memory) { m_S.pop_front(); m_Y.pop_front(); m_RHO.pop_front(); }
    }
    m_sites.swap(trial);
    m_cells.swap(trial_cells);
    m_energy = E_trial;
    m_g.swap(g_new);
    m_report.energy.push_back(m_energy);
    return true;
  }

private:
  static constexpr std::size_t memory = 7;

  double energy_of(const std::vector<Point>& x, std::vector<Cell>& c)
  {
    m_domain.integrate(x, c);
    ++m_report.energy_evaluations;
    double e = 0;
    for(const Cell& cell : c) e += cell.energy;
    return e;
  }
  void gradient_of(const std::vector<Point>& x, const std::vector<Cell>& c, Eigen::VectorXd& g) const
  {
    g.resize(Eigen::Index(m_free) * D);
    for(std::size_t i = 0; i < m_free; ++i) {
      const std::size_t s = m_fixed + i;
      Point gs;
      if constexpr(Has_cell_gradient<Cell>::value)
        gs = c[s].gradient;
      else
        gs = 2.0 * c[s].mass * (x[s] - c[s].centroid);
      // fixed-size segments: GCC 12 misreads a dynamic one assigned from a Vector2d (-Wstringop-overread)
      if constexpr(Has_project_to_tangent_plane<DomainTraits>::value)
        g.template segment<Point::RowsAtCompileTime>(Eigen::Index(i) * D) = m_domain.project_to_tangent_plane(x[s], gs);
      else
        g.template segment<Point::RowsAtCompileTime>(Eigen::Index(i) * D) = gs;
    }
  }
  // the two-loop recursion with the mass preconditioner H0 = diag(1 / (2 m_i)), projected on the tangent planes
  Eigen::VectorXd direction() const
  {
    Eigen::VectorXd q = m_g, alpha(m_S.size());
    for(int k = int(m_S.size()) - 1; k >= 0; --k) {
      alpha[k] = m_RHO[k] * m_S[k].dot(q);
      q -= alpha[k] * m_Y[k];
    }
    for(std::size_t i = 0; i < m_free; ++i) {
      const double m = m_cells[m_fixed + i].mass;
      q.segment(Eigen::Index(i) * D, D) *= (m > 0 ? 0.5 / m : 0.0);
    }
    for(std::size_t k = 0; k < m_S.size(); ++k) {
      const double beta = m_RHO[k] * m_Y[k].dot(q);
      q += (alpha[k] - beta) * m_S[k];
    }
    Eigen::VectorXd d = -q;
    if constexpr(Has_project_to_tangent_plane<DomainTraits>::value)
      for(std::size_t i = 0; i < m_free; ++i) {
        const Point di = d.segment(Eigen::Index(i) * D, D);
        d.segment(Eigen::Index(i) * D, D) = m_domain.project_to_tangent_plane(m_sites[m_fixed + i], di);
      }
    return d;
  }

  const DomainTraits& m_domain;
  std::vector<Point>& m_sites;
  std::size_t m_fixed, m_free;
  Cvt_report& m_report;
  std::vector<Cell> m_cells;
  double m_energy = 0, m_total_mass = 0;
  bool m_monotone = false;
  Eigen::VectorXd m_g;
  std::deque<Eigen::VectorXd> m_S, m_Y;
  std::deque<double> m_RHO;
};

} // namespace internal

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
  const std::size_t max_it = internal::number_of_iterations(np);
  const Cvt_method method = internal::cvt_method(np);
  typename internal::Visitor_reference<NamedParameters>::type vis = internal::get_visitor(np);
  Cvt_report report;
  report.method = method;
  internal::Cvt_optimizer<DomainTraits> opt(domain, sites, number_of_fixed_sites, report);
  for(std::size_t it = 0; it < max_it && opt.number_of_free_sites() > 0; ++it) {
    opt.set_monotone(5 * it >= 4 * max_it);  // the last fifth: see Line_search_halvings
    if(method == Cvt_method::LBFGS && opt.lbfgs_step()) {
      report.iterations = it + 1;
      if(!vis.on_iteration(Stage::CVT, it + 1, max_it, opt.energy())) throw Cancelled("cancelled by the visitor during the CVT");
      continue;
    }
    if(method == Cvt_method::LBFGS) ++report.lloyd_fallbacks;  // the line search failed
    opt.lloyd_step();
    report.iterations = it + 1;
    if(!vis.on_iteration(Stage::CVT, it + 1, max_it, opt.energy())) throw Cancelled("cancelled by the visitor during the CVT");
  }
  report.gradient_norm = opt.relative_gradient_norm();
  return report;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_WEIGHTED_CENTROIDAL_VORONOI_TESSELLATION_H
