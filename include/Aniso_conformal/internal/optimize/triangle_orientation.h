// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_OPTIMIZE_TRIANGLE_ORIENTATION_H
#define ANISO_CONFORMAL_INTERNAL_OPTIMIZE_TRIANGLE_ORIENTATION_H

#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Surface_point.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

// The one test of "inverted" for an output triangle, shared by the output check of stage 6
// (count_inverted_triangles) and the surface optimisation that repairs what it flags.

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

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_OPTIMIZE_TRIANGLE_ORIENTATION_H
