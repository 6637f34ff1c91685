// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_FEATURES_BOUNDARY_DISTANCE_H
#define ANISO_CONFORMAL_INTERNAL_FEATURES_BOUNDARY_DISTANCE_H

#include <Aniso_conformal/Intrinsic_triangulation.h>

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Core>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <vector>

// The distance in the metric from a background vertex to the boundary of a disk, for the plane's crease
// sites and corners (remesh_in_domain.h, issue 15): the boundary edges in an AABB tree (CGAL), queried
// locally instead of measured one by one for every vertex.

namespace Aniso_conformal {
namespace internal {

// The metric distance from the vertices of the disk `itri` to its boundary: for vertex `v` (its metric
// square root Q(v)), the smallest |Q(v) (c - p)| over the boundary edges (straight segments in space),
// with p the position of v and c the point of the edge closest to p in space; infinite without a boundary.
// The number is the one the loop over every boundary edge gives (the same formula, the same minimum):
// the edge nearest in space gives an upper bound D, and an edge whose value is below D has its closest
// point within D / s of p (s the smallest singular value of Q(v), of its first two columns when the disk
// and v lie in z = 0), so only the edges of the AABB tree that meet the cube of half-side about D / s
// around p are measured. Building: O(B log B) for B boundary edges; a query: O(log B + edges in the
// cube). A singular Q(v) measures every edge.
class Boundary_distance {
  typedef CGAL::Simple_cartesian<double> K;
  typedef std::vector<K::Segment_3>::const_iterator Iterator;
  typedef CGAL::AABB_segment_primitive<K, Iterator> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> Tree;

public:
  explicit Boundary_distance(const Intrinsic_triangulation& itri) : m_itri(itri)
  {
    auto point = [](const Eigen::Vector3d& p) { return K::Point_3(p.x(), p.y(), p.z()); };
    for(int e = 0; e < int(itri.number_of_halfedges()); ++e) {
      if(!itri.is_boundary_edge(e)) continue;
      m_edges.push_back(e);
      const Eigen::Vector3d &a = itri.position(itri.tail(e)), &b = itri.position(itri.head(e));
      m_segments.push_back(K::Segment_3(point(a), point(b)));
      m_planar = m_planar && a.z() == 0 && b.z() == 0;
    }
    if(m_segments.empty()) return;
    m_tree.insert(m_segments.begin(), m_segments.end());
    m_tree.build();
    m_tree.accelerate_distance_queries();
  }

  Boundary_distance(const Boundary_distance&) = delete;  // the tree points into m_segments
  Boundary_distance& operator=(const Boundary_distance&) = delete;

  // the metric distance from vertex `v` to the boundary (see the class)
  double operator()(int v) const
  {
    if(m_segments.empty()) return std::numeric_limits<double>::infinity();
    const Eigen::Vector3d& p = m_itri.position(v);
    const K::Point_3 q(p.x(), p.y(), p.z());
    const std::size_t nearest = std::size_t(m_tree.closest_point_and_primitive(q).second - m_segments.begin());
    double d = to_edge(v, nearest);
    const Eigen::Matrix3d& Q = m_itri.Q(v);
    const double s = m_planar && p.z() == 0 ? Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>>(Q.leftCols<2>()).singularValues().minCoeff()
                                            : Eigen::JacobiSVD<Eigen::Matrix3d>(Q).singularValues().minCoeff();
    const double r = (1 + 1e-6) * d / s + 1e-12 * (1 + p.cwiseAbs().maxCoeff());
    if(!(s > 0) || !std::isfinite(r)) {  // no bound: every edge
      for(std::size_t i = 0; i < m_edges.size(); ++i) d = std::min(d, to_edge(v, i));
      return d;
    }
    std::vector<Primitive::Id> near;
    m_tree.all_intersected_primitives(K::Iso_cuboid_3(p.x() - r, p.y() - r, p.z() - r, p.x() + r, p.y() + r, p.z() + r),
                                      std::back_inserter(near));
    for(const auto& id : near) d = std::min(d, to_edge(v, std::size_t(id - m_segments.begin())));
    return d;
  }

private:
  // |Q(v) (c - p)| for the boundary edge `i`, c its point closest to p in space
  double to_edge(int v, std::size_t i) const
  {
    const int e = m_edges[i];
    const Eigen::Vector3d& p = m_itri.position(v);
    const Eigen::Vector3d a = m_itri.position(m_itri.tail(e)), ab = m_itri.position(m_itri.head(e)) - a;
    const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    return (m_itri.Q(v) * (a + t * ab - p)).norm();
  }

  const Intrinsic_triangulation& m_itri;
  std::vector<int> m_edges;  // the boundary halfedges, in the order of m_segments
  std::vector<K::Segment_3> m_segments;
  bool m_planar = true;
  Tree m_tree;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_FEATURES_BOUNDARY_DISTANCE_H
