// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_FEATURES_FIXED_CORNER_SITES_H
#define ANISO_CONFORMAL_INTERNAL_FEATURES_FIXED_CORNER_SITES_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Feature_graph.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/features/boundary_distance.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdio>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

// The corners of the input's feature graph (Feature_graph.h) as fixed sites of the CVT, once for every
// closed domain (issue 15, item 2): each corner's site is its image in the canonical domain, read from the
// embedding at one of its background corners (the domain policy's corner_site()); the site never moves
// (the CVT keeps the first number_of_fixed_sites() sites where they are), and the dual mesh maps it back
// exactly onto the input vertex, because its background location is that corner with barycentric
// coordinate exactly 1 (extract_dual_mesh() then takes the input vertex itself).

namespace Aniso_conformal {
namespace internal {

// a corner of the input as a site: a background face holding it, its corner index there, its point in the domain
template <typename Point>
struct Corner_site {
  int face = -1;
  int corner = 0;
  Point site;

  // the site's location on the background: exactly its corner (barycentric (1, 0, 0) up to the order)
  void background_location(int& f, Eigen::Vector3d& bary) const
  {
    f = face;
    bary = Eigen::Vector3d::Zero();
    bary[corner] = 1.0;
  }
};

// The background halfedge leaving the input vertex `v` (a vertex of `itri` with the same index: the
// intrinsic triangulation keeps the input's vertices first), as (face, corner index of v there).
inline std::pair<int, int> background_corner_of(const Intrinsic_triangulation& itri, std::size_t v)
{
  if(v >= itri.number_of_vertices() || itri.input_vertex(int(v)) != int(v))
    throw Internal_error("fixed corner sites: input vertex " + std::to_string(v) + " is not the background's vertex " +
                         std::to_string(v));
  const std::vector<int> out = itri.outgoing_halfedges(int(v));
  if(out.empty()) throw Internal_error("fixed corner sites: input vertex " + std::to_string(v) + " has no background face");
  const int f = out.front() / 3, k = out.front() % 3;  // halfedge 3 f + k leaves corner k of face f
  if(itri.face_vertices(std::size_t(f))[std::size_t(k)] != int(v))
    throw Internal_error("fixed corner sites: the halfedge leaving vertex " + std::to_string(v) + " does not start there");
  return {f, k};
}

// The corners (input vertex indices) as sites of the closed domain `Domain` (a model of ParametricDomain
// with a static corner_site(emb, face, corner, v)), after its embedding `emb` of `itri`
template <typename Domain>
std::vector<Corner_site<typename Domain::Traits::Point>> corner_sites(const typename Domain::Embedding& emb,
                                                                       const Intrinsic_triangulation& itri,
                                                                       const std::vector<std::size_t>& corners)
{
  std::vector<Corner_site<typename Domain::Traits::Point>> sites;
  sites.reserve(corners.size());
  for(std::size_t v : corners) {
    const std::pair<int, int> fk = background_corner_of(itri, v);
    Corner_site<typename Domain::Traits::Point> c;
    c.face = fk.first;
    c.corner = fk.second;
    c.site = Domain::corner_site(emb, fk.first, fk.second, int(v));
    sites.push_back(c);
  }
  return sites;
}

// A background vertex `v` on a seam (a hole's loop, hole_patches.h; an input vertex or a split of a loop
// edge) as a fixed site of the closed domain `Domain`: read from the embedding at one of its corners
template <typename Domain>
Corner_site<typename Domain::Traits::Point> seam_site(const typename Domain::Embedding& emb, const Intrinsic_triangulation& itri, int v)
{
  const std::vector<int> out = itri.outgoing_halfedges(v);
  if(out.empty()) throw Internal_error("fixed seam sites: background vertex " + std::to_string(v) + " has no face");
  Corner_site<typename Domain::Traits::Point> c;
  c.face = out.front() / 3;
  c.corner = out.front() % 3;
  c.site = Domain::corner_site(emb, c.face, c.corner, v);
  return c;
}

// the length in the metric of the straight segment between background vertices v and w, measured with
// the mean of their two square roots Q (as refine_background() measures)
inline double metric_distance(const Intrinsic_triangulation& itri, int v, int w)
{
  return (0.5 * (itri.Q(v) + itri.Q(w)) * (itri.position(w) - itri.position(v))).norm();
}
// `true` if background vertices v and w are closer than half the output edge length `h` in the metric:
// two fixed sites that close make a sliver
inline bool closer_than_half_an_edge(const Intrinsic_triangulation& itri, int v, int w, double h)
{
  return metric_distance(itri, v, w) < 0.5 * h;
}

// The corners to fix: every corner, except one closer than half the output's edge length `h` (in the
// metric, from the mean of the two square roots, as refine_background() measures) to a corner fixed before
// it: two fixed sites that close make a sliver or an inverted output triangle (the short crease fragments
// of a noisy scan: CGAL's elk has 48 pairs of corners closer than half its edge length at 2000 vertices,
// and failed with an inverted triangle). Corners where 3 or more creases meet come first, then the
// turns of a crease, then the ends of a crease, each in index order. O(k^2) for k corners.
inline std::vector<std::size_t> corners_to_fix(const Feature_graph& g, const Intrinsic_triangulation& itri, double h)
{
  std::vector<std::size_t> degree(itri.number_of_vertices(), 0);
  for(const auto& e : g.crease_edges) {
    ++degree[e[0]];
    ++degree[e[1]];
  }
  auto rank = [&](std::size_t v) { return degree[v] >= 3 ? 0 : degree[v] == 2 ? 1 : 2; };
  std::vector<std::size_t> order = g.corners;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rank(a) < rank(b); });
  std::vector<std::size_t> fixed;
  for(std::size_t v : order) {
    bool apart = true;
    for(std::size_t w : fixed)
      if(closer_than_half_an_edge(itri, int(v), int(w), h)) {
        apart = false;
        break;
      }
    if(apart) fixed.push_back(v);
  }
  std::sort(fixed.begin(), fixed.end());
  return fixed;
}

