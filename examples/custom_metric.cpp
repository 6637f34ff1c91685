// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Writing a model of AnisotropicMetric: a class with `Eigen::Matrix3d tensor(const Surface_point&) const`.
// This one asks for edges 8 times shorter across the diagonal y = x than along it, near the diagonal,
// and isotropic elements far from it (a boundary-layer-like field).
// Usage: custom_metric [number_of_vertices]

#include <Aniso_conformal/Planar_domain.h>
#include <Aniso_conformal/make_square_background.h>
#include <Aniso_conformal/remesh_in_domain.h>

#include <cmath>
#include <cstdlib>
#include <iostream>

namespace AC = Aniso_conformal;

struct Diagonal_layer_metric {
  double stretch = 8;   // ratio of the edge lengths along and across the layer
  double width = 0.1;   // width of the layer
  Eigen::Matrix3d tensor(const AC::Surface_point& p) const
  {
    const Eigen::Vector3d across(std::sqrt(0.5), -std::sqrt(0.5), 0);  // unit normal of the diagonal
    const double d = across.dot(p.position);                           // signed distance to y = x
    const double s = 1 + (stretch - 1) * std::exp(-(d * d) / (width * width));
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();                       // planar: z parts stay 0
    M.topLeftCorner<2, 2>() = Eigen::Matrix2d::Identity();
    M += (s * s - 1) * across * across.transpose();                    // short edges across the layer
    M(2, 2) = 0;
    return M;
  }
};

int main(int argc, char** argv)
{
  const std::size_t n = argc > 1 ? std::size_t(std::atol(argv[1])) : 800;
  const Diagonal_layer_metric metric;
  try {
    const AC::Input_surface square = AC::make_square_background(metric, n);
    AC::Remeshing_result r;
    const AC::Remeshed_surface out =
        AC::remesh_in_domain<AC::Planar_domain>(square, metric, r, AC::parameters::number_of_vertices(n));
    std::cout << out.points.size() << " vertices; in the metric: G_avg " << r.quality.G_avg << ", theta_min "
              << r.quality.theta_min << ", " << r.quality.percent_below_30 << " % of triangles below 30 degrees\n";
  } catch(const AC::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
