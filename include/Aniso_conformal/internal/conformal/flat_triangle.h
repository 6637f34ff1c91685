// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_FLAT_TRIANGLE_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_FLAT_TRIANGLE_H

#include <array>

namespace Aniso_conformal {
namespace internal {

// The convex extension of the discrete conformal energies (Bobenko, Pinkall and Springborn): a triangle
// with side lengths l (l[k] from corner k to k+1) that violates the triangle inequality gets the angles
// of the flat triangle, pi at the corner facing the long side and 0 elsewhere; returns true then.
inline bool flat_triangle_angles(const std::array<double, 3>& l, std::array<double, 3>& angle)
{
  for(int k = 0; k < 3; ++k)
    if(l[(k + 1) % 3] >= l[k] + l[(k + 2) % 3]) {
      angle = {{0, 0, 0}};
      angle[k] = 3.14159265358979323846;
      return true;
    }
  return false;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_FLAT_TRIANGLE_H
