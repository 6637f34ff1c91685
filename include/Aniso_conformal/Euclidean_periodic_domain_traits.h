// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_EUCLIDEAN_PERIODIC_DOMAIN_TRAITS_H
#define ANISO_CONFORMAL_EUCLIDEAN_PERIODIC_DOMAIN_TRAITS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/flat_torus_embedding.h>
#include <Aniso_conformal/internal/CVT/quotient_triangles.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>
#include <Aniso_conformal/internal/CVT/split_delaunay.h>
#include <Aniso_conformal/internal/CVT/torus_delaunay_flips.h>
#include <Aniso_conformal/internal/domains/indexed_delaunay_2.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

/// \file Euclidean_periodic_domain_traits.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the flat torus `R^2 / L` of a closed genus-1 surface: the background triangulation laid out by
 * `flat_torus_embedding()`, each triangle translated by a lattice vector so that its centroid lies in
 * the fundamental cell `{s a + t b : 0 <= s, t < 1}` of the reduced basis `(a, b)`, with the CVT
 * density `cf^2` linear over each triangle.
 *
 * Sites are points of the plane standing for their classes modulo `L`; none is fixed. To integrate,
 * the sites are wrapped into the fundamental cell and translated copies are added in a band around it,
 * wide enough that every Voronoi cell meeting a background triangle is complete: the band starts at
 * three site spacings beyond the triangles' reach and is widened until every Delaunay circle that
 * matters lies inside it (a test, not a guess). The Delaunay graph of the sites and copies gives the
 * Voronoi diagram of the torus. The first time, it is built as two CGAL `Delaunay_triangulation_2` of
 * the two halves of the band, one per thread, whose fans are certified against the whole band (one
 * triangulation of the whole band where that fails, or with one thread; the same graph, so the integrals
 * do not depend on the number of threads); the triangulation of the torus it contains is kept (shared by
 * copies of the traits, one call at a time) and at the next call repaired by edge flips for the sites'
 * new places (internal/CVT/torus_delaunay_flips.h), the band's graph then read from it: the same graph
 * where it matters, in a fraction of the time (CGAL again when the moved triangles no longer
 * triangulate the torus). Each background triangle is clipped against the cells
 * it meets and the integrals of the copies are folded back onto their sites (first moments shifted by
 * the copy's lattice vector). CGAL's `Periodic_2_Delaunay_triangulation_2` is not used because it
 * handles only rectangular (axis-aligned) domains.
 *
 * \cgalModels `ParametricDomainTraits`
 */
class Euclidean_periodic_domain_traits {
public:
  /// \name Types
  /// @{
  typedef Eigen::Vector2d Point;  ///< a point of the plane, standing for its class modulo the lattice
  /// integrals of the density over the Voronoi cell of one site on the torus
  struct Cell {
    double mass = 0;                 ///< integral of rho
    Point centroid = Point::Zero();  ///< (integral of rho y) / mass, next to the site (same lattice translate), or the site when the mass is 0
    double energy = 0;               ///< integral of rho |y - site|^2
  };
  /// @}

  /// \name Creation
  /// @{

  /// lays out the background of `itri` with the embedding `emb`; `threads` workers integrate (0 = hardware)
  Euclidean_periodic_domain_traits(const Intrinsic_triangulation& itri, const Flat_torus_embedding& emb, unsigned threads = 0)
    : m_lattice(emb.lattice)
  {
    m_basis.col(0) = m_lattice[0];
    m_basis.col(1) = m_lattice[1];
    m_inverse = m_basis.inverse();
    m_area = m_basis.determinant();
    if(!(m_area > 0)) throw Invalid_input("Euclidean_periodic_domain_traits: the lattice basis is degenerate");
    m_height = {{m_area / m_lattice[1].norm(), m_area / m_lattice[0].norm()}};
    const std::size_t nf = itri.number_of_faces();
    std::vector<std::array<Eigen::Vector2d, 3>> corners(nf);
    std::vector<Eigen::Vector2d> centroids(nf);
    for(std::size_t f = 0; f < nf; ++f) {
      const auto& c = emb.corner_uv[f];
      const Eigen::Vector2d g = (c[0] + c[1] + c[2]) / 3.0;
      const Eigen::Vector2d shift = wrap(g) - g;
      for(int k = 0; k < 3; ++k) corners[f][k] = c[k] + shift;
      centroids[f] = g + shift;
    }
    const Eigen::Vector2d ab = m_lattice[0] + m_lattice[1];
    const Eigen::Vector2d lo = m_lattice[0].cwiseMin(m_lattice[1]).cwiseMin(ab).cwiseMin(Eigen::Vector2d::Zero());
    const Eigen::Vector2d hi = m_lattice[0].cwiseMax(m_lattice[1]).cwiseMax(ab).cwiseMax(Eigen::Vector2d::Zero());
    const std::vector<std::size_t> order = internal::morton_order(centroids, lo, hi);  // the fundamental cell's box
    m_tri.reserve(nf);
    m_reach = {{0.0, 0.0}};
    for(std::size_t i = 0; i < nf; ++i) {
      const std::size_t f = order[i];
      const auto& c = itri.face_vertices(f);
      std::array<double, 3> rho;
      for(int k = 0; k < 3; ++k) {
        rho[k] = emb.conformal_factor[std::size_t(c[k])] * emb.conformal_factor[std::size_t(c[k])];
        const Eigen::Vector2d st = m_inverse * corners[f][k];
        for(int d = 0; d < 2; ++d) m_reach[d] = std::max({m_reach[d], -st[d], st[d] - 1.0});
      }
      if(itri.is_patch_face(f)) rho = {{0.0, 0.0, 0.0}};  // a hole's patch holds no site
      m_tri.push_back(internal::make_background_triangle(corners[f], rho, int(f)));
      m_total_mass += m_tri.back().area * (rho[0] + rho[1] + rho[2]) / 3.0;
    }
    m_grid.build(m_tri);
    m_threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
    m_delaunay->flips.set_lattice(m_lattice, m_inverse, m_area);
  }
  /// @}

  /// \name Domain
  /// @{

  /// the reduced lattice basis `(a, b)`
  const std::array<Point, 2>& lattice() const { return m_lattice; }
  /// area of the fundamental cell (the area of the flat metric)
  double area() const { return m_area; }
  /// integral of the density over the torus
  double total_mass() const { return m_total_mass; }
  /// the lattice coordinates `(s, t)` of `p = s a + t b`
  Eigen::Vector2d lattice_coordinates(const Point& p) const { return m_inverse * p; }
  /// the translate of `p` in the fundamental cell `{s a + t b : 0 <= s, t < 1}`
  Point wrap(const Point& p) const
  {
    const Eigen::Vector2d st = m_inverse * p;
    Point w = p - m_basis * Eigen::Vector2d(std::floor(st.x()), std::floor(st.y()));
    // rounding can leave a coordinate at exactly 1
    const Eigen::Vector2d st2 = m_inverse * w;
    if(st2.x() >= 1) w -= m_lattice[0];
    if(st2.y() >= 1) w -= m_lattice[1];
    return w;
  }
  /// `true` if `p` is finite (the torus has no boundary)
  bool contains(const Point& p) const { return p.allFinite(); }
  /// `target` (the torus has no boundary)
  Point move_towards(const Point&, const Point& target) const { return target; }
  /// @}

  /// \name Sites
  /// @{

  /*!
   * places `n` sites spread by the sites' density at the CVT's optimum, `rho^(1/2)` (Gersho; stratified
   * along a space-filling curve of the background triangles, `internal::optimally_stratified_samples()`;
   * deterministic for a `seed`), in the fundamental cell.
   * None is fixed.
   * \throws Invalid_input if `n < 1`
   */
  std::vector<Point> initial_sites(std::size_t n, unsigned seed)
  {
    if(n < 1) throw Invalid_input("the flat torus needs at least one site");
    std::mt19937_64 rng(seed);
    std::vector<Point> sites = internal::optimally_stratified_samples(m_tri, n, rng);
    for(Point& p : sites) p = wrap(p);
    return sites;
  }
  /// 0: no site is fixed on a closed surface
  std::size_t number_of_fixed_sites() const { return 0; }
  /*!
   * where site `i` at `site` lies on the background: the face of the `Intrinsic_triangulation` and
   * the barycentric coordinates in it (the site's class is located, whatever its translate).
   * \returns `false` if it cannot be located (a non-finite site)
   */
  bool background_location(std::size_t /*i*/, const Point& site, int& face, Eigen::Vector3d& bary) const
  {
    if(!site.allFinite()) return false;
    const Point w = wrap(site);
    // a background triangle was wrapped by its centroid, so the point may be covered by a neighbour's translate
    for(double tol : {1e-9, 1e-6})
      for(int i : {0, -1, 1})
        for(int j : {0, -1, 1}) {
          int t = -1;
          if(m_grid.locate(m_tri, w + double(i) * m_lattice[0] + double(j) * m_lattice[1], t, bary, tol)) {
            face = m_tri[std::size_t(t)].face;
            return true;
          }
        }
    return false;
  }
  /// @}

  /// \name Integration
  /// @{

  /// how many calls of `integrate()` (by this object and its copies) repaired the previous Delaunay
  /// triangulation by flips instead of building one (diagnostics; the integrals are the same either way)
  std::size_t delaunay_repairs() const { return m_delaunay->repairs; }

  /// computes mass, centroid and energy of the Voronoi cell of every site on the torus
  void integrate(const std::vector<Point>& sites, std::vector<Cell>& cells) const
  {
    const std::size_t ns = sites.size();
    std::vector<Point> wrapped(ns);
    for(std::size_t i = 0; i < ns; ++i) wrapped[i] = wrap(sites[i]);
    std::vector<Point> points;
    std::vector<int> original;
    internal::Delaunay_fans fans;
    periodic_fans(wrapped, points, original, fans);
    std::vector<internal::Cell_accumulator> acc;
    internal::integrate_restricted_voronoi(m_tri, points, fans.start, fans.nbr, m_threads, acc);
    std::vector<internal::Cell_accumulator> folded(ns);
    for(std::size_t e = 0; e < points.size(); ++e) {
      const internal::Cell_accumulator& a = acc[e];
      if(a.mass == 0) continue;
      internal::Cell_accumulator& f = folded[std::size_t(original[e])];
      const Eigen::Vector2d shift = points[e] - wrapped[std::size_t(original[e])];
      f.mass += a.mass;
      f.mx += a.mx - a.mass * shift.x();
      f.my += a.my - a.mass * shift.y();
      f.energy += a.energy;
    }
    cells.assign(ns, Cell());
    for(std::size_t i = 0; i < ns; ++i) {
      const internal::Cell_accumulator& a = folded[i];
      cells[i].mass = a.mass;
      cells[i].energy = a.energy;
      // the centroid next to the given translate of the site, so that site - centroid is the gradient
      cells[i].centroid = a.mass > 0 ? Point(Point(a.mx / a.mass, a.my / a.mass) + (sites[i] - wrapped[i])) : sites[i];
    }
  }
  /// @}

  /// \name Dual mesh
  /// @{
  /*!
   * the periodic Delaunay triangulation of `sites` on the torus: triangles as index triples,
   * counterclockwise, each once (`2 n` of them).
   * \throws Convergence_failure if two sites coincide (within `1e-9` of the mean spacing) or the sites are
   *         too few for a periodic Delaunay triangulation that is a simplicial complex (a triangle meeting two
   *         translates of one site, or two sites joined by two edges)
   */
  std::vector<std::array<std::size_t, 3>> dual_triangles(const std::vector<Point>& sites) const
  {
    const std::size_t ns = sites.size();
    std::vector<Point> wrapped(ns);
    for(std::size_t i = 0; i < ns; ++i) wrapped[i] = wrap(sites[i]);
    Periodic_delaunay pd;
    build_periodic_delaunay(wrapped, pd);
    // sites closer than this are one point for the output (their triangles would be degenerate)
    const double tiny = 1e-9 * std::sqrt(m_area / double(ns));
    for(std::size_t i = 0; i < ns; ++i) {
      if(!pd.has_vertex(i))
        throw Convergence_failure("dual mesh: site " + std::to_string(i) + " coincides with another site on the torus", 0);
      auto c = pd.dt.incident_vertices(pd.handle[i]), done = c;
      do {
        if(!pd.dt.is_infinite(c) && (pd.points[std::size_t(c->info())] - wrapped[i]).norm() < tiny)
          throw Convergence_failure("dual mesh: site " + std::to_string(i) + " coincides with site " +
                                        std::to_string(pd.original[std::size_t(c->info())]) + " on the torus",
                                    0);
      } while(++c != done);
    }
    std::vector<std::array<int, 3>> faces;
    for(auto f = pd.dt.finite_faces_begin(); f != pd.dt.finite_faces_end(); ++f)
      faces.push_back({{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
    return internal::quotient_triangles(faces, pd.original, ns, 2 * ns,
                                        {"the flat torus", "translates", "the periodic Delaunay triangulation"});
  }

  /// the Voronoi cell of every site on the torus, as a counterclockwise polygon around the wrapped site (for pictures)
  std::vector<std::vector<Point>> voronoi_cells(const std::vector<Point>& sites) const
  {
    const std::size_t ns = sites.size();
    std::vector<Point> wrapped(ns);
    for(std::size_t i = 0; i < ns; ++i) wrapped[i] = wrap(sites[i]);
    Periodic_delaunay pd;
    build_periodic_delaunay(wrapped, pd);
    return internal::voronoi_polygons(pd.dt, pd.handle, ns, [&](DT::Face_handle f) { return pd.dt.circumcenter(f); });
  }
  /// @}

private:
  typedef internal::Indexed_delaunay_2::K K;
  typedef internal::Indexed_delaunay_2::Triangulation DT;

  // the wrapped sites (indices 0 .. n-1) and their translates in a band around the fundamental cell
  struct Periodic_delaunay : internal::Indexed_delaunay_2 {
    std::vector<Point> points;
    std::vector<int> original;
  };

  // the band half-widths (lattice coordinates) of attempt `attempt` for ns sites
  std::array<double, 2> band_widths(std::size_t ns, int attempt) const
  {
    const double widen = 3 * std::pow(1.6, attempt), spacing = std::sqrt(m_area / double(ns));
    return {{m_reach[0] + widen * spacing / m_height[0], m_reach[1] + widen * spacing / m_height[1]}};
  }

  // the wrapped sites (indices 0 .. n-1, in `points`) and their translates in the band of half-widths
  // `m` around the fundamental cell, with the site each stands for
  void band_points(const std::vector<Point>& wrapped, const std::array<double, 2>& m, std::vector<Point>& points,
                   std::vector<int>& original, std::vector<internal::Torus_flip_triangulation::Offset>* offsets = nullptr) const
  {
    const std::size_t ns = wrapped.size();
    points.assign(wrapped.begin(), wrapped.end());
    original.resize(ns);
    for(std::size_t i = 0; i < ns; ++i) original[i] = int(i);
    if(offsets) offsets->assign(ns, {{0, 0}});
    std::vector<Eigen::Vector2d> st(ns);
    for(std::size_t i = 0; i < ns; ++i) st[i] = m_inverse * wrapped[i];
    const int ks = int(std::ceil(m[0])), kt = int(std::ceil(m[1]));
    for(int i = -ks; i <= ks + 1; ++i)
      for(int j = -kt; j <= kt + 1; ++j) {
        if(i == 0 && j == 0) continue;
        for(std::size_t s = 0; s < ns; ++s) {
          const double a = st[s].x() + i, b = st[s].y() + j;
          if(a < -m[0] || a > 1 + m[0] || b < -m[1] || b > 1 + m[1]) continue;
          points.push_back(wrapped[s] + double(i) * m_lattice[0] + double(j) * m_lattice[1]);
          original.push_back(int(s));
          if(offsets) offsets->push_back({{i, j}});
        }
      }
  }

  // A Delaunay triangle of the band matters if it has a vertex at an original site or its circumcentre
  // lies where the background triangles reach; each such circle must lie in the band (half-widths m):
  // then no translate left out can be inside it, so those triangles and the Voronoi vertices there are
  // those of the torus.
  bool matters(const std::array<int, 3>& sorted_vertices, std::size_t ns, const Eigen::Vector2d& centre) const
  {
    if(sorted_vertices[0] < int(ns)) return true;
    const Eigen::Vector2d cst = m_inverse * centre;
    return cst.x() >= -m_reach[0] && cst.x() <= 1 + m_reach[0] && cst.y() >= -m_reach[1] && cst.y() <= 1 + m_reach[1];
  }
  bool circle_in_band(const Eigen::Vector2d& centre, double r, const std::array<double, 2>& m) const
  {
    const Eigen::Vector2d cst = m_inverse * centre;
    const double rs = r / m_height[0], rt = r / m_height[1];
    return cst.x() - rs >= -m[0] && cst.x() + rs <= 1 + m[0] && cst.y() - rt >= -m[1] && cst.y() + rt <= 1 + m[1];
  }

  [[noreturn]] static void band_too_narrow(std::size_t ns)
  {
    throw Convergence_failure("flat torus: " + std::to_string(ns) +
                                  " sites leave Voronoi cells too large for the periodic Delaunay triangulation",
                              double(ns));
  }

  // The Delaunay graph of the wrapped sites and their translates in a band wide enough (see the class
  // comment), for the integration: built as two halves on two threads (internal::split_delaunay_fans()),
  // or as one triangulation where a half's margin is too narrow; the same graph either way.
  void periodic_fans(const std::vector<Point>& wrapped, std::vector<Point>& points, std::vector<int>& original,
                     internal::Delaunay_fans& fans) const
  {
    const std::size_t ns = wrapped.size();
    if(ns == 0) throw Invalid_input("Euclidean_periodic_domain_traits: no site");
    std::unique_lock<std::mutex> lock(m_delaunay->mutex, std::try_to_lock);
    if(lock.owns_lock() && m_delaunay->flips.update(wrapped) && fans_from_flips(m_delaunay->flips, wrapped, points, original, fans)) {
      ++m_delaunay->repairs;
      return;
    }
    cgal_fans(wrapped, points, original, fans);
    if(lock.owns_lock()) m_delaunay->flips.take(points, original, fans.faces, ns);
  }

  // periodic_fans() by CGAL's triangulations of the band
  void cgal_fans(const std::vector<Point>& wrapped, std::vector<Point>& points, std::vector<int>& original,
                 internal::Delaunay_fans& fans) const
  {
    const std::size_t ns = wrapped.size();
    const double spacing = std::sqrt(m_area / double(ns));
    for(int attempt = 0; attempt < 8; ++attempt) {
      const std::array<double, 2> m = band_widths(ns, attempt);
      band_points(wrapped, m, points, original);
      const auto face_matters = [&](const std::array<int, 3>& v, const Eigen::Vector2d& c) { return matters(v, ns, c); };
      if(m_threads < 2 || !internal::split_delaunay_fans(points, m_split_margin * spacing, m_threads, face_matters, fans)) {
        if(m_threads >= 2 && ++m_split_failures >= 3) {  // the margin is too narrow for these sites: widen it
          m_split_margin = std::min(32.0, 2 * m_split_margin);
          m_split_failures = 0;
        }
        internal::whole_delaunay_fans(points, face_matters, fans);
      } else {
        m_split_failures = 0;
      }
      bool complete = true;
      for(std::size_t k = 0; k < fans.faces.size() && complete; ++k) complete = circle_in_band(fans.centre[k], fans.radius[k], m);
      if(complete) return;
    }
    band_too_narrow(ns);
  }

  // periodic_fans() from the triangulation of the torus `tf` (repaired for the sites `wrapped`): the band's
  // points as cgal_fans() makes them, each with the translates of its site's neighbours in `tf` (a
  // neighbour's translate outside the band is added as a point without neighbours of its own); false if
  // no band up to cgal_fans()'s widest holds every Delaunay circle that matters
  bool fans_from_flips(const internal::Torus_flip_triangulation& tf, const std::vector<Point>& wrapped, std::vector<Point>& points,
                       std::vector<int>& original, internal::Delaunay_fans& fans) const
  {
    typedef internal::Torus_flip_triangulation::Offset Offset;
    const std::size_t ns = wrapped.size();
    std::vector<int> nstart;
    std::vector<std::pair<int, Offset>> nn;
    std::vector<Offset> offsets;
    for(int attempt = 0; attempt < 8; ++attempt) {
      const std::array<double, 2> m = band_widths(ns, attempt);
      if(!band_holds_circles(tf, m)) continue;
      band_points(wrapped, m, points, original, &offsets);
      tf.neighbours(nstart, nn);
      const std::size_t nb = points.size();
      std::vector<int> cstart(ns + 1, 0), copies(nb);  // the band's points of each site
      for(std::size_t e = 0; e < nb; ++e) ++cstart[std::size_t(original[e]) + 1];
      for(std::size_t i = 0; i < ns; ++i) cstart[i + 1] += cstart[i];
      std::vector<int> next(cstart.begin(), cstart.end() - 1);
      for(std::size_t e = 0; e < nb; ++e) copies[std::size_t(next[std::size_t(original[e])]++)] = int(e);
      std::unordered_map<std::uint64_t, int> extra;  // translates outside the band: (site, offset) -> point
      fans = internal::Delaunay_fans();
      fans.start.assign(nb + 1, 0);
      for(std::size_t e = 0; e < nb; ++e) {
        const int s = original[e];
        fans.start[e + 1] = fans.start[e] + (nstart[std::size_t(s) + 1] - nstart[std::size_t(s)]);
      }
      fans.nbr.resize(std::size_t(fans.start[nb]));
      for(std::size_t e = 0; e < nb; ++e) {
        const int s = original[e];
        int* out = fans.nbr.data() + fans.start[e];
        for(int j = nstart[std::size_t(s)]; j < nstart[std::size_t(s) + 1]; ++j) {
          const int n = nn[std::size_t(j)].first;
          const Offset o{{offsets[e][0] + nn[std::size_t(j)].second[0], offsets[e][1] + nn[std::size_t(j)].second[1]}};
          int found = -1;
          for(int c = cstart[std::size_t(n)]; c < cstart[std::size_t(n) + 1] && found < 0; ++c) {
            const Offset& oc = offsets[std::size_t(copies[std::size_t(c)])];
            if(oc[0] == o[0] && oc[1] == o[1]) found = copies[std::size_t(c)];
          }
          if(found < 0) {
            const std::uint64_t key = (std::uint64_t(std::uint32_t(n)) << 32) | (std::uint64_t(std::uint16_t(o[0])) << 16) |
                                      std::uint64_t(std::uint16_t(o[1]));
            const auto it = extra.emplace(key, int(points.size()));
            if(it.second) {
              points.push_back(wrapped[std::size_t(n)] + double(o[0]) * m_lattice[0] + double(o[1]) * m_lattice[1]);
              original.push_back(n);
            }
            found = it.first->second;
          }
          *out++ = found;
        }
        std::sort(fans.nbr.begin() + fans.start[e], fans.nbr.begin() + fans.start[e + 1]);
      }
      fans.start.resize(points.size() + 1, fans.start[nb]);  // the added translates: no neighbours
      return true;
    }
    return false;
  }

  // whether the band of half-widths m holds every Delaunay circle that matters (matters()): the translates
  // of each triangle of `tf` that have a corner at a wrapped site or their circumcentre where the
  // background triangles reach
  bool band_holds_circles(const internal::Torus_flip_triangulation& tf, const std::array<double, 2>& m) const
  {
    for(std::size_t t = 0; t < tf.number_of_triangles(); ++t) {
      const auto& T = tf.triangle(t);
      const Eigen::Vector2d p = tf.position(T.v[0], T.o[0]);
      const Eigen::Vector2d c = internal::split_delaunay_detail::circumcentre(p, tf.position(T.v[1], T.o[1]), tf.position(T.v[2], T.o[2]));
      const double radius = (c - p).norm() * (1 + 1e-12);
      for(int k = 0; k < 3; ++k)
        if(!circle_in_band(c - double(T.o[std::size_t(k)][0]) * m_lattice[0] - double(T.o[std::size_t(k)][1]) * m_lattice[1], radius, m))
          return false;
      const Eigen::Vector2d cs = m_inverse * c;
      for(double i = std::ceil(-m_reach[0] - cs.x()); i <= std::floor(1 + m_reach[0] - cs.x()); ++i)
        for(double j = std::ceil(-m_reach[1] - cs.y()); j <= std::floor(1 + m_reach[1] - cs.y()); ++j)
          if(!circle_in_band(c + i * m_lattice[0] + j * m_lattice[1], radius, m)) return false;
    }
    return true;
  }

  // the same band in one CGAL triangulation, for the dual mesh and the pictures
  void build_periodic_delaunay(const std::vector<Point>& wrapped, Periodic_delaunay& pd) const
  {
    const std::size_t ns = wrapped.size();
    if(ns == 0) throw Invalid_input("Euclidean_periodic_domain_traits: no site");
    for(int attempt = 0; attempt < 8; ++attempt) {
      const std::array<double, 2> m = band_widths(ns, attempt);
      band_points(wrapped, m, pd.points, pd.original);
      pd.build(pd.points);
      bool complete = true;
      for(auto f = pd.dt.finite_faces_begin(); f != pd.dt.finite_faces_end() && complete; ++f) {
        std::array<int, 3> v{{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}};
        std::sort(v.begin(), v.end());
        const Eigen::Vector2d c = internal::split_delaunay_detail::circumcentre(pd.points, v);
        if(matters(v, ns, c)) complete = circle_in_band(c, (c - pd.points[std::size_t(v[0])]).norm(), m);
      }
      if(complete) return;
    }
    band_too_narrow(ns);
  }

  std::array<Point, 2> m_lattice;
  Eigen::Matrix2d m_basis, m_inverse;
  double m_area = 0, m_total_mass = 0;
  std::array<double, 2> m_height{};  // distance between consecutive lattice lines parallel to b (resp. a)
  std::array<double, 2> m_reach{};   // how far (lattice coordinates) the wrapped triangles reach outside the cell
  std::vector<internal::Background_triangle> m_tri;
  internal::Triangle_grid m_grid;
  unsigned m_threads = 1;
  // how far (site spacings) each half of the split Delaunay triangulation reaches beyond the other's
  // side; doubled when too narrow (it changes the time, never the result)
  mutable double m_split_margin = 4;
  mutable int m_split_failures = 0;  // consecutive
  // the sites' last Delaunay triangulation of the torus, repaired by flips at the next integrate()
  typedef internal::Flip_cache<internal::Torus_flip_triangulation> Delaunay_cache;
  std::shared_ptr<Delaunay_cache> m_delaunay = std::make_shared<Delaunay_cache>();
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_EUCLIDEAN_PERIODIC_DOMAIN_TRAITS_H