// The corners the plane keeps with its creases (corners_to_fix() with output edge length `h`), those on
// the boundary marked as corners of the boundary (its 1D CVT then has a site exactly there; the embedding
// keeps their turning angle): not a boundary vertex within half of `h` (in the metric) of a corner of the
// boundary already, nor an interior one within half of `h` of the boundary, whose fixed site would make a
// sliver with the boundary's sites (CGAL's cylinder_locally_refined at 2000 vertices: theta_min 1.3
// degrees with them, 36.9 without creases followed).
inline std::vector<std::size_t> plane_corners_to_fix(const Feature_graph& g, Intrinsic_triangulation& itri, double h)
{
  std::vector<int> boundary_corners;
  for(int v = 0; v < int(itri.number_of_vertices()); ++v)
    if(itri.is_corner(v)) boundary_corners.push_back(v);
  std::vector<std::size_t> kept;
  const Boundary_distance to_boundary(itri);
  for(std::size_t v : corners_to_fix(g, itri, h)) {
    const int w = int(v);
    if(!itri.is_boundary_vertex(w)) {
      if(to_boundary(w) >= 0.5 * h) kept.push_back(v);
      continue;
    }
    bool apart = true;
    for(int c : boundary_corners)
      if(c != w && closer_than_half_an_edge(itri, w, c, h)) apart = false;
    if(!apart) continue;
    kept.push_back(v);
    if(!itri.is_corner(w)) {
      itri.set_corner(w, true);
      boundary_corners.push_back(w);
    }
  }
  return kept;
}

