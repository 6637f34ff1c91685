// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_HYPERBOLIC_KLEIN_DOMAIN_TRAITS_H
#define ANISO_CONFORMAL_HYPERBOLIC_KLEIN_DOMAIN_TRAITS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/hyperbolic_embedding.h>
#include <Aniso_conformal/internal/CVT/hyperbolic_voronoi.h>
#include <Aniso_conformal/internal/CVT/quotient_triangles.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>
#include <Aniso_conformal/internal/CVT/stratified_samples.h>
#include <Aniso_conformal/internal/conformal/hyperbolic_geometry.h>
#include <Aniso_conformal/internal/domains/hyperbolic_band.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

/// \file Hyperbolic_klein_domain_traits.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * the hyperbolic surface `H^2 / G` of a closed surface of genus `g >= 2`: the fundamental domain laid
 * out by `hyperbolic_embedding()` and its Fuchsian group `G`, with the CVT density `cf^2` linear (in
 * Klein coordinates) over each background triangle.
 *
 * Sites are points of the hyperboloid `-x0^2 + x1^2 + x2^2 = -1` standing for their orbits under `G`.
 * The hyperbolic Voronoi diagram is a power diagram in the Klein disk (Nielsen and Nock): the site `x`
 * becomes the weighted point `((x1, x2) / 2, (x1^2 + x2^2) / 4 - x0)`, whose power at the Klein point
 * `k` orders the sites as their hyperbolic distance to `k` does; a CGAL `Regular_triangulation_2` of the
 * sites and their images gives it. Only images near the fundamental domain are added: the tiles across
 * the cut are explored face by face (a Dijkstra over face copies, each reached through its side
 * pairings), so their number grows with the width of the band, not exponentially with word length; the
 * band starts at three site spacings and is widened until every Delaunay circle that matters lies in it.
 *
 * Integration: each background triangle (a straight triangle in the Klein disk, where geodesics are
 * chords) is clipped against the power cells it meets; mass, hyperboloid first moment, energy
 * `int rho d(y, x)^2` and its gradient are integrated with the hyperbolic area element
 * `(1 - |k|^2)^(-3/2)` by a 6-point rule of degree 4 on a fan of the clipped polygon, moved first by
 * the isometry that takes the triangle to the centre of the disk, where the element is flat (it is not
 * polynomial, and steep far out). The centroid is the hyperboloid mass centre: the first moment normalised onto the
 * hyperboloid. Images' integrals are pulled back to their sites through the group element.
 *
 * For the optimiser the domain is the hyperboloid in `R^3` (optional hooks `project_to_domain`,
 * `project_to_tangent_plane`), and each cell carries the exact gradient of the energy in these
 * coordinates (`Cell::gradient`), so that L-BFGS sees a consistent energy and gradient.
 *
 * \cgalModels `ParametricDomainTraits`
 */
class Hyperbolic_klein_domain_traits {
public:
  /// \name Types
  /// @{
  typedef Eigen::Vector3d Point;  ///< a point of the hyperboloid, standing for its orbit under the group
  /// integrals of the density over the Voronoi cell of one site on the surface
  struct Cell {
    double mass = 0;                 ///< integral of rho (hyperbolic area element)
    Point centroid = Point::UnitX(); ///< hyperboloid mass centre, next to the site (same tile), or the site when the mass is 0
    double energy = 0;               ///< integral of rho d(y, site)^2
    Point gradient = Point::Zero();  ///< derivative of `energy` with respect to the site's coordinates in `R^3`
  };
  /// @}

  /// \name Creation
  /// @{

