// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_CONE_DOMAIN_TRAITS_H
#define ANISO_CONFORMAL_CONE_DOMAIN_TRAITS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/cone_embedding.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>
#include <Aniso_conformal/internal/domains/indexed_delaunay_2.h>
#include <Aniso_conformal/internal/parallel_for.h>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <queue>
#include <random>
#include <set>
#include <unordered_map>
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
 * transitions (a band as wide as three site spacings, widened until every Delaunay circle that matters
 * lies in it), give a CGAL Delaunay triangulation in the chart; the faces are clipped against the cells
 * (`internal::integrate_restricted_voronoi()`) and each copy's integrals are moved back to its site's
 * frame. Around a cone the copies are kept on one sheet: no two copies' wedges at a cone overlap (modulo
 * `2 pi`), so a cone of angle below `2 pi` is seen from both sides and one above `2 pi` over a turn at most
 * (the cells next to a cone of negative curvature are then approximate within a site spacing of it).
 *
 * **Dual.** A Delaunay triangle of a chart is kept where its circumcentre lies in one of the chart's own
 * faces; the triangles of all the charts, each once, must form a closed triangulation of the genus of the
 * surface (`2 n + 4 g - 4` triangles, each edge shared by two), or `dual_triangles()` throws.
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
      c.center = 0.5 * (lo + hi);
      for(std::size_t i = 0; i < c.faces.size(); ++i) {
        const int f = c.faces[i];
        m_slot[std::size_t(f)] = i;
        const auto& p = emb.corner_uv[std::size_t(f)];
        const auto& v = itri.face_vertices(std::size_t(f));
        std::array<double, 3> rho;
        for(int k = 0; k < 3; ++k) {
          const double cf = emb.conformal_factor[std::size_t(v[std::size_t(k)])];
          rho[std::size_t(k)] = cf * cf;
          c.radius = std::max(c.radius, (p[std::size_t(k)] - c.center).norm());
          longest = std::max(longest, (p[std::size_t(k)] - p[std::size_t((k + 1) % 3)]).norm());
        }
        c.tri.push_back(internal::make_background_triangle(p, rho, f));
        c.mass += c.tri.back().mass;
        c.area += c.tri.back().area;
      }
      c.grid.build(c.tri);
      m_total_mass += c.mass;
    }
    m_tolerance = 1e-9 * longest;
    m_is_cone.assign(itri.number_of_vertices(), 0);
    for(int v : emb.cones) m_is_cone[std::size_t(v)] = 1;
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
  /// the charts of the atlas
  std::size_t number_of_charts() const { return m_chart.size(); }
  /// the copies of background faces in the charts' bands, summed over the charts (after an integration)
  std::size_t number_of_band_copies() const
  {
    std::size_t k = 0;
    for(const auto& b : m_band) k += b.size();
    return k;
  }
  /// the straight segments the sites walked, summed over every move (each crossing of a face counts once)
  std::size_t number_of_walk_steps() const { return m_walk_steps; }
  /// @}

  /// \name Sites
  /// @{
  /*!
   * places `n` sites spread over the density (stratified by mass over the charts' faces, uniformly inside
   * a face; deterministic for a `seed`), each in the frame of its face's chart. None is fixed.
   * \throws Invalid_input if `n < 4` on genus 0, `n < 1` otherwise
   */
  std::vector<Point> initial_sites(std::size_t n, unsigned seed)
  {
    if(n < (m_emb->genus == 0 ? 4u : 1u))
      throw Invalid_input("the cone domain needs at least " + std::string(m_emb->genus == 0 ? "4 sites" : "one site"));
    std::vector<std::pair<std::size_t, std::size_t>> slot;
    std::vector<double> cumulative;
    double total = 0;
    for(std::size_t c = 0; c < m_chart.size(); ++c)
      for(std::size_t i = 0; i < m_chart[c].tri.size(); ++i) {
        total += m_chart[c].tri[i].mass;
        cumulative.push_back(total);
        slot.emplace_back(c, i);
      }
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double offset = unit(rng);
    std::vector<Point> sites(n);
    m_state.assign(n, Site_state());
    for(std::size_t k = 0; k < n; ++k) {
      const double q = (double(k) + offset) / double(n) * total;
      const std::size_t j = std::min<std::size_t>(cumulative.size() - 1,
                                                  std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), q) - cumulative.begin()));
      const internal::Background_triangle& T = m_chart[slot[j].first].tri[slot[j].second];
      double a = unit(rng), b = unit(rng);
      if(a + b > 1) a = 1 - a, b = 1 - b;
      const Point x = T.p[0] + a * (T.p[1] - T.p[0]) + b * (T.p[2] - T.p[0]);
      m_state[k].face = T.face;
      m_state[k].x = x;
      m_state[k].point = x;
      sites[k] = x;
    }
    m_band.assign(m_chart.size(), {});
    m_band_width.assign(m_chart.size(), 0.0);
    return sites;
  }
  /// 0: no site is fixed on a closed surface
  std::size_t number_of_fixed_sites() const { return 0; }
  /*!
   * where site `i` at `site` lies on the background: its face of the `Intrinsic_triangulation` and the
   * barycentric coordinates there (the site is walked there from where it was last seen)
   * \returns `false` if `i` is not a site of the last `initial_sites()` or `site` is not finite
   */
  bool background_location(std::size_t i, const Point& site, int& face, Eigen::Vector3d& bary) const
  {
    if(i >= m_state.size() || !site.allFinite()) return false;
    move_site(i, site);
    face = m_state[i].face;
    bary = barycentric(m_emb->corner_uv[std::size_t(face)], m_state[i].x).cwiseMax(0.0);
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
    internal::parallel_for(m_chart.size(), m_threads, [&](std::size_t c) {
      const Chart_points& cp = charts[c];
      std::vector<internal::Cell_accumulator> a;
      internal::integrate_restricted_voronoi(m_chart[c].tri, cp.points, cp.start, cp.nbr, 1, a);
      for(std::size_t e = 0; e < cp.points.size(); ++e) {
        if(a[e].mass == 0) continue;
        const Rigid_motion_2& m = cp.motion[e];  // the site's chart -> this chart
        const Eigen::Vector2d first = m.R.transpose() * (Eigen::Vector2d(a[e].mx, a[e].my) - a[e].mass * m.t);
        part[c].push_back({cp.original[e], {{a[e].mass, first.x(), first.y(), a[e].energy}}});
      }
    }, 1);
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
   * the background, each once
   * \throws Convergence_failure if two sites coincide, or the triangles do not form a closed triangulation
   *         of the surface's genus (too few sites for it, or cells near a cone of negative curvature that
   *         disagree between charts), with the first problem found
   */
  std::vector<std::array<std::size_t, 3>> dual_triangles(const std::vector<Point>& sites) const
  {
    move_sites(sites);
    m_dual_repairs = Dual_repairs();
    const std::size_t ns = sites.size();
    const std::vector<Chart_points> charts = chart_points();
    std::map<std::array<std::size_t, 3>, std::array<std::size_t, 3>> kept;
    for(std::size_t c = 0; c < m_chart.size(); ++c) {
      const Chart_points& cp = charts[c];
      for(std::size_t i = 0; i < cp.own; ++i)
        if(!cp.dt.has_vertex(i))
          throw Convergence_failure("dual mesh: site " + std::to_string(cp.original[i]) + " coincides with another site on the cone surface", 0);
      for(auto f = cp.dt.dt.finite_faces_begin(); f != cp.dt.dt.finite_faces_end(); ++f) {
        const auto cc = cp.dt.dt.circumcenter(f);
        int index = -1;
        Eigen::Vector3d bary;
        if(!m_chart[c].grid.locate(m_chart[c].tri, Eigen::Vector2d(cc.x(), cc.y()), index, bary, 1e-9)) continue;
        std::array<std::size_t, 3> t;
        for(int k = 0; k < 3; ++k) t[std::size_t(k)] = std::size_t(cp.original[std::size_t(f->vertex(k)->info())]);
        if(t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
          ++m_dual_repairs.loops;  // a site joined to its own copy around a sharp cone: left to the hole filling
          continue;
        }
        std::array<std::size_t, 3> key = t;
        std::sort(key.begin(), key.end());
        kept.emplace(key, t);
      }
    }
    std::vector<std::array<std::size_t, 3>> tris;
    for(const auto& k : kept) tris.push_back(k.second);
    close_holes_near_cones(tris, charts);
    if(std::getenv("CONE_DEBUG")) std::fprintf(stderr, "dual: kept %zu, loops %zu conflicts %zu holes %zu filled %zu pinched %zu excised %zu -> %zu\n", kept.size(), m_dual_repairs.loops, m_dual_repairs.conflicts, m_dual_repairs.holes, m_dual_repairs.filled, m_dual_repairs.pinched, m_dual_repairs.excised, tris.size());
    const std::size_t expected = 2 * ns + 4 * std::size_t(m_emb->genus) - 4;
    std::map<std::pair<std::size_t, std::size_t>, int> directed;
    for(const auto& t : tris)
      for(int k = 0; k < 3; ++k) ++directed[{t[std::size_t(k)], t[std::size_t((k + 1) % 3)]}];
    std::size_t unmatched = 0;
    for(const auto& e : directed)
      if(e.second != 1 || directed.count({e.first.second, e.first.first}) == 0) ++unmatched;
    if(tris.size() != expected || unmatched > 0)
      throw Convergence_failure("dual mesh: the Delaunay triangles of the cone surface's charts do not close up (" + std::to_string(tris.size()) +
                                    " triangles instead of " + std::to_string(expected) + ", " + std::to_string(unmatched) +
                                    " edges not shared by two)",
                                double(unmatched));
    return tris;
  }

  /// what `dual_triangles()` mended where the charts' Delaunay triangles did not close up (near cones)
  struct Dual_repairs {
    std::size_t loops = 0;      ///< Delaunay triangles joining a site to its own copy (around a sharp cone), dropped
    std::size_t conflicts = 0;  ///< triangles dropped because another already had one of their oriented edges
    std::size_t holes = 0;      ///< holes filled
    std::size_t filled = 0;     ///< triangles added by the filling
    std::size_t pinched = 0;    ///< vertices where two filled holes met, mended
    std::size_t excised = 0;    ///< rounds of removing and refilling the neighbourhoods of non-manifold vertices
  };
  /// the repairs of the last `dual_triangles()`
  const Dual_repairs& dual_repairs() const { return m_dual_repairs; }
  /// @}

