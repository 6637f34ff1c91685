// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Uses an installed Aniso_conformal (find_package) to remesh a CGAL::Surface_mesh: an open curved patch
// (z = 0.3 (x^2 - y^2) over [-1, 1]^2) with a constant anisotropic metric, edges 3 times shorter along x.
// Usage: remesh_Surface_mesh [number_of_vertices] [output.off]

#include <Aniso_conformal/Planar_domain.h>
#include <Aniso_conformal/Tensor_field_metric.h>
#include <Aniso_conformal/remesh_in_domain.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <cstdlib>
#include <iostream>

namespace AC = Aniso_conformal;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;

int main(int argc, char** argv)
{
  const std::size_t n = argc > 1 ? std::size_t(std::atol(argv[1])) : 400;
  const std::string out_file = argc > 2 ? argv[2] : "remeshed_patch.off";
  Mesh patch, out;
  const int g = 41;
  std::vector<Mesh::Vertex_index> v;
  for(int j = 0; j < g; ++j)
    for(int i = 0; i < g; ++i) {
      const double x = -1 + 2.0 * i / (g - 1), y = -1 + 2.0 * j / (g - 1);
      v.push_back(patch.add_vertex(K::Point_3(x, y, 0.3 * (x * x - y * y))));
    }
  for(int j = 0; j + 1 < g; ++j)
    for(int i = 0; i + 1 < g; ++i) {
      const int a = j * g + i;
      patch.add_face(v[a], v[a + 1], v[a + g + 1]);
      patch.add_face(v[a], v[a + g + 1], v[a + g]);
    }
  // one tensor per vertex, indexed like the vertices: M = diag(9, 1, 1) (3 times shorter edges along x)
  std::vector<Eigen::Matrix3d> tensors(num_vertices(patch), Eigen::Vector3d(9, 1, 1).asDiagonal());
  try {
    // the patch is a disk, which remesh() would send to the plane: remesh_in_domain<Planar_domain>
    // is that same pipeline and compiles the plane only (remesh() compiles all four domains)
    const AC::Remeshing_result r = AC::remesh_in_domain<AC::Planar_domain>(patch, AC::Tensor_field_metric(tensors), out,
                                                                           AC::parameters::number_of_vertices(n).random_seed(1u));
    std::cout << num_vertices(out) << " vertices, " << r.corners << " corners kept; in the metric G_avg "
              << r.quality.G_avg << ", theta_min " << r.quality.theta_min << " degrees\n";
  } catch(const AC::Error& e) {
    std::cerr << "remesh failed: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
  if(!CGAL::IO::write_polygon_mesh(out_file, out, CGAL::parameters::stream_precision(17))) return EXIT_FAILURE;
  std::cout << "wrote " << out_file << "\n";
  return EXIT_SUCCESS;
}
