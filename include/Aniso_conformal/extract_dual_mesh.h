// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_EXTRACT_DUAL_MESH_H
#define ANISO_CONFORMAL_EXTRACT_DUAL_MESH_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Planar_domain_traits.h>
#include <Aniso_conformal/Surface_point.h>

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

/// \file extract_dual_mesh.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * a remeshed surface as arrays: positions, triangles, and where each vertex lies on the input
 */
struct Remeshed_surface {
  std::vector<Eigen::Vector3d> points;                 ///< vertex positions
  std::vector<std::array<std::size_t, 3>> faces;       ///< triangles, oriented like the input
  std::vector<Surface_point> surface_points;           ///< each vertex as a point of the input surface
};

/*!
 * \ingroup PkgAnisoConformalStages
 * builds the output mesh (stage 5): the Delaunay dual of `sites` in `domain` (constrained to the
 * boundary polygon), each site mapped back onto `surface` through its barycentric coordinates in the
 * laid-out background triangle that contains it. Boundary sites are mapped along their boundary edge
 * (so they lie exactly on the input boundary, and corners are exactly input corners); interior points
 * of a curved surface are projected onto it (the background's flipped edges are chords).
 * \throws Convergence_failure if a site cannot be located or the dual is not a valid triangulation
 */
inline Remeshed_surface extract_dual_mesh(const Input_surface& surface, const Intrinsic_triangulation& itri,
                                          const Planar_domain_traits& domain,
                                          const std::vector<Planar_domain_traits::Point>& sites)
{
  Remeshed_surface out;
  out.faces = domain.dual_triangles(sites);
  out.points.resize(sites.size());
  out.surface_points.resize(sites.size());
  const bool planar = surface.is_planar();
  for(std::size_t i = 0; i < sites.size(); ++i) {
    Eigen::Vector3d x;
    if(i < domain.number_of_fixed_sites()) {
      const int v = domain.boundary_site_vertex(i);
      const auto& b = domain.boundary_location(i);
      x = v >= 0 ? itri.position(v)
                 : Eigen::Vector3d((1 - b.t) * itri.position(itri.tail(b.halfedge)) + b.t * itri.position(itri.head(b.halfedge)));
      if(v >= 0 && itri.input_vertex(v) >= 0) {
        out.surface_points[i] = itri.point(v);
      } else {
        out.surface_points[i] = surface.project(x);
        out.surface_points[i].position = x;
      }
    } else {
      int f = -1;
      Eigen::Vector3d bary = Eigen::Vector3d::Zero();
      if(!domain.locate(sites[i], f, bary, 1e-6))
        throw Convergence_failure("dual mesh: site " + std::to_string(i) + " lies outside the domain", 0);
      const auto& c = itri.face_vertices(std::size_t(f));
      x = bary[0] * itri.position(c[0]) + bary[1] * itri.position(c[1]) + bary[2] * itri.position(c[2]);
      out.surface_points[i] = surface.project(x);
      if(planar) out.surface_points[i].position = x;  // exact in the plane; keeps z = 0 bit for bit
    }
    out.points[i] = out.surface_points[i].position;
    if(planar) out.points[i].z() = 0;
  }
  return out;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_EXTRACT_DUAL_MESH_H
