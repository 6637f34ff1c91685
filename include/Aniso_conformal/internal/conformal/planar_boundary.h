// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_PLANAR_BOUNDARY_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_PLANAR_BOUNDARY_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/conformal/layout.h>
#include <Aniso_conformal/internal/conformal/newton_solver.h>
#include <Aniso_conformal/internal/domains/simple_polygon_2.h>
#include <Aniso_conformal/internal/intrinsic/midpoint_split.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

// The boundary of a disk in the plane, for conformal_embedding(): its loop of halfedges, the turning
// angles the layout is given there when it keeps the input's shape (Planar_boundary::KEEP_SHAPE), the
// layout itself and the check that it is an embedding.

namespace Aniso_conformal {
namespace internal {

// The boundary loop of the disk `itri` as its halfedges in order (the domain on their left), starting at
// the first boundary halfedge that leaves a corner, or at the first boundary halfedge when there is no
// corner. Invalid_input if `itri` has no boundary.
inline std::vector<int> boundary_halfedge_loop(const Intrinsic_triangulation& itri, const std::string& who)
{
  int h0 = -1;
  for(int h = 0; h < int(itri.number_of_halfedges()); ++h)
    if(itri.twin(h) < 0) {
      h0 = h;
      break;
    }
  if(h0 < 0) throw Invalid_input(who + ": the background has no boundary");
  int h = h0;
  do {
    if(itri.is_corner(itri.tail(h))) {
      h0 = h;
      break;
    }
    h = itri.outgoing_halfedges(itri.head(h)).front();
  } while(h != h0);
  std::vector<int> loop;
  h = h0;
  do {
    loop.push_back(h);
    h = itri.outgoing_halfedges(itri.head(h)).front();
  } while(h != h0 && loop.size() <= itri.number_of_halfedges());
  return loop;
}

/*
 * The turning angle prescribed at each vertex of the boundary loop `loop` (at the tail of loop[i]) for a
 * layout that keeps the input's shape: the input's own turning angle `pi - input_angle_sum(v)` (its
 * boundary's geodesic curvature on the input surface; exact for a planar input), made to add up to
 * `2 pi` (Gauss-Bonnet for a flat disk). On a planar input they already do, up to rounding; on a curved
 * patch they fall short by the patch's total Gaussian curvature, and the difference is spread over the
 * vertices that are not corners in proportion to their share of the boundary's metric length (a straight
 * run becomes a circular arc), so that corners keep their turning angle.
 *
 * With `convex`, reflex turns are dropped first (negative turning set to 0) and the turns left are
 * scaled to `2 pi`: those of the non-corner vertices, unless the corners alone turn by `2 pi` or more
 * (then only the corners turn, scaled to `2 pi`: a ring cut open along a slit becomes a rectangle).
 * Every turn is then non-negative, so the layout's boundary is a convex polygon, which cannot touch or
 * cross itself. `defect` receives `2 pi` minus the sum of the input's turning angles (radians).
 */
inline std::vector<double> boundary_turning_angles(const Intrinsic_triangulation& itri, const std::vector<int>& loop, bool convex,
                                                   double& defect)
{
  const double pi = 3.14159265358979323846, two_pi = 2 * pi;
  const std::size_t nb = loop.size();
  std::vector<double> turn(nb), weight(nb);
  std::vector<char> corner(nb);
  double sum = 0;
  for(std::size_t i = 0; i < nb; ++i) {
    const int v = itri.tail(loop[i]);
    turn[i] = pi - itri.input_angle_sum(v);
    corner[i] = itri.is_corner(v);
    weight[i] = 0.5 * (itri.length(loop[i]) + itri.length(loop[(i + nb - 1) % nb]));
    sum += turn[i];
  }
  defect = two_pi - sum;
  auto total = [&](int which) {  // which: 0 non-corners, 1 corners, 2 all
    double s = 0;
    for(std::size_t i = 0; i < nb; ++i)
      if(which == 2 || corner[i] == which) s += turn[i];
    return s;
  };
  auto spread = [&](double amount, bool over_all) {  // adds `amount` in proportion to the weights
    double w = 0;
    for(std::size_t i = 0; i < nb; ++i)
      if(over_all || !corner[i]) w += weight[i];
    for(std::size_t i = 0; i < nb; ++i)
      if(over_all || !corner[i]) turn[i] += amount * weight[i] / w;
  };
  const bool has_free = std::find(corner.begin(), corner.end(), char(0)) != corner.end();
  if(!convex) {
    spread(defect, !has_free);
    return turn;
  }
  for(double& t : turn) t = std::max(0.0, t);
  const double at_corners = total(1), elsewhere = total(0);
  if(at_corners > 0 && (at_corners >= two_pi * (1 - 1e-9) || !has_free)) {  // the corners turn all the way alone
    for(std::size_t i = 0; i < nb; ++i) turn[i] = corner[i] ? turn[i] * two_pi / at_corners : 0.0;
  } else if(elsewhere > 0) {
    for(std::size_t i = 0; i < nb; ++i)
      if(!corner[i]) turn[i] *= (two_pi - at_corners) / elsewhere;
  } else {
    spread(two_pi - at_corners, !has_free);
  }
  return turn;
}


// Shifts `u` by the constant that makes the area of the triangulation scaled by `u` equal to its area
// with its own (adjusted) lengths: the scale of a layout whose `u` is free everywhere is arbitrary.
inline void scale_to_adjusted_area(const Intrinsic_triangulation& itri, std::vector<double>& u)
{
  double adjusted = 0, scaled = 0;
  for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
    const std::array<double, 3> l = scaled_face_lengths(itri, int(f), u);
    adjusted += heron_area(itri.length(int(3 * f)), itri.length(int(3 * f + 1)), itri.length(int(3 * f + 2)));
    scaled += heron_area(l[0], l[1], l[2]);
  }
  if(!(adjusted > 0 && scaled > 0 && std::isfinite(scaled)))
    throw Convergence_failure("conformal embedding: the flat metric has no area (" + std::to_string(scaled) + ")", 0);
  const double shift = 0.5 * std::log(adjusted / scaled);  // lengths scale by exp(shift), areas by its square
  for(double& x : u) x += shift;
}

// Lays out the disk `itri` scaled by `emb.u` (breadth-first from face 0, each vertex placed once), checks
// that no triangle is inverted or flat (Convergence_failure), and fills `emb.uv`, the conformal factors
// of paper eq. 6 and the turning angle of the layout at each vertex of the boundary `loop`.
template <typename Embedding>
void lay_out_planar_embedding(const Intrinsic_triangulation& itri, const std::vector<int>& loop, Embedding& emb)
{
  const double pi = 3.14159265358979323846;
  const int nv = int(itri.number_of_vertices()), nf = int(itri.number_of_faces());
  std::vector<std::array<double, 3>> L(static_cast<std::size_t>(nf));
  for(int f = 0; f < nf; ++f) L[std::size_t(f)] = scaled_face_lengths(itri, f, emb.u);
  emb.uv.assign(std::size_t(nv), Eigen::Vector2d::Zero());
  std::vector<char> placed(std::size_t(nv), 0), done;
  unfold_breadth_first(itri, L, 0, Eigen::Vector2d(0, 0), Eigen::Vector2d(L[0][0], 0), [&](int h) { return itri.twin(h) >= 0; },
                       third_point, done, &emb.uv, &placed);
  std::size_t inverted = 0;
  std::vector<double> domain_area(static_cast<std::size_t>(nf)), angle_sum(static_cast<std::size_t>(nv), 0.0);
  for(int f = 0; f < nf; ++f) {
    const auto& c = itri.face_vertices(std::size_t(f));
    const Eigen::Vector2d e1 = emb.uv[std::size_t(c[1])] - emb.uv[std::size_t(c[0])], e2 = emb.uv[std::size_t(c[2])] - emb.uv[std::size_t(c[0])];
    const double a_dom = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    if(!(a_dom > 0)) ++inverted;
    domain_area[std::size_t(f)] = std::max(a_dom, 0.0);
    bool degenerate;
    const std::array<double, 3> a = corner_angles(L[std::size_t(f)], degenerate);
    for(int k = 0; k < 3; ++k) angle_sum[std::size_t(c[k])] += a[std::size_t(k)];
  }
  if(inverted > 0)
    throw Convergence_failure("conformal embedding: the layout has " + std::to_string(inverted) +
                                  " inverted or flat triangles (the metric is too wild, or the surface too thin or sharply folded, for this background: smooth the metric or refine the input)",
                              double(inverted));
  emb.conformal_factor = vertex_conformal_factors(itri, domain_area);
  emb.boundary_turning.assign(std::size_t(nv), 0.0);
  for(int h : loop) emb.boundary_turning[std::size_t(itri.tail(h))] = pi - angle_sum[std::size_t(itri.tail(h))];
}

/*
 * Splits, at their midpoints, the boundary edges of `itri` that an interior vertex encroaches on: the
 * angle of their triangle at its third vertex, an interior one, is obtuse. No intrinsic Delaunay flip
 * can remove such a triangle (its long edge is on the boundary), and the conformal scaling can flatten
 * it onto that edge: the far vertex, scaled down, ends up on the boundary and the layout inverts
 * (CGAL's cylinder_locally_refined.off, isotropic: thin triangles along the boundary with angles of
 * 96 degrees at an interior vertex). As in Ruppert's refinement, the edges are split and `itri` made
 * intrinsic Delaunay again until no boundary edge is encroached on: each split halves a boundary edge and
 * the interior vertices stay where they are, so this ends once the boundary edges are shorter than twice
 * the distance from the interior vertices to the boundary; `max_rounds` bounds the rounds anyway.
 *
 * The lengths stay those of `itri`'s flat metric: the halves of a split edge, and the median of its
 * triangle (Apollonius). The new vertex is the midpoint of a boundary edge, a segment of an input
 * boundary edge, so a point of the input: its barycentric coordinates are the mean of its ends' (the
 * three largest weights kept) and its metric square root the mean of theirs. `itri` must be intrinsic
 * Delaunay for its lengths (flips are made with `flips_per_edge`). Returns the number of splits.
 */
inline std::size_t split_encroached_boundary_edges(Intrinsic_triangulation& itri, std::size_t flips_per_edge, const std::string& who,
                                                   int max_rounds = 32)
{
  std::size_t splits = 0;
  for(int round = 0; round < max_rounds; ++round) {
    std::vector<std::pair<int, int>> encroached;  // ends (tail, head) of the boundary halfedges
    for(int h = 0; h < int(itri.number_of_halfedges()); ++h) {
      if(itri.twin(h) >= 0 || itri.is_boundary_vertex(itri.opposite_vertex(h))) continue;
      const double ab = itri.length(h), bc = itri.length(itri.next(h)), ca = itri.length(itri.prev(h));
      if(ab * ab > bc * bc + ca * ca) encroached.emplace_back(itri.tail(h), itri.head(h));
    }
    if(encroached.empty()) break;
    for(const auto& e : encroached) {
      const int h = itri.find_halfedge(e.first, e.second);
      if(h < 0) continue;
      const int a = e.first, b = e.second;
      const double ab = itri.length(h), bc = itri.length(itri.next(h)), ca = itri.length(itri.prev(h));
      // the point: the mean of the ends' barycentric coordinates over the input vertices
      const Surface_point sp = midpoint_surface_point(itri, a, b);
      const int m = itri.split(h, sp, 0.5 * (itri.Q(a) + itri.Q(b)));
      // the new halfedges: a->m and m->b on the boundary, m->c inside (Intrinsic_triangulation::split)
      for(int o : itri.outgoing_halfedges(m)) {
        const int x = itri.head(o);
        if(x == a || x == b) itri.set_length(o, 0.5 * ab);
        else itri.set_length(o, 0.5 * std::sqrt(std::max(0.0, 2 * bc * bc + 2 * ca * ca - ab * ab)));
      }
      for(int o : itri.outgoing_halfedges(m))  // the boundary halfedge that enters m has no outgoing twin
        if(itri.twin(itri.prev(o)) < 0) itri.set_length(itri.prev(o), 0.5 * ab);
      ++splits;
    }
    make_intrinsic_delaunay(itri, flips_per_edge, who);
  }
  return splits;
}

// `true` if the layout `uv` of the boundary `loop` of `itri` is a simple counterclockwise polygon whose
// non-adjacent edges are farther apart than `relative_margin` times its diameter: then the layout, whose
// triangles are all positively oriented, is an embedding of the disk
inline bool planar_boundary_is_embedded(const std::vector<Eigen::Vector2d>& uv, const Intrinsic_triangulation& itri,
                                        const std::vector<int>& loop, double relative_margin)
{
  std::vector<Eigen::Vector2d> polygon;
  polygon.reserve(loop.size());
  Eigen::Vector2d lo = uv[std::size_t(itri.tail(loop[0]))], hi = lo;
  for(int h : loop) {
    polygon.push_back(uv[std::size_t(itri.tail(h))]);
    lo = lo.cwiseMin(polygon.back());
    hi = hi.cwiseMax(polygon.back());
  }
  return is_simple_counterclockwise(polygon, relative_margin * (hi - lo).norm());
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_PLANAR_BOUNDARY_H
