// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_SPHERE_DELAUNAY_FLIPS_H
#define ANISO_CONFORMAL_INTERNAL_CVT_SPHERE_DELAUNAY_FLIPS_H

#include <Aniso_conformal/internal/CVT/lawson_flips.h>
#include <Aniso_conformal/internal/CVT/spherical_voronoi.h>
#include <Aniso_conformal/internal/conformal/spherical_map.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

// The Delaunay triangulation of the CVT's sites on the sphere, kept from one energy evaluation to the
// next and repaired by Lawson's edge flips. Between two evaluations the sites move by a fraction of
// their spacing: the previous triangulation, with the sites at their new places, is still a
// triangulation of the sphere (or is not, and is rebuilt), and a few flips make it Delaunay again,
// where CGAL's Delaunay_triangulation_on_sphere_2 inserts every site anew (a fifth of the time of an
// evaluation on 2000 sites, on one thread while the integration uses all).
//
// On the unit sphere the Delaunay triangulation is the convex hull of the sites: the edge (a, b) between
// the triangles (c, a, b) and (d, b, a) is Delaunay when d is not strictly beyond the plane of (c, a, b),
// seen from the centre; otherwise the flip to (c, a, d), (d, b, c) makes it so. As in the plane
// (Lawson 1977; through a stereographic projection from a point inside no circumcircle the two criteria
// are the same), flips from any triangulation end at the Delaunay one, which is unique up to
// cospherical sites (any of their triangulations serves: the Voronoi edges between them are points).
// The flips' precondition, a triangulation of the sphere, is checked first: every triangle on the outer
// side of the centre (CGAL's exact orientation predicate), and one direction inside exactly one of them
// (with every triangle positive, a covering of the sphere counts its sheets at any point: once, not
// twice; the sum of spherical areas, 4 pi per sheet, when the direction is too close to an edge).

namespace Aniso_conformal {
namespace internal {

// The triangulation as index triples with their neighbours, and the flips that repair it.
class Sphere_flip_triangulation : public Flip_triangulation_base {
public:
  // takes the triangulation `sd` of `ns` sites (build_sphere_delaunay()); false (and not valid) unless it
  // covers the whole sphere with every site a vertex (no ghost faces, dimension 2)
  bool take(const Sphere_delaunay& sd, std::size_t ns)
  {
    m_valid = false;
    m_mesh.clear();
    if(sd.dt.dimension() != 2 || sd.dt.number_of_ghost_faces() > 0) return false;
    for(std::size_t i = 0; i < ns; ++i)
      if(!sd.has_vertex(i)) return false;
    m_mesh.assign(sd.dt.all_faces_begin(), sd.dt.all_faces_end());
    for(const auto& a : m_mesh.adj)
      for(int t : a)
        if(t < 0) return false;
    m_sites = ns;
    m_valid = m_mesh.tri.size() == 2 * ns - 4;
    return m_valid;
  }

  // moves the sites to `unit` (as many as the triangulation holds) and flips it back to Delaunay; false
  // (and not valid) if the moved triangulation no longer covers the sphere once or the flips exceed
  // their bound (then the caller rebuilds with CGAL)
  bool update(const std::vector<Eigen::Vector3d>& unit)
  {
    m_last_flips = 0;
    if(!m_valid || unit.size() != m_sites) return m_valid = false;
    m_points.resize(unit.size());
    for(std::size_t i = 0; i < unit.size(); ++i) {
      if(!unit[i].allFinite()) return m_valid = false;
      m_points[i] = Point(unit[i].x(), unit[i].y(), unit[i].z());
    }
    for(const auto& t : m_mesh.tri)
      if(side_of_centre(t) != CGAL::NEGATIVE) return m_valid = false;
    if(coverings(unit) != 1) return m_valid = false;
    const auto is_delaunay = [&](int t, int, int u, int m) {
      // the far corner d of the neighbour on the centre's side of t's plane (or on it: cospherical sites)
      const auto& T = m_mesh.tri[std::size_t(t)];
      const Point& d = m_points[std::size_t(m_mesh.tri[std::size_t(u)][std::size_t(m)])];
      return CGAL::orientation(m_points[std::size_t(T[0])], m_points[std::size_t(T[1])], m_points[std::size_t(T[2])], d) != CGAL::POSITIVE;
    };
    return m_valid = m_mesh.make_delaunay(is_delaunay, 10 * m_mesh.tri.size() + 100, m_last_flips);
  }

private:
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;

  // How many times the triangles (all on the outer side of the centre) cover the sphere: the number of
  // them that contain a fixed direction p (on the inner side of each edge's plane through the centre);
  // when p lies within 1e-9 of an edge's plane, the sum of their spherical areas over 4 pi instead
  int coverings(const std::vector<Eigen::Vector3d>& unit) const
  {
    const Eigen::Vector3d p = Eigen::Vector3d(0.5377, 0.1832, 0.8227).normalized();
    int count = 0;
    bool near_an_edge = false;
    for(const auto& t : m_mesh.tri) {
      const Eigen::Vector3d &a = unit[std::size_t(t[0])], &b = unit[std::size_t(t[1])], &c = unit[std::size_t(t[2])];
      const double d0 = p.dot(a.cross(b)), d1 = p.dot(b.cross(c)), d2 = p.dot(c.cross(a));
      near_an_edge = near_an_edge || (std::abs(d0) < 1e-9 && d1 > -1e-9 && d2 > -1e-9) ||
                     (std::abs(d1) < 1e-9 && d0 > -1e-9 && d2 > -1e-9) || (std::abs(d2) < 1e-9 && d0 > -1e-9 && d1 > -1e-9);
      count += d0 > 0 && d1 > 0 && d2 > 0;
    }
    if(!near_an_edge) return count;
    double area = 0;
    for(const auto& t : m_mesh.tri) area += spherical_triangle_area(unit[std::size_t(t[0])], unit[std::size_t(t[1])], unit[std::size_t(t[2])]);
    const double pi = 3.14159265358979323846;
    return int(std::lround(area / (4 * pi)));
  }
  typedef K::Point_3 Point;

  // the side of the plane of t where the centre lies: NEGATIVE for a triangle counterclockwise seen
  // from outside and away from the centre
  CGAL::Orientation side_of_centre(const std::array<int, 3>& t) const
  {
    return CGAL::orientation(m_points[std::size_t(t[0])], m_points[std::size_t(t[1])], m_points[std::size_t(t[2])], Point(0, 0, 0));
  }
  std::vector<Point> m_points;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_SPHERE_DELAUNAY_FLIPS_H
