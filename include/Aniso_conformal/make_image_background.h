// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_MAKE_IMAGE_BACKGROUND_H
#define ANISO_CONFORMAL_MAKE_IMAGE_BACKGROUND_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/IO/read_image.h>
#include <Aniso_conformal/Input_surface.h>

#include <Eigen/Core>

#include <string>
#include <vector>

/// \file make_image_background.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * builds the grid `nx` x `ny` over `[0, width] x [0, height]` (z = 0), two counterclockwise triangles
 * per cell with diagonals alternating in a checkerboard (so the grid has no preferred direction).
 * \throws Invalid_input if `nx < 2`, `ny < 2` or a size is not positive
 */
inline Input_surface make_rectangle_background(double width, double height, int nx, int ny)
{
  if(nx < 2 || ny < 2 || !(width > 0) || !(height > 0))
    throw Invalid_input("make_rectangle_background(): needs at least 2 x 2 vertices and a positive size");
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(std::size_t(nx) * std::size_t(ny));
  for(int j = 0; j < ny; ++j)
    for(int i = 0; i < nx; ++i) pts.emplace_back(width * i / (nx - 1), height * j / (ny - 1), 0.0);
  std::vector<Input_surface::Face> faces;
  faces.reserve(2 * std::size_t(nx - 1) * std::size_t(ny - 1));
  for(int j = 0; j + 1 < ny; ++j)
    for(int i = 0; i + 1 < nx; ++i) {
      const std::size_t a = std::size_t(j) * std::size_t(nx) + std::size_t(i), b = a + 1, c = a + std::size_t(nx) + 1,
                        d = a + std::size_t(nx);
      if((i + j) % 2 == 0) { faces.push_back({{a, b, c}}); faces.push_back({{a, c, d}}); }
      else { faces.push_back({{a, b, d}}); faces.push_back({{b, c, d}}); }
    }
  return Input_surface(std::move(pts), std::move(faces));
}

/*!
 * \ingroup PkgAnisoConformalDomains
 * builds the background of an image, as the paper does: one vertex per pixel centre (so a 323 x 323
 * image gives 104329 vertices), at the positions `Image_metric` uses: the rectangle
 * `[0, 1] x [0, (H - 1) / (W - 1)]`.
 */
inline Input_surface make_image_background(const IO::Image& img)
{
  if(img.width < 2 || img.height < 2) throw Invalid_input("image background: the image must be at least 2 x 2 pixels");
  return make_rectangle_background(1.0, double(img.height - 1) / double(img.width - 1), img.width, img.height);
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_MAKE_IMAGE_BACKGROUND_H
