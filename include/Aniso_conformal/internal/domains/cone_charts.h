// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_CHARTS_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_CHARTS_H

#include <Aniso_conformal/cone_embedding.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>
#include <Aniso_conformal/internal/domains/convex_overlap_2.h>
#include <Aniso_conformal/internal/domains/indexed_delaunay_2.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

// The charts of Cone_domain_traits' atlas of the cone surface (each a patch of background faces laid out
// in one plane, with a band of copies of the faces around it, joined to their own charts by rigid motions)
// and the planar tests its band and its Delaunay triangulations need.

namespace Aniso_conformal {
namespace internal {

// one chart: its faces, their triangles in its plane with a grid over them, and its extent
struct Cone_chart {
  std::vector<int> faces;  // in Morton order
  std::vector<Background_triangle> tri;
  Triangle_grid grid;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0, mass = 0, area = 0;
};
struct Cone_face_copy {
  int face;
  Rigid_motion_2 motion;  // the face's chart -> the band's chart
};
// a chart's sites (the first `own`) and copies, with their Delaunay triangulation and neighbours
struct Cone_chart_points {
  std::vector<Eigen::Vector2d> points;
  std::vector<int> original;
  std::vector<Rigid_motion_2> motion;
  std::size_t own = 0;
  Indexed_delaunay_2 dt;
  std::vector<int> start, nbr;
};


// `true` if the Delaunay triangulation of a chart's sites and copies (`cp`) is complete over the chart:
// every Delaunay circle at an own site or centred over the chart lies within `width` of it
inline bool chart_is_complete(const Cone_chart& chart, const Cone_chart_points& cp, double width)
{
  if(cp.points.size() < 3) return false;
  for(auto f = cp.dt.dt.all_faces_begin(); f != cp.dt.dt.all_faces_end(); ++f) {
    bool at_own = false;
    for(int k = 0; k < 3; ++k)
      if(!cp.dt.dt.is_infinite(f->vertex(k)) && std::size_t(f->vertex(k)->info()) < cp.own) at_own = true;
    if(cp.dt.dt.is_infinite(f)) {
      if(at_own) return false;
      continue;
    }
    const Indexed_delaunay_2::K::Point_2 c = cp.dt.dt.circumcenter(f);
    const Eigen::Vector2d cc(c.x(), c.y());
    const double d = (cc - chart.center).norm();
    const double r = (cc - cp.points[std::size_t(f->vertex(0)->info())]).norm();
    // the circles of the Voronoi vertices over the chart (and a third of the band beyond, where the cells
    // of copies that reach into the chart have theirs)
    if(!at_own && d > chart.radius + width / 3) continue;
    if(d + r > chart.radius + width) return false;
  }
  return true;
}

// The picture of chart `chart` (its background faces `faces`, its points `cp`) for Cone_domain_traits::
// voronoi_cells(): its triangles, the edges where it meets another chart (or itself: corners farther apart
// than `tolerance`), the cones at its corners (once each), and the Voronoi cells of its points.
inline Cone_chart_cells cone_chart_cells(const std::vector<int>& faces, int chart, const Cone_embedding& emb,
                                         const std::vector<std::array<int, 3>>& face_vertices, const std::vector<int>& twin,
                                         const std::vector<char>& is_cone, const Cone_chart_points& cp, double tolerance)
{
  Cone_chart_cells cc;
  for(int f : faces) {
    const auto& p = emb.corner_uv[std::size_t(f)];
    cc.triangles.push_back(p);
    for(std::size_t k = 0; k < 3; ++k) {
      const int t = twin[3 * std::size_t(f) + k];
      if(t < 0 || emb.chart_of_face[std::size_t(t / 3)] != chart ||
         (emb.corner_uv[std::size_t(t / 3)][std::size_t(t % 3)] - p[(k + 1) % 3]).norm() > tolerance)
        cc.outline.push_back({{p[k], p[(k + 1) % 3]}});
      const int v = face_vertices[std::size_t(f)][k];
      if(is_cone[std::size_t(v)] == 0 ||
         std::any_of(cc.cones.begin(), cc.cones.end(), [&](const Eigen::Vector2d& q) { return (q - p[k]).norm() <= tolerance; }))
        continue;
      cc.cones.push_back(p[k]);
      const std::size_t i = std::size_t(std::find(emb.cones.begin(), emb.cones.end(), v) - emb.cones.begin());
      cc.cone_angles.push_back(i < emb.cone_angles.size() ? emb.cone_angles[i] : 2 * 3.14159265358979323846);
    }
  }
  cc.points = cp.points;
  cc.own = cp.own;
  for(int o : cp.original) cc.sites.push_back(std::size_t(o));
  cc.cells = voronoi_polygons(cp.dt.dt, cp.dt.handle, cp.points.size(),
                              [&](Indexed_delaunay_2::Triangulation::Face_handle f) { return cp.dt.dt.circumcenter(f); });
  return cc;
}

// Walks on the cone surface of `emb` (over the background `itri`) from x in face f straight to `target`
// (both in f's chart); returns the face reached, the position in its chart and the motion from that chart
// to f's, and adds the faces crossed to `steps`. Convergence_failure after 4 times the faces.
inline void walk_on_cone_surface(const Intrinsic_triangulation& itri, const Cone_embedding& emb, int f, Eigen::Vector2d x,
                                 Eigen::Vector2d target, int& f_out, Eigen::Vector2d& x_out, Rigid_motion_2& to_start, std::size_t& steps)
{
  to_start = Rigid_motion_2();
  int entered = -1;
  const std::size_t bound = 4 * itri.number_of_faces() + 16;
  for(std::size_t step = 0; step < bound; ++step) {
    const auto& p = emb.corner_uv[std::size_t(f)];
    const Eigen::Vector3d b = internal::barycentric_2(p, target);
    if(b.minCoeff() >= -1e-12) {
      f_out = f;
      x_out = target;
      return;
    }
    const Eigen::Vector3d bx = internal::barycentric_2(p, x);
    int exit = -1;
    double first = 1e300;
    for(int k = 0; k < 3; ++k) {
      const int j = (k + 2) % 3;  // edge k is opposite corner k + 2
      if(!(b[j] < 0) || 3 * f + k == entered) continue;
      const double s = std::max(0.0, bx[j]) / (std::max(0.0, bx[j]) - b[j]);
      if(s < first) first = s, exit = k;
    }
    if(exit < 0) {  // rounding: the target is outside only across the edge we came in by
      f_out = f;
      x_out = target;
      return;
    }
    x += std::min(1.0, first) * (target - x);
    const int t = itri.twin(3 * f + exit);
    const Rigid_motion_2& m = emb.transition[std::size_t(t)];  // f's chart -> the next face's
    x = m(x);
    target = m(target);
    to_start = to_start * m.inverse();
    f = t / 3;
    entered = t;
    ++steps;
  }
  throw Convergence_failure("cone domain: a site's move crossed more than " + std::to_string(bound) + " faces", double(bound));
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_CHARTS_H
