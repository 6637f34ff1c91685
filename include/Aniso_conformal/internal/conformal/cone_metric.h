// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_CONE_METRIC_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_CONE_METRIC_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/conformal/layout.h>
#include <Aniso_conformal/internal/conformal/newton_solver.h>
#include <Aniso_conformal/internal/printable.h>
#include <Aniso_conformal/internal/visitor_helper.h>

#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

// A flat metric with cone singularities, conformal to the metric of an intrinsic triangulation: the first
// stage of issue 16 (surfaces with long limbs, whose uniformization metric on the sphere shrinks a limb
// exponentially in its length over its width). Two entry points:
//  - solve_cone_metric(): the conformal factor u for prescribed cone angles (Gauss-Bonnet checked), by
//    the Newton solve of every domain (newton_solver.h, with intrinsic Delaunay flips: Gillespie,
//    Springborn and Crane 2021, "Discrete conformal equivalence of polyhedral surfaces", which guarantee
//    a solution for any cone angles that satisfy Gauss-Bonnet);
//  - place_cones(): cones that bound the area distortion, by the greedy method of Ben-Chen, Gotsman and
//    Bunin 2008 ("Conformal flattening by curvature prescription and metric scaling", section 4).
// cone_embedding() (the cone domain) calls place_cones(); the linearised rounds of the placement are
// Linear_cone_placement.

