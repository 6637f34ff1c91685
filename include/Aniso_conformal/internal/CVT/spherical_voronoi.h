// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_SPHERICAL_VORONOI_H
#define ANISO_CONFORMAL_INTERNAL_CVT_SPHERICAL_VORONOI_H

#include <Aniso_conformal/internal/CVT/clip_integrate.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>

#include <CGAL/Delaunay_triangulation_on_sphere_2.h>
#include <CGAL/Delaunay_triangulation_on_sphere_traits_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_on_sphere_face_base_2.h>
#include <CGAL/Triangulation_on_sphere_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

// The restricted Voronoi diagram of sites on the unit sphere over a chordal (flat-faced) background.
// For unit sites the bisector of two sites is a plane through the origin, so a chordal triangle is cut
// by a cell exactly as its central projection is cut by the spherical cell. Each triangle is integrated
// in an orthonormal frame of its own plane, which turns the problem into the planar one of
// clip_integrate.h: with y = o + u e1 + v e2 and a site x = o + s e1 + t e2 + h n,
// |y - x|^2 = |(u, v) - (s, t)|^2 + h^2, and the bisectors stay half-planes of the frame.

namespace Aniso_conformal {
namespace internal {

// a chordal background triangle: the planar triangle `flat` (with its density and precomputed moments)
// in the orthonormal frame (o, e1, e2) of its plane, n = e1 x e2 (outward for a counterclockwise triangle)
struct Spherical_background_triangle {
  Background_triangle flat;
  std::array<Eigen::Vector3d, 3> p;  // corners in space
  std::array<int, 3> v{{-1, -1, -1}};   // and their indices in the background's vertex list
  Eigen::Vector3d g = Eigen::Vector3d::Zero();  // centroid in space
  Eigen::Vector3d o = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::Zero(), e2 = Eigen::Vector3d::Zero(),
                  n = Eigen::Vector3d::Zero();
};

// mass, first moment (in space) and energy of a cell
struct Spherical_cell_accumulator {
  double mass = 0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  double energy = 0;
  void operator+=(const Spherical_cell_accumulator& o) { mass += o.mass; moment += o.moment; energy += o.energy; }
};

// The frame of the triangle p (origin at p[0], e1 along p[0]p[1]); false if the triangle is degenerate
// (zero or non-finite area), which then carries no mass.
inline bool make_spherical_background_triangle(const std::array<Eigen::Vector3d, 3>& p, const std::array<double, 3>& rho,
                                               int face, Spherical_background_triangle& T)
{
  T.p = p;
  T.g = (p[0] + p[1] + p[2]) / 3.0;
  const Eigen::Vector3d a = p[1] - p[0], b = p[2] - p[0];
  const Eigen::Vector3d c = a.cross(b);
  const double la = a.norm(), lc = c.norm();
  if(!(la > 0) || !(lc > 0) || !std::isfinite(lc)) return false;
  T.o = p[0];
  T.e1 = a / la;
  T.n = c / lc;
  T.e2 = T.n.cross(T.e1);
  const std::array<Eigen::Vector2d, 3> q = {
      {Eigen::Vector2d::Zero(), Eigen::Vector2d(la, 0.0), Eigen::Vector2d(b.dot(T.e1), b.dot(T.e2))}};
  T.flat = make_background_triangle(q, rho, face);
  return T.flat.area > 0 && std::isfinite(T.flat.mass);
}

// indices of `points` sorted along a 3D Morton curve over the cube [-1, 1]^3 (unit vectors, centroids of
// chordal triangles): nearby items are processed together, as morton_order() does in the plane
inline std::vector<std::size_t> morton_order_3(const std::vector<Eigen::Vector3d>& points)
{
  auto spread = [](std::uint64_t x) {  // 21 bits, two zeros between each
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
  };
  auto quantise = [](double v) {
    const double t = std::isfinite(v) ? std::min(1.0, std::max(0.0, 0.5 * (v + 1.0))) : 0.0;
    return std::uint64_t(t * 2097151.0);
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> key(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& g = points[i];
    key[i] = {spread(quantise(g.x())) | spread(quantise(g.y())) << 1 | spread(quantise(g.z())) << 2, i};
  }
  std::sort(key.begin(), key.end());
  std::vector<std::size_t> order(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) order[i] = key[i].second;
  return order;
}

// CGAL's Delaunay triangulation on the unit sphere with the site index as vertex info
typedef CGAL::Exact_predicates_inexact_constructions_kernel Sphere_kernel;
typedef CGAL::Delaunay_triangulation_on_sphere_traits_2<Sphere_kernel> Sphere_delaunay_traits;
typedef CGAL::Triangulation_on_sphere_vertex_base_2<Sphere_delaunay_traits> Sphere_vertex_base;
typedef CGAL::Triangulation_vertex_base_with_info_2<int, Sphere_delaunay_traits, Sphere_vertex_base> Sphere_vertex_base_with_info;
typedef CGAL::Triangulation_on_sphere_face_base_2<Sphere_delaunay_traits> Sphere_face_base;
typedef CGAL::Triangulation_data_structure_2<Sphere_vertex_base_with_info, Sphere_face_base> Sphere_tds;
typedef CGAL::Delaunay_triangulation_on_sphere_2<Sphere_delaunay_traits, Sphere_tds> Sphere_delaunay_triangulation;

// The Delaunay triangulation of unit sites. handle[i] is site i's vertex; a default handle (a point CGAL
// finds off the sphere: not finite, or not normalised) or one whose info differs (a site closer than
// CGAL's separation bound 2^-23 to an earlier one) marks a site that has no vertex, hence no cell.
struct Sphere_delaunay {
  Sphere_delaunay_triangulation dt;
  std::vector<Sphere_delaunay_triangulation::Vertex_handle> handle;

  bool has_vertex(std::size_t i) const
  {
    return handle[i] != Sphere_delaunay_triangulation::Vertex_handle() && handle[i]->info() == int(i);
  }
};

// inserts the (unit) sites in Morton order, each located from the previous one
inline void build_sphere_delaunay(const std::vector<Eigen::Vector3d>& unit_sites, Sphere_delaunay& sd)
{
  typedef Sphere_delaunay_triangulation::Vertex_handle Vertex_handle;
  sd.dt.clear();
  sd.handle.assign(unit_sites.size(), Vertex_handle());
  Sphere_delaunay_triangulation::Face_handle hint;
  for(std::size_t i : morton_order_3(unit_sites)) {
    const Eigen::Vector3d& x = unit_sites[i];
    if(!x.allFinite()) continue;
    const std::size_t before = sd.dt.number_of_vertices();
    const Vertex_handle v = sd.dt.insert(Sphere_kernel::Point_3(x.x(), x.y(), x.z()), hint);
    if(v == Vertex_handle()) continue;
    if(sd.dt.number_of_vertices() > before) v->info() = int(i);  // else too close to the site v holds
    sd.handle[i] = v;
    if(v->face() != Sphere_delaunay_triangulation::Face_handle()) hint = v->face();
  }
}

// Delaunay neighbours in CSR form (neighbours of i: nbr[start[i] .. start[i+1])). They must include every
// Voronoi neighbour; extra ones cost time only. With all sites in one hemisphere CGAL closes the hole with
// "ghost" faces whose edges are not Delaunay: the missing Voronoi neighbours are then among the sites on
// the hole's border (the silhouette of the convex hull seen from the centre), which are all joined. Below
// dimension 2 (fewer than three sites, or all on one great circle) every pair is joined.
inline void sphere_delaunay_neighbours(const Sphere_delaunay& sd, std::vector<int>& start, std::vector<int>& nbr)
{
  const std::size_t ns = sd.handle.size();
  start.assign(ns + 1, 0);
  nbr.clear();
  std::vector<int> border;
  std::vector<char> on_border(ns, 0);
  if(sd.dt.dimension() == 2)
    for(auto f = sd.dt.all_faces_begin(); f != sd.dt.all_faces_end(); ++f)
      if(sd.dt.is_ghost(f))
        for(int k = 0; k < 3; ++k) {
          const int v = f->vertex(k)->info();
          if(!on_border[std::size_t(v)]) border.push_back(v);
          on_border[std::size_t(v)] = 1;
        }
  std::sort(border.begin(), border.end());
  for(std::size_t i = 0; i < ns; ++i) {
    start[i] = int(nbr.size());
    if(!sd.has_vertex(i)) continue;
    if(sd.dt.dimension() == 2) {
      auto c = sd.dt.incident_vertices(sd.handle[i]), done = c;
      do {
        nbr.push_back(c->info());
      } while(++c != done);
      if(on_border[i])
        for(int b : border)
          if(b != int(i)) nbr.push_back(b);
    } else {
      for(std::size_t j = 0; j < ns; ++j)
        if(j != i && sd.has_vertex(j)) nbr.push_back(int(j));
    }
  }
  start[ns] = int(nbr.size());
}

// The cell geometry of the sphere (integrate_restricted_voronoi()): each chordal triangle is clipped
// in its own frame, where the bisector of unit sites s and n, 2 y.(x_n - x_s) <= |x_n|^2 - |x_s|^2, is a
// half-plane; it is first tested on the corners in space (most bisectors of a cell miss a small
// triangle). A triangle whose three corners have the same nearest site (`owner`) lies in that site's
// convex cell and is added whole; the walk for the others goes from the nearest site of the first corner
// to the site nearest to the centroid, whose cell meets the triangle in a piece of positive area even
// on a tie (the plane of T does not pass through the centre, so it cuts the cell's cone through the
// centroid), which a corner's nearest site does not guarantee (a corner on a Voronoi vertex).
class Spherical_cell_geometry {
public:
  typedef Spherical_cell_accumulator Accumulator;
  Spherical_cell_geometry(const std::vector<Spherical_background_triangle>& tri, const std::vector<Eigen::Vector3d>& sites,
                          const std::vector<double>& squared_norm, const std::vector<int>& owner)
    : m_tri(tri), m_sites(sites), m_sq(squared_norm), m_owner(owner)
  {}
  std::size_t number_of_triangles() const { return m_tri.size(); }
  const Background_triangle& triangle(std::size_t f) const { return m_tri[f].flat; }
  bool in_one_cell(std::size_t f, int& s) const
  {
    const auto& v = m_tri[f].v;
    s = m_owner[std::size_t(v[0])];
    return s == m_owner[std::size_t(v[1])] && s == m_owner[std::size_t(v[2])];
  }
  bool in_cell_of(std::size_t, int) const { return false; }  // in_one_cell() covers it
  int walk_start(std::size_t f, int) const { return m_owner[std::size_t(m_tri[f].v[0])]; }
  const Eigen::Vector3d& walk_target(std::size_t f) const { return m_tri[f].g; }
  double distance(int s, const Eigen::Vector3d& y) const { return -m_sites[std::size_t(s)].dot(y); }  // unit sites
  Bisector bisector(std::size_t f, int s, int n, Eigen::Vector2d& a, double& b) const
  {
    // y nearer to s than to n:  2 y.(x_n - x_s) <= |x_n|^2 - |x_s|^2
    const Spherical_background_triangle& S = m_tri[f];
    const Eigen::Vector3d w = m_sites[std::size_t(n)] - m_sites[std::size_t(s)];
    const double c = m_sq[std::size_t(n)] - m_sq[std::size_t(s)];
    if(2 * S.p[0].dot(w) <= c && 2 * S.p[1].dot(w) <= c && 2 * S.p[2].dot(w) <= c) return Bisector::misses;
    // the half-plane in the frame, y = o + u e1 + v e2
    a = Eigen::Vector2d(2 * S.e1.dot(w), 2 * S.e2.dot(w));
    b = c - 2 * S.o.dot(w);
    return Bisector::meets;
  }
  void add_piece(std::size_t f, int s, const Small_polygon& poly, Accumulator& acc) const
  {
    const Background_triangle& T = m_tri[f].flat;
    Cell_accumulator A;
    integrate_polygon(poly.p, std::size_t(poly.n), T.r0, T.rg, foot(f, s), A);
    add(f, s, A, acc);
  }
  void add_whole(std::size_t f, int s, Accumulator& acc) const { add(f, s, whole_triangle_moments(m_tri[f].flat, foot(f, s)), acc); }

private:
  // the site's foot on the plane of T, in T's frame
  Eigen::Vector2d foot(std::size_t f, int s) const
  {
    const Spherical_background_triangle& S = m_tri[f];
    const Eigen::Vector3d ds = m_sites[std::size_t(s)] - S.o;
    return Eigen::Vector2d(S.e1.dot(ds), S.e2.dot(ds));
  }
  // a piece's integrals in the frame, to space: |y - x|^2 = |(u, v) - foot|^2 + h^2
  void add(std::size_t f, int s, const Cell_accumulator& A, Accumulator& C) const
  {
    const Spherical_background_triangle& S = m_tri[f];
    const Eigen::Vector3d ds = m_sites[std::size_t(s)] - S.o;
    const double hs = S.n.dot(ds);  // the site's height over the plane
    C.mass += A.mass;
    C.moment += A.mass * S.o + A.mx * S.e1 + A.my * S.e2;
    C.energy += A.energy + hs * hs * A.mass;
  }

  const std::vector<Spherical_background_triangle>& m_tri;
  const std::vector<Eigen::Vector3d>& m_sites;
  const std::vector<double>& m_sq;
  const std::vector<int>& m_owner;
};

/*
 * Integrates the density of the chordal triangles `tri` (in Morton order; their corners index `vertices`,
 * also in Morton order) over the Voronoi cells of the unit `sites`: out[i] receives the mass, the first
 * moment and the energy about sites[i] of the part of the triangles nearer to sites[i] than to any other
 * site. `first` is a site that has a vertex in the Delaunay triangulation.
 *
 * First the site nearest to every background vertex, by a greedy walk on the Delaunay graph (exact: the
 * graph holds the edges of the convex hull of the sites, on which a linear function has no local maximum
 * but the global one), in fixed chunks; then integrate_restricted_voronoi() with the sphere's cell
 * geometry. The result does not depend on the number of threads.
 */
inline void integrate_spherical_restricted_voronoi(const std::vector<Spherical_background_triangle>& tri,
                                                   const std::vector<Eigen::Vector3d>& vertices,
                                                   const std::vector<Eigen::Vector3d>& sites, const std::vector<int>& start,
                                                   const std::vector<int>& nbr, int first, unsigned threads,
                                                   std::vector<Spherical_cell_accumulator>& out)
{
  const std::size_t ns = sites.size(), chunks = 16, nv = vertices.size();
  std::vector<double> sq(ns);
  for(std::size_t i = 0; i < ns; ++i) sq[i] = sites[i].squaredNorm();
  std::vector<int> owner(nv);
  auto owners = [&](std::size_t chunk) {
    int seed = first;
    for(std::size_t v = chunk * nv / chunks; v < (chunk + 1) * nv / chunks; ++v)
      owner[v] = seed = greedy_walk(seed, start, nbr, [&](int i) { return -sites[std::size_t(i)].dot(vertices[v]); });
  };
  run_chunks(threads, chunks, owners);
  integrate_restricted_voronoi(Spherical_cell_geometry(tri, sites, sq, owner), ns, start, nbr, first, threads, out);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_SPHERICAL_VORONOI_H
