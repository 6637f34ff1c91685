// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_HYPERBOLIC_EMBEDDING_H
#define ANISO_CONFORMAL_HYPERBOLIC_EMBEDDING_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/conformal/hyperbolic_geometry.h>
#include <Aniso_conformal/internal/conformal/hyperbolic_vertex_scaling.h>
#include <Aniso_conformal/internal/conformal/layout.h>
#include <Aniso_conformal/internal/conformal/newton_solver.h>
#include <Aniso_conformal/internal/conformal/tree_cotree.h>
#include <Aniso_conformal/internal/printable.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/parameters.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

/// \file hyperbolic_embedding.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * a conformal embedding of a closed `Intrinsic_triangulation` of genus `g >= 2` into the hyperbolic
 * plane (stage 3): the fundamental domain laid out on the hyperboloid (and in the Klein disk) and the
 * deck transformations of the Fuchsian group that glue it into the surface.
 *
 * Points of the hyperbolic plane are points `x` of the upper sheet of the hyperboloid
 * `-x0^2 + x1^2 + x2^2 = -1`; isometries are 3x3 Lorentz matrices; the Klein disk point of `x` is
 * `(x1, x2) / x0`.
 */
struct Hyperbolic_embedding {
  int genus = 0;  ///< genus of the surface
  /// per face, its three corners (counterclockwise) on the hyperboloid, in the fundamental domain; the
  /// domain is centred (the hyperboloid mass centre of its corners is the apex `(1, 0, 0)`)
  std::vector<std::array<Eigen::Vector3d, 3>> corner_hyperboloid;
  /// the same corners in the Klein disk (geodesics are chords; the CVT works there)
  std::vector<std::array<Eigen::Vector2d, 3>> corner_klein;
  /// the same corners in the Poincare disk (conformal to the hyperbolic plane: angles are true)
  std::vector<std::array<Eigen::Vector2d, 3>> corner_poincare;
  /// per halfedge `h`: the deck transformation that takes the copy of the face of `twin(h)` in the
  /// fundamental domain to the tile across `h` from the face of `h` (so `side_pairing[twin(h)]` is its
  /// inverse); exactly the identity where both faces are adjacent in the fundamental domain
  std::vector<Eigen::Matrix3d> side_pairing;
  /// the `2 g` deck transformations of the generator edges (tree-cotree), which generate the group
  std::vector<Eigen::Matrix3d> generators;
  /// the `2 g` closed vertex loops of the generators (a homology basis)
  std::vector<std::vector<int>> homology_basis;
  std::vector<double> u;                 ///< log scale factor of each vertex
  std::vector<double> conformal_factor;  ///< `cf(v)`: adjusted area around v over hyperbolic area around v (paper eq. 6)
  double scale = 1;                      ///< `s`: `sinh(l / 2) = exp((u_i + u_j) / 2) s L` for edge length `L`
  std::size_t iterations = 0;            ///< Newton iterations
  double residual = 0;                   ///< max |2 pi - angle sum| over the vertices at the end
  std::size_t degenerate_triangles = 0;  ///< triangles treated as flat at the end of the solve (0 normally)
  std::size_t flips = 0;                 ///< intrinsic Delaunay flips made during the solve
  /// hyperbolic area of the layout (Gauss-Bonnet: `4 pi (g - 1)`)
  double area = 0;
  /// the group relations checked numerically: around every vertex, the product of the side pairings
  /// crossed is the identity; the largest entry of `product - I` (the layout error)
  double relation_error = 0;
  /// largest distance between a cut edge's end in one face and the image of its end in the twin face
  double gluing_error = 0;
  /// largest hyperbolic distance from the centre to a corner (how far the fundamental domain reaches)
  double radius = 0;
  /// `Hyperbolic_domain::embed()`: the hyperbolic spacing that the requested number of sites would have
  /// where the conformal metric shrinks the surface most (0 when not computed)
  double smallest_site_spacing = 0;
};