namespace Aniso_conformal {
namespace internal {

/*
 * A flat metric with cone singularities on an intrinsic triangulation: the edge of vertices i, j has
 * length `exp((u_i + u_j) / 2) l_ij` (Springborn, Schroeder and Pinkall 2008), with `l_ij` the lengths of
 * the triangulation after its flips (which keep the conformal class), and angle sum 2 pi at every vertex
 * but the cones.
 */
struct Cone_metric {
  std::vector<int> cones;           // vertices of the triangulation carrying a cone (possibly none)
  std::vector<double> cone_angles;  // per cone, its angle sum in the flat metric (radians, in (0, inf))
  std::vector<double> u;            // per vertex (number_of_vertices()), the log scale factor (dimensionless);
                                    // shifted so that the flat metric has the area of the triangulation's
  double u_range = 0;               // max u - min u; the area distortion is exp(2 u_range)
  double start_u_range = 0;         // place_cones(): the range of u with the starting cones only (of the linearised
                                    // problem unless positive_cones_only)
  int genus = 0;                    // of the closed surface
  std::size_t iterations = 0;       // Newton iterations, summed over the solves
  std::size_t solves = 0;           // Newton solves (solve_cone_metric(): one; place_cones(): one per nonlinear round)
  bool double_edges = false;        // place_cones(): its flips could double edges (Cone_placement_options)
  std::size_t flips = 0;            // intrinsic Delaunay flips (the first, metric-keeping pass and the solves')
  double residual = 0;              // max |target - angle sum| over every vertex, cones included (radians)
  std::size_t rejected_cones = 0;   // place_cones() with positive_cones_only: cones withdrawn (angle 2 pi or more)
  std::size_t linearised_cones = 0; // place_cones(): cones placed by the linearised rounds (Linear_cone_placement)
};

// the bounds of place_cones()
struct Cone_placement_options {
  double max_log_range = 2.0;   // budget on the range of u (area distortion exp(2 max_log_range))
  // when `max_cones` cones (or the solves, or the candidates) are spent with the range still above the
  // budget: accepted if at most this (area distortion e^8 at 4, which the CVT's density carries; the
  // sphere accepts far more), else Convergence_failure. CGAL's blade.off with the curvature metric: 2.19
  // after 160 cones
  double acceptable_log_range = 4.0;
  std::size_t max_cones = 64;   // the most cones placed (at least the start's)
  // genus 0 only: keep every cone angle in (0, 2 pi) (positive curvature). Off by default: a body with
  // limbs needs cones of negative curvature where the limbs join it (benchmark/cones.md)
  bool positive_cones_only = false;
  // the Newton solves' Delaunay flips may double an edge (cone_metric_geometry()); the retry of
  // cone_embedding() when a placement without ends with flat triangles
  bool double_edges = false;
};

// the angle sum of every vertex in the metric scaled by `u`, and the number of flat triangles
inline std::vector<double> scaled_angle_sums(const Intrinsic_triangulation& itri, const std::vector<double>& u, std::size_t& degenerate)
{
  std::vector<double> sum(itri.number_of_vertices(), 0.0);
  degenerate = 0;
  for(int f = 0; f < int(itri.number_of_faces()); ++f) {
    bool deg;
    const std::array<double, 3> a = corner_angles(scaled_face_lengths(itri, f, u), deg);
    if(deg) ++degenerate;
    const auto& c = itri.face_vertices(std::size_t(f));
    for(int k = 0; k < 3; ++k) sum[std::size_t(c[k])] += a[std::size_t(k)];
  }
  return sum;
}

// the total area of `itri` scaled by `u`
inline double scaled_area(const Intrinsic_triangulation& itri, const std::vector<double>& u)
{
  double area = 0;
  for(int f = 0; f < int(itri.number_of_faces()); ++f) {
    const std::array<double, 3> l = scaled_face_lengths(itri, f, u);
    area += heron_area(l[0], l[1], l[2]);
  }
  return area;
}

// Shifts m.u by a constant so that the area is `area`, and fills u_range, residual (against `target`) and
// the cone angles; Convergence_failure if a triangle is flat in the solution, after adding to `flat_edges`
// (if given) the longest edge of each flat triangle (its end vertices), the one facing its angle of 180 degrees
inline void finish_cone_metric(const Intrinsic_triangulation& itri, double area, const std::vector<double>& target, const std::string& who,
                               Cone_metric& m, std::vector<std::pair<int, int>>* flat_edges = nullptr)
{
  const double shift = 0.5 * std::log(area / scaled_area(itri, m.u));
  for(double& x : m.u) x += shift;
  const auto mm = std::minmax_element(m.u.begin(), m.u.end());
  m.u_range = *mm.second - *mm.first;
  std::size_t degenerate = 0;
  const std::vector<double> sums = scaled_angle_sums(itri, m.u, degenerate);
  if(degenerate > 0 && flat_edges)
    for(int f = 0; f < int(itri.number_of_faces()); ++f) {
      bool flat;
      const std::array<double, 3> l = scaled_face_lengths(itri, f, m.u);
      corner_angles(l, flat);
      if(!flat) continue;
      const int k = int(std::max_element(l.begin(), l.end()) - l.begin());  // edge k of face f: halfedge 3 f + k
      flat_edges->emplace_back(itri.tail(3 * f + k), itri.head(3 * f + k));
    }
  if(degenerate > 0 || !std::isfinite(m.u_range))
    throw Convergence_failure(who + ": " + std::to_string(degenerate) +
                                  " triangles are flat in the cone metric (range of u " + std::to_string(m.u_range) + ")",
                              m.u_range);
  m.residual = 0;
  for(std::size_t v = 0; v < sums.size(); ++v) m.residual = std::max(m.residual, std::abs(target[v] - sums[v]));
  m.cone_angles.clear();
  for(int c : m.cones) m.cone_angles.push_back(sums[std::size_t(c)]);
}

/*
 * Checks prescribed cones on the closed triangulation `itri`: vertices in range and distinct, angles
 * finite and positive, and the discrete Gauss-Bonnet theorem `sum_c (2 pi - angle_c) = 2 pi chi` within
 * `1e-9 (1 + sum |2 pi - angle_c|)`. Returns the genus. Invalid_input (naming `who`) otherwise, or if
 * `itri` has a boundary.
 */
inline int check_cone_angles(const Intrinsic_triangulation& itri, const std::vector<int>& cones, const std::vector<double>& angles,
                             const std::string& who)
{
  const double two_pi = 2 * 3.14159265358979323846;
  const int genus = require_closed_surface(itri, who, "a cone metric", [](int) { return true; }, "any genus");
  if(cones.size() != angles.size())
    throw Invalid_input(who + ": " + std::to_string(cones.size()) + " cones but " + std::to_string(angles.size()) + " angles");
  std::vector<char> seen(itri.number_of_vertices(), 0);
  double curvature = 0, scale = 1;
  for(std::size_t i = 0; i < cones.size(); ++i) {
    if(cones[i] < 0 || std::size_t(cones[i]) >= seen.size() || seen[std::size_t(cones[i])])
      throw Invalid_input(who + ": cone " + std::to_string(i) + " names vertex " + std::to_string(cones[i]) +
                          " (out of range or repeated)");
    seen[std::size_t(cones[i])] = 1;
    if(!(angles[i] > 0) || !std::isfinite(angles[i]))
      throw Invalid_input(who + ": cone " + std::to_string(i) + " has angle " + std::to_string(angles[i]) + " (must be positive)");
    curvature += two_pi - angles[i];
    scale += std::abs(two_pi - angles[i]);
  }
  const double chi = 2.0 - 2.0 * genus;
  if(!(std::abs(curvature - two_pi * chi) <= 1e-9 * scale))
    throw Invalid_input(who + ": the cones' curvatures sum to " + std::to_string(curvature) + " but Gauss-Bonnet needs 2 pi chi = " +
                        std::to_string(two_pi * chi) + " (genus " + std::to_string(genus) + ")");
  return genus;
}

// The geometry of the cone placement's Newton solves: Euclidean vertex scaling whose Delaunay flips may,
// with `double_edges`, join two vertices joined already (a Delta-complex, as Gillespie, Springborn and
// Crane 2021 allow; their existence proof needs it). Without such flips a triangle can stay flat at the
// solution where the flip that opens it would double an edge around a handle narrower than a triangle
// (CGAL's femur with the curvature metric: 3 such triangles, the angles facing the long edge summing to
// pi + 2.5; cheese, genus 133: 14), and the placement was refused.
inline Euclidean_vertex_scaling cone_metric_geometry(bool double_edges)
{
  Euclidean_vertex_scaling g;
  g.allow_double_edges = double_edges;
  return g;
}

/*
 * Solves for the flat metric with cone angle `angles[i]` (radians) at vertex `cones[i]` and angle sum
 * 2 pi at every other vertex, conformal to the metric of `itri` (its edge lengths, as after
 * `adjust_edge_lengths()`): a first intrinsic Delaunay pass that keeps the metric, then Newton's method
 * with intrinsic Delaunay flips (Ptolemy lengths, which keep the conformal class) on the convex energy
 * of Springborn, Schroeder and Pinkall 2008, u fixed at one vertex (the first cone, or vertex 0) for the
 * gauge; by Gauss-Bonnet that vertex then has its target too. u is shifted at the end so that the flat
 * metric has the area of `itri` (u = 0: no scaling). Bounds and visitor from the named parameters
 * (`max_conformal_iterations`, `conformal_tolerance`, `max_flips_per_edge`, `visitor`).
 *
 * Shapes: `cones` and `angles` of one size (0 allowed: a flat torus); the result's `u` has one entry per
 * vertex. `itri`'s edges are flipped. Source: Gillespie, Springborn and Crane 2021 (existence for any
 * angles satisfying Gauss-Bonnet, with flips); Ben-Chen, Gotsman and Bunin 2008 (cone metrics).
 * \throws Invalid_input from check_cone_angles() (boundary, bad cones, Gauss-Bonnet violated)
 * \throws Convergence_failure if Newton's method does not reach the tolerance within its bounds (with the
 *         angle-sum error reached), or a triangle is flat in the solution
 */
template <typename NamedParameters>
Cone_metric solve_cone_metric(Intrinsic_triangulation& itri, const std::vector<int>& cones, const std::vector<double>& angles,
                              const NamedParameters& np)
{
  const double two_pi = 2 * 3.14159265358979323846;
  const std::string who = "cone metric";
  Cone_metric m;
  m.genus = check_cone_angles(itri, cones, angles, "solve_cone_metric()");
  m.cones = cones;
  const Newton_bounds bounds = Newton_bounds::from(np);
  typename Visitor_reference<NamedParameters>::type vis = get_visitor(np);
  m.flips = make_intrinsic_delaunay(itri, bounds.flips_per_edge, who);
  const double area = scaled_area(itri, std::vector<double>(itri.number_of_vertices(), 0.0));
  std::vector<double> target(itri.number_of_vertices(), two_pi);
  for(std::size_t i = 0; i < cones.size(); ++i) target[std::size_t(cones[i])] = angles[i];
  std::vector<char> fixed(itri.number_of_vertices(), 0);
  fixed[cones.empty() ? 0 : std::size_t(cones[0])] = 1;
  Conformal_solution sol = solve_conformal_metric(itri, Euclidean_vertex_scaling(), fixed, std::vector<double>(itri.number_of_vertices(), 0.0),
                                                  bounds, vis, who, nullptr, &target);
  m.u = std::move(sol.u);
  m.iterations = sol.iterations;
  m.flips += sol.flips;
  m.solves = 1;
  finish_cone_metric(itri, area, target, who, m);
  // the gauge vertex gets its angle only through Gauss-Bonnet: its error is the sum of the others'
  if(!(m.residual <= std::max(1e-6, 1e3 * bounds.tolerance)))
    throw Convergence_failure(who + ": the angle-sum error reached " + std::to_string(m.residual) + " at the gauge vertex", m.residual);
  return m;
}

// Start of place_cones(): genus 0, four vertices by farthest-point sampling in space from the one
// farthest from the centroid (extreme points: the tips of the limbs); genus 1, none; genus >= 2, the
// vertex farthest from the centroid (its cone takes the whole curvature 2 pi chi, angle above 2 pi).
inline std::vector<int> starting_cones(const Intrinsic_triangulation& itri, int genus)
{
  const int nv = int(itri.number_of_vertices());
  if(genus == 1 || nv == 0) return {};
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for(int v = 0; v < nv; ++v) centroid += itri.position(v);
  centroid /= double(nv);
  std::vector<double> distance(static_cast<std::size_t>(nv));
  for(int v = 0; v < nv; ++v) distance[std::size_t(v)] = (itri.position(v) - centroid).norm();
  std::vector<int> cones;
  const std::size_t count = genus == 0 ? 4 : 1;
  for(std::size_t k = 0; k < count && k < std::size_t(nv); ++k) {
    const int c = int(std::max_element(distance.begin(), distance.end()) - distance.begin());
    cones.push_back(c);
    for(int v = 0; v < nv; ++v)  // from now on, the distance to the nearest chosen vertex
      distance[std::size_t(v)] = std::min(k == 0 ? std::numeric_limits<double>::infinity() : distance[std::size_t(v)],
                                          (itri.position(v) - itri.position(c)).norm());
  }
  return cones;
}

/*
 * The Dirichlet step of Ben-Chen, Gotsman and Bunin 2008: u = 0 at the cones (at vertex 0 too for genus
 * 1 without cones, the gauge), angle sum 2 pi elsewhere, from u = 0 (a warm start from the previous
 * round, with the new cone's u set to 0, made the flips cycle on the cow: a jump of 5 in u at one vertex
 * is far from the solution for Newton's method); the cone angles are then
 * the angle sums the solution has at the cones (Gauss-Bonnet holds by construction). The solve's figures
 * are added to `m`; `itri` is flipped by Ptolemy flips (same conformal class).
 */
template <typename Visitor>
std::vector<double> dirichlet_cone_solve(Intrinsic_triangulation& itri, const std::vector<int>& cones, const Newton_bounds& bounds,
                                         Visitor& vis, Cone_metric& m)
{
  std::vector<char> fixed(itri.number_of_vertices(), 0);
  for(int c : cones) fixed[std::size_t(c)] = 1;
  if(cones.empty()) fixed[0] = 1;
  Conformal_solution sol = solve_conformal_metric(itri, cone_metric_geometry(m.double_edges), fixed,
                                                  std::vector<double>(itri.number_of_vertices(), 0.0), bounds, vis, "cone placement", nullptr, nullptr);
  m.iterations += sol.iterations;
  m.flips += sol.flips;
  ++m.solves;
  return std::move(sol.u);
}

/*
 * The linearised Dirichlet problem of the greedy placement, as Ben-Chen, Gotsman and Bunin 2008 solve
 * it (section 4: the Poisson equation of the cotangent Laplacian, `L u = Theta - 2 pi`, u = 0 at the
 * cones): one Newton step from u = 0 of dirichlet_cone_solve(), on `itri` as it is (intrinsic Delaunay
 * for u = 0), with no flip. The Laplacian with u = 0 at the `base` cones is factorised once; each cone
 * added afterwards is one more Dirichlet condition, imposed by the capacitance (Schur complement) method:
 * u = L^-1 (g + sum_j lambda_j e_(a_j)) with the k x k system S lambda = -x_A, S_ij = (L^-1 e_(a_j))_(a_i),
 * x = L^-1 g, so that adding a cone costs two triangular solves, not a factorisation, and the memory
 * is that of one factor plus k^2 numbers. `base` empty (genus 1, no cone): vertex 0 holds the gauge
 * until the first cone is added, which then becomes the base (the factorisation is redone once).
 *
 * Shapes: every vector of u has number_of_vertices() entries, 0 at the cones.
 * \throws Convergence_failure if the factorisation or a triangular solve fails (a Laplacian with a
 *         zero pivot: flat triangles), with the reason
 */
class Linear_cone_placement {
public:
  Linear_cone_placement(const Intrinsic_triangulation& itri, const std::vector<int>& base) : m_itri(itri)
  {
    factorise(base.empty() ? std::vector<int>{0} : base);
    m_gauge_only = base.empty();
  }

