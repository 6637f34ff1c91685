// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_CONFORMAL_EMBEDDING_H
#define ANISO_CONFORMAL_CONFORMAL_EMBEDDING_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <string>
#include <vector>

/// \file conformal_embedding.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * a conformal embedding of a disk-topology `Intrinsic_triangulation` into the plane (stage 3)
 */
struct Planar_embedding {
  std::vector<Eigen::Vector2d> uv;         ///< domain position of each vertex
  std::vector<double> u;                   ///< log scale factor of each vertex (0 on the boundary)
  std::vector<double> conformal_factor;    ///< `cf(v)`: adjusted area around v over domain area around v (paper eq. 6)
  std::size_t iterations = 0;              ///< Newton iterations
  double residual = 0;                     ///< max |2 pi - angle sum| over interior vertices at the end
  std::size_t degenerate_triangles = 0;    ///< triangles treated as flat at the end of the solve (0 normally)
  std::size_t flips = 0;                   ///< intrinsic Delaunay flips made during the solve
};

namespace internal {

inline double heron_area(double a, double b, double c)
{
  const double s = (a + b + c) / 2;
  return std::sqrt(std::max(0.0, s * (s - a) * (s - b) * (s - c)));
}

// Angles of a triangle with side lengths l[k] (l[k] = length of halfedge k, from corner k to k+1);
// the angle at corner k is opposite halfedge k+1. A triangle that violates the triangle inequality gets
// the angles of the flat triangle (0, 0, pi): the convex extension of the energy of Bobenko, Pinkall
// and Springborn, which keeps Newton's method well defined.
inline std::array<double, 3> corner_angles(const std::array<double, 3>& l, bool& degenerate)
{
  std::array<double, 3> angle;
  degenerate = false;
  for(int k = 0; k < 3; ++k) {
    const double opp = l[(k + 1) % 3], a = l[k], b = l[(k + 2) % 3];
    if(opp >= a + b) { degenerate = true; angle = {{0, 0, 0}}; angle[k] = 3.14159265358979323846; return angle; }
  }
  for(int k = 0; k < 3; ++k) {
    const double opp = l[(k + 1) % 3], a = l[k], b = l[(k + 2) % 3];
    double c = (a * a + b * b - opp * opp) / (2 * a * b);
    angle[k] = std::acos(std::max(-1.0, std::min(1.0, c)));
  }
  return angle;
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * computes a conformal embedding of the disk `itri` into the plane (stage 3, DESIGN.md 3): discrete
 * conformal equivalence (Springborn, Schroeder, Pinkall 2008) with per-vertex log scales `u`, scaled
 * lengths `l'_ij = exp((u_i + u_j) / 2) l_ij`, `u = 0` on the boundary (boundary lengths are kept) and
 * angle sum `2 pi` at interior vertices, solved by Newton's method with the cotangent Laplacian as
 * Hessian (Eigen's sparse Cholesky) and a backtracking line search; then laid out by unfolding
 * triangles breadth-first, and the conformal factor computed per vertex (paper eq.\ 6).
 *
 * Before every evaluation the triangulation is made intrinsically Delaunay for the scaled lengths
 * (Gillespie, Springborn and Crane 2021): interior edges are flipped, the new edge's length given by
 * Ptolemy's relation, which is invariant under the scaling. This keeps every triangle valid during the
 * solve, so metrics the paper had to tame (strong images, high stretch) embed without inverted
 * triangles. `itri` is modified by these flips (its vertices, boundary and corners are not).
 *
 * \param itri a disk-topology triangulation with valid edge lengths (after `adjust_edge_lengths()`);
 *        interior edges may be flipped
 * \param np optional named parameters: `max_conformal_iterations` (default 100), `conformal_tolerance`
 *        (default `1e-9`, on the max angle-sum error in radians), `visitor`
 *        (`on_iteration(Stage::EMBEDDING, it, bound, residual)`).
 * \throws Invalid_input if `itri` has no boundary or no interior vertex
 * \throws Convergence_failure if Newton's method does not reach the tolerance within the bound, if the
 *         factorisation fails, or if the layout has inverted triangles (with the residual reached)
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Planar_embedding conformal_embedding(Intrinsic_triangulation& itri,
                                     const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const std::size_t max_it = choose_parameter(get_parameter(np, internal_np::max_conformal_iterations), 100u);
  const double tol = choose_parameter(get_parameter(np, internal_np::conformal_tolerance), 1e-9);
  typename internal::Visitor_reference<NamedParameters>::type vis = internal::get_visitor(np);
  const double two_pi = 2 * 3.14159265358979323846;

  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  std::vector<int> index(nv, -1);  // interior vertex -> unknown
  int n = 0;
  for(int v = 0; v < nv; ++v)
    if(!itri.is_boundary_vertex(v)) index[v] = n++;
  if(n == nv) throw Invalid_input("conformal_embedding(): the triangulation has no boundary (not a disk)");

  Planar_embedding emb;
  emb.u.assign(nv, 0.0);
  std::vector<double> angle_sum(nv);
  std::vector<Eigen::Triplet<double>> triplets;
  // Intrinsic Delaunay flips for the lengths scaled by u (Gillespie, Springborn, Crane 2021): the new
  // edge gets its length by Ptolemy's relation, which commutes with the scaling, so the flipped
  // triangulation describes the same discrete conformal class and the solve stays well posed (no
  // triangle degenerates) for any input lengths. Returns the number of flips.
  std::size_t flips_total = 0;
  auto scaled = [&](int h, const std::vector<double>& u) {
    return itri.length(h) * std::exp(0.5 * (u[itri.tail(h)] + u[itri.head(h)]));
  };
  auto opposite_angle = [&](int h, const std::vector<double>& u) {  // angle at the corner facing h
    const double o = scaled(h, u), a = scaled(Intrinsic_triangulation::next(h), u), b = scaled(Intrinsic_triangulation::prev(h), u);
    if(o >= a + b) return 3.14159265358979323846;
    if(a >= o + b || b >= o + a) return 0.0;
    return std::acos(std::max(-1.0, std::min(1.0, (a * a + b * b - o * o) / (2 * a * b))));
  };
  auto make_delaunay = [&](const std::vector<double>& u) {
    std::size_t flips = 0;
    const int nh = int(itri.number_of_halfedges());
    std::deque<int> queue;
    std::vector<char> queued(std::size_t(nh), 0);
    auto enqueue = [&](int h) {
      const int r = itri.is_edge_representative(h) ? h : itri.twin(h);
      if(itri.twin(r) >= 0 && !queued[std::size_t(r)]) { queued[std::size_t(r)] = 1; queue.push_back(r); }
    };
    for(int h = 0; h < nh; ++h) enqueue(h);
    const std::size_t budget = 50 * std::size_t(nh) + 100;  // Delaunay flips terminate; this only guards
    while(!queue.empty() && flips < budget) {
      const int h = queue.front();
      queue.pop_front();
      queued[std::size_t(h)] = 0;
      const int t = itri.twin(h);
      if(t < 0 || opposite_angle(h, u) + opposite_angle(t, u) <= 3.14159265358979323846 + 1e-10) continue;
      const int c = itri.opposite_vertex(h), d = itri.opposite_vertex(t);
      if(c == d || itri.find_halfedge(c, d) >= 0) continue;  // would create a double edge
      const double l_ab = itri.length(h), l_bc = itri.length(Intrinsic_triangulation::next(h)),
                   l_ca = itri.length(Intrinsic_triangulation::prev(h)), l_ad = itri.length(Intrinsic_triangulation::next(t)),
                   l_db = itri.length(Intrinsic_triangulation::prev(t));
      const int g = itri.flip(h);
      itri.set_length(g, (l_ad * l_bc + l_db * l_ca) / l_ab);  // Ptolemy on the quad a, d, b, c
      ++flips;
      for(int e : {Intrinsic_triangulation::next(g), Intrinsic_triangulation::prev(g),
                   Intrinsic_triangulation::next(itri.twin(g)), Intrinsic_triangulation::prev(itri.twin(g))})
        enqueue(e);
    }
    flips_total += flips;
    return flips;
  };

  // Evaluates angle sums and (optionally) the cotangent Laplacian at scales u, after making the
  // triangulation Delaunay for them.
  bool connectivity_changed = false;
  auto evaluate = [&](const std::vector<double>& u, bool with_hessian, std::size_t& degenerate) {
    if(make_delaunay(u) > 0) connectivity_changed = true;
    std::fill(angle_sum.begin(), angle_sum.end(), 0.0);
    triplets.clear();
    degenerate = 0;
    for(int f = 0; f < nf; ++f) {
      const auto& c = itri.face_vertices(f);
      std::array<double, 3> l;
      for(int k = 0; k < 3; ++k)
        l[k] = itri.length(3 * f + k) * std::exp(0.5 * (u[c[k]] + u[c[(k + 1) % 3]]));
      bool deg;
      std::array<double, 3> a = internal::corner_angles(l, deg);
      if(deg) ++degenerate;
      for(int k = 0; k < 3; ++k) angle_sum[c[k]] += a[k];
      if(!with_hessian) continue;
      for(int k = 0; k < 3; ++k) {
        // the edge opposite corner k is halfedge k+1, between corners k+1 and k+2
        const double w = deg ? 0.0 : 0.5 / std::tan(a[k]);
        const int i = index[c[(k + 1) % 3]], j = index[c[(k + 2) % 3]];
        if(i >= 0) triplets.emplace_back(i, i, w);
        if(j >= 0) triplets.emplace_back(j, j, w);
        if(i >= 0 && j >= 0) {
          triplets.emplace_back(i, j, -w);
          triplets.emplace_back(j, i, -w);
        }
      }
    }
    double r = 0;
    for(int v = 0; v < nv; ++v)
      if(index[v] >= 0) r = std::max(r, std::abs(two_pi - angle_sum[v]));
    return r;
  };

  Eigen::SparseMatrix<double> H(n, n);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  bool analysed = false;
  std::size_t degenerate = 0;
  double residual = evaluate(emb.u, true, degenerate);
  std::size_t it = 0;
  for(; it < max_it && residual > tol; ++it) {
    H.setFromTriplets(triplets.begin(), triplets.end());
    // a tiny diagonal shift keeps the factorisation definite where degenerate triangles zero a row
    for(int i = 0; i < n; ++i) H.coeffRef(i, i) += 1e-12;
    if(!analysed || connectivity_changed) {  // flips change the sparsity pattern
      solver.analyzePattern(H);
      analysed = true;
      connectivity_changed = false;
    }
    solver.factorize(H);
    if(solver.info() != Eigen::Success)
      throw Convergence_failure("conformal embedding: the sparse Cholesky factorisation failed at Newton iteration " +
                                    std::to_string(it),
                                residual);
    Eigen::VectorXd g(n);
    for(int v = 0; v < nv; ++v)
      if(index[v] >= 0) g[index[v]] = angle_sum[v] - two_pi;
    Eigen::VectorXd du = solver.solve(g);
    // backtracking on the residual: the energy is convex, so a full step is nearly always taken
    std::vector<double> trial(nv);
    double step = 1.0, r_new = residual;
    std::size_t deg_new = 0;
    for(int k = 0; k < 40; ++k, step *= 0.5) {
      for(int v = 0; v < nv; ++v) trial[v] = index[v] >= 0 ? emb.u[v] + step * du[index[v]] : 0.0;
      r_new = evaluate(trial, false, deg_new);
      if(r_new < residual || k == 39) break;
    }
    emb.u.swap(trial);
    residual = evaluate(emb.u, true, degenerate);
    if(!vis.on_iteration(Stage::EMBEDDING, it + 1, max_it, residual))
      throw Cancelled("cancelled by the visitor during the conformal embedding");
  }
  emb.iterations = it;
  emb.residual = residual;
  emb.degenerate_triangles = degenerate;
  emb.flips = flips_total;
  if(residual > tol)
    throw Convergence_failure("conformal embedding: Newton's method reached angle-sum error " + std::to_string(residual) +
                                  " after " + std::to_string(it) + " iterations (tolerance " + std::to_string(tol) + ")",
                              residual);

  // ---- layout: unfold breadth-first from the face nearest the "centre" (fewest hops to all)
  std::vector<std::array<double, 3>> L(nf);
  for(int f = 0; f < nf; ++f) {
    const auto& c = itri.face_vertices(f);
    for(int k = 0; k < 3; ++k)
      L[f][k] = itri.length(3 * f + k) * std::exp(0.5 * (emb.u[c[k]] + emb.u[c[(k + 1) % 3]]));
  }
  emb.uv.assign(nv, Eigen::Vector2d::Zero());
  std::vector<char> placed(nv, 0), done(nf, 0);
  std::deque<int> queue;  // halfedges whose face is to be laid out across them
  {
    const auto& c = itri.face_vertices(0);
    emb.uv[c[0]] = Eigen::Vector2d(0, 0);
    emb.uv[c[1]] = Eigen::Vector2d(L[0][0], 0);
    placed[c[0]] = placed[c[1]] = 1;
    queue.push_back(0);  // lay out face 0 across its halfedge 0
  }
  auto third_point = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, double lpr, double lqr) {
    // r to the left of p->q with |pr| = lpr, |qr| = lqr
    const Eigen::Vector2d e = q - p;
    const double d = e.norm();
    const double x = (lpr * lpr - lqr * lqr + d * d) / (2 * d);
    const double y = std::sqrt(std::max(0.0, lpr * lpr - x * x));
    const Eigen::Vector2d ex = e / d, ey(-ex.y(), ex.x());
    return Eigen::Vector2d(p + x * ex + y * ey);
  };
  while(!queue.empty()) {
    const int h = queue.front();
    queue.pop_front();
    const int f = Intrinsic_triangulation::face(h);
    if(done[f]) continue;
    done[f] = 1;
    const int a = itri.tail(h), b = itri.head(h), c = itri.opposite_vertex(h);
    const int k = h % 3;
    if(!placed[c]) {
      // corner k+2 = c; |ac| is halfedge k+2 (c->a), |bc| is halfedge k+1 (b->c)
      emb.uv[c] = third_point(emb.uv[a], emb.uv[b], L[f][(k + 2) % 3], L[f][(k + 1) % 3]);
      placed[c] = 1;
    }
    for(int j = 0; j < 3; ++j) {
      const int t = itri.twin(3 * f + j);
      if(t >= 0 && !done[Intrinsic_triangulation::face(t)]) queue.push_back(t);
    }
  }

  // ---- validity and conformal factor
  std::size_t inverted = 0;
  std::vector<double> adjusted_area(nv, 0.0), domain_area(nv, 0.0);
  for(int f = 0; f < nf; ++f) {
    const auto& c = itri.face_vertices(f);
    const Eigen::Vector2d e1 = emb.uv[c[1]] - emb.uv[c[0]], e2 = emb.uv[c[2]] - emb.uv[c[0]];
    const double a_dom = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    if(!(a_dom > 0)) ++inverted;
    const double a_adj = internal::heron_area(itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2));
    for(int k = 0; k < 3; ++k) {
      adjusted_area[c[k]] += a_adj;
      domain_area[c[k]] += std::max(a_dom, 0.0);
    }
  }
  if(inverted > 0)
    throw Convergence_failure("conformal embedding: the layout has " + std::to_string(inverted) +
                                  " inverted or flat triangles (the metric is too wild for this background)",
                              double(inverted));
  emb.conformal_factor.resize(nv);
  for(int v = 0; v < nv; ++v) emb.conformal_factor[v] = adjusted_area[v] / domain_area[v];
  return emb;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_CONFORMAL_EMBEDDING_H
