// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_REPAIR_REPORT_H
#define ANISO_CONFORMAL_IO_REPAIR_REPORT_H

#include <cstddef>
#include <string>
#include <vector>

/// \file Repair_report.h
/// What `IO::repair_polygon_soup()` may repair (`Repair_options`) and what it did (`Repair_report`). A
/// light header: `Remeshing_result` holds a `Repair_report` without pulling in Polygon Mesh Processing.

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalIO
 * the repairs `IO::repair_polygon_soup()` (and the readers and the tool that call it) may make; all on
 * by default, `none()` turns them all off (the tool's `--no-repair`): the input must then be a valid
 * triangle mesh as it is, and `Input_surface` refuses it otherwise.
 */
struct Repair_options {
  /// polygons of 4 or more vertices are split into triangles (CGAL's `triangulate_face()`)
  bool triangulate_polygons = true;
  /// points at the same position are merged into one (`merge_duplicate_points_in_polygon_soup()`) and
  /// polygons over the same vertices are kept once (`merge_duplicate_polygons_in_polygon_soup()`)
  bool weld_duplicates = true;
  /// points that belong to no polygon are dropped (`remove_isolated_points_in_polygon_soup()`)
  bool drop_isolated_points = true;
  /// faces are oriented consistently (`orient_polygon_soup()`; an open surface keeps the orientation of
  /// the majority of its faces), a closed surface outward (`is_outward_oriented()`), and a planar
  /// clockwise input is handed to the remesher counter-clockwise (`restore_input_orientation()` turns
  /// the output back)
  bool orient = true;

  /// every repair off
  static Repair_options none()
  {
    Repair_options o;
    o.triangulate_polygons = o.weld_duplicates = o.drop_isolated_points = o.orient = false;
    return o;
  }
  /// `true` if at least one repair is on
  bool any() const { return triangulate_polygons || weld_duplicates || drop_isolated_points || orient; }
};

/*!
 * \ingroup PkgAnisoConformalIO
 * what `IO::repair_polygon_soup()` did to a polygon soup, with the maps between the input's indices and
 * the repaired surface's. Counts are of the input's points and polygons ("vertices" and "faces" of the
 * file), in the order the repairs run: weld, drop isolated points, triangulate, orient.
 */
struct Repair_report {
  /// the value of `kept_vertex[i]` for an input point that was dropped
  static constexpr std::size_t dropped = std::size_t(-1);

  std::size_t input_points = 0;                ///< points of the soup as given
  std::size_t input_polygons = 0;              ///< polygons of the soup as given
  std::size_t polygons_triangulated = 0;       ///< polygons of 4 or more vertices split into triangles
  std::size_t triangles_from_polygons = 0;     ///< the triangles those polygons became
  std::size_t points_welded = 0;               ///< points merged into an earlier point at the same position
  /// points at the position of an earlier point that were not welded, because welding them would have
  /// made the surface non-manifold where the input, without it, was a valid surface (two parts that touch)
  std::size_t points_left_unwelded = 0;
  std::size_t duplicate_polygons_removed = 0;  ///< polygons over the same vertices as an earlier one, removed
  std::size_t isolated_points_dropped = 0;     ///< points of no polygon, dropped
  /// triangles whose orientation was reversed, so that the surface is consistently oriented (and, if
  /// closed, outward): counted against the input, so a surface reversed as a whole counts all its faces
  std::size_t faces_reoriented = 0;
  /// `true` if the faces of a closed surface, consistently oriented, pointed inward and were reversed
  bool reversed_to_outward = false;
  /// `true` if the input lies in the plane z = 0 and is oriented clockwise seen from +z: the repaired
  /// surface is its counter-clockwise copy (the convention of 2D meshes; `remesh()` also takes a clockwise
  /// one as it is, since the plane's layout keeps the input's orientation), and
  /// `restore_input_orientation()` reverses the output's triangles back (not counted in `faces_reoriented`)
  bool planar_clockwise = false;
  /// for each input point, its vertex in the repaired surface (welded points share one), or `dropped`;
  /// this is how a per-vertex input such as a metric file lines up with the repaired surface
  std::vector<std::size_t> kept_vertex;
  /// for each vertex of the repaired surface, the first input point mapped to it (what messages name)
  std::vector<std::size_t> input_vertex;
  /// for each triangle of the repaired surface, the input polygon it comes from (what messages name)
  std::vector<std::size_t> input_face;

  /// `true` if there is anything to report: something changed, or points were left unwelded (when
  /// `false`, the index maps are the identity)
  bool any() const
  {
    return polygons_triangulated + points_welded + points_left_unwelded + duplicate_polygons_removed + isolated_points_dropped +
               faces_reoriented > 0 ||
           reversed_to_outward || planar_clockwise;
  }

  /// the repairs in words, e.g. "400 polygons triangulated into 800 triangles, 1200 points welded";
  /// empty if there were none
  std::string summary() const
  {
    std::string s;
    auto add = [&s](std::size_t n, const std::string& one, const std::string& many) {
      if(n == 0) return;
      s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + (n == 1 ? one : many);
    };
    add(polygons_triangulated, "polygon triangulated", "polygons triangulated");
    if(polygons_triangulated > 0) s += " into " + std::to_string(triangles_from_polygons) + " triangles";
    add(points_welded, "duplicated point welded", "duplicated points welded");
    add(points_left_unwelded, "point at the position of another left apart (welding would make the surface non-manifold)",
        "points at the position of others left apart (welding would make the surface non-manifold)");
    add(duplicate_polygons_removed, "duplicated face removed", "duplicated faces removed");
    add(isolated_points_dropped, "vertex of no face dropped", "vertices of no face dropped");
    add(faces_reoriented, "face reoriented", "faces reoriented");
    if(reversed_to_outward) s += std::string(s.empty() ? "" : " ") + "(the closed surface now points outward)";
    if(planar_clockwise)
      s += std::string(s.empty() ? "" : ", ") + "clockwise planar input remeshed counter-clockwise, output turned back clockwise";
    return s;
  }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_REPAIR_REPORT_H