private:
  typedef internal::Indexed_delaunay_2::K K;

  struct Chart {
    std::vector<int> faces;  // in Morton order
    std::vector<internal::Background_triangle> tri;
    internal::Triangle_grid grid;
    Eigen::Vector2d center = Eigen::Vector2d::Zero();
    double radius = 0, mass = 0, area = 0;
  };
  struct Site_state {
    Point point = Point::Zero();     // the last position the CVT gave
    int face = -1;                   // the face it lies in
    Eigen::Vector2d x = Eigen::Vector2d::Zero();  // its position in that face's chart
    Rigid_motion_2 frame;            // that chart -> the site's frame
  };
  struct Face_copy {
    int face;
    Rigid_motion_2 motion;  // the face's chart -> the band's chart
  };
  // a chart's sites (the first `own`) and copies, with their Delaunay triangulation and neighbours
  struct Chart_points {
    std::vector<Eigen::Vector2d> points;
    std::vector<int> original;
    std::vector<Rigid_motion_2> motion;
    std::size_t own = 0;
    internal::Indexed_delaunay_2 dt;
    std::vector<int> start, nbr;
  };

  static Eigen::Vector3d barycentric(const std::array<Eigen::Vector2d, 3>& p, const Eigen::Vector2d& x)
  {
    const Eigen::Vector2d e1 = p[1] - p[0], e2 = p[2] - p[0], w = x - p[0];
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    const double b1 = (w.x() * e2.y() - w.y() * e2.x()) / det, b2 = (e1.x() * w.y() - e1.y() * w.x()) / det;
    return Eigen::Vector3d(1 - b1 - b2, b1, b2);
  }

  // the area-weighted normal of the triangles at site v (of `tris`)
  Eigen::Vector3d vertex_normal(std::size_t v, const std::vector<std::array<std::size_t, 3>>& tris) const
  {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for(const auto& t : tris)
      if(t[0] == v || t[1] == v || t[2] == v) {
        const Eigen::Vector3d a = site_position(t[0]), b = site_position(t[1]), c = site_position(t[2]);
        n += (b - a).cross(c - a);
      }
    return n;
  }

  // the site's position in space: its barycentric coordinates on the background's chords
  Eigen::Vector3d site_position(std::size_t i) const
  {
    const Site_state& st = m_state[i];
    const Eigen::Vector3d b = barycentric(m_emb->corner_uv[std::size_t(st.face)], st.x);
    const auto& v = m_itri->face_vertices(std::size_t(st.face));
    return b[0] * m_itri->position(v[0]) + b[1] * m_itri->position(v[1]) + b[2] * m_itri->position(v[2]);
  }

  // Where the charts' triangles do not close up (a sharp cone inside a triangle, cells that disagree next to
  // a cone): drops the triangles that repeat an oriented edge, then fills every hole left by ear clipping
  // in space, the ear of largest smallest angle first (never an edge the mesh has). A hole pinched at a
  // vertex is left (the count check then throws).
  void close_holes_near_cones(std::vector<std::array<std::size_t, 3>>& tris, const std::vector<Chart_points>& charts) const
  {
    std::map<std::pair<std::size_t, std::size_t>, int> directed;
    for(const auto& t : tris)
      for(int k = 0; k < 3; ++k) ++directed[{t[std::size_t(k)], t[std::size_t((k + 1) % 3)]}];
    std::vector<std::array<std::size_t, 3>> keep;
    for(const auto& t : tris) {
      bool repeated = false;
      for(int k = 0; k < 3; ++k) repeated = repeated || directed[{t[std::size_t(k)], t[std::size_t((k + 1) % 3)]}] > 1;
      if(repeated) ++m_dual_repairs.conflicts;
      else keep.push_back(t);
    }
    tris.swap(keep);
    std::set<std::pair<std::size_t, std::size_t>> edges;
    for(const auto& t : tris)
      for(int k = 0; k < 3; ++k) edges.insert({t[std::size_t(k)], t[std::size_t((k + 1) % 3)]});
    const std::vector<std::vector<std::size_t>> loops = hole_loops(tris);
    // A site in no triangle (at the tip of a sharp cone every Delaunay triangle joins it to its own copy)
    // lies in the hole that most of its Delaunay neighbours (in its own chart) bound.
    std::map<std::size_t, std::size_t> loop_of;
    for(std::size_t l = 0; l < loops.size(); ++l)
      for(std::size_t w : loops[l]) loop_of[w] = l;
    std::vector<char> used(m_state.size(), 0);
    for(const auto& t : tris)
      for(std::size_t v : t) used[v] = 1;
    std::vector<std::vector<std::size_t>> inside(loops.size());
    std::size_t stray = 0;
    for(std::size_t v = 0; v < used.size(); ++v) {
      if(used[v]) continue;
      const Chart_points& cp = charts[std::size_t(m_emb->chart_of_face[std::size_t(m_state[v].face)])];
      std::map<std::size_t, int> votes;
      for(std::size_t i = 0; i < cp.own; ++i) {
        if(std::size_t(cp.original[i]) != v || !cp.dt.has_vertex(i)) continue;
        auto c = cp.dt.dt.incident_vertices(cp.dt.handle[i]), done = c;
        do {
          if(cp.dt.dt.is_infinite(c)) continue;
          const auto it = loop_of.find(std::size_t(cp.original[std::size_t(c->info())]));
          if(it != loop_of.end()) ++votes[it->second];
        } while(++c != done);
      }
      if(votes.empty()) {
        ++stray;
        continue;
      }
      const auto best = std::max_element(votes.begin(), votes.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
      inside[best->first].push_back(v);
    }
    for(std::size_t l = 0; l < loops.size(); ++l) {
      if(loops[l].size() < 3) continue;
      ++m_dual_repairs.holes;
      const std::size_t before = tris.size();
      const bool projected = fill_hole_by_projection(loops[l], inside[l], edges, tris);
      if(!projected && inside[l].empty()) fill_hole_by_ears(loops[l], edges, tris);
      if(!projected && !inside[l].empty()) fill_hole_by_fan(loops[l], inside[l], tris);
      if(std::getenv("CONE_DEBUG")) std::fprintf(stderr, "hole %zu: size %zu, inside %zu, projected %d\n", l, loops[l].size(), inside[l].size(), int(projected));
      m_dual_repairs.filled += tris.size() - before;
    }
    if(std::getenv("CONE_DEBUG")) std::fprintf(stderr, "stray %zu\n", stray);
    unpinch_vertices(tris);
    excise_and_refill(tris);
  }

  // The vertices where `tris` is not one closed surface: a link that is not one closed cycle (an oriented
  // edge twice, a hole's border, or a pinch where two charts each claimed a whole umbrella next to a cone),
  // or a triangle apart from the largest piece.
  // A site in no triangle at all brings in its nearest site that has some.
  std::set<std::size_t> vertices_without_disk_link(const std::vector<std::array<std::size_t, 3>>& tris) const
  {
    std::map<std::size_t, std::map<std::size_t, std::size_t>> link;  // v -> (a -> b) for triangles (v, a, b)
    std::set<std::size_t> bad;
    for(const auto& t : tris)
      for(int k = 0; k < 3; ++k) {
        auto& l = link[t[std::size_t(k)]];
        if(!l.emplace(t[std::size_t((k + 1) % 3)], t[std::size_t((k + 2) % 3)]).second) bad.insert(t[std::size_t(k)]);
      }
    for(const auto& l : link) {
      std::size_t a = l.second.begin()->first, steps = 0;
      do {
        const auto it = l.second.find(a);
        if(it == l.second.end()) break;
        a = it->second;
        ++steps;
      } while(a != l.second.begin()->first && steps <= l.second.size());
      if(a != l.second.begin()->first || steps != l.second.size()) bad.insert(l.first);
    }
    // a closed pocket apart from the rest (two charts' umbrellas around a cone closing on each other): all
    // its vertices, whatever their links; the surface is the largest piece joined through edges
    std::vector<std::size_t> piece(tris.size());
    for(std::size_t i = 0; i < tris.size(); ++i) piece[i] = i;
    std::function<std::size_t(std::size_t)> root = [&](std::size_t i) { return piece[i] == i ? i : piece[i] = root(piece[i]); };
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> first_with_edge;
    for(std::size_t i = 0; i < tris.size(); ++i)
      for(int k = 0; k < 3; ++k) {
        const auto e = std::minmax(tris[i][std::size_t(k)], tris[i][std::size_t((k + 1) % 3)]);
        const auto it = first_with_edge.emplace(e, i).first;
        piece[root(i)] = root(it->second);
      }
    std::map<std::size_t, std::size_t> piece_size;
    for(std::size_t i = 0; i < tris.size(); ++i) ++piece_size[root(i)];
    std::size_t largest = 0, largest_size = 0;
    for(const auto& ps : piece_size)
      if(ps.second > largest_size) largest_size = ps.second, largest = ps.first;
    for(std::size_t i = 0; i < tris.size(); ++i)
      if(root(i) != largest) bad.insert(tris[i].begin(), tris[i].end());
    for(std::size_t v = 0; v < m_state.size(); ++v) {
      if(link.count(v)) continue;
      const Eigen::Vector3d p = site_position(v);
      std::size_t nearest = std::size_t(-1);
      double d = 1e300;
      for(const auto& l : link)
        if((site_position(l.first) - p).squaredNorm() < d) d = (site_position(l.first) - p).squaredNorm(), nearest = l.first;
      if(nearest != std::size_t(-1)) bad.insert(nearest);
    }
    return bad;
  }

  // Where the repairs above still leave vertices without a disk around them, the charts' views of that
  // neighbourhood cannot be reconciled triangle by triangle: every triangle within `ring` rings of such a
  // vertex is removed, and each hole left is refilled with the sites it swallowed by a constrained Delaunay
  // triangulation in the hole's plane (else a fan from one of them, else ears). The ring grows (up to 6)
  // while some vertex is still bad; what is left then makes `dual_triangles()` throw.
  void excise_and_refill(std::vector<std::array<std::size_t, 3>>& tris) const
  {
    for(int ring = 1; ring <= 6; ++ring) {
      const std::set<std::size_t> bad = vertices_without_disk_link(tris);
      if(bad.empty()) return;
      ++m_dual_repairs.excised;
      std::map<std::size_t, std::set<std::size_t>> adj;
      for(const auto& t : tris)
        for(int k = 0; k < 3; ++k) {
          adj[t[std::size_t(k)]].insert(t[std::size_t((k + 1) % 3)]);
          adj[t[std::size_t((k + 1) % 3)]].insert(t[std::size_t(k)]);
        }
      std::set<std::size_t> region = bad;
      for(int r = 0; r < ring; ++r) {
        std::set<std::size_t> grown = region;
        for(std::size_t v : region)
          for(std::size_t w : adj[v]) grown.insert(w);
        region.swap(grown);
      }
      std::vector<std::array<std::size_t, 3>> rest;
      for(const auto& t : tris)
        if(!region.count(t[0]) && !region.count(t[1]) && !region.count(t[2])) rest.push_back(t);
      tris.swap(rest);
      std::vector<char> used(m_state.size(), 0);
      for(const auto& t : tris)
        for(std::size_t v : t) used[v] = 1;
      const std::vector<std::vector<std::size_t>> loops = hole_loops(tris);
      std::map<std::size_t, std::size_t> loop_of;
      for(std::size_t l = 0; l < loops.size(); ++l)
        for(std::size_t w : loops[l]) loop_of[w] = l;
      // a pocket removed whole leaves no hole: its sites, now in no triangle, open one at the next round
      if(loops.empty()) continue;
      // each swallowed site goes to the hole it reaches first along the removed edges (the nearest border
      // site in space if it was in no triangle)
      std::vector<std::vector<std::size_t>> inside(loops.size());
      for(std::size_t v = 0; v < m_state.size(); ++v) {
        if(used[v]) continue;
        std::size_t hole = std::size_t(-1);
        std::set<std::size_t> seen{v};
        std::vector<std::size_t> front{v};
        while(hole == std::size_t(-1) && !front.empty()) {
          std::vector<std::size_t> next;
          for(std::size_t u : front)
            for(std::size_t w : adj[u]) {
              if(!seen.insert(w).second) continue;
              const auto it = loop_of.find(w);
              if(it != loop_of.end() && hole == std::size_t(-1)) hole = it->second;
              next.push_back(w);
            }
          front.swap(next);
        }
        if(hole == std::size_t(-1)) {
          const Eigen::Vector3d p = site_position(v);
          double d = 1e300;
          for(const auto& lw : loop_of)
            if((site_position(lw.first) - p).squaredNorm() < d) d = (site_position(lw.first) - p).squaredNorm(), hole = lw.second;
        }
        inside[hole].push_back(v);
      }
      std::set<std::pair<std::size_t, std::size_t>> edges;
      for(const auto& t : tris)
        for(int k = 0; k < 3; ++k) edges.insert({t[std::size_t(k)], t[std::size_t((k + 1) % 3)]});
      for(std::size_t l = 0; l < loops.size(); ++l) {
        if(loops[l].size() < 3) continue;
        const bool projected = fill_hole_by_projection(loops[l], inside[l], edges, tris);
        if(!projected && inside[l].empty()) fill_hole_by_ears(loops[l], edges, tris);
        if(!projected && !inside[l].empty()) fill_hole_by_fan(loops[l], inside[l], tris);
        if(std::getenv("CONE_DEBUG")) std::fprintf(stderr, "excised ring %d hole %zu: size %zu, inside %zu, projected %d\n", ring, l, loops[l].size(), inside[l].size(), int(projected));
      }
    }
  }

  // The holes of `tris` as simple cycles, each oriented as its missing triangles have their edges
  std::vector<std::vector<std::size_t>> hole_loops(const std::vector<std::array<std::size_t, 3>>& tris) const
  {
    std::set<std::pair<std::size_t, std::size_t>> edges;
    for(const auto& t : tris)
      for(int k = 0; k < 3; ++k) edges.insert({t[std::size_t(k)], t[std::size_t((k + 1) % 3)]});
    std::map<std::size_t, std::vector<std::size_t>> next;  // the holes' edges, oriented as the missing triangles have them
    for(const auto& e : edges)
      if(!edges.count({e.second, e.first})) next[e.second].push_back(e.first);
    // the holes' edges form cycles (each vertex has as many in as out); split them into simple cycles
    std::vector<std::vector<std::size_t>> loops;
    while(!next.empty()) {
      std::vector<std::size_t> path{next.begin()->first};
      std::map<std::size_t, std::size_t> at{{path.front(), 0}};
      while(true) {
        auto it = next.find(path.back());
        if(it == next.end()) break;
        // where the hole touches itself at v, the exit that bounds the same side (the hole on the left): the
        // first one clockwise from the way back, about v's normal
        std::size_t pick = it->second.size() - 1;
        if(it->second.size() > 1 && path.size() > 1) {
          const std::size_t v = path.back(), u = path[path.size() - 2];
          const Eigen::Vector3d n = vertex_normal(v, tris), xv = site_position(v), back = site_position(u) - xv;
          double least = 1e300;
          for(std::size_t j = 0; j < it->second.size(); ++j) {
            const Eigen::Vector3d out = site_position(it->second[j]) - xv;
            double ccw = std::atan2(n.dot(back.cross(out)), back.dot(out));
            if(ccw < 0) ccw += 2 * 3.14159265358979323846;
            const double cw = 2 * 3.14159265358979323846 - ccw;
            if(cw < least) least = cw, pick = j;
          }
        }
        const std::size_t w = it->second[pick];
        it->second.erase(it->second.begin() + std::ptrdiff_t(pick));
        if(it->second.empty()) next.erase(it);
        const auto seen = at.find(w);
        if(seen == at.end()) {
          at[w] = path.size();
          path.push_back(w);
          continue;
        }
        loops.emplace_back(path.begin() + std::ptrdiff_t(seen->second), path.end());
        for(std::size_t j = seen->second + 1; j < path.size(); ++j) at.erase(path[j]);
        path.resize(seen->second + 1);
      }
    }
    return loops;
  }

  // A vertex whose link is several cycles (two holes met there and were filled apart): its triangles are
  // removed, each cycle filled without it by ear clipping, and it is put back by splitting the filled
  // triangle nearest to it. At most 64 vertices are mended (the count check then throws if any is left).
  void unpinch_vertices(std::vector<std::array<std::size_t, 3>>& tris) const
  {
    for(int round = 0; round < 64; ++round) {
      std::map<std::size_t, std::map<std::size_t, std::size_t>> link;  // v -> (a -> b) for triangles (v, a, b)
      for(const auto& t : tris)
        for(int k = 0; k < 3; ++k) link[t[std::size_t(k)]][t[std::size_t((k + 1) % 3)]] = t[std::size_t((k + 2) % 3)];
      std::size_t pinched = std::size_t(-1);
      std::vector<std::vector<std::size_t>> cycles;
      for(const auto& l : link) {
        std::map<std::size_t, std::size_t> next = l.second;
        cycles.clear();
        while(!next.empty()) {
          std::vector<std::size_t> c{next.begin()->first};
          for(std::size_t guard = 0; guard <= l.second.size(); ++guard) {
            const auto it = next.find(c.back());
            if(it == next.end()) break;
            const std::size_t w = it->second;
            next.erase(it);
            if(w == c.front()) break;
            c.push_back(w);
          }
          cycles.push_back(c);
        }
        if(cycles.size() > 1) {
          pinched = l.first;
          break;
        }
      }
      if(pinched == std::size_t(-1)) return;
      if(std::getenv("CONE_DEBUG")) { std::fprintf(stderr, "pinched %zu:", pinched); for(auto& c : cycles) std::fprintf(stderr, " %zu", c.size()); std::fprintf(stderr, "\n"); }
      ++m_dual_repairs.pinched;
      std::vector<std::array<std::size_t, 3>> rest;
      for(const auto& t : tris)
        if(t[0] != pinched && t[1] != pinched && t[2] != pinched) rest.push_back(t);
      tris.swap(rest);
      std::set<std::pair<std::size_t, std::size_t>> edges;
      for(const auto& t : tris)
        for(int k = 0; k < 3; ++k) edges.insert({t[std::size_t(k)], t[std::size_t((k + 1) % 3)]});
      const std::size_t before = tris.size();
      for(const auto& c : cycles) fill_hole_by_ears(c, edges, tris);
      if(tris.size() == before) return;
      const Eigen::Vector3d p = site_position(pinched);
      std::size_t best = before;
      double d = 1e300;
      for(std::size_t j = before; j < tris.size(); ++j) {
        const Eigen::Vector3d g = (site_position(tris[j][0]) + site_position(tris[j][1]) + site_position(tris[j][2])) / 3.0;
        if((g - p).squaredNorm() < d) d = (g - p).squaredNorm(), best = j;
      }
      const std::array<std::size_t, 3> t = tris[best];
      tris[best] = {{t[0], t[1], pinched}};
      tris.push_back({{t[1], t[2], pinched}});
      tris.push_back({{t[2], t[0], pinched}});
    }
  }

  // Fills the hole `loop` (oriented as its missing triangles have their edges) with the sites `inside` by a
  // constrained Delaunay triangulation in the plane of the loop (Newell's normal); `false` if the loop is
  // not a simple polygon there or a site falls outside it.
  bool fill_hole_by_projection(const std::vector<std::size_t>& loop, const std::vector<std::size_t>& inside,
                               std::set<std::pair<std::size_t, std::size_t>>& edges, std::vector<std::array<std::size_t, 3>>& tris) const
  {
    typedef CGAL::Exact_predicates_inexact_constructions_kernel EK;
    typedef CGAL::Triangulation_vertex_base_with_info_2<std::size_t, EK> Vb;
    typedef CGAL::Constrained_triangulation_face_base_2<EK> Fb;
    typedef CGAL::Triangulation_data_structure_2<Vb, Fb> Tds;
    typedef CGAL::Constrained_Delaunay_triangulation_2<EK, Tds, CGAL::No_constraint_intersection_tag> CDT;
    const std::size_t m = loop.size();
    std::vector<Eigen::Vector3d> x;
    for(std::size_t v : loop) x.push_back(site_position(v));
    Eigen::Vector3d normal = Eigen::Vector3d::Zero(), mean = Eigen::Vector3d::Zero();
    for(std::size_t i = 0; i < m; ++i) normal += x[i].cross(x[(i + 1) % m]), mean += x[i];
    mean /= double(m);
    if(!(normal.norm() > 0)) return false;
    normal.normalize();
    const Eigen::Vector3d e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
    auto project = [&](const Eigen::Vector3d& p) { return EK::Point_2((p - mean).dot(e1), (p - mean).dot(e2)); };
    std::vector<EK::Point_2> polygon;
    for(const auto& p : x) polygon.push_back(project(p));
    // the loop must be a simple polygon, counterclockwise about the normal
    for(std::size_t i = 0; i < m; ++i)
      for(std::size_t j = i + 1; j < m; ++j) {
        if(j == i + 1 || (i == 0 && j == m - 1)) continue;
        if(CGAL::do_intersect(EK::Segment_2(polygon[i], polygon[(i + 1) % m]), EK::Segment_2(polygon[j], polygon[(j + 1) % m]))) {
          if(std::getenv("CONE_DEBUG")) std::fprintf(stderr, "  not simple\n");
          return false;
        }
      }
    CDT cdt;
    try {
      std::vector<CDT::Vertex_handle> h;
      for(std::size_t i = 0; i < m; ++i) {
        h.push_back(cdt.insert(polygon[i]));
        h.back()->info() = loop[i];
      }
      for(std::size_t i = 0; i < m; ++i) cdt.insert_constraint(h[i], h[(i + 1) % m]);
      for(std::size_t v : inside) {
        const EK::Point_2 q = project(site_position(v));
        if(CGAL::bounded_side_2(polygon.begin(), polygon.end(), q) != CGAL::ON_BOUNDED_SIDE) {
          if(std::getenv("CONE_DEBUG")) { std::fprintf(stderr, "  site %zu outside the hole's polygon (%g %g):", v, q.x(), q.y()); for(auto& pp : polygon) std::fprintf(stderr, " (%g %g)", pp.x(), pp.y()); std::fprintf(stderr, "\n"); }
          return false;
        }
        CDT::Vertex_handle w = cdt.insert(q);
        w->info() = v;
      }
      if(cdt.number_of_vertices() != m + inside.size()) return false;
    } catch(const std::exception&) {
      return false;
    }
    const bool ccw = CGAL::orientation_2(polygon.begin(), polygon.end()) == CGAL::COUNTERCLOCKWISE;
    std::vector<std::array<std::size_t, 3>> added;
    for(auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
      EK::Point_2 c = CGAL::centroid(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
      if(CGAL::bounded_side_2(polygon.begin(), polygon.end(), c) != CGAL::ON_BOUNDED_SIDE) continue;
      std::array<std::size_t, 3> t{{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}};
      if(!ccw) std::swap(t[1], t[2]);
      added.push_back(t);
    }
    // a diagonal the mesh already has elsewhere would join two sites twice
    std::set<std::pair<std::size_t, std::size_t>> loop_edges;
    for(std::size_t i = 0; i < m; ++i) loop_edges.insert(std::minmax(loop[i], loop[(i + 1) % m]));
    for(const auto& t : added)
      for(int k = 0; k < 3; ++k) {
        const auto e = std::minmax(t[std::size_t(k)], t[std::size_t((k + 1) % 3)]);
        if(!loop_edges.count(e) && (edges.count(e) || edges.count({e.second, e.first}))) return false;
      }
    if(added.size() != m - 2 + 2 * inside.size()) {
      if(std::getenv("CONE_DEBUG")) std::fprintf(stderr, "  %zu triangles\n", added.size());
      return false;
    }
    tris.insert(tris.end(), added.begin(), added.end());
    for(const auto& t : added)
      for(int k = 0; k < 3; ++k) edges.insert({t[std::size_t(k)], t[std::size_t((k + 1) % 3)]});
    return true;
  }

  // Fills the hole `loop` by a fan from its first inside site, each further one splitting the fan's triangle
  // whose centroid is nearest to it in space (a disk whatever the shape: the tip of a curved horn does not
  // project into its loop)
  void fill_hole_by_fan(const std::vector<std::size_t>& loop, const std::vector<std::size_t>& inside,
                        std::vector<std::array<std::size_t, 3>>& tris) const
  {
    std::vector<std::array<std::size_t, 3>> added;
    for(std::size_t i = 0; i < loop.size(); ++i) added.push_back({{loop[i], loop[(i + 1) % loop.size()], inside.front()}});
    for(std::size_t k = 1; k < inside.size(); ++k) {
      const Eigen::Vector3d p = site_position(inside[k]);
      std::size_t best = 0;
      double d = 1e300;
      for(std::size_t j = 0; j < added.size(); ++j) {
        const Eigen::Vector3d g = (site_position(added[j][0]) + site_position(added[j][1]) + site_position(added[j][2])) / 3.0;
        if((g - p).squaredNorm() < d) d = (g - p).squaredNorm(), best = j;
      }
      const std::array<std::size_t, 3> t = added[best];
      added[best] = {{t[0], t[1], inside[k]}};
      added.push_back({{t[1], t[2], inside[k]}});
      added.push_back({{t[2], t[0], inside[k]}});
    }
    tris.insert(tris.end(), added.begin(), added.end());
  }

  // Fills the hole `loop` by ear clipping in space, the ear of largest smallest angle first, never adding an
  // edge the mesh has (`edges`, updated)
  void fill_hole_by_ears(std::vector<std::size_t> loop, std::set<std::pair<std::size_t, std::size_t>>& edges,
                         std::vector<std::array<std::size_t, 3>>& tris) const
  {
    std::vector<Eigen::Vector3d> x;
    for(std::size_t v : loop) x.push_back(site_position(v));
    auto has_edge = [&](std::size_t a, std::size_t b) { return edges.count({a, b}) || edges.count({b, a}); };
    auto angle = [](const Eigen::Vector3d& o, const Eigen::Vector3d& u, const Eigen::Vector3d& w) {
      return std::atan2((u - o).cross(w - o).norm(), (u - o).dot(w - o));
    };
    while(loop.size() > 3) {
      int best = -1;
      double best_angle = -1;
      const std::size_t m = loop.size();
      for(std::size_t i = 0; i < m; ++i) {
        const std::size_t a = (i + m - 1) % m, c = (i + 1) % m;
        if(has_edge(loop[a], loop[c])) continue;
        const double smallest = std::min({angle(x[a], x[i], x[c]), angle(x[i], x[c], x[a]), angle(x[c], x[a], x[i])});
        if(smallest > best_angle) best_angle = smallest, best = int(i);
      }
      if(best < 0) {
        if(std::getenv("CONE_DEBUG")) std::fprintf(stderr, "  ears stuck at %zu of the loop\n", loop.size());
        return;
      }
      const std::size_t i = std::size_t(best), a = (i + m - 1) % m, c = (i + 1) % m;
      tris.push_back({{loop[a], loop[i], loop[c]}});
      edges.insert({loop[a], loop[i]});
      edges.insert({loop[i], loop[c]});
      edges.insert({loop[c], loop[a]});
      loop.erase(loop.begin() + std::ptrdiff_t(i));
      x.erase(x.begin() + std::ptrdiff_t(i));
    }
    if(loop.size() == 3) tris.push_back({{loop[0], loop[1], loop[2]}});
  }

  // Walks from x in face f straight to `target` (f's chart); returns the face reached, the position in its
  // chart and the motion from that chart to f's.
  void walk(int f, Eigen::Vector2d x, Eigen::Vector2d target, int& f_out, Eigen::Vector2d& x_out, Rigid_motion_2& to_start,
            std::size_t& steps) const
  {
    to_start = Rigid_motion_2();
    int entered = -1;
    const std::size_t bound = 4 * m_itri->number_of_faces() + 16;
    for(std::size_t step = 0; step < bound; ++step) {
      const auto& p = m_emb->corner_uv[std::size_t(f)];
      const Eigen::Vector3d b = barycentric(p, target);
      if(b.minCoeff() >= -1e-12) {
        f_out = f;
        x_out = target;
        return;
      }
      const Eigen::Vector3d bx = barycentric(p, x);
      int exit = -1;
      double first = 1e300;
      for(int k = 0; k < 3; ++k) {
        const int j = (k + 2) % 3;  // edge k is opposite corner k + 2
        if(!(b[j] < 0) || 3 * f + k == entered) continue;
        const double s = std::max(0.0, bx[j]) / (std::max(0.0, bx[j]) - b[j]);
        if(s < first) first = s, exit = k;
      }
      if(exit < 0) {  // rounding: the target is outside only across the edge we came in by
        f_out = f;
        x_out = target;
        return;
      }
      x += std::min(1.0, first) * (target - x);
      const int t = m_itri->twin(3 * f + exit);
      const Rigid_motion_2& m = m_emb->transition[std::size_t(t)];  // f's chart -> the next face's
      x = m(x);
      target = m(target);
      to_start = to_start * m.inverse();
      f = t / 3;
      entered = t;
      ++steps;
    }
    throw Convergence_failure("cone domain: a site's move crossed more than " + std::to_string(bound) + " faces", double(bound));
  }

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
    walk(s.face, s.x, s.x + d, f, x, m, steps);
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
    for(std::size_t i = 0; i < sites.size(); ++i) move_site(i, sites[i]);
  }

  // `true` if the interiors of the triangles a and b overlap (separating axis test; touching is not overlapping)
  static bool triangles_overlap(const std::array<Eigen::Vector2d, 3>& a, const std::array<Eigen::Vector2d, 3>& b, double eps)
  {
    for(const auto* t : {&a, &b})
      for(int k = 0; k < 3; ++k) {
        const Eigen::Vector2d e = (*t)[std::size_t((k + 1) % 3)] - (*t)[std::size_t(k)];
        const Eigen::Vector2d n(-e.y(), e.x());
        const double len = n.norm();
        if(!(len > 0)) continue;
        double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
        for(const auto& p : a) a0 = std::min(a0, n.dot(p) / len), a1 = std::max(a1, n.dot(p) / len);
        for(const auto& p : b) b0 = std::min(b0, n.dot(p) / len), b1 = std::max(b1, n.dot(p) / len);
        if(a1 <= b0 + eps || b1 <= a0 + eps) return false;
      }
    return true;
  }

  // The copies of the faces within `width` of chart c (beyond its own): a Dijkstra from the chart across
  // the transitions by the distance of a copy's centroid to the chart's centre, keeping a copy only if it
  // overlaps no copy kept (nor the chart): the band is one sheet of the plane, so every distance in the
  // chart is the length of a path on the surface. Around a cone of angle below 2 pi the fan is copied as
  // often as it takes to go around once; around one above 2 pi, one turn of it is kept.
  void build_band(std::size_t c, double width) const
  {
    const Chart& chart = m_chart[c];
    std::vector<Face_copy>& band = m_band[c];
    band.clear();
    const double cell = std::max(1e-300, 2 * std::sqrt(chart.area / double(std::max<std::size_t>(1, chart.faces.size()))));
    const double eps = m_tolerance;
    std::unordered_map<long long, std::vector<std::size_t>> grid;  // cell -> copies whose box meets it
    std::vector<std::array<Eigen::Vector2d, 3>> placed;
    auto cells_of = [&](const std::array<Eigen::Vector2d, 3>& q, std::vector<long long>& keys) {
      keys.clear();
      const Eigen::Vector2d lo = q[0].cwiseMin(q[1]).cwiseMin(q[2]), hi = q[0].cwiseMax(q[1]).cwiseMax(q[2]);
      const long long x0 = (long long)std::floor(lo.x() / cell), x1 = (long long)std::floor(hi.x() / cell);
      const long long y0 = (long long)std::floor(lo.y() / cell), y1 = (long long)std::floor(hi.y() / cell);
      for(long long x = x0; x <= x1; ++x)
        for(long long y = y0; y <= y1; ++y) keys.push_back(x * 2000003LL + y);
    };
    std::vector<long long> keys;
    auto overlaps = [&](const std::array<Eigen::Vector2d, 3>& q) {
      cells_of(q, keys);
      for(long long k : keys) {
        const auto it = grid.find(k);
        if(it == grid.end()) continue;
        for(std::size_t i : it->second)
          if(triangles_overlap(q, placed[i], eps)) return true;
      }
      return false;
    };
    auto place = [&](const std::array<Eigen::Vector2d, 3>& q) {
      cells_of(q, keys);
      for(long long k : keys) grid[k].push_back(placed.size());
      placed.push_back(q);
    };
    std::vector<Face_copy> copies;
    std::priority_queue<std::pair<double, std::size_t>, std::vector<std::pair<double, std::size_t>>, std::greater<>> queue;
    for(int f : chart.faces) {
      place(m_emb->corner_uv[std::size_t(f)]);
      copies.push_back({f, Rigid_motion_2()});
      queue.push({0.0, copies.size() - 1});
    }
    const std::size_t bound = 64 * chart.faces.size() + 4096;
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
        if((centroid - chart.center).norm() - reach > chart.radius + width) continue;
        if(overlaps(q)) continue;
        place(q);
        band.push_back({g, m});
        copies.push_back({g, m});
        queue.push({(centroid - chart.center).norm(), copies.size() - 1});
        if(band.size() > bound)
          throw Convergence_failure("cone domain: the band of chart " + std::to_string(c) + " holds more than " + std::to_string(bound) +
                                        " face copies",
                                    double(band.size()));
      }
    }
  }

  // Every chart's sites and copies, with a Delaunay triangulation whose circles that matter lie in the band
  // (widened up to 8 times by 1.6).
  std::vector<Chart_points> chart_points() const
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
    std::vector<Chart_points> out(m_chart.size());
    internal::parallel_for(m_chart.size(), m_threads, [&](std::size_t c) {
      const Chart& chart = m_chart[c];
      Chart_points& cp = out[c];
      if(m_band_width[c] == 0) {
        const double sites_here = std::max(1.0, double(ns) * chart.mass / m_total_mass);
        m_band_width[c] = 3 * std::sqrt(chart.area / sites_here);
        build_band(c, m_band_width[c]);
      }
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
        cp.dt.build(cp.points);
        if(complete(chart, cp, m_band_width[c])) break;
        if(std::getenv("CONE_DEBUG")) std::fprintf(stderr, "chart %zu: %zu faces, radius %g, own %zu, points %zu, band %zu copies, width %g\n", c, chart.faces.size(), chart.radius, cp.own, cp.points.size(), m_band[c].size(), m_band_width[c]);
        if(attempt == 8)
          throw Convergence_failure("cone domain: the Voronoi cells of chart " + std::to_string(c) + " are not complete within a band of width " +
                                        std::to_string(m_band_width[c]) + " (too few sites for the surface)",
                                    m_band_width[c]);
        m_band_width[c] *= 1.6;
        build_band(c, m_band_width[c]);
      }
      internal::delaunay_neighbours(cp.dt.dt, cp.dt.handle, cp.start, cp.nbr);
    }, 1);
    return out;
  }

  // every Delaunay circle at an own site or centred over the chart lies within `width` of it
  static bool complete(const Chart& chart, const Chart_points& cp, double width)
  {
    if(cp.points.size() < 3) return false;
    for(auto f = cp.dt.dt.all_faces_begin(); f != cp.dt.dt.all_faces_end(); ++f) {
      bool at_own = false;
      for(int k = 0; k < 3; ++k)
        if(!cp.dt.dt.is_infinite(f->vertex(k)) && std::size_t(f->vertex(k)->info()) < cp.own) at_own = true;
      if(cp.dt.dt.is_infinite(f)) {
        if(at_own && std::getenv("CONE_DEBUG")) {
          for(int k = 0; k < 3; ++k)
            if(!cp.dt.dt.is_infinite(f->vertex(k)) && std::size_t(f->vertex(k)->info()) < cp.own) {
              const Eigen::Vector2d x = cp.points[std::size_t(f->vertex(k)->info())];
              std::fprintf(stderr, "  own site %d on the hull at (%g %g), %g from the centre\n", cp.original[std::size_t(f->vertex(k)->info())], x.x(), x.y(), (x - chart.center).norm());
            }
        }
        if(at_own) return false;
        continue;
      }
      const K::Point_2 c = cp.dt.dt.circumcenter(f);
      const Eigen::Vector2d cc(c.x(), c.y());
      const double d = (cc - chart.center).norm();
      const double r = (cc - cp.points[std::size_t(f->vertex(0)->info())]).norm();
      // the circles of the Voronoi vertices over the chart (and a third of the band beyond, where the cells
      // of copies that reach into the chart have theirs)
      if(!at_own && d > chart.radius + width / 3) continue;
      if(d + r > chart.radius + width) return false;
    }
    return true;
  }

  const Intrinsic_triangulation* m_itri;
  const Cone_embedding* m_emb;
  unsigned m_threads = 1;
  std::vector<Chart> m_chart;
  std::vector<std::size_t> m_slot;
  std::vector<char> m_is_cone;
  double m_total_mass = 0, m_tolerance = 0;
  mutable std::vector<Site_state> m_state;
  mutable std::vector<std::vector<Face_copy>> m_band;
  mutable std::vector<double> m_band_width;
  mutable std::size_t m_walk_steps = 0;
  mutable Dual_repairs m_dual_repairs;
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_CONE_DOMAIN_TRAITS_H