  /// lays out the background of `itri` with the embedding `emb`; `threads` workers integrate (0 = hardware)
  Hyperbolic_klein_domain_traits(const Intrinsic_triangulation& itri, const Hyperbolic_embedding& emb, unsigned threads = 0)
    : m_genus(emb.genus), m_area(emb.area)
  {
    const std::size_t nf = itri.number_of_faces();
    std::vector<Eigen::Vector2d> centroids(nf);
    for(std::size_t f = 0; f < nf; ++f) {
      const auto& c = emb.corner_klein[f];
      centroids[f] = (c[0] + c[1] + c[2]) / 3.0;
    }
    const std::vector<std::size_t> order = internal::morton_order(centroids, Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
    // the density's floor: cf^2 spreads the sites evenly over the surface, so that a cell's hyperbolic
    // area goes as 1 / cf; where a part small on the surface is large in the hyperbolic plane (a thin
    // handle or a small hole takes a hyperbolic area of 4 pi whatever its size) that starves it of sites,
    // its Voronoi cells reach across it, and the band of images that the cells need grows exponentially
    // with their radius. The factor is kept at least 1/16 of its mean over the hyperbolic area, so that
    // no cell is larger than about 16 times the mean (at most 1/16 of the sites go to such parts)
    double cf_area = 0, hyperbolic_area = 0;
    for(std::size_t f = 0; f < nf; ++f) {
      const auto& X = emb.corner_hyperboloid[f];
      bool deg;
      const std::array<double, 3> a = internal::hyperbolic_corner_angles(
          {{internal::hyperbolic_distance(X[0], X[1]), internal::hyperbolic_distance(X[1], X[2]), internal::hyperbolic_distance(X[2], X[0])}}, deg);
      const double area = std::max(0.0, 3.14159265358979323846 - a[0] - a[1] - a[2]);
      const auto& c = itri.face_vertices(f);
      cf_area += area * (emb.conformal_factor[std::size_t(c[0])] + emb.conformal_factor[std::size_t(c[1])] + emb.conformal_factor[std::size_t(c[2])]) / 3;
      hyperbolic_area += area;
    }
    const double cf_floor = hyperbolic_area > 0 ? cf_area / hyperbolic_area / 16 : 0;
    m_tri.reserve(nf);
    m_rho.resize(nf);
    m_frame.reserve(nf);
    m_slot.assign(nf, 0);
    for(std::size_t i = 0; i < nf; ++i) {
      const std::size_t f = order[i];
      const auto& c = itri.face_vertices(f);
      std::array<double, 3> rho, sample;
      for(int k = 0; k < 3; ++k) {
        const double cf = std::max(emb.conformal_factor[std::size_t(c[k])], cf_floor);
        rho[k] = cf * cf;
        // the samples' weight is the sites' density at the CVT's optimum, rho^(1/2) = cf per hyperbolic
        // area (a cell's area goes as rho^(-1/2) in two dimensions, Gersho), times the area element: by
        // rho itself the first sites would crowd where cf is large and leave the parts that are large
        // in the hyperbolic plane with cells whose band of images no memory holds
        sample[k] = cf * std::pow(std::max(1e-300, 1 - emb.corner_klein[f][k].squaredNorm()), -1.5);
      }
      if(itri.is_patch_face(f)) rho = sample = {{0.0, 0.0, 0.0}};  // a hole's patch holds no site
      m_tri.push_back(internal::make_background_triangle(emb.corner_klein[f], sample, int(f)));
      m_rho[i] = internal::make_background_triangle(emb.corner_klein[f], rho, int(f));
      const auto& X = emb.corner_hyperboloid[f];
      const Point g = internal::normalize_on_hyperboloid(X[0] + X[1] + X[2]);
      // the frame's direction from an edge; from none (the pure boost) when the metric shrinks that edge
      // below where two points determine a direction (CGAL's femur: 4e-14), where hyperbolic_frame()
      // returns no Lorentz matrix
      m_frame.push_back(internal::hyperbolic_distance(X[0], X[1]) >= 1e-6
                            ? internal::hyperbolic_frame(g, internal::normalize_on_hyperboloid(g + X[0] - X[1]))
                            : internal::hyperbolic_boost(g));
      m_slot[f] = i;
      for(int k = 0; k < 3; ++k)
        m_face_size = std::max(m_face_size, internal::hyperbolic_distance(emb.corner_hyperboloid[f][k], emb.corner_hyperboloid[f][(k + 1) % 3]));
    }
    m_grid.build(m_tri);
    m_threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
    std::vector<int> face_of_slot(nf);
    for(std::size_t i = 0; i < nf; ++i) face_of_slot[i] = m_tri[i].face;
    m_band = internal::Hyperbolic_band(itri, std::move(face_of_slot), m_slot, emb.side_pairing, emb.corner_hyperboloid);
    m_cosh_tile_reach = std::cosh(m_band.reach_of_domain());
    m_total_mass = 0;
    m_whole.resize(nf);
    for(std::size_t i = 0; i < nf; ++i) {
      m_whole[i] = internal::hyperbolic_triangle_nodes(m_rho[i], m_frame[i]);
      for(const auto& q : m_whole[i]) m_total_mass += q.w;
    }
  }
  /// @}

  /// \name Domain
  /// @{
  int genus() const { return m_genus; }                ///< genus of the surface
  double area() const { return m_area; }               ///< hyperbolic area, `4 pi (g - 1)`
  double total_mass() const { return m_total_mass; }   ///< integral of the density over the surface
  /// `true` if `p` is a finite point of the upper sheet of the hyperboloid (within rounding)
  bool contains(const Point& p) const
  {
    return p.allFinite() && p.x() > 0 && std::abs(internal::minkowski_dot(p, p) + 1) <= 1e-6 * p.x() * p.x();
  }
  /// `target` (the surface has no boundary)
  Point move_towards(const Point&, const Point& target) const { return target; }
  /// the point of the hyperboloid on the ray through `p` (a retraction for the optimiser)
  Point project_to_domain(const Point& p) const
  {
    if(!(p.allFinite() && p.x() > 0 && internal::minkowski_dot(p, p) < 0)) return Point::Constant(std::numeric_limits<double>::quiet_NaN());
    return internal::normalize_on_hyperboloid(p);
  }
  /// the component of `v` tangent to the hyperboloid at `x` (Euclidean projection in `R^3`)
  Point project_to_tangent_plane(const Point& x, const Point& v) const
  {
    const Point n(-x.x(), x.y(), x.z());
    return v - (v.dot(n) / n.squaredNorm()) * n;
  }
  /*!
   * the image of `p` in the fundamental domain, and the group element `T` with `T p` that image;
   * \returns `false` if `p` is not in the fundamental domain nor in a tile the band has reached
   */
  bool wrap(const Point& p, Point& image, Eigen::Matrix3d& T) const
  {
    int face;
    Eigen::Vector3d bary = Eigen::Vector3d::Zero();
    const std::size_t reached = m_band.elements().size();
    for(std::size_t gi = 0; gi < reached; ++gi) {
      // tiles in order of their distance: the fundamental domain first; a tile g D whose reference image
      // lies farther from p than D's reach cannot hold p, nor lead the grid to locate it (a dot product
      // instead of a location: couplingdown's sites that drifted across the cut tried up to thousands of
      // tiles, 12 % of the run in Triangle_grid::locate())
      if(gi > 0 && !(-internal::minkowski_dot(m_band.reference_images()[gi], p) <= m_cosh_tile_reach)) continue;
      const Eigen::Matrix3d Ti = gi == 0 ? Eigen::Matrix3d::Identity() : m_band.inverse_elements()[gi];
      const Point q = internal::normalize_on_hyperboloid(Ti * p);
      if(locate_klein(internal::to_klein(q), face, bary)) {
        image = q;
        T = Ti;
        return true;
      }
    }
    // then the tiles next to those, across one side of theirs (g P, P a side pairing), the new element
    // added: the optimiser's sites are not wrapped between iterations, so a site that the band's tile g
    // held drifts in g's frame and can cross g's far side. On CGAL's couplingdown (genus 9, a fundamental
    // domain reaching 6 from the centre) a site in such a tile moved by 0.1 into one two steps from the
    // fundamental domain; the band was doubled to find it, its copies grew to the cap (11-18 s) and the
    // run failed
    for(std::size_t gi = 0; gi < reached; ++gi)
      for(const Eigen::Matrix3d& P : m_band.side_pairings()) {
        const Eigen::Matrix3d G = m_band.elements()[gi] * P;
        const Point q = internal::normalize_on_hyperboloid(internal::lorentz_inverse(G) * p);
        if(!locate_klein(internal::to_klein(q), face, bary)) continue;
        T = m_band.inverse_elements()[std::size_t(m_band.element_index(G))];
        image = internal::normalize_on_hyperboloid(T * p);
        return true;
      }
    return false;
  }
  /// @}

  /// \name Sites
  /// @{

  /*!
   * places `n` sites spread over the density (stratified along a space-filling curve of the background
   * triangles, `internal::stratified_samples()`, weighted by the hyperbolic area element; deterministic
   * for a `seed`), in the fundamental domain. None is fixed.
   * \throws Invalid_input if `n < 1`
   */
  std::vector<Point> initial_sites(std::size_t n, unsigned seed)
  {
    if(n < 1) throw Invalid_input("the hyperbolic domain needs at least one site");
    std::mt19937_64 rng(seed);
    // m_tri's density is already the sites' optimal density (times the Klein area element): drawn by mass
    const std::vector<Eigen::Vector2d> k = internal::stratified_samples(
        m_tri.size(), [&](std::size_t f) { return m_tri[f].mass; },
        [&](std::size_t f) -> const std::array<Eigen::Vector2d, 3>& { return m_tri[f].p; }, n, rng);
    std::vector<Point> sites;
    sites.reserve(n);
    for(const Eigen::Vector2d& q : k) sites.push_back(internal::from_klein(q));
    return sites;
  }
  /// 0: no site is fixed on a closed surface
  std::size_t number_of_fixed_sites() const { return 0; }
  /*!
   * where `site` lies on the background: the face of the `Intrinsic_triangulation` and the barycentric
   * coordinates in it (of its image in the fundamental domain, in Klein coordinates).
   * \returns `false` if it cannot be located
   */
  bool background_location(std::size_t /*i*/, const Point& site, int& face, Eigen::Vector3d& bary) const
  {
    if(!contains(site)) return false;
    Point w;
    Eigen::Matrix3d T;
    if(!wrap(site, w, T)) return false;
    int t = -1;
    if(!locate_klein(internal::to_klein(w), t, bary)) return false;
    face = m_tri[std::size_t(t)].face;
    return true;
  }
  /// @}

  /// \name Integration
  /// @{

  /// computes mass, centroid, energy and energy gradient of the Voronoi cell of every site on the surface
  void integrate(const std::vector<Point>& sites, std::vector<Cell>& cells) const
  {
    const std::size_t ns = sites.size();
    Wrapped w;
    internal::Hyperbolic_power_diagram pr;
    power_diagram(sites, w, pr);
    std::vector<int> start, nbr;
    internal::delaunay_neighbours(pr.rt, pr.handle, start, nbr);
    std::vector<internal::Hyperbolic_cell_accumulator> acc;
    internal::integrate_hyperbolic_restricted_voronoi(m_rho, m_frame, m_whole, pr.points, start, nbr, m_threads, acc);
    std::vector<internal::Hyperbolic_cell_accumulator> folded(ns);
    for(std::size_t e = 0; e < pr.points.size(); ++e) {
      const internal::Hyperbolic_cell_accumulator& a = acc[e];
      if(a.mass == 0) continue;
      internal::Hyperbolic_cell_accumulator& f = folded[std::size_t(pr.original[e])];
      const Eigen::Matrix3d& G = m_band.elements()[std::size_t(pr.element[e])];  // image = G * site
      f.mass += a.mass;
      f.moment += internal::lorentz_inverse(G) * a.moment;  // first moments pulled back
      f.energy += a.energy;
      f.gradient += G.transpose() * a.gradient;             // chain rule through image = G site
    }
    cells.assign(ns, Cell());
    for(std::size_t i = 0; i < ns; ++i) {
      const internal::Hyperbolic_cell_accumulator& a = folded[i];
      cells[i].mass = a.mass;
      cells[i].energy = a.energy;
      // back to the given copy of the site: it is T^-1 of its image in the fundamental domain
      const Eigen::Matrix3d Tinv = internal::lorentz_inverse(w.T[i]);
      cells[i].centroid = a.mass > 0 ? Point(internal::normalize_on_hyperboloid(Tinv * a.moment)) : sites[i];
      cells[i].gradient = w.T[i].transpose() * a.gradient;
    }
  }
  /// @}

  /// \name Dual mesh
  /// @{
  /*!
   * the Delaunay triangulation of `sites` on the surface: triangles as index triples, counterclockwise,
   * each once (`2 n + 4 (g - 1)` of them).
   * \throws Convergence_failure if two sites coincide or the sites are too few for a Delaunay
   *         triangulation of the surface that is a simplicial complex
   */
  std::vector<std::array<std::size_t, 3>> dual_triangles(const std::vector<Point>& sites) const
  {
    const std::size_t ns = sites.size();
    Wrapped w;
    internal::Hyperbolic_power_diagram pr;
    power_diagram(sites, w, pr);
    for(std::size_t i = 0; i < ns; ++i)
      if(!pr.has_vertex(i)) {
        // how near the nearest other site lies (in the fundamental domain; an image may be nearer): sites
        // closer than double precision resolves where the metric shrinks the surface (CGAL's femur: an
        // end shrunk to hyperbolic lengths of 1e-14, 13 minutes of CVT before this message)
        double nearest = std::numeric_limits<double>::infinity();
        for(std::size_t j = 0; j < ns; ++j)
          if(j != i) nearest = std::min(nearest, internal::hyperbolic_distance(sites[i], sites[j]));
        char text[200];
        std::snprintf(text, sizeof(text), " (the nearest other site in the fundamental domain lies %.3g away in the hyperbolic plane)", nearest);
        throw Convergence_failure("dual mesh: site " + std::to_string(i) + " coincides with another site on the surface" + text +
                                      (nearest < 1e-9 ? std::string("; the conformal metric shrinks part of the surface below what double "
                                                                    "precision resolves in the hyperbolic disk")
                                                      : std::string()),
                                  nearest);
      }
    std::vector<std::array<int, 3>> faces;
    for(auto f = pr.rt.finite_faces_begin(); f != pr.rt.finite_faces_end(); ++f)
      faces.push_back({{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
    return internal::quotient_triangles(faces, pr.original, ns, 2 * ns + 4 * std::size_t(m_genus - 1),
                                        {"the hyperbolic surface", "images", "the Delaunay triangulation of the hyperbolic surface"});
  }

  /// the Voronoi cell of every site (its image in the fundamental domain) as a counterclockwise polygon in the Klein disk (for pictures)
  std::vector<std::vector<Eigen::Vector2d>> voronoi_cells(const std::vector<Point>& sites) const
  {
    Wrapped w;
    internal::Hyperbolic_power_diagram pr;
    power_diagram(sites, w, pr);
    return internal::voronoi_polygons(pr.rt, pr.handle, sites.size(),
                                      [&](internal::Klein_regular_triangulation::Face_handle f) { return pr.rt.weighted_circumcenter(f); });
  }
  /// the sites' images in the fundamental domain, in the Klein disk (for pictures)
  std::vector<Eigen::Vector2d> klein_sites(const std::vector<Point>& sites) const
  {
    Wrapped w;
    wrap_all(sites, w);
    std::vector<Eigen::Vector2d> k;
    for(const Point& p : w.points) k.push_back(internal::to_klein(p));
    return k;
  }
  /// the background triangles in the Klein disk (for pictures)
  std::vector<std::array<Eigen::Vector2d, 3>> klein_triangles() const
  {
    std::vector<std::array<Eigen::Vector2d, 3>> t;
    for(const auto& T : m_tri) t.push_back(T.p);
    return t;
  }
  /// the edges of the fundamental domain glued by a non-trivial deck transformation, as Klein segments (for pictures)
  std::vector<std::array<Eigen::Vector2d, 2>> fundamental_domain_boundary() const
  {
    std::vector<std::array<Eigen::Vector2d, 2>> cut;
    const auto& pairing = m_band.pairing();
    for(std::size_t h = 0; h < pairing.size(); ++h) {
      if(pairing[h] == Eigen::Matrix3d::Identity()) continue;
      const auto& c = m_band.corners()[h / 3];
      cut.push_back({{internal::to_klein(c[h % 3]), internal::to_klein(c[(h % 3 + 1) % 3])}});
    }
    return cut;
  }
  /// the number of group elements whose tiles the band has reached so far (tiles near the fundamental domain)
  std::size_t number_of_group_elements() const { return m_band.elements().size(); }
  /// @}

private:
  struct Wrapped {
    std::vector<Point> points;          // images in the fundamental domain
    std::vector<Eigen::Matrix3d> T;     // points[i] = T[i] sites[i]
    std::vector<std::size_t> slot;      // background triangle containing it
  };

  bool locate_klein(const Eigen::Vector2d& k, int& t, Eigen::Vector3d& bary) const
  {
    for(double tol : {1e-9, 1e-6})
      if(m_grid.locate(m_tri, k, t, bary, tol)) return true;
    return false;
  }

  // The triangle of each site at the last wrap_all(), tried first: sites move little between two energy
  // evaluations, and the grid's cells hold many of the triangles where the layout is dense (couplingdown's
  // CVT on one thread 5.98 -> 5.55 s with this alone; most of its locations were wrap()'s). A site strictly inside its old triangle (barycentric
  // coordinates above 1e-12: no other triangle holds it, the layout being an embedding) is located there,
  // any other by the grid, so the slots are the grid's. Shared by copies of the traits; a call that finds
  // it in use does without it.
  struct Slot_cache {
    std::mutex mutex;
    std::vector<int> slot;
  };

  void wrap_all(const std::vector<Point>& sites, Wrapped& w) const
  {
    const std::size_t ns = sites.size();
    if(ns == 0) throw Invalid_input("Hyperbolic_klein_domain_traits: no site");
    std::unique_lock<std::mutex> lock(m_slot_cache->mutex, std::try_to_lock);
    std::vector<int>* last = lock.owns_lock() ? &m_slot_cache->slot : nullptr;
    if(last && last->size() != ns) last->assign(ns, -1);
    w.points.resize(ns);
    w.T.resize(ns);
    w.slot.resize(ns);
    for(std::size_t i = 0; i < ns; ++i) {
      if(!contains(sites[i]))
        throw Convergence_failure("hyperbolic domain: site " + std::to_string(i) + " is not a point of the hyperbolic plane", 0);
      // a site that moved beyond the tiles explored so far widens the band (bounded: 4 doublings)
      for(int k = 0; !wrap(sites[i], w.points[i], w.T[i]); ++k) {
        if(k == 4)
          throw Convergence_failure("hyperbolic domain: site " + std::to_string(i) + " left the neighbourhood of the fundamental domain", 0);
        m_band.ensure(m_band.reached() * 2 + 4 * m_face_size);
      }
      int t = last ? (*last)[i] : -1;
      const Eigen::Vector2d k = internal::to_klein(w.points[i]);
      if(t < 0 || !(internal::Triangle_grid::barycentric(m_tri[std::size_t(t)], k).minCoeff() > 1e-12)) {
        Eigen::Vector3d bary = Eigen::Vector3d::Zero();
        t = 0;
        locate_klein(k, t, bary);
      }
      if(last) (*last)[i] = t;
      w.slot[i] = std::size_t(t);
    }
  }

  // the sites wrapped into the fundamental domain and the power diagram of them and their images
  void power_diagram(const std::vector<Point>& sites, Wrapped& w, internal::Hyperbolic_power_diagram& pr) const
  {
    wrap_all(sites, w);
    internal::build_hyperbolic_power_diagram(m_band, w.points, w.slot, m_tri.size(), m_area, pr);
  }

  int m_genus = 0;
  double m_area = 0, m_total_mass = 0, m_face_size = 0;
  std::vector<internal::Background_triangle> m_tri;  // Klein triangles, density weighted by the area element (sampling, location)
  std::vector<internal::Background_triangle> m_rho;  // the same triangles with the density cf^2 (integration)
  std::vector<std::size_t> m_slot;                   // face of the Intrinsic_triangulation -> index in m_tri
  std::vector<Eigen::Matrix3d> m_frame;              // per triangle, an isometry taking the centre to its centroid
  std::vector<std::array<internal::Hyperbolic_quadrature_node, 6>> m_whole;  // per triangle, its quadrature nodes (whole triangles)
  internal::Triangle_grid m_grid;
  unsigned m_threads = 1;
  // the tiles explored so far (grown on demand; integrate() is const but the band is a cache)
  mutable internal::Hyperbolic_band m_band;
  std::shared_ptr<Slot_cache> m_slot_cache = std::make_shared<Slot_cache>();  // wrap_all()
  double m_cosh_tile_reach = std::numeric_limits<double>::infinity();  // wrap(): cosh of Hyperbolic_band::reach_of_domain()
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_HYPERBOLIC_KLEIN_DOMAIN_TRAITS_H
