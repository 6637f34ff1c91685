// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The paper's Fig. 8: a 323 x 323 colour photo (the bundled CC0 photo_chelsea_323.png stands in for the
// paper's dolphin) meshed with the image metric of eq. 9, s = 0.1: one background vertex per pixel
// (104329, as in the paper), 3000 output vertices. Edges are short across colour edges. The surface
// optimisation runs on the output (Surface_optimization::ALWAYS): the dual mesh's thin triangles sit
// across colour edges, where the metric changes by 40-100 % between a triangle's corners (theta_min 1.7
// degrees before, 29.4 after; issue 17 item 4).
// Usage: fig8_colour_image [output_folder [number_of_vertices [image]]]

#include "figure_common.h"

#include <Aniso_conformal/IO/read_image.h>
#include <Aniso_conformal/Image_metric.h>
#include <Aniso_conformal/Planar_domain.h>
#include <Aniso_conformal/make_image_background.h>

#include <iostream>

int main(int argc, char** argv)
{
  namespace AC = Aniso_conformal;
  const figure::Arguments a(argc, argv, 3000);
  const std::string path = argc > 3 ? argv[3] : std::string(ANISO_CONFORMAL_DATA_DIR) + "/images/photo_chelsea_323.png";
  try {
    const AC::IO::Image image = AC::IO::read_image(path);
    const AC::Image_metric metric(image, 0.1);
    return figure::reproduce<AC::Planar_domain>("fig8", "Fig. 8, colour image (s = 0.1)", AC::make_image_background(image), metric, a, false,
                                                AC::Surface_optimization::ALWAYS);
  } catch(const AC::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
}
