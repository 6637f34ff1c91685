// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_CONE_DOMAIN_TRAITS_H
#define ANISO_CONFORMAL_CONE_DOMAIN_TRAITS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/cone_embedding.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>
#include <Aniso_conformal/internal/domains/cone_charts.h>
#include <Aniso_conformal/internal/domains/cone_surface_delaunay.h>
#include <Aniso_conformal/internal/domains/indexed_delaunay_2.h>
#include <Aniso_conformal/internal/parallel_for.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <queue>
#include <random>
#include <string>
#include <utility>
#include <vector>

/// \file Cone_domain_traits.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the flat surface with cone singularities of `cone_embedding()` (issue 16), as the domain of the CVT and
 * of the dual: the background's faces laid out in the embedding's atlas of planar charts, with the CVT
 * density `cf^2 = exp(-2 u)` linear over each face.
 *
 * **Sites.** A site is a point of the cone surface. Its `Point` is a position in a frame of the plane of
 * its own, fixed when it is created (`initial_sites()`: the chart of its face) and carried along as it moves:
 * the traits remember where each site is (face and chart position) and, when the CVT gives it a new
 * position, walk the straight segment from the old one across the faces, through the charts' transitions
 * (a geodesic of the flat metric, which bends only at cones). So the `Point` of a site, its gradient and
 * its centroid are all in one frame, as the CVT needs, and a site goes around cones and across charts
 * freely. Site `i` of a call is site `i` of `initial_sites()`: the number of sites cannot change and no
 * site is fixed.
 *
 * **Voronoi cells.** Each chart integrates its own faces: its sites and copies of the sites of the faces
 * around it, brought into the chart by the rigid motions along a breadth-first search across the
 * transitions (the faces within three site spacings of the chart's own triangles, a distance widened
 * until every Delaunay circle that matters lies within it), give a Delaunay triangulation in the chart
 * (CGAL's, or the last one moved and repaired by Lawson's flips when the chart holds the same sites'
 * points as at the last integration); the faces are clipped against the cells
 * (`internal::integrate_restricted_voronoi()`) and each copy's integrals are moved back to its site's
 * frame. Around a cone the copies are kept on one sheet: no two copies' wedges at a cone overlap (modulo
 * `2 pi`), so a cone of angle below `2 pi` is seen from both sides and one above `2 pi` over a turn at most
 * (the cells next to a cone of negative curvature are then approximate within a site spacing of it).
 *
 * **Dual.** Not from the charts (whose Euclidean Delaunay triangles disagree next to a cone of negative
 * curvature) but intrinsically, so that it is one triangulation of the surface by construction
 * (`internal::Cone_surface_delaunay`): the sites are inserted into the background's faces in the cone
 * metric, the triangulation is flipped to intrinsic Delaunay (Bobenko and Springborn 2007), the flat
 * background vertices are removed (their unfolded stars triangulated again; Sharp, Soliman and Crane 2019),
 * flipped again, and each cone is merged into its nearest neighbouring site. The result must be a closed
 * triangulation of the genus of the surface (`2 n + 4 g - 4` triangles, each edge shared by two), or
 * `dual_triangles()` throws.
 *
 * \cgalModels `ParametricDomainTraits`
 */
class Cone_domain_traits {
public:
  /// \name Types
  /// @{
  typedef Eigen::Vector2d Point;  ///< a site's position in its own frame (units of the flat metric)
  /// integrals of the density over the Voronoi cell of one site on the cone surface
  struct Cell {
    double mass = 0;                 ///< integral of rho
    Point centroid = Point::Zero();  ///< the cell's centroid in the site's frame, or the site when the mass is 0
    double energy = 0;               ///< integral of rho |y - site|^2
  };
  /// @}

