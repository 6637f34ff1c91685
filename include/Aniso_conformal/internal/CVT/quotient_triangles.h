// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_QUOTIENT_TRIANGLES_H
#define ANISO_CONFORMAL_INTERNAL_CVT_QUOTIENT_TRIANGLES_H

#include <Aniso_conformal/Exceptions.h>

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace Aniso_conformal {
namespace internal {

// The words of a periodic domain's messages: "the flat torus" / "translates" / "the periodic Delaunay
// triangulation", or "the hyperbolic surface" / "images" / "the Delaunay triangulation of the hyperbolic surface".
struct Quotient_names {
  std::string surface, copies, triangulation;
};

// The Delaunay triangulation of a closed quotient surface from that of the sites (points 0 .. ns-1) and
// their copies (point e stands for site original[e]): each triangle of the surface once, the copy whose
// lowest-numbered site is an original, as site triples. Throws Convergence_failure where the sites are too
// few for a simplicial complex (a triangle on two copies of one site, two sites joined by two edges) or
// the count is not `expected`. `faces` are the finite triangles of the triangulation, as point triples.
inline std::vector<std::array<std::size_t, 3>> quotient_triangles(const std::vector<std::array<int, 3>>& faces,
                                                                   const std::vector<int>& original, std::size_t ns,
                                                                   std::size_t expected, const Quotient_names& names)
{
  std::vector<std::array<std::size_t, 3>> tris;
  for(const std::array<int, 3>& e : faces) {
    if(e[0] >= int(ns) && e[1] >= int(ns) && e[2] >= int(ns)) continue;
    std::array<std::size_t, 3> o;
    for(int k = 0; k < 3; ++k) o[std::size_t(k)] = std::size_t(original[std::size_t(e[std::size_t(k)])]);
    if(o[0] == o[1] || o[1] == o[2] || o[2] == o[0])
      throw Convergence_failure("dual mesh: " + std::to_string(ns) + " sites are too few for " + names.surface +
                                    " (a Delaunay triangle meets two " + names.copies + " of site " +
                                    std::to_string(o[0] == o[1] || o[0] == o[2] ? o[0] : o[1]) + ")",
                                0);
    const int k = int(std::min_element(o.begin(), o.end()) - o.begin());
    if(e[std::size_t(k)] < int(ns)) tris.push_back(o);
  }
  if(tris.size() != expected)
    throw Convergence_failure("dual mesh: " + names.triangulation + " has " + std::to_string(tris.size()) +
                                  " triangles instead of " + std::to_string(expected),
                              double(tris.size()));
  // two sites joined by two different edges (through different copies): not a simplicial complex
  std::map<std::pair<std::size_t, std::size_t>, int> edges;
  for(const auto& t : tris)
    for(int k = 0; k < 3; ++k) ++edges[std::minmax(t[std::size_t(k)], t[std::size_t((k + 1) % 3)])];
  for(const auto& e : edges)
    if(e.second != 2)
      throw Convergence_failure("dual mesh: " + std::to_string(ns) + " sites are too few for " + names.surface + " (sites " +
                                    std::to_string(e.first.first) + " and " + std::to_string(e.first.second) +
                                    " are joined by more than one edge)",
                                0);
  return tris;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_QUOTIENT_TRIANGLES_H
