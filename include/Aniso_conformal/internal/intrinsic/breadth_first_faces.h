// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_INTRINSIC_BREADTH_FIRST_FACES_H
#define ANISO_CONFORMAL_INTERNAL_INTRINSIC_BREADTH_FIRST_FACES_H

#include <Aniso_conformal/Intrinsic_triangulation.h>

#include <cstddef>
#include <vector>

namespace Aniso_conformal {
namespace internal {

// A breadth-first search over the faces from `start`, across the halfedges `may_cross` allows: the faces
// in the order reached, their distance (in faces; -1 if not reached) and the halfedge, in the face it
// came from, across which each was reached (-1 for `start`). Serves the cotree and the layouts.
struct Face_breadth_first {
  std::vector<int> order, distance, via;
  std::vector<double> length;  // filled by the searches that measure lengths (tree_cotree()), else empty
};

template <typename MayCross>
Face_breadth_first breadth_first_faces(const Intrinsic_triangulation& itri, int start, MayCross may_cross)
{
  Face_breadth_first b;
  b.distance.assign(itri.number_of_faces(), -1);
  b.via.assign(itri.number_of_faces(), -1);
  b.order.reserve(itri.number_of_faces());
  b.order.push_back(start);
  b.distance[std::size_t(start)] = 0;
  for(std::size_t next = 0; next < b.order.size(); ++next) {
    const int f = b.order[next];
    for(int k = 0; k < 3; ++k) {
      const int h = 3 * f + k;
      if(!may_cross(h)) continue;
      const int g = Intrinsic_triangulation::face(itri.twin(h));
      if(b.distance[std::size_t(g)] >= 0) continue;
      b.distance[std::size_t(g)] = b.distance[std::size_t(f)] + 1;
      b.via[std::size_t(g)] = h;
      b.order.push_back(g);
    }
  }
  return b;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_INTRINSIC_BREADTH_FIRST_FACES_H
