// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CONFORMAL_LAYOUT_H
#define ANISO_CONFORMAL_INTERNAL_CONFORMAL_LAYOUT_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/intrinsic/breadth_first_faces.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

// The pieces of stage 3 that every domain shares once its metric is solved: the breadth-first layout of
// the faces in the domain, the conformal factor of paper eq. 6, and the checks that the triangulation is
// a closed surface of the expected topology.

namespace Aniso_conformal {
namespace internal {

/*
 * Lays out the faces of `itri` breadth-first from face `first`, whose halfedge 0 goes from `p0` to `p1`,
 * crossing only the halfedges for which `may_cross(h)` holds (never a boundary halfedge): each face is
 * placed across the edge by which it is first reached, its two corners there copied from its
 * neighbour, the third constructed by `third(p, q, l_pr, l_qr)` (the point left of p->q at those
 * distances) from the face's lengths `L[f]` (`L[f][k]`: halfedge 3f + k). Returns the corners of every
 * face (`done[f]` says which faces were reached).
 *
 * With `vertex_position` (and `placed`, both sized to the vertices) each vertex is placed once, by the
 * first face that reaches it, and later faces reuse that position: the layout of a disk. Without them
 * every face keeps its own corners: the layout of a surface cut along the edges not crossed, whose
 * vertices on the cut have one position per side.
 */
template <typename Point, typename MayCross, typename ThirdPoint>
std::vector<std::array<Point, 3>> unfold_breadth_first(const Intrinsic_triangulation& itri, const std::vector<std::array<double, 3>>& L,
                                                       int first, const Point& p0, const Point& p1, MayCross may_cross,
                                                       ThirdPoint third, std::vector<char>& done,
                                                       std::vector<Point>* vertex_position = nullptr,
                                                       std::vector<char>* placed = nullptr)
{
  const std::size_t nf = itri.number_of_faces();
  std::vector<std::array<Point, 3>> corners(nf, {{p0, p0, p0}});
  done.assign(nf, 0);
  // the third corner of face g, across its halfedge j from corners a (tail) and b (head)
  auto place_third = [&](int g, int j) {
    auto& c = corners[std::size_t(g)];
    const int w = itri.opposite_vertex(3 * g + j);
    if(vertex_position && (*placed)[std::size_t(w)]) {
      c[std::size_t((j + 2) % 3)] = (*vertex_position)[std::size_t(w)];
      return;
    }
    c[std::size_t((j + 2) % 3)] = third(c[std::size_t(j)], c[std::size_t((j + 1) % 3)], L[std::size_t(g)][std::size_t((j + 2) % 3)],
                                        L[std::size_t(g)][std::size_t((j + 1) % 3)]);
    if(vertex_position) {
      (*vertex_position)[std::size_t(w)] = c[std::size_t((j + 2) % 3)];
      (*placed)[std::size_t(w)] = 1;
    }
  };
  {
    auto& c = corners[std::size_t(first)];
    c[0] = p0;
    c[1] = p1;
    if(vertex_position) {
      const auto& v = itri.face_vertices(std::size_t(first));
      (*vertex_position)[std::size_t(v[0])] = p0;
      (*vertex_position)[std::size_t(v[1])] = p1;
      (*placed)[std::size_t(v[0])] = (*placed)[std::size_t(v[1])] = 1;
    }
    place_third(first, 0);
  }
  // each face across the edge by which the breadth-first search first reached it, in the order reached
  const Face_breadth_first bfs = breadth_first_faces(itri, first, may_cross);
  for(int g : bfs.order) {
    done[std::size_t(g)] = 1;
    const int h = bfs.via[std::size_t(g)];
    if(h < 0) continue;  // the first face
    const int f = Intrinsic_triangulation::face(h), k = h % 3, j = itri.twin(h) % 3;
    auto& c = corners[std::size_t(g)];
    c[std::size_t(j)] = corners[std::size_t(f)][std::size_t((k + 1) % 3)];  // tail(twin) = head(h)
    c[std::size_t((j + 1) % 3)] = corners[std::size_t(f)][std::size_t(k)];  // head(twin) = tail(h)
    place_third(g, j);
  }
  return corners;
}

// The conformal factor of paper eq. 6 at every vertex: the area of the triangles around it with the
// adjusted lengths (Heron) over their area in the domain, `domain_area[f]` (a face of area 0 there, or
// a layout that failed, gives an infinite or NaN factor: the caller checks the layout first).
inline std::vector<double> vertex_conformal_factors(const Intrinsic_triangulation& itri, const std::vector<double>& domain_area)
{
  const std::size_t nv = itri.number_of_vertices(), nf = itri.number_of_faces();
  std::vector<double> adjusted(nv, 0.0), domain(nv, 0.0);
  for(std::size_t f = 0; f < nf; ++f) {
    const auto& c = itri.face_vertices(f);
    const double a = itri.length(int(3 * f)), b = itri.length(int(3 * f + 1)), d = itri.length(int(3 * f + 2)), s = (a + b + d) / 2;
    const double a_adj = std::sqrt(std::max(0.0, s * (s - a) * (s - b) * (s - d)));
    for(int k = 0; k < 3; ++k) {
      adjusted[std::size_t(c[k])] += a_adj;
      domain[std::size_t(c[k])] += domain_area[f];
    }
  }
  std::vector<double> cf(nv);
  for(std::size_t v = 0; v < nv; ++v) cf[v] = adjusted[v] / domain[v];
  return cf;
}

/*
 * The genus of `itri`, which must be a closed surface whose genus `accepts`: Invalid_input naming `who`
 * and `domain` ("the sphere") if it has a boundary, or if its genus is not accepted (`needs` says what
 * is, "genus 0").
 */
template <typename Accepts>
int require_closed_surface(const Intrinsic_triangulation& itri, const std::string& who, const std::string& domain,
                           Accepts accepts, const std::string& needs)
{
  const int nh = int(itri.number_of_halfedges());
  for(int h = 0; h < nh; ++h)
    if(itri.is_boundary_edge(h))
      throw Invalid_input(who + ": the triangulation has a boundary; " + domain + " needs a closed surface");
  const int chi = int(itri.number_of_vertices()) - nh / 2 + int(itri.number_of_faces());
  if(chi % 2 != 0 || !accepts((2 - chi) / 2))
    throw Invalid_input(who + ": the surface has Euler characteristic " + std::to_string(chi) +
                        (chi % 2 == 0 ? " (genus " + std::to_string((2 - chi) / 2) + ")" : std::string()) + "; " + domain +
                        " needs a closed surface of " + needs);
  return (2 - chi) / 2;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CONFORMAL_LAYOUT_H