// The crease components of a feature graph (crease edges connected through their vertices), by union-find
// over the input's vertices: root(v) names the component of crease vertex v, user[root(v)] is set when the
// component holds an edge of `marked_edges` or a vertex of `marked_vertices` (the user's, kept whole)
struct Crease_components {
  std::vector<std::size_t> parent;
  std::vector<char> user;
  Crease_components(std::size_t nv, const Feature_graph& g, const std::vector<std::array<std::size_t, 2>>& marked_edges,
                    const std::vector<std::size_t>& marked_vertices)
    : parent(nv), user(nv, 0)
  {
    for(std::size_t v = 0; v < nv; ++v) parent[v] = v;
    for(const auto& e : g.crease_edges) parent[root(e[0])] = root(e[1]);
    for(const auto& m : marked_edges)
      if(m[0] < nv) user[root(m[0])] = 1;
    for(std::size_t v : marked_vertices)
      if(v < nv) user[root(v)] = 1;
  }
  std::size_t root(std::size_t v)
  {
    while(parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  }
};

// `g` without the crease components for whose root `drop` is true (never one the user marked), each
// counted once into `dropped` with its length `length[root]` (input units) into `dropped_length`; the rest
// chained again by detect_features() with those edges marked (corners by the same rules, local to each
// component, so the kept ones do not change). `g` itself when none is dropped.
template <typename Drop>
Feature_graph without_crease_components(const Input_surface& surface, const Feature_graph& g, Crease_components& c,
                                        const std::vector<double>& length, Drop drop, double corner_angle,
                                        const std::vector<std::array<std::size_t, 2>>& marked_edges,
                                        const std::vector<std::size_t>& marked_vertices, std::size_t& dropped, double& dropped_length)
{
  std::vector<std::array<std::size_t, 2>> kept;
  std::vector<char> counted(c.parent.size(), 0);
  for(const auto& e : g.crease_edges) {
    const std::size_t r = c.root(e[0]);
    if(c.user[r] || !drop(r)) {
      kept.push_back(e);
      continue;
    }
    if(!counted[r]) {
      counted[r] = 1;
      ++dropped;
      dropped_length += length[r];
    }
  }
  if(kept.size() == g.crease_edges.size()) return g;
  kept.insert(kept.end(), marked_edges.begin(), marked_edges.end());
  return detect_features(surface, 180.0, corner_angle, kept, marked_vertices);
}

// The feature graph `g` of `surface` without its crease components shorter than the output edge length
// `h`: a component's length is the sum of its edges' lengths in the metric of `itri` (whose first vertices
// are the input's; the mean of the two square roots, as refine_background() measures). No chain of output
// edges can follow a crease shorter than one output edge, and its corners, fixed sites a fraction of an
// edge apart, made slivers: on a noisy scan most creases are such fragments (CGAL's ChineseDragon-10kv at
// 2000 vertices: 232 of its 375 components, theta_min 0.05 degrees; femur 107 of 274), while no component
// of the CAD meshes (fandisk, pinion, anchor, joint, oblong, cube-meshed, part, rotor_small, spool) is that
// short. A component the user marked is kept whole. Adds the dropped components and their length in the
// input's units to `dropped` and `dropped_length`; returns `g` itself when none is dropped.
inline Feature_graph without_short_crease_components(const Input_surface& surface, const Feature_graph& g, const Intrinsic_triangulation& itri,
                                                     double h, double corner_angle,
                                                     const std::vector<std::array<std::size_t, 2>>& marked_edges,
                                                     const std::vector<std::size_t>& marked_vertices, std::size_t& dropped,
                                                     double& dropped_length)
{
  if(g.crease_edges.empty()) return g;
  const std::size_t nv = surface.number_of_vertices();
  Crease_components c(nv, g, marked_edges, marked_vertices);
  std::vector<double> metric_length(nv, 0.0), length(nv, 0.0);
  for(const auto& e : g.crease_edges) {
    const std::size_t r = c.root(e[0]);
    metric_length[r] += metric_distance(itri, int(e[0]), int(e[1]));
    length[r] += (surface.points()[e[1]] - surface.points()[e[0]]).norm();
  }
  return without_crease_components(
    surface, g, c, length, [&](std::size_t r) { return metric_length[r] < h; }, corner_angle, marked_edges, marked_vertices, dropped,
    dropped_length);
}

// The vertices of the background (any, not only the input's) that a domain keeps as output vertices
// (ParametricDomain::vertices_kept(): the cone domain's cones of negative curvature) and that get a fixed
// site (seam_site()): each of `kept` in its order, unless one of the `corners` or a vertex kept before lies
// within half of the output edge length `h` of it (in the metric; that site serves it, as in
// corners_to_fix()); at most `most` of them.
inline std::vector<std::size_t> kept_vertices_apart(const std::vector<std::size_t>& kept, const std::vector<std::size_t>& corners,
                                                    const Intrinsic_triangulation& itri, double h, std::size_t most)
{
  std::vector<std::size_t> out;
  for(std::size_t v : kept) {
    if(out.size() >= most) break;
    auto near = [&](std::size_t w) {
      return w == v || closer_than_half_an_edge(itri, int(v), int(w), h);
    };
    if(std::none_of(corners.begin(), corners.end(), near) && std::none_of(out.begin(), out.end(), near)) out.push_back(v);
  }
  return out;
}

// Invalid_input if the `corners` of the input (kept as output vertices) outnumber the `n` requested
inline void check_vertices_for_corners(std::size_t corners, std::size_t n, double feature_angle)
{
  if(corners > n) {
    char angle[32];
    std::snprintf(angle, sizeof(angle), "%g", feature_angle);
    throw Invalid_input("remesh(): the input has " + std::to_string(corners) + " corners (where creases sharper than the feature angle, " +
                        angle + " degrees, meet or turn; a corner within half an output edge of another is merged into it), each kept as an output vertex, but only " +
                        std::to_string(n) + " output vertices were requested: ask for at least " + std::to_string(corners) +
                        ", or raise the feature angle (feature_angle; the tool's --feature-angle, or --no-features) or mark fewer "
                        "feature vertices to keep fewer corners");
  }
}

// What the two wrappers below share: domain traits `Traits` with more fixed sites given as background
// vertices (`Corner_site`s), each located exactly at its background corner.
template <typename Traits>
class Traits_with_given_sites : public Traits {
public:
  Traits_with_given_sites(Traits&& traits, std::vector<Corner_site<typename Traits::Point>> sites)
    : Traits(std::move(traits)), m_sites(std::move(sites))
  {}

protected:
  // site `i` on the background: the given site `i - first` exactly at its corner when `i` is one of
  // them (they are sites `first` to `first + m_sites.size() - 1`), else where the traits locate it
  bool locate(std::size_t first, std::size_t i, const typename Traits::Point& site, int& face, Eigen::Vector3d& bary) const
  {
    if(i >= first && i < first + m_sites.size()) {
      m_sites[i - first].background_location(face, bary);
      return true;
    }
    return Traits::background_location(i, site, face, bary);
  }
  std::vector<Corner_site<typename Traits::Point>> m_sites;
};

// `value` is true for traits with `initial_sites_after(fixed, n, seed)`: the fixed sites given as
// background corners (face, corner) and the rest placed by the traits, which keep a state per site
template <typename Traits, typename = void>
struct has_initial_sites_after : std::false_type {};
template <typename Traits>
struct has_initial_sites_after<Traits, std::void_t<decltype(std::declval<Traits&>().initial_sites_after(
                                           std::declval<const std::vector<std::pair<int, int>>&>(), std::size_t(0), 0u))>>
  : std::true_type {};

// Domain traits of a closed domain with the input's corners as fixed sites: the first sites are the
// corners (in the order given), the rest come from the traits' own initial_sites(); everything else is the
// traits' own. With no corner it is the traits exactly (same sites, same output bit for bit).
template <typename Traits>
class Traits_with_fixed_corners : public Traits_with_given_sites<Traits> {
  typedef Traits_with_given_sites<Traits> Base;
  using Base::m_sites;

public:
  typedef typename Traits::Point Point;
  using Base::Base;  // the domain's traits (from its make_traits()) and the corners' sites (corner_sites())

