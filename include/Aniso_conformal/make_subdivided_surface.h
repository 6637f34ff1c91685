// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_MAKE_SUBDIVIDED_SURFACE_H
#define ANISO_CONFORMAL_MAKE_SUBDIVIDED_SURFACE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>

#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>

#include <string>

/// \file make_subdivided_surface.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * reads a closed polygon mesh (any polygons; for example CGAL's coarse genus-3 `3torus.off`),
 * triangulates its faces and refines it by `levels` steps of Loop subdivision (CGAL
 * `Subdivision_method_3`), each of which multiplies the number of triangles by 4 and smooths the
 * surface: a fine, smooth input of the same topology, used for the genus-3 example of Fig. 13.
 *
 * \throws Invalid_input if the file cannot be read as a polygon mesh, `levels` is above 8, or the result
 *         is not a valid triangle mesh (the `Input_surface` checks)
 */
inline Input_surface make_subdivided_surface(const std::string& polygon_file, unsigned levels)
{
  typedef CGAL::Simple_cartesian<double> K;
  typedef CGAL::Surface_mesh<K::Point_3> Mesh;
  if(levels > 8) throw Invalid_input("make_subdivided_surface(): at most 8 levels, not " + std::to_string(levels));
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(polygon_file, mesh) || mesh.is_empty())
    throw Invalid_input("make_subdivided_surface(): cannot read '" + polygon_file + "' as a polygon mesh");
  if(!CGAL::Polygon_mesh_processing::triangulate_faces(mesh))
    throw Invalid_input("make_subdivided_surface(): cannot triangulate the faces of '" + polygon_file + "'");
  if(levels > 0) CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(int(levels)));
  return Input_surface::from_mesh(mesh);
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_MAKE_SUBDIVIDED_SURFACE_H
