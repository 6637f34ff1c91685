// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Sharp features and the final surface optimisation (issue 15 items 1-2, issue 17 item 3): finds the
// creases and corners of a closed surface, adds a user's own, remeshes keeping the corners, measures what
// the output keeps, then runs the surface optimisation in the metric as a stage of its own.
// Usage: sharp_features [mesh.off [features.txt [number_of_vertices]]]
//   without a mesh: a 2 x 1 x 1 box made here, with the centre of its top face marked as a corner.
//   features.txt: one feature per line, two vertex indices for a crease edge, one for a corner.

#include <Aniso_conformal/Feature_graph.h>
#include <Aniso_conformal/IO/read_feature_file.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/measure_features.h>
#include <Aniso_conformal/optimize_surface_mesh.h>
#include <Aniso_conformal/remesh.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace AC = Aniso_conformal;

namespace {

// the closed box [0, 2] x [0, 1] x [0, 1], each face a k x k grid of squares split into two triangles
AC::Input_surface make_box(int k)
{
  std::vector<Eigen::Vector3d> points;
  std::vector<AC::Input_surface::Face> faces;
  std::map<std::array<long, 3>, std::size_t> index;  // vertices shared along the box's edges
  auto vertex = [&](const Eigen::Vector3d& p) {
    const std::array<long, 3> key{{std::lround(p.x() * 4 * k), std::lround(p.y() * 4 * k), std::lround(p.z() * 4 * k)}};
    const auto it = index.find(key);
    if(it != index.end()) return it->second;
    points.push_back(p);
    return index[key] = points.size() - 1;
  };
  const Eigen::Vector3d size(2, 1, 1);
  for(int axis = 0; axis < 3; ++axis)
    for(int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      auto at = [&](int i, int j) {
        Eigen::Vector3d p;
        p[axis] = side * size[axis];
        p[u] = size[u] * i / k;
        p[v] = size[v] * j / k;
        return vertex(p);
      };
      for(int i = 0; i < k; ++i)
        for(int j = 0; j < k; ++j) {
          const std::size_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
          if(side == 1) {  // outward normals: +axis on the far side
            faces.push_back({{a, b, c}});
            faces.push_back({{a, c, d}});
          } else {
            faces.push_back({{a, c, b}});
            faces.push_back({{a, d, c}});
          }
        }
    }
  return AC::Input_surface(points, faces);
}

} // namespace

int main(int argc, char** argv)
{
  try {
    AC::Repair_report repairs;
    const bool own = argc > 1;
    const AC::Input_surface surface = own ? AC::IO::read_triangle_mesh(argv[1], repairs) : make_box(8);
    AC::IO::Marked_features marked;
    if(argc > 2) {
      marked = AC::IO::read_feature_file(argv[2], repairs);  // the file's indices, through the repairs
    } else if(!own) {
      for(std::size_t v = 0; v < surface.number_of_vertices(); ++v)  // the centre of the top face
        if((surface.points()[v] - Eigen::Vector3d(1, 0.5, 1)).norm() < 1e-12) marked.vertices.push_back(v);
    }
    const std::size_t n = argc > 3 ? std::size_t(std::atol(argv[3])) : 800;

    // 1. the feature graph: creases above 60 degrees, corners where 1 or 3+ meet, the user's on top
    const AC::Feature_graph g = AC::detect_features(surface, 60, 30, marked.edges, marked.vertices);
    std::cout << "input: " << g.crease_edges.size() << " crease edges in " << g.curves.size() << " curves (length "
              << g.crease_length() << "), " << g.corners.size() << " corners\n";

    // 2. remesh, the corners kept as fixed sites; the surface optimisation left to step 4
    const AC::Uniform_metric metric;
    AC::Remeshing_result result;
    AC::Remeshed_surface out =
      AC::remesh(surface, metric, result,
                 AC::parameters::number_of_vertices(n).feature_edges(marked.edges).feature_vertices(marked.vertices).surface_optimization(
                   AC::Surface_optimization::OFF));

    // 3. what the output keeps (remesh() measured the same into result.features)
    const AC::Feature_report kept = AC::measure_features(surface, g, out.points, out.faces);
    std::cout << "output: " << out.points.size() << " vertices, " << kept.corners_kept << " of " << kept.corners
              << " corners kept, " << 100 * kept.covered_share << " % of the crease length on output edges, Hausdorff "
              << result.hausdorff_distance_relative << " of the diagonal\n";

    // 4. the final optimisation in the metric (edge flips, moves along the input; corners stay)
    const AC::Surface_optimization_report opt = AC::optimize_surface_mesh(surface, metric, out, 5);
    std::cout << "surface optimisation: " << opt.rounds << " rounds, " << opt.flips << " flips, " << opt.relocations
              << " moves, " << opt.fixed_vertices << " vertices fixed; G_avg " << opt.G_avg_before << " -> " << opt.G_avg_after
              << ", theta_min " << opt.theta_min_before << " -> " << opt.theta_min_after << "\n";
    std::cout << "corners still kept: " << AC::measure_features(surface, g, out.points, out.faces).corners_kept << "\n";
    AC::IO::write_polygon_soup("sharp_features.off", out.points, out.faces);
    std::cout << "wrote sharp_features.off\n";
  } catch(const AC::Error& e) {
    std::cerr << "sharp_features: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
