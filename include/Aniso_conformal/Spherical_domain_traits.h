// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_SPHERICAL_DOMAIN_TRAITS_H
#define ANISO_CONFORMAL_SPHERICAL_DOMAIN_TRAITS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/CVT/sphere_delaunay_flips.h>
#include <Aniso_conformal/internal/CVT/spherical_voronoi.h>
#include <Aniso_conformal/internal/CVT/stratified_samples.h>
#include <Aniso_conformal/spherical_embedding.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

/// \file Spherical_domain_traits.h
/// Uses CGAL's `Delaunay_triangulation_on_sphere_2` and `AABB_tree` (GPL packages).

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the unit sphere of a closed genus-0 surface: the background triangulation embedded by
 * `spherical_embedding()` as chordal (flat) triangles between the unit vectors of its vertices, with the
 * CVT density `rho = cf^2` linear over each chordal triangle.
 *
 * Sites are unit vectors (`Point = Eigen::Vector3d`); none is fixed. The CVT energy is
 * `E = sum_i integral_{V_i} rho(y) |y - x_i|^2 dy` over the chordal polyhedron, `V_i` the part nearer
 * to `x_i` than to any other site. For unit sites the bisector of two sites is a plane through the
 * centre, so `V_i` is exactly the central projection of the spherical Voronoi cell of `x_i` onto the
 * polyhedron, and integrating over the polyhedron is integrating the density `cf^2` of the conformal
 * factor measured against the chordal area (the definition of `cf`): the mass of a cell is its
 * adjusted area. Each chordal triangle is clipped against the cells it meets in an orthonormal frame of
 * its plane (Sutherland-Hodgman against half-planes, `|y - x|^2 = |y - x'|^2 + h^2` with `x'` the
 * site's foot on the plane and `h` its height over it) and the mass, first moment and energy of the
 * linear density over each piece have closed forms. The cells a triangle meets are found from the
 * Delaunay triangulation on the sphere of the sites (CGAL `Delaunay_triangulation_on_sphere_2`, the
 * convex hull of the sites): a greedy walk to the site nearest to a corner, then a flood over the
 * neighbours whose cells can meet the triangle. The work is split into fixed chunks of triangles summed
 * in order, so the result does not depend on the number of threads.
 *
 * The CVT is constrained to the sphere: `Cell::centroid` is the centroid in space (inside the ball);
 * the constrained minimiser of a cell's energy is its direction, where Lloyd's method moves the site
 * (`move_towards()`). The L-BFGS of `weighted_centroidal_Voronoi_tessellation()` uses the optional
 * hooks `project_to_tangent_plane()` (gradients and search directions in the tangent planes) and
 * `project_to_domain()` (trial points normalised back onto the sphere).
 *
 * \cgalModels `ParametricDomainTraits`
 */
class Spherical_domain_traits {
public:
  /// \name Types
  /// @{
  typedef Eigen::Vector3d Point;  ///< a unit vector
  /// integrals of the density over the Voronoi cell of one site on the chordal polyhedron
  struct Cell {
    double mass = 0;                 ///< integral of rho
    Point centroid = Point::Zero();  ///< (integral of rho y) / mass in space (inside the ball), or the site when the mass is 0
    double energy = 0;               ///< integral of rho |y - site|^2
  };
  /// @}

  /// \name Creation
  /// @{

  /*!
   * builds the chordal background of `itri` with the embedding `emb` (the positions are normalised);
   * `threads` workers integrate (0 = hardware). Chordal triangles of zero area carry no mass and are
   * counted by `number_of_degenerate_triangles()`.
   * \throws Invalid_input if `emb` does not have one finite non-zero position and one finite positive
   *         conformal factor per vertex of `itri`, or if every triangle is degenerate
   */
  Spherical_domain_traits(const Intrinsic_triangulation& itri, const Spherical_embedding& emb, unsigned threads = 0)
  {
    const std::size_t nv = itri.number_of_vertices(), nf = itri.number_of_faces();
    if(emb.position.size() != nv || emb.conformal_factor.size() != nv)
      throw Invalid_input("Spherical_domain_traits: the embedding has " + std::to_string(emb.position.size()) + " positions and " +
                          std::to_string(emb.conformal_factor.size()) + " conformal factors for " + std::to_string(nv) +
                          " vertices");
    std::vector<Eigen::Vector3d> unit(nv);
    for(std::size_t v = 0; v < nv; ++v) {
      const double r = emb.position[v].norm(), cf = emb.conformal_factor[v];
      if(!(r > 0) || !std::isfinite(r) || !(cf > 0) || !std::isfinite(cf))
        throw Invalid_input("Spherical_domain_traits: vertex " + std::to_string(v) +
                            " has no direction or no positive conformal factor in the embedding");
      unit[v] = emb.position[v] / r;
    }
    // the vertices in Morton order too: the integration finds the site nearest to each of them in turn
    const std::vector<std::size_t> vertex_order = internal::morton_order_3(unit);
    std::vector<int> rank(nv);
    m_vertices.resize(nv);
    for(std::size_t k = 0; k < nv; ++k) {
      rank[vertex_order[k]] = int(k);
      m_vertices[k] = unit[vertex_order[k]];
    }
    std::vector<Eigen::Vector3d> centroids(nf);
    for(std::size_t f = 0; f < nf; ++f) {
      const auto& c = itri.face_vertices(f);
      centroids[f] = (unit[std::size_t(c[0])] + unit[std::size_t(c[1])] + unit[std::size_t(c[2])]).normalized();
    }
    m_tri.reserve(nf);
    auto locator = std::make_shared<Locator>();
    locator->triangles.reserve(nf);
    for(std::size_t f : internal::morton_order_3(centroids)) {
      const auto& c = itri.face_vertices(f);
      std::array<Eigen::Vector3d, 3> p;
      std::array<double, 3> rho;
      for(int k = 0; k < 3; ++k) {
        p[k] = unit[std::size_t(c[k])];
        rho[k] = emb.conformal_factor[std::size_t(c[k])] * emb.conformal_factor[std::size_t(c[k])];
      }
      if(itri.is_patch_face(f)) rho = {{0.0, 0.0, 0.0}};  // a hole's patch holds no site
      internal::Spherical_background_triangle T;
      if(!internal::make_spherical_background_triangle(p, rho, int(f), T)) {
        ++m_degenerate;
        continue;
      }
      for(int k = 0; k < 3; ++k) T.v[std::size_t(k)] = rank[std::size_t(c[k])];
      m_area += T.flat.area;
      m_total_mass += T.flat.mass;
      locator->triangles.emplace_back(K::Point_3(p[0].x(), p[0].y(), p[0].z()), K::Point_3(p[1].x(), p[1].y(), p[1].z()),
                                      K::Point_3(p[2].x(), p[2].y(), p[2].z()));
      m_tri.push_back(T);
    }
    if(m_tri.empty()) throw Invalid_input("Spherical_domain_traits: every chordal triangle of the embedding is degenerate");
    locator->tree.rebuild(locator->triangles.begin(), locator->triangles.end());
    m_locator = locator;
    m_threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  }
  /// @}

  /// \name Domain
  /// @{

  /// area of the chordal polyhedron (a little less than `4 pi`)
  double area() const { return m_area; }
  /// integral of the density over the chordal polyhedron (the adjusted area of the surface)
  double total_mass() const { return m_total_mass; }
  /// number of chordal triangles of zero area (left out; 0 for a valid embedding)
  std::size_t number_of_degenerate_triangles() const { return m_degenerate; }
  /// `true` if `p` is a unit vector (within `1e-9` in squared norm)
  bool contains(const Point& p) const { return p.allFinite() && std::abs(p.squaredNorm() - 1.0) <= 1e-9; }
  /// the direction of `target` (a cell's centroid in space: the constrained centroid), or `p` if `target` is zero
  Point move_towards(const Point& p, const Point& target) const
  {
    const double r = target.norm();
    return r > 0 && std::isfinite(r) ? Point(target / r) : p;
  }
  /*!
   * the point of the sphere nearest to `p` (`p` normalised), for the CVT's trial steps taken in space;
   * `p` itself (then not in the domain) if it is zero or not finite
   */
  Point project_to_domain(const Point& p) const
  {
    const double r = p.norm();
    return r > 0 && std::isfinite(r) ? Point(p / r) : p;
  }
  /// the component of the vector `v` tangent to the sphere at the unit vector `x` (the CVT's gradients and steps)
  Point project_to_tangent_plane(const Point& x, const Point& v) const { return v - x.dot(v) * x; }
  /// @}

  /// \name Sites
  /// @{

  /*!
   * places `n` sites spread by the sites' density at the CVT's optimum, `rho^(1/2)` (Gersho): stratified
   * along a space-filling curve of the chordal triangles (`internal::stratified_samples()`: evenly spaced
   * quantiles of `internal::optimal_sampling_weight()`, a random point in
   * each chosen triangle), centrally projected onto the sphere; deterministic for a `seed`. None is fixed.
   * \throws Invalid_input if `n < 4` (the smallest triangulation of the sphere is the tetrahedron)
   */
  std::vector<Point> initial_sites(std::size_t n, unsigned seed)
  {
    if(n < 4)
      throw Invalid_input("the sphere needs at least 4 sites (a tetrahedron), " + std::to_string(n) + " were requested");
    std::mt19937_64 rng(seed);
    std::vector<Point> sites = internal::stratified_samples(
        m_tri.size(), [&](std::size_t f) { return internal::optimal_sampling_weight(m_tri[f].flat); },
        [&](std::size_t f) -> const std::array<Eigen::Vector3d, 3>& { return m_tri[f].p; }, n, rng);
    for(Point& x : sites) x = x.normalized();
    return sites;
  }
  /// 0: no site is fixed on a closed surface
  std::size_t number_of_fixed_sites() const { return 0; }
  /*!
   * where site `i` at `site` lies on the background: the chordal triangle hit by the ray from the
   * centre through `site` (an AABB tree query), as the face of the `Intrinsic_triangulation` and the
   * barycentric coordinates of the hit point (with respect to `face_vertices(face)`, clamped to the
   * triangle). Normalised, `sum_k bary[k] position(corner k)` is the direction of `site`.
   * \returns `false` if `site` is zero or not finite (a valid embedding covers every direction)
   */
  bool background_location(std::size_t /*i*/, const Point& site, int& face, Eigen::Vector3d& bary) const
  {
    const double r = site.norm();
    if(!(r > 0) || !std::isfinite(r)) return false;
    const Point x = site / r;
    std::vector<Locator::Tree::Primitive_id> hits;
    m_locator->tree.all_intersected_primitives(K::Ray_3(K::Point_3(0, 0, 0), K::Point_3(x.x(), x.y(), x.z())),
                                               std::back_inserter(hits));
    double best = -std::numeric_limits<double>::infinity();
    auto consider = [&](std::size_t t) {
      const auto& p = m_tri[t].p;
      // the hit point's barycentric coordinates: x.(p_j x p_k) / x.((p_1 - p_0) x (p_2 - p_0))
      const Eigen::Vector3d b(x.dot(p[1].cross(p[2])), x.dot(p[2].cross(p[0])), x.dot(p[0].cross(p[1])));
      const double s = b.sum();
      if(!(s > 0)) return;  // the ray meets the back of the triangle or runs in its plane
      const Eigen::Vector3d c = b / s;
      if(c.minCoeff() > best) {
        best = c.minCoeff();
        face = m_tri[t].flat.face;
        bary = c;
      }
    };
    for(auto id : hits) consider(std::size_t(id - m_locator->triangles.begin()));
    // rounding can leave a direction between the triangles the exact query returned: try them all
    if(best < -1e-9)
      for(std::size_t t = 0; t < m_tri.size(); ++t) consider(t);
    if(best == -std::numeric_limits<double>::infinity()) return false;
    bary = bary.cwiseMax(0.0);
    bary /= bary.sum();
    return true;
  }
  /// @}

  /// \name Integration
  /// @{

  /*!
   * computes mass, centroid (in space) and energy of the Voronoi cell of every site on the chordal
   * polyhedron. The sites are taken as directions (normalised). A site without a direction (zero, not
   * finite) or closer than CGAL's separation bound (`2^-23`) to another one has no cell (mass 0).
   *
   * The Delaunay triangulation of the sites is kept for the next call (shared by copies of the traits,
   * one call at a time: a concurrent call builds its own): when the sites have moved little it is
   * repaired by edge flips (internal/CVT/sphere_delaunay_flips.h) instead of being built again.
   */
  void integrate(const std::vector<Point>& sites, std::vector<Cell>& cells) const
  {
    const std::size_t ns = sites.size();
    cells.assign(ns, Cell());
    for(std::size_t i = 0; i < ns; ++i) cells[i].centroid = sites[i];
    if(ns == 0) return;
    const std::vector<Point> unit = directions(sites);
    std::vector<int> start, nbr;
    int first = 0;
    std::unique_lock<std::mutex> lock(m_delaunay->mutex, std::try_to_lock);
    if(lock.owns_lock() && m_delaunay->flips.update(unit)) {
      m_delaunay->flips.neighbours(start, nbr);
      ++m_delaunay->repairs;
    } else {
      internal::Sphere_delaunay sd;
      internal::build_sphere_delaunay(unit, sd);
      internal::sphere_delaunay_neighbours(sd, start, nbr);
      while(first < int(ns) && !sd.has_vertex(std::size_t(first))) ++first;
      if(first == int(ns)) return;  // no site has a direction
      if(lock.owns_lock()) m_delaunay->flips.take(sd, ns);
    }
    if(lock.owns_lock()) lock.unlock();
    // each site's neighbours in index order: the clipping order, hence the rounding, then depends on the
    // triangulation only, not on how it was reached
    for(std::size_t i = 0; i < ns; ++i) std::sort(nbr.begin() + start[i], nbr.begin() + start[i + 1]);
    std::vector<internal::Spherical_cell_accumulator> acc;
    internal::integrate_spherical_restricted_voronoi(m_tri, m_vertices, unit, start, nbr, first, m_threads, acc);
    for(std::size_t i = 0; i < ns; ++i) {
      cells[i].mass = acc[i].mass;
      cells[i].energy = acc[i].energy;
      if(acc[i].mass > 0) cells[i].centroid = acc[i].moment / acc[i].mass;
    }
  }
  /// @}

  /// \name Dual mesh
  /// @{

  /*!
   * the Delaunay triangulation on the sphere of `sites` (the convex hull of their directions): `2 n - 4`
   * triangles as index triples, counterclockwise seen from outside (like the input), every site a vertex.
   * \throws Convergence_failure if there are fewer than 4 sites, a site has no direction, two sites
   *         coincide (within `1e-9` of the mean spacing, or CGAL's bound `2^-23`), all sites lie on one
   *         great circle or in one open hemisphere (their triangulation does not cover the sphere), a
   *         triangle is not strictly counterclockwise (near-degenerate), or the triangle count is wrong
   */
  std::vector<std::array<std::size_t, 3>> dual_triangles(const std::vector<Point>& sites) const
  {
    const std::size_t ns = sites.size();
    if(ns < 4)
      throw Convergence_failure("dual mesh: " + std::to_string(ns) + " sites are too few for the sphere (at least 4, a tetrahedron)",
                                double(ns));
    const std::vector<Point> unit = directions(sites);
    for(std::size_t i = 0; i < ns; ++i)
      if(!unit[i].allFinite())
        throw Convergence_failure("dual mesh: site " + std::to_string(i) + " is zero or not finite", 0);
    internal::Sphere_delaunay sd;
    internal::build_sphere_delaunay(unit, sd);
    // sites closer than this are one point for the output (their triangles would be degenerate)
    const double tiny = 1e-9 * std::sqrt(4 * 3.14159265358979323846 / double(ns));
    for(std::size_t i = 0; i < ns; ++i) {
      if(sd.handle[i] == internal::Sphere_delaunay_triangulation::Vertex_handle())  // not expected for a unit vector
        throw Convergence_failure("dual mesh: site " + std::to_string(i) + " was refused by the Delaunay triangulation on the sphere", 0);
      if(!sd.has_vertex(i))
        throw Convergence_failure("dual mesh: site " + std::to_string(i) + " coincides with site " +
                                      std::to_string(sd.handle[i]->info()) + " on the sphere",
                                  0);
    }
    if(sd.dt.dimension() < 2)
      throw Convergence_failure("dual mesh: all " + std::to_string(ns) + " sites lie on one great circle of the sphere", 0);
    if(sd.dt.number_of_ghost_faces() > 0)
      throw Convergence_failure("dual mesh: all " + std::to_string(ns) +
                                    " sites lie in one hemisphere, so their Delaunay triangulation does not cover the sphere",
                                0);
    for(std::size_t i = 0; i < ns; ++i) {
      auto c = sd.dt.incident_vertices(sd.handle[i]), done = c;
      do {
        if((unit[std::size_t(c->info())] - unit[i]).norm() < tiny)
          throw Convergence_failure("dual mesh: site " + std::to_string(i) + " coincides with site " + std::to_string(c->info()) +
                                        " on the sphere",
                                    0);
      } while(++c != done);
    }
    std::vector<std::array<std::size_t, 3>> tris;
    tris.reserve(2 * ns);
    for(auto f = sd.dt.all_faces_begin(); f != sd.dt.all_faces_end(); ++f) {
      const std::array<std::size_t, 3> t = {
          {std::size_t(f->vertex(0)->info()), std::size_t(f->vertex(1)->info()), std::size_t(f->vertex(2)->info())}};
      // counterclockwise seen from outside: the centre is on the inner side of the triangle's plane
      if(!(unit[t[0]].dot(unit[t[1]].cross(unit[t[2]])) > 0))
        throw Convergence_failure("dual mesh: the Delaunay triangle (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                                      std::to_string(t[2]) + ") on the sphere is degenerate (its plane passes through the centre)",
                                  0);
      tris.push_back(t);
    }
    if(tris.size() != 2 * ns - 4)
      throw Convergence_failure("dual mesh: the Delaunay triangulation on the sphere has " + std::to_string(tris.size()) +
                                    " triangles instead of " + std::to_string(2 * ns - 4),
                                double(tris.size()));
    return tris;
  }

  /*!
   * the Voronoi cell of every site on the sphere, as a polygon of unit vectors (the circumcentres of
   * the Delaunay triangles around the site, counterclockwise seen from outside), for pictures; empty for
   * a site without a vertex, open where all sites lie in one hemisphere
   */
  std::vector<std::vector<Point>> voronoi_cells(const std::vector<Point>& sites) const
  {
    const std::size_t ns = sites.size();
    std::vector<std::vector<Point>> cells(ns);
    const std::vector<Point> unit = directions(sites);
    internal::Sphere_delaunay sd;
    internal::build_sphere_delaunay(unit, sd);
    if(sd.dt.dimension() < 2) return cells;
    for(std::size_t i = 0; i < ns; ++i) {
      if(!sd.has_vertex(i)) continue;
      auto f = sd.dt.incident_faces(sd.handle[i]), done = f;
      do {
        if(sd.dt.is_ghost(f)) continue;
        const Point a = unit[std::size_t(f->vertex(0)->info())], b = unit[std::size_t(f->vertex(1)->info())],
                    c = unit[std::size_t(f->vertex(2)->info())];
        cells[i].push_back((b - a).cross(c - a).normalized());
      } while(++f != done);
    }
    return cells;
  }
  /// @}

private:
  typedef internal::Sphere_kernel K;
  // the chordal triangles (in the order of m_tri) in an AABB tree, shared by copies of the traits
  struct Locator {
    typedef std::vector<K::Triangle_3>::const_iterator Iterator;
    typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, Iterator>>> Tree;
    std::vector<K::Triangle_3> triangles;
    Tree tree;
  };

  static std::vector<Point> directions(const std::vector<Point>& sites)
  {
    std::vector<Point> unit(sites.size());
    for(std::size_t i = 0; i < sites.size(); ++i) {
      const double r = sites[i].norm();
      unit[i] = r > 0 && std::isfinite(r) ? Point(sites[i] / r) : Point::Constant(std::numeric_limits<double>::quiet_NaN());
    }
    return unit;
  }

  std::vector<internal::Spherical_background_triangle> m_tri;  // in Morton order
  std::vector<Eigen::Vector3d> m_vertices;                       // unit vectors of the background vertices, in Morton order
  std::shared_ptr<const Locator> m_locator;
  // the sites' last Delaunay triangulation, repaired by flips at the next integrate()
  typedef internal::Flip_cache<internal::Sphere_flip_triangulation> Delaunay_cache;
  std::shared_ptr<Delaunay_cache> m_delaunay = std::make_shared<Delaunay_cache>();
  double m_area = 0, m_total_mass = 0;
  std::size_t m_degenerate = 0;
  unsigned m_threads = 1;
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_SPHERICAL_DOMAIN_TRAITS_H