  // adds a cone at vertex `v` (not a cone yet)
  void add(int v)
  {
    if(m_gauge_only) {  // the gauge vertex was not a cone: start again from the new cone
      factorise({v});
      m_gauge_only = false;
      return;
    }
    const int i = m_index[std::size_t(v)];
    Eigen::VectorXd e = Eigen::VectorXd::Zero(m_n), G;
    e[i] = 1;
    solve_into(e, G);
    const Eigen::Index k = Eigen::Index(m_added.size());
    m_added.push_back(i);
    m_S.conservativeResize(k + 1, k + 1);
    for(Eigen::Index j = 0; j <= k; ++j) m_S(j, k) = m_S(k, j) = G[m_added[std::size_t(j)]];
  }

  // u with the cones so far (0 at each), per vertex
  std::vector<double> solve() const
  {
    Eigen::VectorXd rhs = m_g, x = m_x;
    if(!m_added.empty()) {
      Eigen::VectorXd xa(Eigen::Index(m_added.size()));
      for(std::size_t j = 0; j < m_added.size(); ++j) xa[Eigen::Index(j)] = m_x[m_added[j]];
      const Eigen::VectorXd lambda = m_S.ldlt().solve(-xa);
      for(std::size_t j = 0; j < m_added.size(); ++j) rhs[m_added[j]] += lambda[Eigen::Index(j)];
      solve_into(rhs, x);
    }
    std::vector<double> u(m_index.size(), 0.0);
    for(std::size_t v = 0; v < m_index.size(); ++v)
      if(m_index[v] >= 0) u[v] = x[m_index[v]];
    for(int i : m_added) u[std::size_t(m_vertex[std::size_t(i)])] = 0;  // exactly, not to rounding
    return u;
  }

private:
  void factorise(const std::vector<int>& base)
  {
    const std::size_t nv = m_itri.number_of_vertices();
    m_index.assign(nv, -1);
    m_vertex.clear();
    std::vector<char> fixed(nv, 0);
    for(int c : base) fixed[std::size_t(c)] = 1;
    for(std::size_t v = 0; v < nv; ++v)
      if(!fixed[v]) m_index[v] = int(m_vertex.size()), m_vertex.push_back(int(v));
    m_n = Eigen::Index(m_vertex.size());
    std::vector<double> angle_sum(nv, 0.0);
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(12 * m_itri.number_of_faces());
    const Euclidean_vertex_scaling geometry;
    const std::vector<double> zero(nv, 0.0);
    for(int f = 0; f < int(m_itri.number_of_faces()); ++f) {
      bool deg;
      const std::array<double, 3> l = geometry.face_lengths(m_itri, f, zero);
      const std::array<double, 3> a = geometry.angles(l, deg);
      const auto& c = m_itri.face_vertices(std::size_t(f));
      for(int k = 0; k < 3; ++k) angle_sum[std::size_t(c[k])] += a[std::size_t(k)];
      geometry.add_hessian(c, l, a, deg, m_index, triplets);
    }
    Eigen::SparseMatrix<double> H(m_n, m_n);
    H.setFromTriplets(triplets.begin(), triplets.end());
    for(Eigen::Index i = 0; i < m_n; ++i) H.coeffRef(i, i) += 1e-12;  // as the Newton solve: flat triangles zero a row
    H.makeCompressed();
    m_g.resize(m_n);
    for(Eigen::Index i = 0; i < m_n; ++i) m_g[i] = angle_sum[std::size_t(m_vertex[std::size_t(i)])] - 2 * 3.14159265358979323846;
    m_factor.cholmod_enabled = std::size_t(m_n) >= Newton_bounds().cholmod_min_unknowns;
    std::string failure;
    if(!m_factor.factorize(H, true, failure))
      throw Convergence_failure("cone placement: the cotangent Laplacian could not be factorised (" + failure + ")",
                                std::numeric_limits<double>::infinity());
    m_added.clear();
    m_S.resize(0, 0);
    solve_into(m_g, m_x);
  }
  void solve_into(const Eigen::VectorXd& b, Eigen::VectorXd& x) const
  {
    if(!m_factor.solve(b, x) || !x.allFinite())
      throw Convergence_failure(std::string("cone placement: the triangular solves of the cotangent Laplacian failed (") +
                                    m_factor.backend() + ")",
                                std::numeric_limits<double>::infinity());
  }