  // the corners, then `n - corners` sites of the traits (at least as many as it needs, the first kept)
  std::vector<Point> initial_sites(std::size_t n, unsigned seed)
  {
    const std::size_t k = m_sites.size();
    if(k == 0) return Traits::initial_sites(n, seed);
    if(n < k)
      throw Invalid_input("remesh(): the input has " + std::to_string(k) + " corners, each kept as an output vertex, but " +
                          std::to_string(n) + " output vertices were requested");
    if constexpr(has_initial_sites_after<Traits>::value) {  // traits that keep a state per site (the cone domain's)
      std::vector<std::pair<int, int>> at;
      for(const auto& c : m_sites) at.push_back({c.face, c.corner});
      return Traits::initial_sites_after(at, n, seed);
    }
    std::vector<Point> sites;
    sites.reserve(n);
    for(const auto& c : m_sites) sites.push_back(c.site);
    if(n > k) {
      // a domain needs a few sites (the sphere 4): ask for that many and keep the first n - k
      std::vector<Point> free = Traits::initial_sites(std::max<std::size_t>(n - k, 4), seed);
      free.resize(n - k);
      sites.insert(sites.end(), free.begin(), free.end());
    }
    return sites;
  }
  // all the sites given (the corners, then the crease sites, the holes' loop sites and any patch apexes)
  std::size_t number_of_fixed_sites() const { return m_sites.size(); }
  // a corner's site is exactly its background corner; the other sites are located by the traits
  bool background_location(std::size_t i, const Point& site, int& face, Eigen::Vector3d& bary) const
  {
    return Base::locate(0, i, site, face, bary);
  }
  std::size_t number_of_corners() const { return m_sites.size(); }
};

// Domain traits of the plane (Planar_domain_traits, whose own fixed sites are the boundary's, which its
// dual takes as the polygon that bounds the mesh) with the input's interior corners and crease sites as
// more fixed sites (issue 15, item 2, in the plane): the traits' boundary sites first, then these, then
// the traits' free sites less the one nearest to each of these (the free sites are stratified over the
// density; dropping the nearest keeps the sampling even). `boundary_site_vertex()` and the rest are the
// traits' own. With no site given it is the traits exactly (same sites, same output bit for bit).
template <typename Traits>
class Traits_with_interior_fixed_sites : public Traits_with_given_sites<Traits> {
  typedef Traits_with_given_sites<Traits> Base;
  using Base::m_sites;

public:
  typedef typename Traits::Point Point;
  using Base::Base;  // the plane's traits (from its make_traits()) and the interior sites (corner_sites(), seam_site())

