// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The paper's Fig. 6: the unit square with M = diag(s1^2, s2^2), s1 = 1/(0.031 + x), s2 = 1/(0.031 + y)
// (stretch ratio up to 33), 1000 vertices, 100 L-BFGS iterations.
// Usage: fig6_square [output_folder [number_of_vertices]]

#include "figure_common.h"

#include <Aniso_conformal/Analytic_metric_2.h>
#include <Aniso_conformal/Paper_metrics.h>
#include <Aniso_conformal/Planar_domain.h>
#include <Aniso_conformal/make_square_background.h>

#include <iostream>

int main(int argc, char** argv)
{
  namespace AC = Aniso_conformal;
  const figure::Arguments a(argc, argv, 1000);
  try {
    const auto metric = AC::make_analytic_metric_2(AC::Fig6_metric());
    const AC::Input_surface square = AC::make_square_background(metric, a.vertices);  // graded like the metric
    return figure::reproduce<AC::Planar_domain>("fig6", "Fig. 6, unit square", square, metric, a, true);
  } catch(const AC::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
}
