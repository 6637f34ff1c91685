// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_PLANAR_DOMAIN_TRAITS_H
#define ANISO_CONFORMAL_PLANAR_DOMAIN_TRAITS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/conformal_embedding.h>
#include <Aniso_conformal/internal/CVT/planar_delaunay_flips.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/conformal/planar_boundary.h>
#include <Aniso_conformal/internal/domains/indexed_delaunay_2.h>
#include <Aniso_conformal/internal/domains/simple_polygon_2.h>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <list>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

/// \file Planar_domain_traits.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the planar domain of a disk-topology surface or a 2D domain: the background triangulation laid out
 * by `conformal_embedding()`, with the CVT density `cf^2` linear over each background triangle.
 *
 * Sites are ordered: the first `number_of_fixed_sites()` lie on the boundary, in boundary order (each
 * corner, then the sites up to the next corner) and stay fixed; the rest move freely inside. The
 * boundary sites are a 1D CVT of the boundary: spaced evenly in *metric* length (the adjusted lengths of
 * the background's boundary edges) between consecutive corners, at the spacing the requested number of
 * vertices implies for an equilateral mesh of the adjusted area (DESIGN.md 3). With
 * `Planar_boundary::KEEP_LENGTHS` the layout keeps the boundary's metric lengths and they are spaced
 * evenly along the layout (the same spacing, as the paper does).
 *
 * The polygon of the boundary sites bounds the dual mesh. `initial_sites()` makes it simple: where two
 * of its edges would touch or cross (sparse sites along a boundary that the layout bends strongly), a
 * boundary site is added halfway (in metric length) between the two sites of each such edge, until none
 * does (the added sites come out of the interior's share, so the total stays `n`). The free sites are
 * kept strictly inside that polygon as well as inside the layout (`contains()`), so the constrained
 * Delaunay triangulation of the dual has every site as a vertex and cannot fail on a disk whose layout
 * is embedded (which `conformal_embedding()` guarantees by default: it falls back to `Planar_boundary::KEEP_SHAPE`).
 *
 * Integration is exact: each background triangle is clipped against the Voronoi cells it meets (a
 * restricted Voronoi diagram, found by walking the Delaunay graph from the site nearest to a corner),
 * and the mass, first moment and energy of the linear density over each piece have closed forms.
 *
 * \cgalModels `ParametricDomainTraits`
 */
class Planar_domain_traits {
public:
  /// \name Types
  /// @{
  typedef Eigen::Vector2d Point;  ///< a point of the domain
  /// integrals of the density over one Voronoi cell restricted to the domain
  struct Cell {
    double mass = 0;                          ///< integral of rho
    Point centroid = Point::Zero();           ///< (integral of rho y) / mass, or the site when the mass is 0
    double energy = 0;                        ///< integral of rho |y - site|^2
  };
  /// where a boundary site lies: on halfedge `halfedge` of the background, at parameter `t` from its tail
  struct Boundary_location {
    int halfedge = -1;   ///< boundary halfedge of the `Intrinsic_triangulation`
    double t = 0;        ///< parameter along it in [0, 1]
  };
  /// @}

  /// \name Creation
  /// @{

  /*!
   * lays out the background of `itri` with the embedding `emb`; `threads` workers integrate (0 = hardware).
   * Also computes `adjusted_area()` from the current lengths of `itri`, for `initial_sites()`: build the
   * traits after the embedding, from the triangulation it flipped. The boundary sites are spaced in
   * metric length unless `emb.boundary` is `Planar_boundary::KEEP_LENGTHS` (then along the layout).
   * \throws Invalid_input if the background has no boundary
   */
  Planar_domain_traits(const Intrinsic_triangulation& itri, const Planar_embedding& emb, unsigned threads = 0)
    : m_itri(itri), m_metric_spacing(emb.boundary != Planar_boundary::KEEP_LENGTHS)
  {
    const std::size_t nf = itri.number_of_faces();
    std::vector<Eigen::Vector2d> centroids(nf);
    for(std::size_t f = 0; f < nf; ++f) {
      const auto& c = itri.face_vertices(f);
      centroids[f] = (emb.uv[c[0]] + emb.uv[c[1]] + emb.uv[c[2]]) / 3.0;
    }
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for(const auto& p : emb.uv) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
    const std::vector<std::size_t> order = internal::morton_order(centroids, lo, hi);
    m_tri.reserve(nf);
    for(std::size_t i = 0; i < nf; ++i) {
      const std::size_t f = order[i];
      const auto& c = itri.face_vertices(f);
      std::array<Eigen::Vector2d, 3> p;
      std::array<double, 3> rho;
      for(int k = 0; k < 3; ++k) {
        p[k] = emb.uv[c[k]];
        rho[k] = emb.conformal_factor[c[k]] * emb.conformal_factor[c[k]];
      }
      m_tri.push_back(internal::make_background_triangle(p, rho, int(f)));
      m_total_mass += m_tri.back().area * (rho[0] + rho[1] + rho[2]) / 3.0;
      m_area += m_tri.back().area;
    }
    // the area in the metric: of the lengths as they are now (after the embedding's flips, whose
    // lengths the boundary spacing matches)
    for(std::size_t f = 0; f < itri.number_of_faces(); ++f)
      m_adjusted_area += internal::heron_area(itri.length(int(3 * f)), itri.length(int(3 * f + 1)), itri.length(int(3 * f + 2)));
    m_grid.build(m_tri);
    build_boundary();
    m_threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  }
  /// @}

  /// \name Domain
  /// @{

  /// integral of the density over the domain
  double total_mass() const { return m_total_mass; }
  /// area of the domain
  double area() const { return m_area; }
  /// area of the background in the metric: the sum of the Heron areas of the lengths of `itri` at construction
  double adjusted_area() const { return m_adjusted_area; }
  /// the boundary loop as background vertices, counterclockwise (the domain is on the left)
  const std::vector<int>& boundary_vertices() const { return m_boundary; }
  /// the domain position of background vertex `v`
  Point position(int v) const { return m_uv_of_vertex[v]; }
  /// finds the background face containing `p` and the barycentric coordinates of `p` in it; `false` if outside
  bool locate(const Point& p, int& face, Eigen::Vector3d& bary, double tolerance = 1e-9) const
  {
    int t = -1;
    if(!m_grid.locate(m_tri, p, t, bary, tolerance)) return false;
    face = m_tri[std::size_t(t)].face;
    return true;
  }
  /*!
   * `true` if `p` is in the domain and, once `initial_sites()` has placed the boundary sites, strictly
   * inside the polygon of the boundary sites (where a free site must stay for the dual)
   */
  bool contains(const Point& p) const
  {
    int f = -1;
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    return locate(p, f, b, 0.0) && inside_site_polygon(p);
  }
  /// @}

  /// \name Sites
  /// @{
  /*!
   * places `n` sites: the boundary sites first (fixed: `number_of_fixed_sites()` becomes their number) at
   * the spacing `n` implies for an equilateral mesh of the adjusted area, evenly in metric length between
   * corners, with sites added where their polygon would touch or cross itself; then `n - fixed` interior
   * sites spread by the sites' density at the CVT's optimum, `rho^(1/2)` (Gersho; stratified along a
   * space-filling curve, `internal::optimally_stratified_samples()`; deterministic for a `seed`), a sample
   * that falls between the polygon of the boundary sites and the domain's boundary moved just inside the
   * polygon.
   * \throws Invalid_input if `n` is smaller than 3 or than the number of corners
   * \throws Remeshing_failure if the polygon of the boundary sites can only be made simple with more than
   *         `n` sites (a boundary far more convoluted than `n` vertices can follow)
   */
  std::vector<Point> initial_sites(std::size_t n, unsigned seed)
  {
    std::size_t corners = 0;
    for(int v : m_boundary)
      if(m_itri.is_corner(v)) ++corners;
    if(n < std::max<std::size_t>(3, corners))
      throw Invalid_input("the output needs at least " + std::to_string(std::max<std::size_t>(3, corners)) +
                          " vertices (the boundary has " + std::to_string(corners) + " corners); " +
                          std::to_string(n) + " were requested");
    // spacing h of an equilateral mesh with n vertices, nb = P/h of them on the boundary, covering the area
    const double c = std::sqrt(3.0) / 4;
    const double P = m_metric_spacing ? m_metric_perimeter : m_perimeter;
    const double A = m_metric_spacing ? m_adjusted_area : m_adjusted_area * (m_perimeter_metric_ratio);
    const double nn = std::max(1.0, double(n) - 1);
    const double h = (c * P + std::sqrt(c * c * P * P + 8 * c * nn * A)) / (4 * c * nn);
    place_boundary_sites(h, n);
    separate_boundary_sites(n);
    m_sites_fixed = m_boundary_sites.size();
    std::vector<Point> sites;
    for(const auto& b : m_boundary_sites) sites.push_back(boundary_point(b));
    build_site_polygon(sites);
    // interior: stratified sampling of rho^(1/2) along the Morton curve of the background triangles
    std::mt19937_64 rng(seed);
    std::vector<Point> inside = internal::optimally_stratified_samples(m_tri, n - sites.size(), rng);
    for(Point& p : inside)
      if(!inside_site_polygon(p)) p = pull_inside_site_polygon(p);
    sites.insert(sites.end(), inside.begin(), inside.end());
    return sites;
  }
  /// the number of boundary sites `initial_sites()` added to make their polygon simple
  std::size_t number_of_added_boundary_sites() const { return m_sites_added; }
  /// the number of fixed (boundary) sites placed by the last `initial_sites()`
  std::size_t number_of_fixed_sites() const { return m_sites_fixed; }
  /// where boundary site `i` (`i < number_of_fixed_sites()`) lies on the background boundary
  const Boundary_location& boundary_location(std::size_t i) const { return m_boundary_sites[i]; }
  /// the background vertex at boundary site `i` if it sits exactly on one (corners), else -1
  int boundary_site_vertex(std::size_t i) const
  {
    const Boundary_location& b = m_boundary_sites[i];
    if(b.t == 0) return m_itri.tail(b.halfedge);
    if(b.t == 1) return m_itri.head(b.halfedge);
    return -1;
  }
  /*!
   * where site `i` at `site` lies on the background: the face of the `Intrinsic_triangulation` and
   * the barycentric coordinates in it (with respect to `face_vertices(face)`). A boundary site is placed
   * on its boundary edge exactly (a coordinate is exactly 1 at a corner); a free site is located in the
   * layout, within `1e-6` (relative barycentric) of the domain.
   * \returns `false` if a free site lies outside the domain
   */
  bool background_location(std::size_t i, const Point& site, int& face, Eigen::Vector3d& bary) const
  {
    if(i < m_sites_fixed) {
      const Boundary_location& b = m_boundary_sites[i];
      face = Intrinsic_triangulation::face(b.halfedge);
      const int k = b.halfedge % 3;  // the halfedge goes from corner k to corner k + 1 of its face
      bary = Eigen::Vector3d::Zero();
      bary[k] = 1 - b.t;
      bary[(k + 1) % 3] = b.t;
      return true;
    }
    return locate(site, face, bary, 1e-6);
  }
  /// moves `p` towards `target` as far as it stays in the domain (bisection); returns the new position
  Point move_towards(const Point& p, const Point& target) const
  {
    if(contains(target)) return target;
    Point lo = p, hi = target;
    for(int k = 0; k < 30; ++k) {
      const Point mid = 0.5 * (lo + hi);
      if(contains(mid)) lo = mid; else hi = mid;
    }
    return lo;
  }
  /// @}

  /// \name Integration
  /// @{

  /// how many calls of `integrate()` (by this object and its copies) repaired the last Delaunay triangulation
  std::size_t delaunay_repairs() const { return m_delaunay->repairs; }
  /// computes mass, centroid and energy of the restricted Voronoi cell of every site. The Delaunay
  /// triangulation of the sites is kept for the next call (shared by copies of the traits, one call at a
  /// time) and repaired by edge flips when the sites have moved little (internal/CVT/planar_delaunay_flips.h);
  /// each site's neighbours are taken in index order, so the integrals do not depend on which ran
  void integrate(const std::vector<Point>& sites, std::vector<Cell>& cells) const
  {
    const std::size_t ns = sites.size();
    std::vector<int> start, nbr;
    std::unique_lock<std::mutex> lock(m_delaunay->mutex, std::try_to_lock);
    if(lock.owns_lock() && m_delaunay->flips.update(sites)) {
      m_delaunay->flips.neighbours(start, nbr);
      ++m_delaunay->repairs;
    } else {
      internal::Indexed_delaunay_2 d;
      d.build(sites);
      internal::delaunay_neighbours(d.dt, d.handle, start, nbr);
      if(lock.owns_lock()) m_delaunay->flips.take(d, ns);
    }
    if(lock.owns_lock()) lock.unlock();
    for(std::size_t i = 0; i < ns; ++i) std::sort(nbr.begin() + start[i], nbr.begin() + start[i + 1]);
    std::vector<internal::Cell_accumulator> acc;
    internal::integrate_restricted_voronoi(m_tri, sites, start, nbr, m_threads, acc);
    cells.assign(ns, Cell());
    for(std::size_t i = 0; i < ns; ++i) {
      cells[i].mass = acc[i].mass;
      cells[i].energy = acc[i].energy;
      cells[i].centroid = acc[i].mass > 0 ? Point(acc[i].mx / acc[i].mass, acc[i].my / acc[i].mass) : sites[i];
    }
  }
  /// @}

  /// \name Dual mesh
  /// @{
  /*!
   * the Delaunay triangulation of `sites` constrained to the polygon of the boundary sites (the first
   * `number_of_fixed_sites()`, in boundary order), restricted to the inside: triangles as index triples,
   * counterclockwise. \throws Convergence_failure if a site is not a vertex of the result
   */
  std::vector<std::array<std::size_t, 3>> dual_triangles(const std::vector<Point>& sites) const
  {
    CDT cdt;
    std::vector<CDT::Vertex_handle> vh(sites.size());
    for(std::size_t i = 0; i < sites.size(); ++i) {
      const std::size_t before = cdt.number_of_vertices();
      vh[i] = cdt.insert(K::Point_2(sites[i].x(), sites[i].y()));
      if(cdt.number_of_vertices() == before)
        throw Convergence_failure("dual mesh: site " + std::to_string(i) + " coincides with another site", 0);
      vh[i]->info() = int(i);
    }
    const std::size_t nb = m_sites_fixed;
    for(std::size_t i = 0; i < nb; ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % nb]);
    // initial_sites() made the polygon simple, so no constraint splits another: a failure here is ours
    if(cdt.number_of_vertices() != sites.size())
      throw Internal_error("dual mesh: the boundary polygon of the sites intersects itself");
    mark_inside(cdt);
    // An "ear" (three consecutive boundary sites, the middle one not a corner) lies on one boundary
    // edge chain of the input: flat or nearly so on the surface even when the layout bulges. Flip its
    // inner edge when the quad it forms with the inside neighbour is convex.
    if(nb > 3) {
      std::vector<CDT::Face_handle> ears;
      for(auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
        if(f->info() % 2 == 1) ears.push_back(f);
      for(CDT::Face_handle f : ears) {
        for(int k = 0; k < 3; ++k) {
          const int tip = f->vertex(k)->info(), a = f->vertex(CDT::ccw(k))->info(), b = f->vertex(CDT::cw(k))->info();
          if(tip < 0 || a < 0 || b < 0 || std::size_t(tip) >= nb || std::size_t(a) >= nb || std::size_t(b) >= nb) continue;
          const std::size_t t = std::size_t(tip);
          const bool consecutive = (std::size_t(a) == (t + 1) % nb && std::size_t(b) == (t + nb - 1) % nb) ||
                                   (std::size_t(b) == (t + 1) % nb && std::size_t(a) == (t + nb - 1) % nb);
          if(!consecutive) continue;
          const int v = boundary_site_vertex(t);
          if(v >= 0 && m_itri.is_corner(v)) continue;
          CDT::Face_handle g = f->neighbor(k);
          if(cdt.is_infinite(g) || g->info() % 2 != 1 || cdt.is_constrained(CDT::Edge(f, k))) continue;
          const K::Point_2& p = f->vertex(k)->point();
          const K::Point_2& q = g->vertex(g->index(f))->point();
          const CGAL::Orientation oa = CGAL::orientation(p, q, f->vertex(CDT::ccw(k))->point());
          const CGAL::Orientation ob = CGAL::orientation(p, q, f->vertex(CDT::cw(k))->point());
          if(oa == CGAL::COLLINEAR || ob == CGAL::COLLINEAR || oa == ob) continue;  // not strictly convex
          cdt.flip(f, k);
          f->info() = g->info() = 1;
          break;
        }
      }
    }
    std::vector<std::array<std::size_t, 3>> tris;
    std::vector<char> used(sites.size(), 0);
    for(auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
      if(f->info() % 2 != 1) continue;
      std::array<std::size_t, 3> t;
      for(int k = 0; k < 3; ++k) {
        const int id = f->vertex(k)->info();
        t[k] = std::size_t(id);
        used[id] = 1;
      }
      tris.push_back(t);
    }
    for(std::size_t i = 0; i < sites.size(); ++i)
      if(!used[i])  // free sites are kept strictly inside the polygon (contains()): a failure here is ours
        throw Internal_error("dual mesh: site " + std::to_string(i) + " lies outside the polygon of the boundary sites");
    return tris;
  }
  /// @}

private:
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef CGAL::Triangulation_vertex_base_with_info_2<int, K> CVb;
  typedef CGAL::Constrained_triangulation_face_base_2<K> CFb0;
  typedef CGAL::Triangulation_face_base_with_info_2<int, K, CFb0> CFb;
  typedef CGAL::Triangulation_data_structure_2<CVb, CFb> CTds;
  typedef CGAL::Constrained_Delaunay_triangulation_2<K, CTds, CGAL::Exact_predicates_tag> CDT;

  void build_boundary()
  {
    m_uv_of_vertex.assign(m_itri.number_of_vertices(), Point::Zero());
    for(const internal::Background_triangle& T : m_tri)
      for(int k = 0; k < 3; ++k) m_uv_of_vertex[m_itri.face_vertices(std::size_t(T.face))[k]] = T.p[k];
    // starts at a corner if there is one, so corners split the loop into segments
    m_boundary_halfedges = internal::boundary_halfedge_loop(m_itri, "Planar_domain_traits");
    m_boundary.clear();
    m_perimeter = 0;
    m_metric_perimeter = 0;
    for(int h : m_boundary_halfedges) {
      m_boundary.push_back(m_itri.tail(h));
      m_perimeter += (m_uv_of_vertex[m_itri.head(h)] - m_uv_of_vertex[m_itri.tail(h)]).norm();
      m_metric_perimeter += m_itri.length(h);
    }
    // KEEP_LENGTHS makes both equal; the ratio converts metric areas to domain units
    m_perimeter_metric_ratio = m_metric_perimeter > 0 ? std::pow(m_perimeter / m_metric_perimeter, 2) : 1.0;
  }

  Point boundary_point(const Boundary_location& b) const
  {
    return (1 - b.t) * m_uv_of_vertex[m_itri.tail(b.halfedge)] + b.t * m_uv_of_vertex[m_itri.head(b.halfedge)];
  }

  // corners, then evenly spaced points in between, in boundary order
  void place_boundary_sites(double h, std::size_t n)
  {
    m_boundary_sites.clear();
    m_boundary_site_index.clear();
    const std::size_t nb = m_boundary.size();
    std::vector<std::size_t> corner_pos;
    for(std::size_t i = 0; i < nb; ++i)
      if(m_itri.is_corner(m_boundary[i])) corner_pos.push_back(i);
    const bool no_corner = corner_pos.empty();
    if(no_corner) corner_pos.push_back(0);
    std::vector<std::size_t> counts;  // sites strictly inside each segment
    std::vector<double> seg_len;
    std::size_t total = no_corner ? 0 : corner_pos.size();
    for(std::size_t s = 0; s < corner_pos.size(); ++s) {
      const std::size_t i0 = corner_pos[s], i1 = (s + 1 < corner_pos.size()) ? corner_pos[s + 1] : corner_pos[0] + nb;
      double len = 0;
      for(std::size_t i = i0; i < i1; ++i) len += edge_length(i % nb);
      seg_len.push_back(len);
      std::size_t m = std::size_t(std::max(0.0, std::round(len / h) - (no_corner ? 0 : 1)));
      if(no_corner) m = std::max<std::size_t>(m, 3);
      counts.push_back(m);
      total += m;
    }
    // never more boundary sites than the budget allows (keep a few interior ones when possible)
    while(total > n) {
      std::size_t s = std::size_t(std::max_element(counts.begin(), counts.end()) - counts.begin());
      if(counts[s] == 0) break;
      --counts[s];
      --total;
    }
    for(std::size_t s = 0; s < corner_pos.size(); ++s) {
      const std::size_t i0 = corner_pos[s];
      if(!no_corner) {
        m_boundary_sites.push_back({m_boundary_halfedges[i0], 0.0});
        m_boundary_site_index.push_back(i0);
      }
      const std::size_t m = counts[s];
      const double step = seg_len[s] / double(no_corner ? m : m + 1);
      // walk the segment, dropping a site every `step` of arclength
      std::size_t i = i0;
      double walked = 0, next = no_corner ? 0.5 * step : step;
      for(std::size_t k = 0; k < m; ++k, next += step) {
        while(walked + edge_length(i % nb) < next) walked += edge_length(i++ % nb);
        const double t = std::min(1.0, std::max(0.0, (next - walked) / edge_length(i % nb)));
        m_boundary_sites.push_back({m_boundary_halfedges[i % nb], t});
        m_boundary_site_index.push_back(i % nb);
      }
    }
  }

  // Adds boundary sites until their polygon is simple: halfway, in the spacing's length, between the
  // two sites of every edge of the polygon that touches or crosses another (or folds back on its
  // neighbour). It ends: the polygon tends to the layout's boundary, which is simple.
  void separate_boundary_sites(std::size_t n)
  {
    m_sites_added = 0;
    const std::size_t nb = m_boundary.size();
    std::vector<double> start(nb + 1, 0.0);  // arclength at the tail of each boundary edge
    for(std::size_t i = 0; i < nb; ++i) start[i + 1] = start[i] + edge_length(i);
    const double total = start[nb];
    auto arclength = [&](std::size_t k) { return start[m_boundary_site_index[k]] + m_boundary_sites[k].t * edge_length(m_boundary_site_index[k]); };
    std::vector<char> bad;
    for(int round = 0; round < 200; ++round) {
      std::vector<Point> polygon;
      for(const Boundary_location& b : m_boundary_sites) polygon.push_back(boundary_point(b));
      if(internal::polygon_defects(polygon, 0.0, bad) == 0) return;
      for(std::size_t k = m_boundary_sites.size(); k-- > 0;) {
        if(!bad[k]) continue;
        double a = arclength(k), b = arclength((k + 1) % m_boundary_sites.size());
        if(b <= a) b += total;
        const double mid = std::fmod(0.5 * (a + b), total);
        const std::size_t i = std::min(nb - 1, std::size_t(std::upper_bound(start.begin(), start.end(), mid) - start.begin()) - 1);
        const double t = std::min(1.0, std::max(0.0, (mid - start[i]) / edge_length(i)));
        m_boundary_sites.insert(m_boundary_sites.begin() + std::ptrdiff_t(k + 1), Boundary_location{m_boundary_halfedges[i], t});
        m_boundary_site_index.insert(m_boundary_site_index.begin() + std::ptrdiff_t(k + 1), i);
        ++m_sites_added;
      }
      if(m_boundary_sites.size() > n)
        throw Remeshing_failure("the polygon of the boundary sites touches or crosses itself with fewer than " + std::to_string(n) +
                                    " of them: the boundary is too convoluted in the layout for " + std::to_string(n) + " vertices");
    }
    throw Internal_error("Planar_domain_traits: the polygon of the boundary sites is still not simple after 200 rounds of added sites");
  }

  // the constrained Delaunay triangulation of the polygon of the boundary sites, for inside_site_polygon()
  void build_site_polygon(const std::vector<Point>& boundary_sites)
  {
    m_polygon.clear();
    std::vector<CDT::Vertex_handle> vh;
    for(const Point& p : boundary_sites) {
      vh.push_back(m_polygon.insert(K::Point_2(p.x(), p.y())));
      vh.back()->info() = int(vh.size()) - 1;
    }
    for(std::size_t i = 0; i < vh.size(); ++i) m_polygon.insert_constraint(vh[i], vh[(i + 1) % vh.size()]);
    if(m_polygon.number_of_vertices() != boundary_sites.size())
      throw Internal_error("Planar_domain_traits: the polygon of the boundary sites is not simple");
    mark_inside(m_polygon);
  }

  // `true` if `p` is strictly inside the polygon of the boundary sites (exact predicates), or if there
  // is no such polygon yet
  bool inside_site_polygon(const Point& p) const
  {
    if(m_polygon.number_of_vertices() == 0) return true;
    CDT::Locate_type lt;
    int li = -1;
    const CDT::Face_handle f = m_polygon.locate(K::Point_2(p.x(), p.y()), lt, li);
    if(lt == CDT::FACE) return f->info() % 2 == 1;
    if(lt == CDT::EDGE) return !m_polygon.is_constrained(CDT::Edge(f, li)) && f->info() % 2 == 1;
    return false;  // on a boundary site, or outside the hull
  }

  // A point of the domain just inside the polygon of the boundary sites, near `p` (which lies between the
  // polygon and the domain's boundary): across the nearest edge of the polygon, as far inside as `p` is
  // outside, closer if that leaves the domain.
  Point pull_inside_site_polygon(const Point& p) const
  {
    const std::size_t nb = m_boundary_sites.size();
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    Point foot = p;
    for(std::size_t k = 0; k < nb; ++k) {
      const Point a = boundary_point(m_boundary_sites[k]), b = boundary_point(m_boundary_sites[(k + 1) % nb]);
      const double t = std::min(0.9, std::max(0.1, (p - a).dot(b - a) / std::max(1e-300, (b - a).squaredNorm())));
      const Point q = a + t * (b - a);
      if((p - q).norm() < best_d) {
        best_d = (p - q).norm();
        best = k;
        foot = q;
      }
    }
    const Point a = boundary_point(m_boundary_sites[best]), b = boundary_point(m_boundary_sites[(best + 1) % nb]);
    const Point inward = Point(a.y() - b.y(), b.x() - a.x()).normalized();  // left of a -> b: the polygon is counterclockwise
    double d = best_d + 1e-3 * (b - a).norm();
    for(int k = 0; k < 60; ++k, d *= 0.5) {
      const Point q = foot + d * inward;
      if(contains(q)) return q;
    }
    throw Internal_error("Planar_domain_traits: no point of the domain inside the polygon of the boundary sites near an initial site");
  }

  // marks the faces of `cdt` inside its constraints (info odd: reached from the infinite face by
  // crossing an odd number of constraints), the others even
  static void mark_inside(CDT& cdt)
  {
    for(auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
    std::list<CDT::Face_handle> border;
    auto flood = [&](CDT::Face_handle start, int level) {
      std::list<CDT::Face_handle> q(1, start);
      while(!q.empty()) {
        CDT::Face_handle f = q.front();
        q.pop_front();
        if(f->info() != -1) continue;
        f->info() = level;
        for(int i = 0; i < 3; ++i) {
          CDT::Face_handle g = f->neighbor(i);
          if(g->info() != -1) continue;
          if(cdt.is_constrained(CDT::Edge(f, i))) border.push_back(g); else q.push_back(g);
        }
      }
    };
    flood(cdt.infinite_face(), 0);
    while(!border.empty()) {
      CDT::Face_handle f = border.front();
      border.pop_front();
      if(f->info() == -1) flood(f, 1);
    }
  }

  // the length of boundary edge i that the boundary sites are spaced along: metric, or in the layout
  double edge_length(std::size_t i) const
  {
    const int h = m_boundary_halfedges[i];
    if(m_metric_spacing) return m_itri.length(h);
    return (m_uv_of_vertex[m_itri.head(h)] - m_uv_of_vertex[m_itri.tail(h)]).norm();
  }

  const Intrinsic_triangulation& m_itri;
  bool m_metric_spacing = true;  // boundary sites spaced in metric length (else along the layout)
  std::vector<internal::Background_triangle> m_tri;
  std::vector<Point> m_uv_of_vertex;
  std::vector<int> m_boundary, m_boundary_halfedges;
  std::vector<Boundary_location> m_boundary_sites;
  std::vector<std::size_t> m_boundary_site_index;  // position in the loop of each boundary site's edge
  std::size_t m_sites_fixed = 0, m_sites_added = 0;
  CDT m_polygon;  // the polygon of the boundary sites, faces inside marked odd
  double m_total_mass = 0, m_area = 0, m_adjusted_area = 0, m_perimeter = 0, m_metric_perimeter = 0, m_perimeter_metric_ratio = 1;
  internal::Triangle_grid m_grid;
  unsigned m_threads = 1;
  // the sites' last Delaunay triangulation, repaired by flips at the next integrate()
  typedef internal::Flip_cache<internal::Planar_flip_triangulation> Delaunay_cache;
  std::shared_ptr<Delaunay_cache> m_delaunay = std::make_shared<Delaunay_cache>();
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_PLANAR_DOMAIN_TRAITS_H
