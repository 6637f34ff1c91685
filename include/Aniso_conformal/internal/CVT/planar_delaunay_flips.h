// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_PLANAR_DELAUNAY_FLIPS_H
#define ANISO_CONFORMAL_INTERNAL_CVT_PLANAR_DELAUNAY_FLIPS_H

#include <Aniso_conformal/internal/CVT/lawson_flips.h>
#include <Aniso_conformal/internal/domains/indexed_delaunay_2.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <vector>

// The Delaunay triangulation of the CVT's sites in the plane, kept from one energy evaluation to the next
// and repaired by Lawson's edge flips (as on the sphere and the flat torus), where CGAL's
// Delaunay_triangulation_2 would insert every site anew (serially, while the integration uses every
// thread). The planar domain's outer sites are its fixed boundary sites, so the convex hull rarely changes.
//
// The moved triangulation is still one of the convex hull of the sites when every triangle is
// counterclockwise (CGAL's exact orientation) and its boundary, a closed chain of edges, turns left or
// goes straight at each vertex and winds once: a locally convex closed polygon that winds once is convex
// and simple, triangles of positive area whose chain has that boundary cover its inside once, and then no
// site lies outside it. Flips never change the boundary; Lawson's flips of the inner edges then end at
// the Delaunay triangulation (unique up to cocircular sites, any of whose triangulations serves). When the
// check fails (a site left the old hull, or a triangle folded over) the caller triangulates anew.

namespace Aniso_conformal {
namespace internal {

class Planar_flip_triangulation : public Flip_triangulation_base {
public:
  // takes the triangulation `d` of `ns` sites; false (and not valid) unless every site is a vertex of it
  // and it has dimension 2
  bool take(const Indexed_delaunay_2& d, std::size_t ns)
  {
    m_valid = false;
    m_mesh.clear();
    if(d.dt.dimension() != 2 || d.handle.size() != ns) return false;
    for(std::size_t i = 0; i < ns; ++i)
      if(!d.has_vertex(i)) return false;
    m_mesh.assign(d.dt.finite_faces_begin(), d.dt.finite_faces_end());  // an infinite neighbour: the hull
    m_sites = ns;
    return m_valid = true;
  }

  // moves the sites to `sites` and flips the triangulation back to Delaunay; false (and not valid) if the
  // moved triangles are no longer a triangulation of the sites' convex hull, or the flips exceed their
  // bound (then the caller triangulates anew)
  bool update(const std::vector<Eigen::Vector2d>& sites)
  {
    m_last_flips = 0;
    if(!m_valid || sites.size() != m_sites) return m_valid = false;
    m_points.resize(sites.size());
    for(std::size_t i = 0; i < sites.size(); ++i) {
      if(!sites[i].allFinite()) return m_valid = false;
      m_points[i] = Point(sites[i].x(), sites[i].y());
    }
    for(const auto& t : m_mesh.tri)
      if(CGAL::orientation(point(t[0]), point(t[1]), point(t[2])) != CGAL::LEFT_TURN) return m_valid = false;
    if(!boundary_is_convex()) return m_valid = false;
    const auto is_delaunay = [&](int t, int, int u, int m) {
      const auto& T = m_mesh.tri[std::size_t(t)];
      return CGAL::side_of_oriented_circle(point(T[0]), point(T[1]), point(T[2]), point(m_mesh.tri[std::size_t(u)][std::size_t(m)])) !=
             CGAL::ON_POSITIVE_SIDE;
    };
    return m_valid = m_mesh.make_delaunay(is_delaunay, 10 * m_mesh.tri.size() + 100, m_last_flips);
  }

private:
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef K::Point_2 Point;
  const Point& point(int i) const { return m_points[std::size_t(i)]; }

  // whether the boundary edges (counterclockwise around the triangles) make one closed chain that turns
  // left or goes straight at every vertex and winds once around
  bool boundary_is_convex() const
  {
    std::vector<int> next(m_sites, -1);
    std::size_t edges = 0;
    int first = -1;
    for(std::size_t t = 0; t < m_mesh.tri.size(); ++t)
      for(int k = 0; k < 3; ++k)
        if(m_mesh.adj[t][std::size_t(k)] < 0) {
          const int p = m_mesh.tri[t][std::size_t((k + 1) % 3)], q = m_mesh.tri[t][std::size_t((k + 2) % 3)];
          if(next[std::size_t(p)] >= 0) return false;  // the boundary passes p twice
          next[std::size_t(p)] = q;
          first = p;
          ++edges;
        }
    if(edges < 3) return false;
    double turning = 0;
    int a = first, b = next[std::size_t(first)];
    for(std::size_t i = 0; i < edges; ++i) {
      const int c = next[std::size_t(b)];
      if(c < 0) return false;
      if(CGAL::orientation(point(a), point(b), point(c)) == CGAL::RIGHT_TURN) return false;
      const Eigen::Vector2d u(point(b).x() - point(a).x(), point(b).y() - point(a).y()),
          v(point(c).x() - point(b).x(), point(c).y() - point(b).y());
      turning += std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
      a = b;
      b = c;
    }
    const double pi = 3.14159265358979323846;
    return a == first && std::abs(turning - 2 * pi) < pi;  // the chain closed after `edges` steps, once around
  }

  std::vector<Point> m_points;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_PLANAR_DELAUNAY_FLIPS_H