  // the traits' `n` sites with `k` free ones replaced by the interior fixed sites after the boundary's
  // \throws Remeshing_failure if the traits leave fewer than `k` free sites (a boundary that takes most)
  std::vector<Point> initial_sites(std::size_t n, unsigned seed)
  {
    const std::size_t k = m_sites.size();
    std::vector<Point> sites = Traits::initial_sites(n, seed);
    if(k == 0) return sites;
    const std::size_t nb = Traits::number_of_fixed_sites();
    if(sites.size() < nb + k)
      throw Remeshing_failure("remesh(): the boundary takes " + std::to_string(nb) + " of the " + std::to_string(n) +
                              " output vertices, too many to keep " + std::to_string(k) + " corners and crease vertices inside");
    std::vector<Point> free(sites.begin() + std::ptrdiff_t(nb), sites.end());
    for(const auto& c : m_sites) {
      std::size_t best = 0;
      for(std::size_t j = 1; j < free.size(); ++j)
        if((free[j] - c.site).squaredNorm() < (free[best] - c.site).squaredNorm()) best = j;
      free.erase(free.begin() + std::ptrdiff_t(best));
    }
    sites.resize(nb);
    for(const auto& c : m_sites) sites.push_back(c.site);
    sites.insert(sites.end(), free.begin(), free.end());
    return sites;
  }
  // the boundary's sites and the interior fixed sites
  std::size_t number_of_fixed_sites() const { return Traits::number_of_fixed_sites() + m_sites.size(); }
  // the boundary's sites as many as the traits placed
  std::size_t number_of_boundary_sites() const { return Traits::number_of_fixed_sites(); }
  // an interior fixed site is exactly its background corner; the others are located by the traits
  bool background_location(std::size_t i, const Point& site, int& face, Eigen::Vector3d& bary) const
  {
    return Base::locate(Traits::number_of_fixed_sites(), i, site, face, bary);
  }
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_FEATURES_FIXED_CORNER_SITES_H
