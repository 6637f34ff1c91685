// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_OPTIMIZE_TRIANGLE_ORIENTATION_H
#define ANISO_CONFORMAL_INTERNAL_OPTIMIZE_TRIANGLE_ORIENTATION_H

#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Surface_point.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>

// The one test of "inverted" for an output triangle, shared by the output check of stage 6
// (count_inverted_triangles) and the surface optimisation that repairs what it flags; and the one test
// that an edge flip of the output keeps the surface's shape, shared by the optimisation's flips and the
// crowded-vertex move's.

namespace Aniso_conformal {
namespace internal {

// the side of z = 0 a planar input's faces face: the sign of its signed area seen from +z (positive when
// counter-clockwise); 0 for a curved input
inline double planar_side(const Input_surface& surface)
{
  double side = 0;
  if(surface.is_planar())
    for(const auto& t : surface.faces()) {
      const Eigen::Vector3d &a = surface.points()[t[0]], &b = surface.points()[t[1]], &c = surface.points()[t[2]];
      side += (b - a).cross(c - a).z();
    }
  return side;
}

// `true` if the triangle (p0, p1, p2), whose corners lie on `surface` at s0, s1, s2, is inverted or
// degenerate: its normal disagrees (dot <= 0) with every reference normal of the input around it, the
// vertex normals interpolated at its corners and the normal of each input face that holds one of its
// corners (for a planar input, the side its faces face, `side` = planar_side(surface): the layout keeps
// the input's orientation, clockwise or not). On a smooth input these agree; on a coarse faceted one (a
// 12-triangle cube, a 140-vertex blob) a triangle close to a sharp crease can disagree with the averaged
// vertex normals while lying correctly on the faces it touches, which alone would flag a valid triangle.
inline bool triangle_is_inverted(const Input_surface& surface, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                 const Eigen::Vector3d& p2, const Surface_point& s0, const Surface_point& s1,
                                 const Surface_point& s2, double side)
{
  const Eigen::Vector3d nf = (p1 - p0).cross(p2 - p0);
  if(surface.is_planar()) return !(nf.z() * side > 0);
  Eigen::Vector3d ref = Eigen::Vector3d::Zero();
  bool agrees = false;
  for(const Surface_point* sp : {&s0, &s1, &s2}) {
    for(int j = 0; j < 3; ++j) ref += sp->barycentric[j] * surface.vertex_normals()[sp->vertices[j]];
    if(sp->vertices[0] != sp->vertices[1]) {  // inside or on the border of an input face: its normal
      const Eigen::Vector3d& a = surface.points()[sp->vertices[0]];
      const Eigen::Vector3d nface = (surface.points()[sp->vertices[1]] - a).cross(surface.points()[sp->vertices[2]] - a);
      agrees = agrees || nf.dot(nface) > 0;
    }
  }
  return !(agrees || nf.dot(ref) > 0);
}

// `true` if flipping the edge (a, b) of the output triangles (a, b, c) and (b, a, d) into (c, d) keeps the
// surface's shape: the two new triangles (a, d, c) and (d, b, c) do not fold onto each other and, unless the
// flip repairs an inverted triangle (`repairs`) or the input is planar, the new diagonal stays as close to
// the input as the old one, within twice its distance or 5 % of its length (measured at the midpoints): a
// flip across a ridge would cut through the solid
inline bool flip_keeps_the_shape(const Input_surface& surface, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c, const Eigen::Vector3d& d, bool repairs)
{
  const Eigen::Vector3d n1 = (d - a).cross(c - a), n2 = (b - d).cross(c - d);
  if(!(n1.dot(n2) > 0)) return false;
  if(surface.is_planar() || repairs) return true;
  const Eigen::Vector3d m_old = 0.5 * (a + b), m_new = 0.5 * (c + d);
  const double d_old = (surface.project(m_old).position - m_old).norm();
  const double d_new = (surface.project(m_new).position - m_new).norm();
  return d_new <= std::max(2 * d_old, 0.05 * (c - d).norm());
}

// The angle deficit above which an output vertex is at a tip (the end of a horn, a tail, a finger, where
// the CVT leaves one vertex): 2 pi minus the sum of its triangles' angles in space above 1 radian. The
// surface optimisation neither moves such a vertex off the tip nor removes it (surface_optimizer.h,
// crowded_vertices.h).
inline constexpr double tip_angle_deficit = 1.0;

// the angle deficit in space at `p`, of the triangles (p, a, b) for each (a, b) in `opposite` (the ring's
// edges opposite the vertex)
template <typename Opposite_edges, typename Position>
double angle_deficit(const Eigen::Vector3d& p, const Opposite_edges& opposite, const Position& position)
{
  double angles = 0;
  for(const auto& e : opposite) {
    const Eigen::Vector3d x = position(e.first) - p, y = position(e.second) - p;
    angles += std::atan2(x.cross(y).norm(), x.dot(y));
  }
  return 2 * 3.14159265358979323846 - angles;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_OPTIMIZE_TRIANGLE_ORIENTATION_H
