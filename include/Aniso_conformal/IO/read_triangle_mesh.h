// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_READ_TRIANGLE_MESH_H
#define ANISO_CONFORMAL_IO_READ_TRIANGLE_MESH_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Core>

#include <array>
#include <fstream>
#include <string>
#include <vector>

/// \file read_triangle_mesh.h

namespace Aniso_conformal {
namespace IO {

namespace internal {
typedef CGAL::Simple_cartesian<double>::Point_3 Soup_point;
inline std::string extension_of(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for(char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}
} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * reads a triangle mesh from an OFF, OBJ or PLY file (by extension) and validates it (`Input_surface`).
 * \throws Invalid_input naming the file if it cannot be opened or parsed, has an unsupported extension,
 *         or has a face that is not a triangle; and as `Input_surface` does for a broken mesh
 */
inline Input_surface read_triangle_mesh(const std::string& path)
{
  const std::string ext = internal::extension_of(path);
  if(ext != "off" && ext != "obj" && ext != "ply")
    throw Invalid_input("file " + path + ": unsupported extension (use .off, .obj or .ply)");
  if(!std::ifstream(path).good()) throw Invalid_input("file " + path + ": cannot be opened");
  std::vector<internal::Soup_point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false));
  } catch(const std::exception& e) {
    throw Invalid_input("file " + path + ": cannot be parsed (" + e.what() + ")");
  }
  if(!ok) throw Invalid_input("file " + path + ": cannot be parsed as " + ext);
  if(points.empty() || polygons.empty()) throw Invalid_input("file " + path + ": the mesh is empty");
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(points.size());
  for(const auto& p : points) pts.emplace_back(p.x(), p.y(), p.z());
  std::vector<Input_surface::Face> faces;
  faces.reserve(polygons.size());
  for(std::size_t f = 0; f < polygons.size(); ++f) {
    if(polygons[f].size() != 3)
      throw Invalid_input("file " + path + ": face " + std::to_string(f) + " has " + std::to_string(polygons[f].size()) +
                          " vertices; only triangle meshes are supported");
    faces.push_back({{polygons[f][0], polygons[f][1], polygons[f][2]}});
  }
  try {
    return Input_surface(std::move(pts), std::move(faces));
  } catch(const Invalid_input& e) {
    throw Invalid_input("file " + path + ": " + e.what());
  }
}

/*!
 * \ingroup PkgAnisoConformalIO
 * writes a triangle mesh as OFF, OBJ or PLY (by extension), with full double precision.
 * \throws Invalid_input if the extension is not supported or the file cannot be written
 */
inline void write_polygon_soup(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                               const std::vector<std::array<std::size_t, 3>>& faces)
{
  const std::string ext = internal::extension_of(path);
  if(ext != "off" && ext != "obj" && ext != "ply")
    throw Invalid_input("cannot write " + path + ": unsupported extension (use .off, .obj or .ply)");
  std::vector<internal::Soup_point> pts;
  pts.reserve(points.size());
  for(const auto& p : points) pts.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<std::size_t>> polys;
  polys.reserve(faces.size());
  for(const auto& f : faces) polys.push_back({f[0], f[1], f[2]});
  bool ok = false;
  try {
    ok = CGAL::IO::write_polygon_soup(path, pts, polys, CGAL::parameters::stream_precision(17));
  } catch(const std::exception&) {
    ok = false;
  }
  if(!ok) throw Invalid_input("cannot write " + path);
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_READ_TRIANGLE_MESH_H