  const Intrinsic_triangulation& m_itri;
  std::vector<int> m_index, m_vertex;  // vertex -> unknown (-1 at the base), unknown -> vertex
  std::vector<int> m_added;            // unknowns of the cones added after the factorisation
  Eigen::Index m_n = 0;
  Sparse_factor m_factor;
  Eigen::VectorXd m_g, m_x;  // angle sums - 2 pi, and L^-1 of it
  Eigen::MatrixXd m_S;       // the capacitance matrix of the added cones
  bool m_gauge_only = false;
};

// the index in `cones` of the cone with the largest angle sum in the metric scaled by `u` if that angle is
// 2 pi or more (a cone of negative or no curvature), -1 otherwise
inline int widest_cone(const Intrinsic_triangulation& itri, const std::vector<double>& u, const std::vector<int>& cones)
{
  std::size_t degenerate = 0;
  const std::vector<double> sums = scaled_angle_sums(itri, u, degenerate);
  int widest = -1;
  double angle = 2 * 3.14159265358979323846;
  for(std::size_t i = 0; i < cones.size(); ++i)
    if(sums[std::size_t(cones[i])] >= angle) angle = sums[std::size_t(cones[i])], widest = int(i);
  return widest;
}

// The next cone of place_cones(): the vertex, not a cone nor refused, where |u| is largest, u being the
// Dirichlet solution (0 at the cones: the scale the cones share), as Ben-Chen, Gotsman and Bunin 2008,
// section 4 (`below`: only where u < 0, where a cone takes positive curvature); -1 if there is none.
inline int next_cone(const std::vector<double>& u, const std::vector<char>& taken, bool below)
{
  int best = -1;
  double worst = -1;
  for(std::size_t v = 0; v < u.size(); ++v) {
    if(taken[v] || (below && !(u[v] < 0))) continue;
    if(std::abs(u[v]) > worst) worst = std::abs(u[v]), best = int(v);
  }
  return best;
}

/*
 * Places cones on the closed triangulation `itri` (edge lengths of the metric, as after
 * `adjust_edge_lengths()`) until the flat cone metric's range of u is at most
 * `options.max_log_range` (area distortion at most `exp(2 max_log_range)`): the greedy method of
 * Ben-Chen, Gotsman and Bunin 2008, section 4. Start: starting_cones() (genus 0: four extreme points;
 * genus 1: none, the flat torus; genus >= 2: one). The cones are first placed on the linearised problem
 * (Linear_cone_placement: the cotangent Laplacian factorised once, two triangular solves per cone, as
 * Ben-Chen et al. do) until its range of u is within the budget; then, as long as the range of the
 * nonlinear solution is not, the nonlinear rounds go on. Every nonlinear round solves the Dirichlet
 * problem u = 0 at the cones, angle sum 2 pi elsewhere (their rule: each cone's curvature is what the
 * solve gives it, so Gauss-Bonnet holds), and puts the next cone at the vertex where |u| is largest (u = 0 at the cones:
 * the distance to the cones' common scale; for the Dirichlet solution this is their rule, and |u - mean u|
 * is not: it kept choosing vertices at the cones' own scale while the body stayed expanded).
 *
 * The linearised rounds cut the placement's time 10 to 40 times on CGAL's limb models (cow 3.6 s ->
 * 0.1 s, armadillo 32 s -> 2.5 s, man 36 s -> 0.9 s; benchmark/cones.md): one Newton solve, not one per
 * cone; they underestimate the range where the limbs are long, so 0 to 12 nonlinear rounds follow.
 * start_u_range is then that of the linearised problem.
 *
 * Cones of either sign are kept by default. With `options.positive_cones_only` (genus 0, only nonlinear
 * rounds), cone angles are kept in (0, 2 pi): the next cone is sought where u < 0 only (where a cone takes positive curvature),
 * and while more than three cones are left, the widest cone is withdrawn and the metric solved again
 * whenever its angle is 2 pi or more (its vertex is not tried again; `rejected_cones` counts them); three
 * cones (the fewest whose curvatures, each below 2 pi, can sum to 4 pi) are never withdrawn, so with three
 * left an angle of 2 pi or more is kept and reported. That variant cannot bound a body with several
 * limbs: a limb whose tip cone takes less than the curvature 2 pi of its cap carries the rest through its
 * cylinder, whose scale then changes exponentially along it (as on the sphere), and the positive
 * curvatures sum to 4 pi only, so all the limbs' caps cannot be absorbed at their tips; the joints'
 * negative curvature has to go to cones of angle above 2 pi. Genus >= 1 always needs those (total
 * curvature 0 or negative).
 *
 * The result's u is shifted so that the flat metric has the area of `itri`, as in solve_cone_metric()
 * with the same cones and angles (which reproduces it). Bounded: at most `max_cones` cones; a cone is
 * added only while fewer than `2 max_cones + 2` Newton solves were made (withdrawals' included; the
 * linearised rounds stop at `max_cones` cones too), and each
 * withdrawal removes a cone the start or an addition put, so there are at most `2 (2 max_cones + 2) + 4`
 * solves, each bounded by the Newton bounds of the named parameters (and their visitor).
 * \throws Invalid_input if `itri` has a boundary
 * \throws Convergence_failure if the range of u is above `options.acceptable_log_range` when `max_cones`
 *         cones are placed (or no candidate vertex is left, or the solves are spent; between the budget
 *         and that bound the metric is returned), with the range of u reached as its residual and in its message;
 *         or if a Newton solve fails (with its angle-sum error)
 */
template <typename NamedParameters>
Cone_metric place_cones(Intrinsic_triangulation& itri, const Cone_placement_options& options, const NamedParameters& np,
                        std::vector<std::pair<int, int>>* flat_edges = nullptr)
{
  const double two_pi = 2 * 3.14159265358979323846;
  const std::string who = "cone placement";
  Cone_metric m;
  m.genus = require_closed_surface(itri, "place_cones()", "a cone metric", [](int) { return true; }, "any genus");
  m.double_edges = options.double_edges;
  const Newton_bounds bounds = Newton_bounds::from(np);
  typename Visitor_reference<NamedParameters>::type vis = get_visitor(np);
  const std::size_t nv = itri.number_of_vertices();
  m.flips = make_intrinsic_delaunay(itri, bounds.flips_per_edge, who);
  const double area = scaled_area(itri, std::vector<double>(nv, 0.0));
  std::vector<char> taken(nv, 0);
  m.cones = starting_cones(itri, m.genus);
  for(int c : m.cones) taken[std::size_t(c)] = 1;
  const std::size_t max_solves = 2 * options.max_cones + 2;
  auto range_of = [](const std::vector<double>& x) {
    const auto mm = std::minmax_element(x.begin(), x.end());
    return *mm.second - *mm.first;
  };
  std::vector<double> u;
  if(!options.positive_cones_only) {
    // the linearised rounds: one factorisation, two triangular solves per cone
    Linear_cone_placement linear(itri, m.cones);
    u = linear.solve();
    m.start_u_range = range_of(u);
    while(range_of(u) > options.max_log_range && m.cones.size() < options.max_cones) {
      const int v = next_cone(u, taken, false);
      if(v < 0) break;
      taken[std::size_t(v)] = 1;
      m.cones.push_back(v);
      linear.add(v);
      u = linear.solve();
      ++m.linearised_cones;
    }
    u = dirichlet_cone_solve(itri, m.cones, bounds, vis, m);
  } else {
    u = dirichlet_cone_solve(itri, m.cones, bounds, vis, m);
    m.start_u_range = range_of(u);
  }
  std::string stop;
  while(true) {
    // positive_cones_only: withdraw the widest cone if its curvature is not positive
    if(options.positive_cones_only && m.genus == 0 && m.cones.size() > 3) {
      const int w = widest_cone(itri, u, m.cones);
      if(w >= 0) {
        m.cones.erase(m.cones.begin() + w);
        ++m.rejected_cones;
        u = dirichlet_cone_solve(itri, m.cones, bounds, vis, m);
        continue;  // bounded: a withdrawn vertex is not taken again (see the bound above)
      }
    }
    if(range_of(u) <= options.max_log_range) break;
    if(m.cones.size() >= options.max_cones) stop = std::to_string(options.max_cones) + " cones (the most allowed)";
    else if(m.solves >= max_solves) stop = std::to_string(max_solves) + " solves (the most allowed)";
    const int v = stop.empty() ? next_cone(u, taken, options.positive_cones_only && m.genus == 0) : -1;
    if(v < 0 && stop.empty()) stop = "no candidate vertex left";
    if(!stop.empty() && range_of(u) <= options.acceptable_log_range) break;
    if(!stop.empty())
      throw Convergence_failure(who + ": the range of the log scale factor is still " + short_number(range_of(u)) +
                                    " (area distortion " + short_number(std::exp(2 * range_of(u))) + ") above the budget " +
                                    short_number(options.max_log_range) + " after " + std::to_string(m.cones.size()) +
                                    " cones: " + stop,
                                range_of(u));
    taken[std::size_t(v)] = 1;
    m.cones.push_back(v);
    u = dirichlet_cone_solve(itri, m.cones, bounds, vis, m);
  }
  m.u = std::move(u);
  std::vector<double> target(nv, two_pi);
  std::size_t degenerate = 0;
  const std::vector<double> sums = scaled_angle_sums(itri, m.u, degenerate);
  for(int c : m.cones) target[std::size_t(c)] = sums[std::size_t(c)];
  finish_cone_metric(itri, area, target, who, m, flat_edges);
  return m;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_CONE_METRIC_H