  /// The CVT's line search tries at most 4 step lengths here, not 12, and forgets its L-BFGS memory after
  /// a shortened step: the energy on the cone surface jumps by about 1e-8 where a site crosses a seam of
  /// a chart's band (one sheet around each cone), so the extra halvings find no descent and only cost
  /// energy evaluations (cow, 3000 sites: 434 evaluations per 100 iterations with 12, 217 with 4;
  /// benchmark/cones.md). Declaring it also makes the line search non-monotone over the first four fifths
  /// of the iterations (a step is compared with the largest of the last 10 energies; see
  /// `weighted_centroidal_Voronoi_tessellation()`): 163 evaluations on that cow since stop 63.
  static constexpr int line_search_halvings = 4;

  /// \name Creation
  /// @{
  /// the atlas of `emb` over the background `itri` (flipped by `cone_embedding()`); `threads` workers (0 = all cores)
  Cone_domain_traits(const Intrinsic_triangulation& itri, const Cone_embedding& emb, unsigned threads = 0)
    : m_itri(&itri), m_emb(&emb), m_threads(internal::resolve_thread_count(threads))
  {
    const std::size_t nf = itri.number_of_faces();
    if(emb.corner_uv.size() != nf || emb.chart_of_face.size() != nf || emb.transition.size() != 3 * nf ||
       emb.conformal_factor.size() != itri.number_of_vertices())
      throw Invalid_input("Cone_domain_traits: the embedding does not match the background");
    m_chart.resize(emb.number_of_charts);
    for(std::size_t f = 0; f < nf; ++f) m_chart[std::size_t(emb.chart_of_face[f])].faces.push_back(int(f));
    m_slot.assign(nf, 0);
    double longest = 0;
    for(Chart& c : m_chart) {
      Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
      std::vector<Eigen::Vector2d> g;
      for(int f : c.faces) {
        const auto& p = emb.corner_uv[std::size_t(f)];
        g.push_back((p[0] + p[1] + p[2]) / 3.0);
        for(const auto& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      }
      const std::vector<std::size_t> order = internal::morton_order(g, lo, hi);
      std::vector<int> faces;
      for(std::size_t i : order) faces.push_back(c.faces[i]);
      c.faces = faces;
      for(std::size_t i = 0; i < c.faces.size(); ++i) {
        const int f = c.faces[i];
        m_slot[std::size_t(f)] = i;
        const auto& p = emb.corner_uv[std::size_t(f)];
        const auto& v = itri.face_vertices(std::size_t(f));
        std::array<double, 3> rho;
        for(int k = 0; k < 3; ++k) {
          const double cf = emb.conformal_factor[std::size_t(v[std::size_t(k)])];
          rho[std::size_t(k)] = cf * cf;
          longest = std::max(longest, (p[std::size_t(k)] - p[std::size_t((k + 1) % 3)]).norm());
        }
        if(itri.is_patch_face(std::size_t(f))) rho = {{0.0, 0.0, 0.0}};  // a hole's patch holds no site
        c.tri.push_back(internal::make_background_triangle(p, rho, f));
        c.mass += c.tri.back().mass;
        c.area += c.tri.back().area;
      }
      c.grid.build(c.tri);
      m_total_mass += c.mass;
    }
    m_tolerance = 1e-9 * longest;
    m_chart_order.resize(m_chart.size());
    for(std::size_t c = 0; c < m_chart.size(); ++c) m_chart_order[c] = c;
    std::stable_sort(m_chart_order.begin(), m_chart_order.end(),
                     [&](std::size_t a, std::size_t b) { return m_chart[a].faces.size() > m_chart[b].faces.size(); });
    m_is_cone.assign(itri.number_of_vertices(), 0);
    for(int v : emb.cones) m_is_cone[std::size_t(v)] = 1;
    m_faces.resize(nf);
    m_twin.resize(3 * nf);
    for(std::size_t f = 0; f < nf; ++f) {
      m_faces[f] = itri.face_vertices(f);
      for(int k = 0; k < 3; ++k) m_twin[3 * f + std::size_t(k)] = itri.twin(int(3 * f) + k);
    }
  }
  /// @}

  /// \name Domain
  /// @{
  /// `true` if `p` is finite (the cone surface has no boundary)
  bool contains(const Point& p) const { return p.allFinite(); }
  /// `target` (the cone surface has no boundary)
  Point move_towards(const Point&, const Point& target) const { return target; }
  /// the integral of the density over the surface (the background's metric area)
  double total_mass() const { return m_total_mass; }
  /// the background the atlas lays out (the `Intrinsic_triangulation` given at creation)
  const Intrinsic_triangulation& background() const { return *m_itri; }
  /// the charts of the atlas
  std::size_t number_of_charts() const { return m_chart.size(); }
  /// the copies of background faces in the charts' bands, summed over the charts (after an integration)
  std::size_t number_of_band_copies() const
  {
    std::size_t k = 0;
    for(const auto& b : m_band) k += b.size();
    return k;
  }
  /// the charts' Delaunay triangulations that an integration repaired by flips (the chart held the same
  /// sites' points as at the last one) and that it built anew, summed over every integration
  std::pair<std::size_t, std::size_t> number_of_chart_triangulations() const
  {
    std::pair<std::size_t, std::size_t> n(0, 0);
    for(const auto& k : m_kept) n.first += k.repairs, n.second += k.builds;
    return n;
  }
  /// the straight segments the sites walked, summed over every move (each crossing of a face counts once)
  std::size_t number_of_walk_steps() const { return m_walk_steps; }
  /// @}

  /// \name Sites
  /// @{
  /*!
   * places `n` sites spread by the sites' density at the CVT's optimum, `rho^(1/2)` (Gersho; stratified by
   * `internal::optimal_sampling_weight()` over the charts' faces, uniformly inside a face; deterministic
   * for a `seed`), each in the frame of its face's chart. None is fixed.
   * \throws Invalid_input if `n < 4` on genus 0, `n < 1` otherwise
   */
  std::vector<Point> initial_sites(std::size_t n, unsigned seed) { return initial_sites_after({}, n, seed); }
  /*!
   * the `fixed` sites, each exactly at corner `second` of background face `first` (its `Point` that
   * corner's position in the face's chart, as `Cone_domain::corner_site()` gives), followed by
   * `n - fixed.size()` sites placed as `initial_sites()` places them; a fixed site is the CVT's to keep
   * where it is (`number_of_fixed_sites()` of the wrapper that gives them)
   * \throws Invalid_input if fewer than `fixed.size()` sites, or fewer than 4 (genus 0) or 1 in all, are asked for,
   *         or a face or corner is out of range
   */
  std::vector<Point> initial_sites_after(const std::vector<std::pair<int, int>>& fixed, std::size_t n, unsigned seed)
  {
    if(n < (m_emb->genus == 0 ? 4u : 1u))
      throw Invalid_input("the cone domain needs at least " + std::string(m_emb->genus == 0 ? "4 sites" : "one site"));
    if(n < fixed.size())
      throw Invalid_input("the cone domain: " + std::to_string(fixed.size()) + " fixed sites but only " + std::to_string(n) + " sites in all");
    const std::size_t k = m_first_free = fixed.size();
    m_moved.clear();
    std::vector<std::pair<std::size_t, std::size_t>> slot;
    std::vector<double> cumulative;
    double total = 0;
    for(std::size_t c = 0; c < m_chart.size(); ++c)
      for(std::size_t i = 0; i < m_chart[c].tri.size(); ++i) {
        total += internal::optimal_sampling_weight(m_chart[c].tri[i]);
        cumulative.push_back(total);
        slot.emplace_back(c, i);
      }
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double offset = unit(rng);
    std::vector<Point> sites(n);
    m_state.assign(n, Site_state());
    for(std::size_t j = 0; j < k; ++j) {
      const int f = fixed[j].first, c = fixed[j].second;
      if(f < 0 || std::size_t(f) >= m_emb->corner_uv.size() || c < 0 || c > 2)
        throw Invalid_input("the cone domain: fixed site " + std::to_string(j) + " is not at a corner of a background face");
      m_state[j].face = f;
      m_state[j].x = m_emb->corner_uv[std::size_t(f)][std::size_t(c)];
      m_state[j].point = m_state[j].x;
      sites[j] = m_state[j].x;
    }
    const std::size_t free = n - k;
    for(std::size_t i = 0; i < free; ++i) {
      const std::size_t k2 = k + i;
      const double q = (double(i) + offset) / double(free) * total;
      const std::size_t j = std::min<std::size_t>(cumulative.size() - 1,
                                                  std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), q) - cumulative.begin()));
      const internal::Background_triangle& T = m_chart[slot[j].first].tri[slot[j].second];
      double a = unit(rng), b = unit(rng);
      if(a + b > 1) a = 1 - a, b = 1 - b;
      const Point x = T.p[0] + a * (T.p[1] - T.p[0]) + b * (T.p[2] - T.p[0]);
      m_state[k2].face = T.face;
      m_state[k2].x = x;
      m_state[k2].point = x;
      sites[k2] = x;
    }
    m_band.assign(m_chart.size(), {});
    m_band_width.assign(m_chart.size(), 0.0);
    m_kept.assign(m_chart.size(), {});
    return sites;
  }
  /// 0: no site is fixed on a closed surface
  std::size_t number_of_fixed_sites() const { return 0; }
  /*!
   * where site `i` at `site` lies on the background: its face of the `Intrinsic_triangulation` and the
   * barycentric coordinates there (the site is walked there from where it was last seen; a site that the
   * last `dual_triangles()` moved onto a cone: that cone's background vertex)
   * \returns `false` if `i` is not a site of the last `initial_sites()` or `site` is not finite
   */
  bool background_location(std::size_t i, const Point& site, int& face, Eigen::Vector3d& bary) const
  {
    if(i >= m_state.size() || !site.allFinite()) return false;
    for(const auto& m : m_moved)  // moved onto a cone by the dual
      if(m.point == i) {
        face = m.face;
        bary = Eigen::Vector3d::Unit(m.corner);
        return true;
      }
    move_site(i, site);
    face = m_state[i].face;
    bary = internal::barycentric_2(m_emb->corner_uv[std::size_t(face)], m_state[i].x).cwiseMax(0.0);
    bary /= bary.sum();
    return true;
  }
  /// @}

  /// \name Integration
  /// @{
  /*!
   * computes mass, centroid and energy of the Voronoi cell of every site on the cone surface
   * \throws Invalid_input if `sites` are not as many as `initial_sites()` made
   * \throws Convergence_failure if a site cannot be walked to its new position (not finite, or more face
   *         crossings than 4 times the faces) or a chart's band cannot be made wide enough
   */
  void integrate(const std::vector<Point>& sites, std::vector<Cell>& cells) const
  {
    move_sites(sites);
    const std::vector<Chart_points> charts = chart_points();
    std::vector<std::array<double, 4>> acc(sites.size(), {{0.0, 0.0, 0.0, 0.0}});  // mass, first moment (home frame), energy
    std::vector<std::vector<std::pair<int, std::array<double, 4>>>> part(m_chart.size());
    internal::parallel_for_dynamic(m_chart_order, m_threads, [&](std::size_t c) {
      const Chart_points& cp = charts[c];
      std::vector<internal::Cell_accumulator> a;
      internal::integrate_restricted_voronoi(m_chart[c].tri, cp.points, cp.start, cp.nbr, 1, a);
      for(std::size_t e = 0; e < cp.points.size(); ++e) {
        if(a[e].mass == 0) continue;
        const Rigid_motion_2& m = cp.motion[e];  // the site's chart -> this chart
        const Eigen::Vector2d first = m.R.transpose() * (Eigen::Vector2d(a[e].mx, a[e].my) - a[e].mass * m.t);
        part[c].push_back({cp.original[e], {{a[e].mass, first.x(), first.y(), a[e].energy}}});
      }
    });
    for(const auto& p : part)
      for(const auto& q : p)
        for(int k = 0; k < 4; ++k) acc[std::size_t(q.first)][std::size_t(k)] += q.second[std::size_t(k)];
    cells.assign(sites.size(), Cell());
    for(std::size_t i = 0; i < sites.size(); ++i) {
      cells[i].mass = acc[i][0];
      cells[i].energy = acc[i][3];
      cells[i].centroid = acc[i][0] > 0 ? m_state[i].frame(Eigen::Vector2d(acc[i][1] / acc[i][0], acc[i][2] / acc[i][0])) : sites[i];
    }
  }
  /// @}

  /// \name Dual mesh
  /// @{
  /*!
   * the Delaunay triangulation of `sites` on the cone surface: triangles as index triples, oriented like
   * the background, each once. A cone that no site can be merged into (a part thinner than the sites'
   * spacing) gets its nearest free site moved onto it (`background_location()` then gives the cone).
   * \throws Convergence_failure if two sites coincide, or the triangles do not form a closed triangulation
   *         of the surface's genus (too few sites for it, or cells near a cone of negative curvature that
   *         disagree between charts), with the first problem found
   */
  std::vector<std::array<std::size_t, 3>> dual_triangles(const std::vector<Point>& sites) const
  {
    move_sites(sites);
    const std::size_t ns = sites.size();
    std::vector<internal::Cone_surface_delaunay::Point_on_face> points(ns);
    for(std::size_t i = 0; i < ns; ++i) points[i].face = m_state[i].face, points[i].x = m_state[i].x;
    internal::Cone_surface_delaunay delaunay(m_faces, m_twin, m_emb->corner_uv, m_is_cone);
    std::vector<std::array<std::size_t, 3>> tris = delaunay.triangulate(points, m_first_free);
    m_dual_statistics = delaunay.statistics();
    m_moved = delaunay.moved_points();
    const std::size_t expected = 2 * ns + 4 * std::size_t(m_emb->genus) - 4;
    std::map<std::pair<std::size_t, std::size_t>, int> directed;
    for(const auto& t : tris)
      for(int k = 0; k < 3; ++k) ++directed[{t[std::size_t(k)], t[std::size_t((k + 1) % 3)]}];
    std::size_t unmatched = 0;
    for(const auto& e : directed)
      if(e.second != 1 || directed.count({e.first.second, e.first.first}) == 0) ++unmatched;
    if(tris.size() != expected || unmatched > 0)
      throw Convergence_failure("dual mesh: the Delaunay triangulation of the sites on the cone surface is not a simple closed mesh (" +
                                    std::to_string(tris.size()) + " triangles instead of " + std::to_string(expected) + ", " +
                                    std::to_string(unmatched) + " edges not shared by two triangles: too few sites for the cones)",
                                double(unmatched));
    return tris;
  }

  /// what the last `dual_triangles()` did: Delaunay flips, flat background vertices removed, vertices (the cones) merged into a site
  const internal::Cone_surface_delaunay::Statistics& dual_statistics() const { return m_dual_statistics; }
  /// @}

  /// \name Pictures
  /// @{
  /// one chart of the atlas with the Voronoi cells that the CVT integrates over it (`voronoi_cells()`)
  typedef Cone_chart_cells Chart_cells;

  /*!
   * the restricted Voronoi tessellation of `sites` on the cone surface, chart by chart, as the CVT's
   * integration sees it (for pictures: `IO::write_cone_cvt_svg()`; the paper's Fig.\ 10 (a) and 11 (a) show
   * the same in the sphere and the flat torus). In each chart, its own sites and the copies of the sites
   * around it (brought in by the rigid motions of the transitions, one sheet around each cone) and their
   * Euclidean Voronoi cells; the part of a cell inside the chart's triangles is where the site's cell
   * covers the chart. A site lies in exactly one chart (as an own point) and may have copies in others.
   * \param sites the CVT's sites, as many as `initial_sites()` made (each in its own frame)
   * \returns one entry per chart, in the order of `Cone_embedding::chart_of_face`
   * \throws Invalid_input if `sites` are not as many as `initial_sites()` made
   * \throws Convergence_failure as `integrate()`
   */
  std::vector<Chart_cells> voronoi_cells(const std::vector<Point>& sites) const
  {
    move_sites(sites);
    const std::vector<Chart_points> charts = chart_points(true);
    std::vector<Chart_cells> out(charts.size());
    for(std::size_t c = 0; c < charts.size(); ++c)
      out[c] = internal::cone_chart_cells(m_chart[c].faces, int(c), *m_emb, m_faces, m_twin, m_is_cone, charts[c], 1e3 * m_tolerance);
    return out;
  }
  /// @}

