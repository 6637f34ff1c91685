// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_HYPERBOLIC_BAND_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_HYPERBOLIC_BAND_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/hyperbolic_geometry.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <queue>
#include <string>
#include <utility>
#include <vector>

// The images of the sites near the fundamental domain of a hyperbolic surface H^2 / G and their power
// diagram in the Klein disk (Hyperbolic_klein_domain_traits): the tiles across the cut are explored face
// by face (a Dijkstra over face copies, each reached through its side pairings), so their number grows
// with the width of the band, not exponentially with word length.

namespace Aniso_conformal {
namespace internal {

// The group elements and face copies (tiles) reached so far around the fundamental domain, grown on
// demand. A slot is the index of a background triangle in the traits' (Morton) order.
class Hyperbolic_band {
public:
  // a face copy of the Dijkstra over the tiles: background triangle (slot) and group element
  struct Face_copy {
    std::size_t slot;
    int element;
    double distance;
  };

  Hyperbolic_band() = default;
  // itri: the background; face_of_slot / slot_of_face: the traits' order of its faces; pairing: the side
  // pairing of every halfedge (identity inside the fundamental domain); corners: each face's corners on
  // the hyperboloid
  Hyperbolic_band(const Intrinsic_triangulation& itri, std::vector<int> face_of_slot, std::vector<std::size_t> slot_of_face,
                  std::vector<Eigen::Matrix3d> pairing, std::vector<std::array<Eigen::Vector3d, 3>> corners)
    : m_itri(&itri), m_face_of_slot(std::move(face_of_slot)), m_slot_of_face(std::move(slot_of_face)),
      m_pairing(std::move(pairing)), m_corners(std::move(corners)), m_group(1, Eigen::Matrix3d::Identity()),
      m_group_inverse(1, Eigen::Matrix3d::Identity())
  {}

  const std::vector<Eigen::Matrix3d>& elements() const { return m_group; }          // element 0 is the identity
  const std::vector<Eigen::Matrix3d>& inverse_elements() const { return m_group_inverse; }
  const std::vector<Face_copy>& copies() const { return m_copies; }                  // by distance, without element 0
  double reached() const { return m_band_reached; }                                  // the band explored so far
  const std::vector<Eigen::Matrix3d>& pairing() const { return m_pairing; }
  const std::vector<std::array<Eigen::Vector3d, 3>>& corners() const { return m_corners; }

  // the index of group element G, added if new. Elements differ by where they take the apex: the group
  // acts freely, so two elements take it at least the shortest closed geodesic apart (far above 1e-3),
  // while one element reached along two paths differs by the layout's rounding (about 1e-6 far out)
  int element_index(const Eigen::Matrix3d& G)
  {
    const Eigen::Vector3d o = G.col(0);
    for(std::size_t i = 0; i < m_group.size(); ++i)
      if(hyperbolic_distance(m_group[i].col(0), o) < 1e-3) return int(i);
    m_group.push_back(G);
    m_group_inverse.push_back(lorentz_inverse(G));
    return int(m_group.size() - 1);
  }

