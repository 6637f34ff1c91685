// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_HYPERBOLIC_KLEIN_DOMAIN_TRAITS_H
#define ANISO_CONFORMAL_HYPERBOLIC_KLEIN_DOMAIN_TRAITS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/hyperbolic_embedding.h>
#include <Aniso_conformal/internal/CVT/quotient_triangles.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>
#include <Aniso_conformal/internal/conformal/hyperbolic_geometry.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <queue>
#include <random>
#include <string>
#include <thread>
#include <utility>
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
    : m_itri(&itri), m_genus(emb.genus), m_area(emb.area)
  {
    const std::size_t nf = itri.number_of_faces();
    std::vector<Eigen::Vector2d> centroids(nf);
    for(std::size_t f = 0; f < nf; ++f) {
      const auto& c = emb.corner_klein[f];
      centroids[f] = (c[0] + c[1] + c[2]) / 3.0;
    }
    const std::vector<std::size_t> order = internal::morton_order(centroids, Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
    m_tri.reserve(nf);
    m_rho.resize(nf);
    m_frame.reserve(nf);
    m_slot.assign(nf, 0);
    for(std::size_t i = 0; i < nf; ++i) {
      const std::size_t f = order[i];
      const auto& c = itri.face_vertices(f);
      std::array<double, 3> rho, sample;
      for(int k = 0; k < 3; ++k) {
        const double cf = emb.conformal_factor[std::size_t(c[k])];
        rho[k] = cf * cf;
        // the samples' weight includes the area element, so that they follow the hyperbolic mass
        sample[k] = rho[k] * std::pow(std::max(1e-300, 1 - emb.corner_klein[f][k].squaredNorm()), -1.5);
      }
      m_tri.push_back(internal::make_background_triangle(emb.corner_klein[f], sample, int(f)));
      m_rho[i] = internal::make_background_triangle(emb.corner_klein[f], rho, int(f));
      const auto& X = emb.corner_hyperboloid[f];
      const Point g = internal::normalize_on_hyperboloid(X[0] + X[1] + X[2]);
      m_frame.push_back(internal::hyperbolic_frame(g, internal::normalize_on_hyperboloid(g + X[0] - X[1])));
      m_slot[f] = i;
      for(int k = 0; k < 3; ++k)
        m_face_size = std::max(m_face_size, internal::hyperbolic_distance(emb.corner_hyperboloid[f][k], emb.corner_hyperboloid[f][(k + 1) % 3]));
    }
    m_grid.build(m_tri);
    m_threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
    m_pairing = emb.side_pairing;
    m_corners = emb.corner_hyperboloid;
    m_group.assign(1, Eigen::Matrix3d::Identity());
    m_total_mass = 0;
    for(std::size_t i = 0; i < nf; ++i) {
      Cell c;
      integrate_piece(m_rho[i].p, 3, i, Point::UnitX(), c);
      m_total_mass += c.mass;
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
    Eigen::Vector3d bary;
    for(std::size_t gi = 0; gi < m_group.size(); ++gi) {
      // tiles in order of their distance: the fundamental domain first
      const Eigen::Matrix3d Ti = gi == 0 ? Eigen::Matrix3d::Identity() : m_group_inverse[gi];
      const Point q = internal::normalize_on_hyperboloid(Ti * p);
      if(locate_klein(internal::to_klein(q), face, bary)) {
        image = q;
        T = Ti;
        return true;
      }
    }
    return false;
  }
  /// @}

  /// \name Sites
  /// @{

  /*!
   * places `n` sites spread over the density (stratified along a space-filling curve of the background
   * triangles; deterministic for a `seed`), in the fundamental domain.
   * \throws Invalid_input if `n < 1`
   */
  std::vector<Point> initial_sites(std::size_t n, unsigned seed) const
  {
    if(n < 1) throw Invalid_input("the hyperbolic domain needs at least one site");
    std::mt19937_64 rng(seed);
    const std::vector<Eigen::Vector2d> k = internal::stratified_samples(m_tri, n, rng);
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
    wrap_all(sites, w);
    Periodic_regular pr;
    build(w, pr);
    std::vector<int> start, nbr;
    internal::delaunay_neighbours(pr.rt, pr.handle, start, nbr);
    std::vector<Cell> acc;
    integrate_cells(pr.points, start, nbr, acc);
    std::vector<Cell> folded(ns);
    for(auto& c : folded) c.centroid = Point::Zero();
    for(std::size_t e = 0; e < pr.points.size(); ++e) {
      const Cell& a = acc[e];
      if(a.mass == 0) continue;
      Cell& f = folded[std::size_t(pr.original[e])];
      const Eigen::Matrix3d& G = m_group[std::size_t(pr.element[e])];  // image = G * site
      f.mass += a.mass;
      f.centroid += internal::lorentz_inverse(G) * a.centroid;  // first moments pulled back
      f.energy += a.energy;
      f.gradient += G.transpose() * a.gradient;                 // chain rule through image = G site
    }
    cells.assign(ns, Cell());
    for(std::size_t i = 0; i < ns; ++i) {
      const Cell& a = folded[i];
      cells[i].mass = a.mass;
      cells[i].energy = a.energy;
      // back to the given copy of the site: it is T^-1 of its image in the fundamental domain
      const Eigen::Matrix3d Tinv = internal::lorentz_inverse(w.T[i]);
      cells[i].centroid = a.mass > 0 ? Point(internal::normalize_on_hyperboloid(Tinv * a.centroid)) : sites[i];
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
    wrap_all(sites, w);
    Periodic_regular pr;
    build(w, pr);
    for(std::size_t i = 0; i < ns; ++i)
      if(pr.handle[i] == RT::Vertex_handle() || pr.handle[i]->info() != int(i))
        throw Convergence_failure("dual mesh: site " + std::to_string(i) + " coincides with another site on the surface", 0);
    std::vector<std::array<int, 3>> faces;
    for(auto f = pr.rt.finite_faces_begin(); f != pr.rt.finite_faces_end(); ++f)
      faces.push_back({{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
    return internal::quotient_triangles(faces, pr.original, ns, 2 * ns + 4 * std::size_t(m_genus - 1),
                                        {"the hyperbolic surface", "images", "the Delaunay triangulation of the hyperbolic surface"});
  }

  /// the Voronoi cell of every site (its image in the fundamental domain) as a counterclockwise polygon in the Klein disk (for pictures)
  std::vector<std::vector<Eigen::Vector2d>> voronoi_cells(const std::vector<Point>& sites) const
  {
    const std::size_t ns = sites.size();
    Wrapped w;
    wrap_all(sites, w);
    Periodic_regular pr;
    build(w, pr);
    std::vector<std::vector<Eigen::Vector2d>> cells(ns);
    for(std::size_t i = 0; i < ns; ++i) {
      if(pr.handle[i] == RT::Vertex_handle() || pr.handle[i]->info() != int(i)) continue;
      auto f = pr.rt.incident_faces(pr.handle[i]), done = f;
      do {
        if(!pr.rt.is_infinite(f)) {
          const K::Point_2 c = pr.rt.weighted_circumcenter(f);
          cells[i].emplace_back(c.x(), c.y());
        }
      } while(++f != done);
    }
    return cells;
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
    for(std::size_t h = 0; h < m_pairing.size(); ++h) {
      if(m_pairing[h] == Eigen::Matrix3d::Identity()) continue;
      const auto& c = m_corners[h / 3];
      cut.push_back({{internal::to_klein(c[h % 3]), internal::to_klein(c[(h % 3 + 1) % 3])}});
    }
    return cut;
  }
  /// the number of group elements whose tiles the band has reached so far (tiles near the fundamental domain)
  std::size_t number_of_group_elements() const { return m_group.size(); }
  /// @}

private:
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef CGAL::Regular_triangulation_vertex_base_2<K> Rvb;
  typedef CGAL::Triangulation_vertex_base_with_info_2<int, K, Rvb> Vb;
  typedef CGAL::Regular_triangulation_face_base_2<K> Fb;
  typedef CGAL::Triangulation_data_structure_2<Vb, Fb> Tds;
  typedef CGAL::Regular_triangulation_2<K, Tds> RT;

  struct Wrapped {
    std::vector<Point> points;          // images in the fundamental domain
    std::vector<Eigen::Matrix3d> T;     // points[i] = T[i] sites[i]
    std::vector<std::size_t> slot;      // background triangle containing it
  };
  // the sites and their images in the band (indices 0 .. n-1 are the sites)
  struct Periodic_regular {
    std::vector<Point> points;
    std::vector<int> original, element;  // site and group element of each point
    RT rt;
    std::vector<RT::Vertex_handle> handle;
  };
  // a face copy of the Dijkstra over the tiles: background triangle (slot) and group element
  struct Face_copy {
    std::size_t slot;
    int element;
    double distance;
  };

  bool locate_klein(const Eigen::Vector2d& k, int& t, Eigen::Vector3d& bary) const
  {
    for(double tol : {1e-9, 1e-6})
      if(m_grid.locate(m_tri, k, t, bary, tol)) return true;
    return false;
  }

  void wrap_all(const std::vector<Point>& sites, Wrapped& w) const
  {
    const std::size_t ns = sites.size();
    if(ns == 0) throw Invalid_input("Hyperbolic_klein_domain_traits: no site");
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
        ensure_band(m_band_reached * 2 + 4 * m_face_size);
      }
      int t = 0;
      Eigen::Vector3d bary;
      locate_klein(internal::to_klein(w.points[i]), t, bary);
      w.slot[i] = std::size_t(t);
    }
  }

  // the index of group element G, added if new. Elements differ by where they take the apex: the group
  // acts freely, so two elements take it at least the shortest closed geodesic apart (far above 1e-3),
  // while one element reached along two paths differs by the layout's rounding (about 1e-6 far out)
  int element_index(const Eigen::Matrix3d& G) const
  {
    const Point o = G.col(0);
    for(std::size_t i = 0; i < m_group.size(); ++i)
      if(internal::hyperbolic_distance(m_group[i].col(0), o) < 1e-3) return int(i);
    m_group.push_back(G);
    m_group_inverse.push_back(internal::lorentz_inverse(G));
    return int(m_group.size() - 1);
  }

  // Explores the tiles across the cut up to `band` from the fundamental domain: a Dijkstra over face
  // copies, the distance of a copy being that of its centroid to the point where the path left the
  // fundamental domain. Bounded: at most 60 x (faces) copies.
  void ensure_band(double band) const
  {
    if(band <= m_band_reached) return;
    const std::size_t nf = m_tri.size();
    if(m_group_inverse.empty()) m_group_inverse.assign(1, Eigen::Matrix3d::Identity());
    std::map<std::pair<std::size_t, int>, double> best;
    std::map<std::pair<std::size_t, int>, Point> source;
    typedef std::pair<double, std::pair<std::size_t, int>> Entry;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    auto centroid = [&](std::size_t slot, int element) {
      const auto& c = m_corners[std::size_t(m_tri[slot].face)];
      return Point(internal::normalize_on_hyperboloid(m_group[std::size_t(element)] * (c[0] + c[1] + c[2])));
    };
    for(std::size_t s = 0; s < nf; ++s) queue.push({0.0, {s, 0}});
    for(std::size_t s = 0; s < nf; ++s) best[{s, 0}] = 0.0;
    const std::size_t cap = 60 * nf;
    m_copies.clear();
    while(!queue.empty()) {
      const Entry top = queue.top();
      queue.pop();
      const auto key = top.second;
      if(top.first > best[key]) continue;
      if(key.second != 0) m_copies.push_back({key.first, key.second, top.first});
      if(m_copies.size() > cap)
        throw Convergence_failure("hyperbolic domain: the band of " + std::to_string(band) +
                                      " around the fundamental domain needs more than " + std::to_string(cap) +
                                      " face copies (too few sites for this surface and metric)",
                                  band);
      const int f = m_tri[key.first].face;
      for(int k = 0; k < 3; ++k) {
        const int h = 3 * f + k, t = m_itri->twin(h);
        const Eigen::Matrix3d& P = m_pairing[std::size_t(h)];
        const bool cut = P != Eigen::Matrix3d::Identity();
        const int element = cut ? element_index(m_group[std::size_t(key.second)] * P) : key.second;
        const std::pair<std::size_t, int> next(m_slot[std::size_t(Intrinsic_triangulation::face(t))], element);
        if(element == 0) continue;  // back in the fundamental domain
        Point src;
        if(key.second == 0) {  // leaving the fundamental domain through the edge of h
          const auto& c = m_corners[std::size_t(f)];
          src = internal::normalize_on_hyperboloid(c[std::size_t(k)] + c[std::size_t((k + 1) % 3)]);
        } else {
          src = source[key];
        }
        const double d = internal::hyperbolic_distance(src, centroid(next.first, next.second));
        if(d > band) continue;
        auto it = best.find(next);
        if(it != best.end() && it->second <= d) continue;
        best[next] = d;
        source[next] = src;
        queue.push({d, next});
      }
    }
    m_band_reached = band;
  }

  void build(const Wrapped& w, Periodic_regular& pr) const
  {
    const std::size_t ns = w.points.size();
    const double spacing = std::sqrt(m_area / double(ns));
    double widen = 3;
    for(int attempt = 0; attempt < 8; ++attempt, widen *= 1.6) {
      const double band = widen * spacing + m_face_size;
      ensure_band(band);
      pr.points.assign(w.points.begin(), w.points.end());
      pr.original.resize(ns);
      pr.element.assign(ns, 0);
      for(std::size_t i = 0; i < ns; ++i) pr.original[i] = int(i);
      // an image of site s by element g lies in the copy (slot of s, g)
      std::vector<std::vector<std::size_t>> by_slot(m_tri.size());
      for(std::size_t i = 0; i < ns; ++i) by_slot[w.slot[i]].push_back(i);
      for(const Face_copy& c : m_copies) {
        if(c.distance > band) continue;
        for(std::size_t s : by_slot[c.slot]) {
          pr.points.push_back(internal::normalize_on_hyperboloid(m_group[std::size_t(c.element)] * w.points[s]));
          pr.original.push_back(int(s));
          pr.element.push_back(c.element);
        }
      }
      pr.rt.clear();
      std::vector<std::pair<K::Weighted_point_2, int>> pts;
      pts.reserve(pr.points.size());
      for(std::size_t e = 0; e < pr.points.size(); ++e) {
        const Point& x = pr.points[e];
        const double cx = 0.5 * x.y(), cy = 0.5 * x.z();
        pts.emplace_back(K::Weighted_point_2(K::Point_2(cx, cy), cx * cx + cy * cy - x.x()), int(e));
      }
      pr.rt.insert(pts.begin(), pts.end());
      pr.handle.assign(pr.points.size(), RT::Vertex_handle());
      for(auto v = pr.rt.finite_vertices_begin(); v != pr.rt.finite_vertices_end(); ++v) pr.handle[std::size_t(v->info())] = v;
      // every Delaunay circle at an original site must lie within the band: its centre is within r of
      // the fundamental domain, so its disk lies within 2 r, where every image is present
      bool complete = true;
      for(auto f = pr.rt.finite_faces_begin(); f != pr.rt.finite_faces_end() && complete; ++f) {
        const bool at_original = f->vertex(0)->info() < int(ns) || f->vertex(1)->info() < int(ns) || f->vertex(2)->info() < int(ns);
        if(!at_original) continue;
        const K::Point_2 c = pr.rt.weighted_circumcenter(f);
        const Eigen::Vector2d k(c.x(), c.y());
        if(!(k.squaredNorm() < 1)) { complete = false; break; }  // not a hyperbolic circle: an image is missing
        const double r = internal::hyperbolic_distance(internal::from_klein(k), pr.points[std::size_t(f->vertex(0)->info())]);
        complete = 2 * r + m_face_size <= band;
      }
      if(complete) return;
    }
    throw Convergence_failure("hyperbolic domain: " + std::to_string(ns) +
                                  " sites leave Voronoi cells too large for the band of images around the fundamental domain",
                              double(ns));
  }

  // Integrals over the convex Klein polygon `poly` (a part of background triangle `slot`) about the site
  // x (hyperboloid). The area element (1 - |k|^2)^(-3/2) is steep far out in the disk, so the polygon is
  // first moved by the isometry that takes the triangle's centroid to the centre (a projective map of
  // the Klein disk: polygons stay polygons), where the element is flat to second order; then a 6-point
  // rule of degree 4 on a fan, the density evaluated at the node's place in the domain.
  template <typename Points>
  void integrate_piece(const Points& poly, int n, std::size_t slot, const Point& x, Cell& acc) const
  {
    static const double w6[2] = {0.223381589678011, 0.109951743655322};
    static const double b6[2][3] = {{0.108103018168070, 0.445948490915965, 0.445948490915965},
                                    {0.816847572980459, 0.091576213509771, 0.091576213509771}};
    const internal::Background_triangle& T = m_rho[slot];
    const Eigen::Matrix3d& F = m_frame[slot];
    const Eigen::Matrix3d Finv = internal::lorentz_inverse(F);
    Eigen::Vector2d local[internal::Small_polygon::capacity];
    for(int i = 0; i < n; ++i) local[i] = internal::to_klein(Finv * internal::from_klein(poly[i]));
    for(int i = 2; i < n; ++i) {
      const Eigen::Vector2d &a = local[0], &b = local[i - 1], &c = local[i];
      const double A = 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
      if(!(A > 0)) continue;
      for(int q = 0; q < 6; ++q) {
        const double* l = b6[q / 3];
        const int r = q % 3;
        const Eigen::Vector2d k = l[r] * a + l[(r + 1) % 3] * b + l[(r + 2) % 3] * c;
        const double s = 1.0 / std::sqrt(std::max(1e-300, 1 - k.squaredNorm()));
        const Point y = F * Point(s, s * k.x(), s * k.y());  // the node in the domain
        const double rho = T.r0 + T.rg.dot(Eigen::Vector2d(y.y() / y.x(), y.z() / y.x()));
        const double w = A * w6[q / 3] * rho * s * s * s;  // area element (1 - |k|^2)^(-3/2)
        const double d = internal::hyperbolic_distance(y, x);
        acc.mass += w;
        acc.centroid += w * y;
        acc.energy += w * d * d;
        const double f = d > 1e-8 ? d / std::sinh(d) : 1.0;
        acc.gradient += (2 * w * f) * Point(y.x(), -y.y(), -y.z());
      }
    }
  }

  // per point (site or image), the integrals over the parts of the background triangles in its cell
  void integrate_cells(const std::vector<Point>& pts, const std::vector<int>& start, const std::vector<int>& nbr,
                       std::vector<Cell>& out) const
  {
    const std::size_t np = pts.size(), chunks = 16, nf = m_rho.size();
    std::vector<std::vector<Cell>> acc(chunks);
    int any = 0;
    while(any < int(np) && start[std::size_t(any)] == start[std::size_t(any) + 1] && np > 1) ++any;
    auto work = [&](std::size_t chunk) {
      std::vector<Cell>& A = acc[chunk];
      A.assign(np, Cell());
      for(Cell& c : A) c.centroid = Point::Zero();
      std::vector<int> stamp(np, -1), stack;
      internal::Small_polygon poly_a, poly_b;
      int seed = any;
      for(std::size_t f = chunk * nf / chunks; f < (chunk + 1) * nf / chunks; ++f) {
        const internal::Background_triangle& T = m_rho[f];
        const Point y0 = internal::from_klein(T.p[0]);
        // greedy walk to the point nearest to a corner (exact on a Voronoi graph)
        double best = -internal::minkowski_dot(pts[std::size_t(seed)], y0);
        for(bool moved = true; moved;) {
          moved = false;
          for(int j = start[std::size_t(seed)]; j < start[std::size_t(seed) + 1]; ++j) {
            const double d = -internal::minkowski_dot(pts[std::size_t(nbr[std::size_t(j)])], y0);
            if(d < best) { best = d; seed = nbr[std::size_t(j)]; moved = true; break; }
          }
        }
        stack.assign(1, seed);
        stamp[std::size_t(seed)] = int(f);
        while(!stack.empty()) {
          const int s = stack.back();
          stack.pop_back();
          internal::Small_polygon* poly = &poly_a;
          internal::Small_polygon* tmp = &poly_b;
          poly->assign(T.p[0], T.p[1], T.p[2]);
          const Point& ps = pts[std::size_t(s)];
          bool clipped = false;
          // closer to s than to n: (n1 - s1, n2 - s2) . k <= n0 - s0
          for(int j = start[std::size_t(s)]; j < start[std::size_t(s) + 1] && poly->n >= 3; ++j) {
            const Point& pn = pts[std::size_t(nbr[std::size_t(j)])];
            if(internal::clip_half_plane(*poly, Eigen::Vector2d(pn.y() - ps.y(), pn.z() - ps.z()), pn.x() - ps.x(), *tmp)) {
              clipped = true;
              std::swap(poly, tmp);
            }
          }
          if(poly->n < 3) continue;
          integrate_piece(poly->p, poly->n, f, ps, A[std::size_t(s)]);
          if(!clipped) continue;  // the whole triangle is in the cell
          for(int j = start[std::size_t(s)]; j < start[std::size_t(s) + 1]; ++j) {
            const int n = nbr[std::size_t(j)];
            if(stamp[std::size_t(n)] == int(f)) continue;
            const Point& pn = pts[std::size_t(n)];
            const Eigen::Vector2d a(pn.y() - ps.y(), pn.z() - ps.z());
            const double b = pn.x() - ps.x();
            if(a.dot(T.p[0]) <= b && a.dot(T.p[1]) <= b && a.dot(T.p[2]) <= b) continue;
            stamp[std::size_t(n)] = int(f);
            stack.push_back(n);
          }
        }
      }
    };
    internal::run_chunks(m_threads, chunks, work);
    out.assign(np, Cell());
    for(std::size_t i = 0; i < np; ++i) {
      out[i].centroid = Point::Zero();
      for(std::size_t c = 0; c < chunks; ++c) {
        out[i].mass += acc[c][i].mass;
        out[i].centroid += acc[c][i].centroid;
        out[i].energy += acc[c][i].energy;
        out[i].gradient += acc[c][i].gradient;
      }
    }
  }

  const Intrinsic_triangulation* m_itri;
  int m_genus = 0;
  double m_area = 0, m_total_mass = 0, m_face_size = 0;
  std::vector<internal::Background_triangle> m_tri;  // Klein triangles, density weighted by the area element (sampling, location)
  std::vector<internal::Background_triangle> m_rho;  // the same triangles with the density cf^2 (integration)
  std::vector<std::size_t> m_slot;                   // face of the Intrinsic_triangulation -> index in m_tri
  std::vector<Eigen::Matrix3d> m_frame;              // per triangle, an isometry taking the centre to its centroid
  internal::Triangle_grid m_grid;
  unsigned m_threads = 1;
  std::vector<Eigen::Matrix3d> m_pairing;
  std::vector<std::array<Eigen::Vector3d, 3>> m_corners;
  // the tiles explored so far (grown on demand; integrate() is const but the band is a cache)
  mutable std::vector<Eigen::Matrix3d> m_group, m_group_inverse;
  mutable std::vector<Face_copy> m_copies;
  mutable double m_band_reached = 0;
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_HYPERBOLIC_KLEIN_DOMAIN_TRAITS_H
