// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_FEATURES_RAGGED_CREASES_H
#define ANISO_CONFORMAL_INTERNAL_FEATURES_RAGGED_CREASES_H

#include <Aniso_conformal/Feature_graph.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/internal/directed_edges.h>
#include <Aniso_conformal/internal/features/fixed_corner_sites.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

// Ragged creases (issue 15, noisy creases; issue 14, the scans of CGAL's data set): the dihedral-angle
// test of detect_features() also fires on edges that are not a discontinuity of the surface. On a noisy
// scan (CGAL's femur, elk, cow) or a crease that runs across the triangles instead of along their edges
// (fandisk_large: a staircase of edges of 20 to 90 degrees), the turning of the surface is spread over
// neighbouring edges, and the edges above the feature angle form fragments: fandisk_large has 205 crease
// components and 419 loose ends at 60 degrees where fandisk has one component, and its 580 corners,
// fixed sites among 2000, cost 0.07 of G_avg with the curvature metric. A sharp crease has flat or gently
// bending triangles on its two sides.
//
// The test: a crease edge is *ragged* when a non-crease edge of one of its two triangles bends by at least
// half the feature angle (the angle between its triangles' normals) and is shorter than the edges of an
// isotropic mesh of the surface with the output's vertex count (noise below the output's resolution,
// whatever the metric: the edges of a coarse polyhedron, a tetrahedron or a star, are longer, and their
// creases stay). A crease component (crease edges connected through their
// vertices) of which ragged edges make 20 % of the length or more is a ragged component and is left out
// with its corners, unless the user marked an edge or a vertex of it. When the ragged components make a
// quarter of the detected crease length or more, the surface is rough: the rest of its creases come from
// the same noise (the test sees one ring only, and on a bumpy surface some fragments have no bending
// neighbour), and every detected component is left out.
//
// Measured at 60 degrees and 2000 output vertices on the 94 meshes of CGAL 5.5's data set with a crease:
// no component of 68 of them is ragged, every CAD and polyhedral model among them (fandisk, pinion,
// oblong, spool, part, rotor, anchor, joint, cactus, the cubes, patch-01, hedra, the tetrahedra, star,
// cheese's 979 curves...); 15 scans
// are rough with their ragged components alone at half their crease length or more (femur, elk, cow, bull,
// man, armadillo, elephant, helmet, homer, mannequin-devil, ChineseDragon-10kv, diplodocus, fandisk_large,
// and the two coarse double tori, whose 60-degree edges are the tessellation of their smooth tubes), and 5
// more between a quarter and a half (camel 29 %, mech-holes-shark 32 %, elephant-with-holes 37 %,
// triceratops 45 %, dino 47 %), where the fragments left by the component test still cost the limb
// models 10 to 25 degrees of their smallest angle; 6 scans keep most of their creases (pig 6 %,
// three_peaks 13 %, hand 17 %, head 20 %, lion 22 %, lion-head 24 % of the length left out).

namespace Aniso_conformal {
namespace internal {

// what without_ragged_crease_components() left out
struct Ragged_creases {
  std::size_t components = 0;  // crease components left out
  double length = 0;           // their length, in the input's units
  bool rough = false;          // every detected component left out (ragged ones made a quarter of the length or more)
};

// The feature graph `g` of `surface` (detected with `feature_angle`) without its ragged crease components
// (see above; `n` the number of output vertices); the components holding a marked edge or vertex are
// kept whole. O(V + E log E).
inline Feature_graph without_ragged_crease_components(const Input_surface& surface, const Feature_graph& g,
                                                      std::size_t n, double feature_angle,
                                                      double corner_angle, const std::vector<std::array<std::size_t, 2>>& marked_edges,
                                                      const std::vector<std::size_t>& marked_vertices, Ragged_creases& left_out)
{
  constexpr double ragged_share = 0.2, rough_share = 0.25;
  left_out = Ragged_creases();
  if(g.crease_edges.empty() || !(feature_angle < 180)) return g;  // at 180 every crease is the user's
  const std::size_t nv = surface.number_of_vertices(), nf = surface.number_of_faces();
  const auto& P = surface.points();
  const auto& F = surface.faces();
  const Directed_edges<std::size_t> out(nv, F, nf);
  std::vector<Eigen::Vector3d> normal(nf);
  double area = 0;
  for(std::size_t f = 0; f < nf; ++f) {
    const Eigen::Vector3d c = (P[F[f][1]] - P[F[f][0]]).cross(P[F[f][2]] - P[F[f][0]]);
    normal[f] = c.normalized();
    area += 0.5 * c.norm();
  }
  // the edge of n vertices of an equilateral mesh of that area (each vertex sqrt(3) / 2 h^2)
  const double h = std::sqrt(2 * area / (std::sqrt(3.0) * double(std::max<std::size_t>(n, 1))));
  auto is_crease = [&](std::size_t a, std::size_t b) {
    const std::array<std::size_t, 2> e = {{std::min(a, b), std::max(a, b)}};
    return std::binary_search(g.crease_edges.begin(), g.crease_edges.end(), e);
  };
  const double bend = 0.5 * feature_angle * 3.14159265358979323846 / 180;
  // an interior edge (a, b), not a crease, that bends by at least `bend` and is shorter than `h`
  auto bends = [&](std::size_t a, std::size_t b) {
    const std::size_t i = out.find(a, b), j = out.find(b, a);
    if(i == out.none || j == out.none || is_crease(a, b)) return false;
    const Eigen::Vector3d &n1 = normal[out.face[i]], &n2 = normal[out.face[j]];
    return std::atan2(n1.cross(n2).norm(), n1.dot(n2)) >= bend && (P[b] - P[a]).norm() < h;
  };
  auto ragged = [&](const std::array<std::size_t, 2>& e) {
    for(const std::size_t d : {out.find(e[0], e[1]), out.find(e[1], e[0])}) {
      if(d == out.none) continue;
      const auto& t = F[out.face[d]];
      std::size_t apex = t[0];  // the triangle's vertex off the crease edge
      for(int k = 0; k < 3; ++k)
        if(std::size_t(t[k]) != e[0] && std::size_t(t[k]) != e[1]) apex = std::size_t(t[k]);
      if(bends(e[0], apex) || bends(e[1], apex)) return true;
    }
    return false;
  };
  Crease_components c(nv, g, marked_edges, marked_vertices);
  std::vector<double> length(nv, 0.0), ragged_length(nv, 0.0);
  for(const auto& e : g.crease_edges) {
    const double l = (P[e[1]] - P[e[0]]).norm();
    length[c.root(e[0])] += l;
    if(ragged(e)) ragged_length[c.root(e[0])] += l;
  }
  double detected = 0, dropped = 0;
  for(std::size_t v = 0; v < nv; ++v)
    if(c.parent[v] == v && length[v] > 0 && !c.user[v]) {
      detected += length[v];
      if(ragged_length[v] >= ragged_share * length[v]) dropped += length[v];
    }
  if(dropped == 0) return g;
  left_out.rough = dropped >= rough_share * detected;
  return without_crease_components(
    surface, g, c, length, [&](std::size_t r) { return left_out.rough || ragged_length[r] >= ragged_share * length[r]; }, corner_angle,
    marked_edges, marked_vertices, left_out.components, left_out.length);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_FEATURES_RAGGED_CREASES_H