namespace internal {

// Moves the layout by the boost that takes the mass centre of its corners to the apex (1, 0, 0).
inline void centre_on_apex(std::vector<std::array<Eigen::Vector3d, 3>>& X)
{
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for(const auto& c : X) m += c[0] + c[1] + c[2];
  const Eigen::Vector3d o = normalize_on_hyperboloid(m);
  // the boost along the direction of o: T^-1 with T the frame of o (any frame taking the apex to o)
  const Eigen::Vector3d toward = Eigen::Vector3d(o.x(), o.y() + 1e-3, o.z());  // any other direction works
  const Eigen::Matrix3d Tinv = lorentz_inverse(hyperbolic_frame(o, normalize_on_hyperboloid(toward)));
  for(auto& c : X)
    for(auto& x : c) x = normalize_on_hyperboloid(Tinv * x);
}

// The cut that bounds the fundamental domain: the edges not in the cotree, less the trees hanging from
// them (repeatedly, an edge with an end of degree 1 in what is left). Such a hanging edge has the same
// face copy on both sides up to the layout's rounding, so its deck transformation is the identity by the
// topology (Erickson and Har-Peled 2004: the reduced cut graph); deciding it from the rounded matrices
// failed where the layout's relations hold to 1e-2 only (CGAL's couplingdown, isotropic: near-identity
// "deck transformations" moving a site by 0.002). Returns, per halfedge, 1 if its edge is in the reduced cut
// graph; every vertex of that graph has degree 2 or more. Linear time (each edge is removed once).
inline std::vector<char> reduced_cut_graph(const Intrinsic_triangulation& itri, const Tree_cotree& tc)
{
  const int nh = int(itri.number_of_halfedges()), nv = int(itri.number_of_vertices());
  std::vector<char> cut(std::size_t(nh), 0);
  std::vector<int> degree(std::size_t(nv), 0);
  for(int h = 0; h < nh; ++h)
    if(!tc.in_cotree[std::size_t(h)]) {
      cut[std::size_t(h)] = 1;
      ++degree[std::size_t(itri.tail(h))];  // each edge counted once at each end (both halfedges)
    }
  std::vector<int> leaves;
  for(int v = 0; v < nv; ++v)
    if(degree[std::size_t(v)] == 1) leaves.push_back(v);
  while(!leaves.empty()) {
    const int v = leaves.back();
    leaves.pop_back();
    if(degree[std::size_t(v)] != 1) continue;
    for(int h : itri.outgoing_halfedges(v)) {
      if(!cut[std::size_t(h)]) continue;
      cut[std::size_t(h)] = cut[std::size_t(itri.twin(h))] = 0;
      --degree[std::size_t(v)];
      const int w = itri.head(h);
      if(--degree[std::size_t(w)] == 1) leaves.push_back(w);
      break;
    }
  }
  return cut;
}

// The side pairing of every cut edge (the isometry taking the twin face's copy of the edge onto this
// face's copy), the generators and their loops, and the checks: each pairing is a Lorentz matrix that
// maps its edge onto its twin, and around every vertex the product of the pairings crossed is the
// identity (the relations of the group, Poincare's polygon theorem). Convergence_failure otherwise.
// The edges of the cut outside the reduced cut graph (reduced_cut_graph()) glue the domain to itself:
// their pairing is the identity, exactly, by the topology. It was decided from the computed matrix
// (within 1e-6 of the identity), which a layout whose relations hold to 1e-2 only fails: on
// couplingdown's isotropic metric (radius 6.3, edges down to 0.016, relation error 1.7e-2) hanging
// edges kept near-identity "deck transformations" whose images of a site lay 0.002 from it, and the
// dual refused the triangle joining the two.
// Such an edge is checked by the distances between its two copies of each end (the identity maps one
// onto the other), no fitted isometry: two points within the rounding of each other determine no frame,
// and the isometry fitted to an edge the metric shrinks to 4e-14 (CGAL's femur) had a Lorentz defect
// of 1e-2 although the layout was right. An edge of the reduced cut graph shorter than
// frame_min_length takes the isometry fitted to the two points farthest apart on its side of the cut
// (the path between two vertices of degree 3 or more of that graph, whose edges all share one
// pairing); a longer edge keeps the isometry fitted to itself.
inline void glue_fundamental_domain(const Intrinsic_triangulation& itri, const Tree_cotree& tc, Hyperbolic_embedding& emb)
{
  const double frame_min_length = 1e-6;  // below this hyperbolic length an edge's frame is judged ill-conditioned
  const auto& X = emb.corner_hyperboloid;
  const int nh = int(itri.number_of_halfedges()), nv = int(itri.number_of_vertices());
  emb.side_pairing.assign(std::size_t(nh), Eigen::Matrix3d::Identity());
  double lorentz = 0;
  const std::vector<char> cut = reduced_cut_graph(itri, tc);
  auto tail_in = [&](int h) -> const Eigen::Vector3d& { return X[std::size_t(h / 3)][std::size_t(h % 3)]; };            // tail(h) in face(h)
  auto head_in = [&](int h) -> const Eigen::Vector3d& { return X[std::size_t(h / 3)][std::size_t((h % 3 + 1) % 3)]; };  // head(h) in face(h)
  // the sides of the reduced cut graph: chains of its halfedges through the vertices of degree 2
  std::vector<int> degree(std::size_t(nv), 0);
  for(int h = 0; h < nh; ++h)
    if(cut[std::size_t(h)]) ++degree[std::size_t(itri.tail(h))];
  std::vector<int> side_of(std::size_t(nh), -1);
  std::vector<std::vector<int>> sides;
  for(int pass = 0; pass < 2; ++pass)  // chains from a vertex of degree above 2 first, then any cycle left
    for(int h0 = 0; h0 < nh; ++h0) {
      if(!cut[std::size_t(h0)] || side_of[std::size_t(h0)] >= 0 || (pass == 0 && degree[std::size_t(itri.tail(h0))] == 2)) continue;
      const int id = int(sides.size());
      sides.emplace_back();
      for(int k = h0; k >= 0 && side_of[std::size_t(k)] < 0;) {  // each halfedge joins one side once: bounded
        side_of[std::size_t(k)] = id;
        sides.back().push_back(k);
        const int v = itri.head(k);
        int next = -1;
        if(degree[std::size_t(v)] == 2)
          for(int o : itri.outgoing_halfedges(v))
            if(cut[std::size_t(o)] && o != itri.twin(k)) next = o;
        k = next;
      }
    }
  // per side, the isometry fitted to its first point and the point of the side farthest from it
  std::vector<Eigen::Matrix3d> side_fit(sides.size());
  std::vector<char> side_fitted(sides.size(), 0);
  double shortest_fit = std::numeric_limits<double>::infinity();  // for the message
  auto fit_side = [&](int id) {
    if(side_fitted[std::size_t(id)]) return;
    const std::vector<int>& m = sides[std::size_t(id)];
    const int h0 = m.front();
    const Eigen::Vector3d& p = tail_in(h0);
    const Eigen::Vector3d& p2 = head_in(itri.twin(h0));
    int far = h0;
    double far_d = -1;
    for(int k : m) {
      const double d = hyperbolic_distance(head_in(k), p);
      if(d > far_d) far_d = d, far = k;
    }
    shortest_fit = std::min(shortest_fit, far_d);
    side_fit[std::size_t(id)] = hyperbolic_frame(p, head_in(far)) * lorentz_inverse(hyperbolic_frame(p2, tail_in(itri.twin(far))));
    side_fitted[std::size_t(id)] = 1;
  };
  for(int h = 0; h < nh; ++h) {
    if(tc.in_cotree[std::size_t(h)]) continue;
    const int t = itri.twin(h);
    const Eigen::Vector3d& a = tail_in(h);   // tail(h) in face(h)
    const Eigen::Vector3d& b = head_in(h);   // head(h) in face(h)
    const Eigen::Vector3d& a2 = head_in(t);  // tail(h) = head(t) in face(t)
    const Eigen::Vector3d& b2 = tail_in(t);  // head(h) = tail(t) in face(t)
    if(!cut[std::size_t(h)]) {  // a hanging edge: glued by the identity, checked by distances
      emb.gluing_error = std::max({emb.gluing_error, hyperbolic_distance(a2, a), hyperbolic_distance(b2, b)});
      continue;
    }
    Eigen::Matrix3d P;
    if(hyperbolic_distance(a, b) >= frame_min_length && hyperbolic_distance(a2, b2) >= frame_min_length) {
      P = hyperbolic_frame(a, b) * lorentz_inverse(hyperbolic_frame(a2, b2));
    } else {
      fit_side(side_of[std::size_t(h)]);
      P = side_fit[std::size_t(side_of[std::size_t(h)])];
    }
    lorentz = std::max(lorentz, lorentz_defect(P));
    emb.gluing_error = std::max({emb.gluing_error, hyperbolic_distance(P * a2, a), hyperbolic_distance(P * b2, b)});
    emb.side_pairing[std::size_t(h)] = P;
  }
  for(int h : tc.generators) {
    emb.generators.push_back(emb.side_pairing[std::size_t(h)]);
    emb.homology_basis.push_back(generator_loop(itri, tc, h));
  }
  // the relations: going once around a vertex, crossing the cut edges met, must give the identity
  for(int v = 0; v < int(itri.number_of_vertices()); ++v) {
    Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
    bool crossed = false;
    for(int h : itri.outgoing_halfedges(v)) {
      // rotating counterclockwise from h to twin(prev(h))'s face crosses the edge of prev(h)
      const int p = Intrinsic_triangulation::prev(h);
      if(!tc.in_cotree[std::size_t(p)]) {
        G = G * emb.side_pairing[std::size_t(p)];
        crossed = true;
      }
    }
    if(crossed) emb.relation_error = std::max(emb.relation_error, (G - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff());
  }
  for(const auto& c : X)
    for(const auto& x : c) emb.radius = std::max(emb.radius, hyperbolic_distance(x, Eigen::Vector3d::UnitX()));
  // a corner that is not finite (a layout beyond double precision) must not pass the checks: std::max
  // keeps its first argument when compared with NaN
  bool finite = true;
  for(const auto& c : X)
    for(const auto& x : c) finite = finite && x.allFinite();
  const double layout_tol = 1e-6 * std::cosh(emb.radius) * std::cosh(emb.radius);
  if(!finite)
    throw Convergence_failure("hyperbolic embedding: the layout of the fundamental domain left double precision (a corner is not finite)",
                              std::numeric_limits<double>::infinity());
  if(!(lorentz <= layout_tol && emb.gluing_error <= 1e-6 && emb.relation_error <= layout_tol))
    throw Convergence_failure("hyperbolic embedding: the layout is inconsistent (Lorentz defect " + std::to_string(lorentz) +
                                  ", gluing error " + std::to_string(emb.gluing_error) + ", relation error " +
                                  std::to_string(emb.relation_error) + "; the fundamental domain reaches radius " +
                                  std::to_string(emb.radius) + ", tolerances " + std::to_string(layout_tol) + " and 1e-6" +
                                  (shortest_fit < frame_min_length
                                       ? "; a side of the cut spans " + internal::short_number(shortest_fit) + " only, too short to fit its isometry"
                                       : std::string()) +
                                  ")",
                              std::max({lorentz, emb.gluing_error, emb.relation_error}));
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * computes a hyperbolic conformal metric of the closed surface `itri` of genus `g >= 2` and lays out its
 * fundamental domain (stage 3 for genus above 1, DESIGN.md 3):
 * 1. per-vertex log scales `u` with hyperbolic lengths `sinh(l_ij / 2) = exp((u_i + u_j) / 2) s L_ij` and
 *    angle sum `2 pi` at every vertex, by Newton's method on the strictly convex energy of Bobenko,
 *    Pinkall and Springborn, with intrinsic Delaunay flips that keep the current hyperbolic metric;
 * 2. a homology basis by tree-cotree; the surface cut along the edges not in the cotree (a disk) is
 *    unfolded breadth-first on the hyperboloid, and given in the Klein and the Poincare disks;
 * 3. the deck transformation across every cut edge, from the two copies of the edge (for an edge shorter
 *    than `1e-6`, from the two points farthest apart on its side of the cut); the edges hanging from the
 *    cut (outside the reduced cut graph) get the identity; those of the `2 g` generator edges generate
 *    the Fuchsian group;
 * 4. checks: each is a Lorentz matrix, each maps its edge onto its twin (a hanging edge: its two copies
 *    coincide), and around every vertex the product of the transformations crossed is the identity (the
 *    relations of the group, Poincare's polygon theorem); the layout's area is `4 pi (g - 1)`;
 * 5. the domain is moved by an isometry so that the mass centre of its corners is the centre of the disk.
 *
 * \param itri a closed triangulation of genus at least 2 with valid edge lengths (after
 *        `adjust_edge_lengths()`); its edges may be flipped
 * \param np optional named parameters: `max_conformal_iterations` (default 100), `conformal_tolerance`
 *        (default `1e-9`), `max_flips_per_edge` (default 50), `visitor`
 * \throws Invalid_input if `itri` has a boundary or genus below 2, or its edge lengths are not set
 *         (`Intrinsic_triangulation::has_edge_lengths()`)
 * \throws Convergence_failure if Newton's method or the flips do not finish within their bounds, some
 *         triangles are flat in the solution, or the layout fails its checks (with the error reached)
 */
template <typename NamedParameters = parameters::Default_named_parameters>
Hyperbolic_embedding hyperbolic_embedding(Intrinsic_triangulation& itri, const NamedParameters& np = parameters::default_values())
{
  const double pi = 3.14159265358979323846;
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  Hyperbolic_embedding emb;
  emb.genus = internal::require_closed_surface(itri, "hyperbolic_embedding()", "the hyperbolic disk", [](int g) { return g >= 2; },
                                               "genus 2 or more");
  internal::require_edge_lengths(itri, "hyperbolic_embedding()");

  // ---- 1. the hyperbolic metric; the global scale s makes the input's Euclidean area equal to the
  // hyperbolic area 4 pi (g - 1), so that u = 0 is a good start
  {
    double euclidean_area = 0;
    for(int f = 0; f < nf; ++f) euclidean_area += internal::heron_area(itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2));
    emb.scale = std::sqrt(4 * pi * (emb.genus - 1) / euclidean_area);
    typename internal::Visitor_reference<NamedParameters>::type vis = internal::get_visitor(np);
    // Below CHOLMOD's size every Newton system is factorised, as before 2026-12-06: with LDLT's factor
    // reused as CG's preconditioner (the Euclidean solves' default), CGAL's turbine (genus 11) at 2000
    // sites lost its hyperbolic remesh (a 77 s CVT ending in a doubled dual edge, against 6 s and G_avg
    // 0.876): the hyperbolic path is that sensitive to the last bits of u, and the solve is a small part of it
    internal::Newton_bounds bounds = internal::Newton_bounds::from(np);
    bounds.reuse_ldlt_factor = false;
    internal::Conformal_solution sol =
        internal::solve_conformal_metric(itri, internal::Hyperbolic_vertex_scaling{emb.scale}, std::vector<char>(std::size_t(nv), 0),
                                         std::vector<double>(std::size_t(nv), 0.0), bounds, vis, "hyperbolic embedding");
    emb.u = std::move(sol.u);
    emb.iterations = sol.iterations;
    emb.residual = sol.residual;
    emb.degenerate_triangles = sol.degenerate;
    emb.flips = sol.flips;
  }
  if(emb.degenerate_triangles > 0)
    throw Convergence_failure("hyperbolic embedding: " + std::to_string(emb.degenerate_triangles) +
                                  " triangles are flat in the solution (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)",
                              double(emb.degenerate_triangles));

  // ---- 2. cut along the edges not in the cotree and unfold the disk breadth-first on the hyperboloid
  std::vector<std::array<double, 3>> L(static_cast<std::size_t>(nf));
  std::vector<double> domain_area(static_cast<std::size_t>(nf));
  std::size_t layout_degenerate = 0;  // triangles whose lengths, scaled, break the triangle inequality
  double smallest_angle = pi;
  for(int f = 0; f < nf; ++f) {
    L[std::size_t(f)] = internal::hyperbolic_face_lengths(itri, f, emb.scale, emb.u);
    bool deg;
    const std::array<double, 3> a = internal::hyperbolic_corner_angles(L[std::size_t(f)], deg);
    layout_degenerate += deg;
    smallest_angle = std::min({smallest_angle, a[0], a[1], a[2]});
    domain_area[std::size_t(f)] = pi - a[0] - a[1] - a[2];
    emb.area += domain_area[std::size_t(f)];
  }
  if(!(std::abs(emb.area - 4 * pi * (emb.genus - 1)) <= 1e-6 * emb.area))
    throw Convergence_failure("hyperbolic embedding: the hyperbolic area is " + std::to_string(emb.area) + " instead of 4 pi (g - 1) = " +
                                  std::to_string(4 * pi * (emb.genus - 1)),
                              std::abs(emb.area - 4 * pi * (emb.genus - 1)));
  // the cotree grows along shortest hyperbolic paths from a central face (a dual edge measured by the
  // mean edge length of its two faces), so that the fundamental domain reaches no farther than it must
  std::vector<double> dual_length(itri.number_of_halfedges());
  for(int h = 0; h < int(itri.number_of_halfedges()); ++h) {
    const auto& p = L[std::size_t(h / 3)];
    const auto& q = L[std::size_t(Intrinsic_triangulation::face(itri.twin(h)))];
    dual_length[std::size_t(h)] = (p[0] + p[1] + p[2] + q[0] + q[1] + q[2]) / 6;
  }
  const internal::Tree_cotree tc = internal::tree_cotree(itri, &dual_length);
  if(int(tc.generators.size()) != 2 * emb.genus)
    throw Internal_error("hyperbolic embedding: the tree-cotree decomposition found " + std::to_string(tc.generators.size()) +
                         " generators instead of " + std::to_string(2 * emb.genus));
  std::vector<char> done;
  const int root = tc.root_face;  // the central face: the layout stays as close to the centre as it can
  const double l0 = L[std::size_t(root)][0];
  emb.corner_hyperboloid = internal::unfold_breadth_first(
      itri, L, root, Eigen::Vector3d(Eigen::Vector3d::UnitX()), Eigen::Vector3d(std::cosh(l0), std::sinh(l0), 0),
      [&](int h) { return tc.in_cotree[std::size_t(h)] != 0; }, internal::hyperbolic_third_point, done);

  // ---- 3. centre the domain, 4. deck transformations and the group's relations, checked
  internal::centre_on_apex(emb.corner_hyperboloid);
  try {
    internal::glue_fundamental_domain(itri, tc, emb);
  } catch(const Convergence_failure& e) {  // what the layout was made of, for the message
    throw Convergence_failure(std::string(e.what()) + " (" + std::to_string(layout_degenerate) +
                                  " triangles of the solution break the triangle inequality; smallest angle " +
                                  std::to_string(smallest_angle * 180 / pi) + " degrees)",
                              e.residual());
  }
  emb.corner_klein.resize(std::size_t(nf));
  emb.corner_poincare.resize(std::size_t(nf));
  for(int f = 0; f < nf; ++f)
    for(int k = 0; k < 3; ++k) {
      emb.corner_klein[std::size_t(f)][std::size_t(k)] = internal::to_klein(emb.corner_hyperboloid[std::size_t(f)][std::size_t(k)]);
      emb.corner_poincare[std::size_t(f)][std::size_t(k)] = internal::to_poincare(emb.corner_hyperboloid[std::size_t(f)][std::size_t(k)]);
    }

  // ---- 5. conformal factor (paper eq. 6): adjusted (Euclidean) area over hyperbolic area around each vertex
  emb.conformal_factor = internal::vertex_conformal_factors(itri, domain_area);
  return emb;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_HYPERBOLIC_EMBEDDING_H
