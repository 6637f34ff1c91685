// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The BGL entry point on CGAL::Polyhedron_3: remeshes a planar mesh of the unit square with the
// paper's Fig. 6 metric and writes the result next to the binary.
// Usage: remesh_Polyhedron_3 [number_of_vertices]

#include <Aniso_conformal/Analytic_metric_2.h>
#include <Aniso_conformal/Paper_metrics.h>
#include <Aniso_conformal/make_square_background.h>
#include <Aniso_conformal/remesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <cstdlib>
#include <iostream>

namespace AC = Aniso_conformal;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Polyhedron_3<K> Polyhedron;

int main(int argc, char** argv)
{
  const std::size_t n = argc > 1 ? std::size_t(std::atol(argv[1])) : 500;
  const auto metric = AC::make_analytic_metric_2(AC::Fig6_metric());

  // any planar triangle mesh of the square will do; here the library's own background builder
  const AC::Input_surface square = AC::make_square_background(metric, n);
  Polyhedron input, output;
  std::vector<K::Point_3> points;
  for(const auto& p : square.points()) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<std::size_t>> faces;
  for(const auto& f : square.faces()) faces.push_back({f[0], f[1], f[2]});
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, input);

  try {
    const AC::Remeshing_result r =
        AC::remesh(input, metric, output, AC::parameters::number_of_vertices(n).number_of_iterations(100u));
    std::cout << "Polyhedron_3: " << num_vertices(output) << " vertices, G_avg " << r.quality.G_avg << ", theta_min "
              << r.quality.theta_min << " degrees\n";
  } catch(const AC::Error& e) {
    std::cerr << "remesh failed: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
  if(!CGAL::IO::write_polygon_mesh("remeshed_polyhedron.off", output, CGAL::parameters::stream_precision(17)))
    return EXIT_FAILURE;
  std::cout << "wrote remeshed_polyhedron.off\n";
  return EXIT_SUCCESS;
}