private:
  typedef internal::Cone_chart Chart;
  typedef internal::Cone_chart_points Chart_points;
  typedef internal::Cone_face_copy Face_copy;
  struct Site_state {
    Point point = Point::Zero();     // the last position the CVT gave
    int face = -1;                   // the face it lies in
    Eigen::Vector2d x = Eigen::Vector2d::Zero();  // its position in that face's chart
    Rigid_motion_2 frame;            // that chart -> the site's frame
  };

  void move_site(std::size_t i, const Point& p) const
  {
    Site_state& s = m_state[i];
    if(p == s.point) return;
    if(!p.allFinite()) throw Convergence_failure("cone domain: site " + std::to_string(i) + " is not finite", 0);
    const Eigen::Vector2d d = s.frame.R.transpose() * (p - s.point);
    int f;
    Eigen::Vector2d x;
    Rigid_motion_2 m;
    std::size_t steps = 0;
    internal::walk_on_cone_surface(*m_itri, *m_emb, s.face, s.x, s.x + d, f, x, m, steps);
    s.frame = s.frame * m;
    s.face = f;
    s.x = x;
    s.point = p;
    m_walk_steps += steps;
  }

  void move_sites(const std::vector<Point>& sites) const
  {
    if(sites.size() != m_state.size())
      throw Invalid_input("Cone_domain_traits: " + std::to_string(sites.size()) + " sites given, but initial_sites() made " +
                          std::to_string(m_state.size()));
    m_moved.clear();
    for(std::size_t i = 0; i < sites.size(); ++i) move_site(i, sites[i]);
  }


  // The copies of the faces within `width` of chart c (beyond its own): a Dijkstra from the chart across
  // the transitions by the distance of a copy's centroid to the chart (internal::Cone_chart_distance, a
  // grid over the chart's triangles built here for this width), keeping a copy only if it
  // overlaps no copy kept (nor the chart): the band is one sheet of the plane, so every distance in the
  // chart is the length of a path on the surface. Around a cone of angle below 2 pi the fan is copied as
  // often as it takes to go around once; around one above 2 pi, one turn of it is kept.
  void build_band(std::size_t c, double width) const
  {
    const Chart& chart = m_chart[c];
    std::vector<Face_copy>& band = m_band[c];
    band.clear();
    internal::Cone_chart_distance& dist = m_distance[c];
    dist.build(chart.tri, width);
    const double eps = m_tolerance;
    // the copies kept, in an R-tree of their bounding boxes (Boost.Geometry): copies differ in size by
    // orders of magnitude where the cone metric shrinks a region (a chart of two faces of area 4.5e-12 next
    // to faces of size 0.006 on CGAL's cheese with 450 cones), which a uniform grid sized by the chart's own
    // faces turned into 760 000 cells per copy and 24 GB
    using Box = boost::geometry::model::box<boost::geometry::model::point<double, 2, boost::geometry::cs::cartesian>>;
    boost::geometry::index::rtree<std::pair<Box, std::size_t>, boost::geometry::index::quadratic<16>> tree;
    std::vector<std::array<Eigen::Vector2d, 3>> placed;
    auto box_of = [](const std::array<Eigen::Vector2d, 3>& q) {
      const Eigen::Vector2d lo = q[0].cwiseMin(q[1]).cwiseMin(q[2]), hi = q[0].cwiseMax(q[1]).cwiseMax(q[2]);
      return Box({lo.x(), lo.y()}, {hi.x(), hi.y()});
    };
    auto overlaps = [&](const std::array<Eigen::Vector2d, 3>& q) {
      for(auto it = tree.qbegin(boost::geometry::index::intersects(box_of(q))); it != tree.qend(); ++it)
        if(internal::convex_polygons_overlap(q, placed[it->second], eps)) return true;
      return false;
    };
    auto place = [&](const std::array<Eigen::Vector2d, 3>& q) {
      tree.insert(std::make_pair(box_of(q), placed.size()));
      placed.push_back(q);
    };
    std::vector<Face_copy> copies;
    std::priority_queue<std::pair<double, std::size_t>, std::vector<std::pair<double, std::size_t>>, std::greater<>> queue;
    for(int f : chart.faces) {
      place(m_emb->corner_uv[std::size_t(f)]);
      copies.push_back({f, Rigid_motion_2()});
      queue.push({0.0, copies.size() - 1});
    }
    // a tiny chart between cones may need a band over much of the surface (each face a few times around
    // its cones), so the cap grows with the whole background, not only with the chart
    const std::size_t bound = 64 * chart.faces.size() + 4 * m_itri->number_of_faces() + 4096;
    while(!queue.empty()) {
      const Face_copy fc = copies[queue.top().second];
      queue.pop();
      for(int k = 0; k < 3; ++k) {
        const int h = 3 * fc.face + k, t = m_itri->twin(h);
        if(t < 0) continue;
        const int g = t / 3;
        const Rigid_motion_2 m = fc.motion * m_emb->transition[std::size_t(h)];
        std::array<Eigen::Vector2d, 3> q;
        for(int j = 0; j < 3; ++j) q[std::size_t(j)] = m(m_emb->corner_uv[std::size_t(g)][std::size_t(j)]);
        const Eigen::Vector2d centroid = (q[0] + q[1] + q[2]) / 3.0;
        const double reach = std::max({(q[0] - centroid).norm(), (q[1] - centroid).norm(), (q[2] - centroid).norm()});
        const double from_chart = dist.lower(centroid);
        if(from_chart - reach > width) continue;
        if(overlaps(q)) continue;
        place(q);
        band.push_back({g, m});
        copies.push_back({g, m});
        queue.push({from_chart, copies.size() - 1});
        if(band.size() > bound)
          throw Convergence_failure("cone domain: the band of chart " + std::to_string(c) + " holds more than " + std::to_string(bound) +
                                        " face copies",
                                    double(band.size()));
      }
    }
  }

  // Every chart's sites and copies, with a Delaunay triangulation whose circles that matter lie in the band
  // (widened up to 24 times by 1.6; build_band()'s bound on the number of copies stops it sooner on a
  // surface with too few sites). A chart expecting less than one site starts from a band three times the
  // square root of its own area, far narrower than the cells around it: 8 widenings (a factor 43) left
  // CGAL's camel at 500 sites refused ("not complete within a band of width 0.0096"), which 12 remesh.
  // Where a chart holds the same points as at the last call, its triangulation is repaired by flips
  // (Cone_chart_kept_delaunay); `cgal_triangulations` builds each anew with CGAL, for the pictures.
  std::vector<Chart_points> chart_points(bool cgal_triangulations = false) const
  {
    const std::size_t ns = m_state.size();
    std::vector<int> start(m_itri->number_of_faces() + 1, 0), list(ns);
    for(const Site_state& s : m_state) ++start[std::size_t(s.face) + 1];
    for(std::size_t f = 0; f + 1 < start.size(); ++f) start[f + 1] += start[f];
    {
      std::vector<int> fill(start.begin(), start.end() - 1);
      for(std::size_t i = 0; i < ns; ++i) list[std::size_t(fill[std::size_t(m_state[i].face)]++)] = int(i);
    }
    if(m_band_width.size() != m_chart.size()) {
      m_band.assign(m_chart.size(), {});
      m_band_width.assign(m_chart.size(), 0.0);
    }
    m_kept.resize(m_chart.size());
    m_distance.resize(m_chart.size());
    std::vector<Chart_points> out(m_chart.size());
    internal::parallel_for_dynamic(m_chart_order, m_threads, [&](std::size_t c) {
      const Chart& chart = m_chart[c];
      Chart_points& cp = out[c];
      internal::Cone_chart_kept_delaunay& kept = m_kept[c];
      if(m_band_width[c] == 0) {
        const double sites_here = std::max(1.0, double(ns) * chart.mass / m_total_mass);
        m_band_width[c] = 3 * std::sqrt(chart.area / sites_here);
        build_band(c, m_band_width[c]);
      }
      const int max_widenings = 24;
      for(int attempt = 0;; ++attempt) {
        cp = Chart_points();
        for(int f : chart.faces)
          for(int j = start[std::size_t(f)]; j < start[std::size_t(f) + 1]; ++j) {
            cp.points.push_back(m_state[std::size_t(list[std::size_t(j)])].x);
            cp.original.push_back(list[std::size_t(j)]);
            cp.motion.push_back(Rigid_motion_2());
          }
        cp.own = cp.points.size();
        for(const Face_copy& fc : m_band[c])
          for(int j = start[std::size_t(fc.face)]; j < start[std::size_t(fc.face) + 1]; ++j) {
            cp.points.push_back(fc.motion(m_state[std::size_t(list[std::size_t(j)])].x));
            cp.original.push_back(list[std::size_t(j)]);
            cp.motion.push_back(fc.motion);
          }
        // the last triangulation moved and repaired by flips where the chart holds the same sites' points, else CGAL's
        if(cgal_triangulations || !kept.repair(cp, m_band_width[c])) {
          cp.dt.build(cp.points);
          kept.take(cp, m_band_width[c]);
        }
        if(internal::chart_is_complete(m_distance[c], cp, kept.flips, m_band_width[c])) break;
        if(attempt == max_widenings)
          throw Convergence_failure("cone domain: the Voronoi cells of chart " + std::to_string(c) + " are not complete within a band of width " +
                                        std::to_string(m_band_width[c]) + " (too few sites for the surface)",
                                    m_band_width[c]);
        m_band_width[c] *= 1.6;
        build_band(c, m_band_width[c]);
      }
      if(kept.flips.valid())
        kept.flips.neighbours(cp.start, cp.nbr);
      else
        internal::delaunay_neighbours(cp.dt.dt, cp.dt.handle, cp.start, cp.nbr);
      // each point's neighbours in index order, so that the integrals do not depend on how the triangulation was made
      for(std::size_t i = 0; i + 1 < cp.start.size(); ++i) std::sort(cp.nbr.begin() + cp.start[i], cp.nbr.begin() + cp.start[i + 1]);
    });
    return out;
  }


  const Intrinsic_triangulation* m_itri;
  const Cone_embedding* m_emb;
  unsigned m_threads = 1;
  std::vector<Chart> m_chart;
  std::vector<std::size_t> m_chart_order;  // the charts by decreasing number of faces: the threads take the costliest first
  std::vector<std::size_t> m_slot;
  std::vector<char> m_is_cone;
  double m_total_mass = 0, m_tolerance = 0;
  mutable std::vector<Site_state> m_state;
  mutable std::vector<std::vector<Face_copy>> m_band;
  mutable std::vector<double> m_band_width;
  mutable std::vector<internal::Cone_chart_distance> m_distance;  // to each chart, within its band's width (build_band())
  mutable std::vector<internal::Cone_chart_kept_delaunay> m_kept;  // each chart's last triangulation (chart_points())
  mutable std::size_t m_walk_steps = 0;
  mutable internal::Cone_surface_delaunay::Statistics m_dual_statistics;
  mutable std::vector<internal::Cone_surface_delaunay::Moved_point> m_moved;  // by the last dual_triangles()
  std::size_t m_first_free = 0;  // the sites before it are fixed
  std::vector<std::array<int, 3>> m_faces;  // the background faces and twins, for the dual
  std::vector<int> m_twin;
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_CONE_DOMAIN_TRAITS_H