  // Explores the tiles across the cut up to `band` from the fundamental domain: a Dijkstra over face
  // copies, the distance of a copy being that of its centroid to the point where the path left the
  // fundamental domain. Bounded: at most 60 x (faces) copies.
  // \throws Convergence_failure if the band needs more copies
  void ensure(double band)
  {
    if(band <= m_band_reached) return;
    const std::size_t nf = m_face_of_slot.size();
    typedef std::pair<std::size_t, int> Key;
    std::map<Key, double> best;
    std::map<Key, Eigen::Vector3d> source;
    typedef std::pair<double, Key> Entry;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    for(std::size_t s = 0; s < nf; ++s) queue.push({0.0, {s, 0}});
    for(std::size_t s = 0; s < nf; ++s) best[{s, 0}] = 0.0;
    const std::size_t cap = 60 * nf;
    m_copies.clear();
    while(!queue.empty()) {
      const Entry top = queue.top();
      queue.pop();
      const Key key = top.second;
      if(top.first > best[key]) continue;
      if(key.second != 0) m_copies.push_back({key.first, key.second, top.first});
      if(m_copies.size() > cap)
        throw Convergence_failure("hyperbolic domain: the band of " + std::to_string(band) +
                                      " around the fundamental domain needs more than " + std::to_string(cap) +
                                      " face copies (too few sites for this surface and metric)",
                                  band);
      const int f = m_face_of_slot[key.first];
      for(int k = 0; k < 3; ++k) {
        const int h = 3 * f + k, t = m_itri->twin(h);
        const Eigen::Matrix3d& P = m_pairing[std::size_t(h)];
        const bool cut = P != Eigen::Matrix3d::Identity();
        const int element = cut ? element_index(m_group[std::size_t(key.second)] * P) : key.second;
        const Key next(m_slot_of_face[std::size_t(Intrinsic_triangulation::face(t))], element);
        if(element == 0) continue;  // back in the fundamental domain
        Eigen::Vector3d src;
        if(key.second == 0) {  // leaving the fundamental domain through the edge of h
          const auto& c = m_corners[std::size_t(f)];
          src = normalize_on_hyperboloid(c[std::size_t(k)] + c[std::size_t((k + 1) % 3)]);
        } else {
          src = source[key];
        }
        const double d = hyperbolic_distance(src, copy_centroid(next.first, next.second));
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

private:
  Eigen::Vector3d copy_centroid(std::size_t slot, int element) const
  {
    const auto& c = m_corners[std::size_t(m_face_of_slot[slot])];
    return Eigen::Vector3d(normalize_on_hyperboloid(m_group[std::size_t(element)] * (c[0] + c[1] + c[2])));
  }

  const Intrinsic_triangulation* m_itri = nullptr;
  std::vector<int> m_face_of_slot;
  std::vector<std::size_t> m_slot_of_face;
  std::vector<Eigen::Matrix3d> m_pairing;
  std::vector<std::array<Eigen::Vector3d, 3>> m_corners;
  std::vector<Eigen::Matrix3d> m_group, m_group_inverse;
  std::vector<Face_copy> m_copies;
  double m_band_reached = 0;
};

// CGAL's regular triangulation of the Klein disk with the point index as vertex info
typedef CGAL::Exact_predicates_inexact_constructions_kernel Klein_kernel;
typedef CGAL::Triangulation_vertex_base_with_info_2<int, Klein_kernel, CGAL::Regular_triangulation_vertex_base_2<Klein_kernel>> Klein_vb;
typedef CGAL::Triangulation_data_structure_2<Klein_vb, CGAL::Regular_triangulation_face_base_2<Klein_kernel>> Klein_tds;
typedef CGAL::Regular_triangulation_2<Klein_kernel, Klein_tds> Klein_regular_triangulation;

// the sites in the fundamental domain (indices 0 .. n-1) and their images in the band, with their power diagram
struct Hyperbolic_power_diagram {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> original, element;  // site and group element of each point
  Klein_regular_triangulation rt;
  std::vector<Klein_regular_triangulation::Vertex_handle> handle;

  bool has_vertex(std::size_t i) const
  {
    return handle[i] != Klein_regular_triangulation::Vertex_handle() && handle[i]->info() == int(i);
  }
};

// the points and their power diagram: the point x becomes the weighted point ((x1, x2) / 2,
// (x1^2 + x2^2) / 4 - x0), whose power at the Klein point k orders the points as their hyperbolic
// distance to k does (Nielsen and Nock)
inline void build_power_diagram(Hyperbolic_power_diagram& pr)
{
  typedef Klein_kernel K;
  pr.rt.clear();
  std::vector<std::pair<K::Weighted_point_2, int>> pts;
  pts.reserve(pr.points.size());
  for(std::size_t e = 0; e < pr.points.size(); ++e) {
    const Eigen::Vector3d& x = pr.points[e];
    const double cx = 0.5 * x.y(), cy = 0.5 * x.z();
    pts.emplace_back(K::Weighted_point_2(K::Point_2(cx, cy), cx * cx + cy * cy - x.x()), int(e));
  }
  pr.rt.insert(pts.begin(), pts.end());
  pr.handle.assign(pr.points.size(), Klein_regular_triangulation::Vertex_handle());
  for(auto v = pr.rt.finite_vertices_begin(); v != pr.rt.finite_vertices_end(); ++v) pr.handle[std::size_t(v->info())] = v;
}

// true if every Delaunay circle at an original site (one of the first ns points) lies within the band:
// its centre is within r of the fundamental domain, so its disk lies within 2 r, where every image is present
inline bool power_diagram_is_complete(const Hyperbolic_power_diagram& pr, std::size_t ns, double band, double face_size)
{
  for(auto f = pr.rt.finite_faces_begin(); f != pr.rt.finite_faces_end(); ++f) {
    const bool at_original = f->vertex(0)->info() < int(ns) || f->vertex(1)->info() < int(ns) || f->vertex(2)->info() < int(ns);
    if(!at_original) continue;
    const Klein_kernel::Point_2 c = pr.rt.weighted_circumcenter(f);
    const Eigen::Vector2d k(c.x(), c.y());
    if(!(k.squaredNorm() < 1)) return false;  // not a hyperbolic circle: an image is missing
    const double r = hyperbolic_distance(from_klein(k), pr.points[std::size_t(f->vertex(0)->info())]);
    if(!(2 * r + face_size <= band)) return false;
  }
  return true;
}

/*
 * The power diagram of the sites `wrapped` (in the fundamental domain; slot[i]: the background triangle
 * holding site i) and of their images in a band around the fundamental domain: the band starts at three
 * site spacings (sqrt(area / n)) plus `face_size` and is widened (x1.6, 8 attempts) until every Delaunay
 * circle that matters lies in it.
 * \throws Convergence_failure if it never does (Voronoi cells too large for the band)
 */
inline void build_hyperbolic_power_diagram(Hyperbolic_band& band, const std::vector<Eigen::Vector3d>& wrapped,
                                           const std::vector<std::size_t>& slot, std::size_t number_of_slots, double area,
                                           double face_size, Hyperbolic_power_diagram& pr)
{
  const std::size_t ns = wrapped.size();
  const double spacing = std::sqrt(area / double(ns));
  double widen = 3;
  for(int attempt = 0; attempt < 8; ++attempt, widen *= 1.6) {
    const double width = widen * spacing + face_size;
    band.ensure(width);
    pr.points.assign(wrapped.begin(), wrapped.end());
    pr.original.resize(ns);
    pr.element.assign(ns, 0);
    for(std::size_t i = 0; i < ns; ++i) pr.original[i] = int(i);
    // an image of site s by element g lies in the copy (slot of s, g)
    std::vector<std::vector<std::size_t>> by_slot(number_of_slots);
    for(std::size_t i = 0; i < ns; ++i) by_slot[slot[i]].push_back(i);
    for(const Hyperbolic_band::Face_copy& c : band.copies()) {
      if(c.distance > width) continue;
      for(std::size_t s : by_slot[c.slot]) {
        pr.points.push_back(normalize_on_hyperboloid(band.elements()[std::size_t(c.element)] * wrapped[s]));
        pr.original.push_back(int(s));
        pr.element.push_back(c.element);
      }
    }
    build_power_diagram(pr);
    if(power_diagram_is_complete(pr, ns, width, face_size)) return;
  }
  throw Convergence_failure("hyperbolic domain: " + std::to_string(ns) +
                                " sites leave Voronoi cells too large for the band of images around the fundamental domain",
                            double(ns));
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_HYPERBOLIC_BAND_H
