// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A synthetic body with limbs for the tests of the cone metric (issue 16): the unit sphere with five
// tubes along +-x, +-y and +z, each `aspect` times longer than wide, remeshed isotropically by CGAL's
// Polygon Mesh Processing so that the tubes are triangulated as well as the body.

#ifndef ANISO_CONFORMAL_TEST_LIMB_BODY_H
#define ANISO_CONFORMAL_TEST_LIMB_BODY_H

#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/make_ellipsoid.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <vector>

namespace limb_body {

// The point of the unit sphere `x` moved onto the tube along the unit vector `d` of radius `radius`
// and length `length` (beyond the sphere) if `x` is within the angle `alpha = asin(radius)` of `d`:
// the inner half of that cap becomes the tube's end (a flattened dome of the tube's radius), the outer
// half its wall (radius `radius`, from the end down to the sphere); `x` itself otherwise.
inline Eigen::Vector3d onto_tube(const Eigen::Vector3d& x, const Eigen::Vector3d& d, double radius, double length)
{
  const double alpha = std::asin(radius), theta = std::acos(std::max(-1.0, std::min(1.0, x.dot(d))));
  if(theta >= alpha) return x;
  const Eigen::Vector3d perp = x - x.dot(d) * d;
  const double s = theta / alpha, half = 0.5 * alpha;
  if(s < 0.5) return (length + std::cos(theta)) * d + perp * (radius / std::sin(half));
  const double t = (s - 0.5) / 0.5;
  const double axial = (1 - t) * (length + std::cos(half)) + t * std::cos(alpha);
  return axial * d + perp.normalized() * radius;
}

// The body: a level-4 icosphere (2562 vertices) with five tubes of radius `radius` and length
// `2 radius aspect`, then isotropic remeshing (CGAL PMP) at `edge_length`, 5 iterations. Closed, genus 0.
inline Aniso_conformal::Input_surface make_limb_body(double radius = 0.25, double aspect = 8, double edge_length = 0.12)
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef CGAL::Surface_mesh<K::Point_3> Mesh;
  const Aniso_conformal::Input_surface sphere = Aniso_conformal::make_ellipsoid(4, 1, 1, 1);
  const std::array<Eigen::Vector3d, 5> arms = {{Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                                Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0, 0, 1)}};
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertex;
  for(const Eigen::Vector3d& x : sphere.points()) {
    Eigen::Vector3d p = x;
    for(const Eigen::Vector3d& d : arms) p = onto_tube(p, d, radius, 2 * radius * aspect);
    vertex.push_back(mesh.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
  }
  for(const auto& f : sphere.faces()) mesh.add_face(vertex[f[0]], vertex[f[1]], vertex[f[2]]);
  CGAL::Polygon_mesh_processing::isotropic_remeshing(faces(mesh), edge_length, mesh,
                                                     CGAL::parameters::number_of_iterations(5));
  mesh.collect_garbage();
  std::vector<Eigen::Vector3d> points;
  for(Mesh::Vertex_index v : mesh.vertices()) points.emplace_back(mesh.point(v).x(), mesh.point(v).y(), mesh.point(v).z());
  std::vector<Aniso_conformal::Input_surface::Face> faces_out;
  for(Mesh::Face_index f : mesh.faces()) {
    Aniso_conformal::Input_surface::Face t;
    int k = 0;
    for(Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh)) t[std::size_t(k++)] = std::size_t(v);
    faces_out.push_back(t);
  }
  return Aniso_conformal::Input_surface(std::move(points), std::move(faces_out));
}

} // namespace limb_body

#endif // ANISO_CONFORMAL_TEST_LIMB_BODY_H
