// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_EXTRACT_DUAL_MESH_H
#define ANISO_CONFORMAL_EXTRACT_DUAL_MESH_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Surface_point.h>
#include <Aniso_conformal/internal/parallel_for.h>

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
  /// the first `fixed_vertices` vertices are the fixed sites of the CVT (boundary sites of the plane, then
  /// the input's corners kept inside it and the crease sites; in a closed domain the corners, crease sites
  /// and loop sites): later stages (`optimize_surface_mesh()`) never move them
  std::size_t fixed_vertices = 0;
  /// fixed sites of the CVT among the first `fixed_vertices` that later stages may move, as vertex indices:
  /// the cone domain's kept cones (`Cone_domain::vertices_kept()`: a cone of negative curvature needs a
  /// site on it for the dual, issue 16), which on the output are ordinary vertices of the input surface
  std::vector<std::size_t> released_vertices;
  /// output edges on the input's creases, as (smaller, larger) vertex index pairs, joining consecutive
  /// crease sites (issue 15 item 2): later stages (`optimize_surface_mesh()`) never flip them
  std::vector<std::array<std::size_t, 2>> kept_edges;
};

/*!
 * \ingroup PkgAnisoConformalStages
 * builds the output mesh (stage 5): the Delaunay dual of `sites` in `domain`
 * (`domain.dual_triangles(sites)`), each site mapped back onto `surface` through its barycentric
 * coordinates in the background triangle that contains it (`domain.background_location()`).
 *
 * A site that falls exactly on a background vertex that is an input vertex (a boundary corner) becomes
 * that vertex. Fixed sites (on the boundary of a planar domain) and every site of a planar input keep
 * their barycentric position exactly, so they lie on the input boundary; the other sites of a curved
 * surface are projected onto it (the background's flipped edges are chords).
 *
 * Time linear in the number of sites (plus the domain's Delaunay dual and one closest-point query per
 * site); the projections run on `number_of_threads` threads (0 = every core), the domain's location
 * queries on the calling thread (a traits class need not be safe for concurrent use). The result does not
 * depend on the number of threads.
 *
 * \tparam DomainTraits a model of `ParametricDomainTraits` (`Planar_domain_traits`)
 * \throws Convergence_failure if a site cannot be located or the dual is not a valid triangulation
 */
template <typename DomainTraits>
Remeshed_surface extract_dual_mesh(const Input_surface& surface, const Intrinsic_triangulation& itri,
                                   const DomainTraits& domain, const std::vector<typename DomainTraits::Point>& sites,
                                   unsigned number_of_threads = 0)
{
  Remeshed_surface out;
  out.faces = domain.dual_triangles(sites);
  const std::size_t ns = sites.size();
  out.points.resize(ns);
  out.surface_points.resize(ns);
  const bool planar = surface.is_planar();
  // where each site lies on the background
  std::vector<int> face(ns, -1);
  std::vector<Eigen::Vector3d> bary(ns, Eigen::Vector3d::Zero());
  for(std::size_t i = 0; i < ns; ++i)
    if(!domain.background_location(i, sites[i], face[i], bary[i]))
      throw Convergence_failure("dual mesh: site " + std::to_string(i) + " lies outside the domain", 0);
  const std::size_t fixed = domain.number_of_fixed_sites();
  out.fixed_vertices = std::min(fixed, ns);
  if(ns > 0) surface.project(surface.points().front());  // builds the AABB tree before the threads query it
  // back onto the input
  internal::parallel_for(ns, number_of_threads, [&](std::size_t i) {
    const auto& c = itri.face_vertices(std::size_t(face[i]));
    int at_vertex = -1;
    for(int k = 0; k < 3; ++k)
      if(bary[i][k] == 1.0) at_vertex = c[k];
    if(at_vertex >= 0 && itri.input_vertex(at_vertex) >= 0) {
      out.surface_points[i] = itri.point(at_vertex);
    } else {
      const Eigen::Vector3d x = bary[i][0] * itri.position(c[0]) + bary[i][1] * itri.position(c[1]) + bary[i][2] * itri.position(c[2]);
      out.surface_points[i] = surface.project(x);
      // exact in the plane (keeps z = 0 bit for bit) and on boundary edges, which are input edges
      if(planar || i < fixed) out.surface_points[i].position = x;
    }
    out.points[i] = out.surface_points[i].position;
    if(planar) out.points[i].z() = 0;
  }, 512);
  return out;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_EXTRACT_DUAL_MESH_H
