// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_CHARTS_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_CONE_CHARTS_H

#include <Aniso_conformal/cone_embedding.h>
#include <Aniso_conformal/internal/CVT/planar_delaunay_flips.h>
#include <Aniso_conformal/internal/CVT/restricted_voronoi.h>
#include <Aniso_conformal/internal/domains/convex_overlap_2.h>
#include <Aniso_conformal/internal/domains/indexed_delaunay_2.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <limits>
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
  double mass = 0, area = 0;
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


// A chart's last Delaunay triangulation of its sites and copies, kept for its next integration. When each
// site then has as many points in the chart as before (itself or copies of it, within the same band), the
// old triangulation is moved to the new points and repaired by Lawson's flips (planar_delaunay_flips.h)
// instead of being built anew by CGAL: a site's points are matched to its old ones nearest first, and the
// repair is valid whatever the matching, as long as the moved triangles still cover the points' convex hull
// once (update() checks that, or the caller builds anew). A site crossing into or out of the band changes
// the chart's points and forces a build; late in the CVT few do.
struct Cone_chart_kept_delaunay {
  std::vector<std::pair<int, int>> by_site;  // (site, point) of the kept triangulation's points, sorted
  std::vector<Eigen::Vector2d> points;       // their positions
  double band_width = 0;                     // the band they were taken in
  Planar_flip_triangulation flips;
  std::size_t repairs = 0, builds = 0;

  // moves the kept triangulation to the points of `cp` (taken in a band of width `width`) and flips it back
  // to Delaunay; false if the points are not those of the kept triangulation moved, or the moved triangles
  // fold (then `flips` is not valid)
  bool repair(const Cone_chart_points& cp, double width)
  {
    if(!flips.valid() || width != band_width || cp.points.size() != points.size()) return false;
    const std::vector<std::pair<int, int>> now = sorted_by_site(cp);
    std::vector<int> new_of_old(points.size(), -1);
    for(std::size_t i = 0; i < now.size();) {
      std::size_t j = i;
      while(j < now.size() && now[j].first == now[i].first) ++j;
      if(by_site[i].first != now[i].first || (j < now.size() && by_site[j].first == now[i].first) ||
         by_site[j - 1].first != now[i].first)
        return false;
      for(std::size_t k = i; k < j; ++k) {  // each new point takes the nearest old point of its site left
        std::size_t best = j;
        double d = 0;
        for(std::size_t o = i; o < j; ++o) {
          if(new_of_old[std::size_t(by_site[o].second)] >= 0) continue;
          const double e = (points[std::size_t(by_site[o].second)] - cp.points[std::size_t(now[k].second)]).squaredNorm();
          if(best == j || e < d) best = o, d = e;
        }
        new_of_old[std::size_t(by_site[best].second)] = now[k].second;
      }
      i = j;
    }
    flips.relabel(new_of_old);
    if(!flips.update(cp.points)) return false;
    by_site = now;
    points = cp.points;
    ++repairs;
    return true;
  }
  // keeps CGAL's triangulation `cp.dt` of the points of `cp` (taken in a band of width `width`)
  void take(const Cone_chart_points& cp, double width)
  {
    flips.take(cp.dt, cp.points.size());
    by_site = sorted_by_site(cp);
    points = cp.points;
    band_width = width;
    ++builds;
  }

private:
  static std::vector<std::pair<int, int>> sorted_by_site(const Cone_chart_points& cp)
  {
    std::vector<std::pair<int, int>> v(cp.original.size());
    for(std::size_t i = 0; i < v.size(); ++i) v[i] = {cp.original[i], int(i)};
    std::sort(v.begin(), v.end());
    return v;
  }
};

// The distance from the points of a chart's plane to the chart (the union of its triangles), sampled at
// the centres of a grid over the chart's box widened by 1.5 `margin` (cells of an eighth of the margin, at
// most 256 a side): lower() and upper() bound the distance of any point from its cell's sample (plus or
// minus half the cell's diagonal); where no triangle lies within 1.5 `margin` of a cell, or outside the
// grid, only a lower bound is known (1.5 `margin`, or the distance to the chart's box). The band and the completeness test measure
// from the chart itself, not from a circle around it: an elongated chart's circle is several times its area
// and its band took five to ten times its own sites (cow, 3000 sites).
struct Cone_chart_distance {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), box_lo = Eigen::Vector2d::Zero(), box_hi = Eigen::Vector2d::Zero();
  double step = 1, margin = 0;
  int nx = 0, ny = 0;
  std::vector<double> sample;  // per cell, the distance of its centre to the chart, or infinity beyond the margin

  void build(const std::vector<Background_triangle>& tri, double margin_)
  {
    margin = margin_;
    box_lo = Eigen::Vector2d(1e300, 1e300), box_hi = -box_lo;
    for(const Background_triangle& T : tri)
      for(const Eigen::Vector2d& p : T.p) box_lo = box_lo.cwiseMin(p), box_hi = box_hi.cwiseMax(p);
    lo = box_lo - Eigen::Vector2d::Constant(known());
    const Eigen::Vector2d extent = box_hi - box_lo + Eigen::Vector2d::Constant(2 * known());
    step = std::max({margin / 8, extent.x() / 256, extent.y() / 256, 1e-300});
    nx = std::max(1, int(std::ceil(extent.x() / step))), ny = std::max(1, int(std::ceil(extent.y() / step)));
    sample.assign(std::size_t(nx) * std::size_t(ny), std::numeric_limits<double>::infinity());
    const double reach = known() + half_diagonal();
    for(const Background_triangle& T : tri) {
      const Eigen::Vector2d a = T.p[0].cwiseMin(T.p[1]).cwiseMin(T.p[2]), b = T.p[0].cwiseMax(T.p[1]).cwiseMax(T.p[2]);
      const int i0 = std::max(0, int(std::floor((a.x() - reach - lo.x()) / step))), i1 = std::min(nx - 1, int(std::floor((b.x() + reach - lo.x()) / step)));
      const int j0 = std::max(0, int(std::floor((a.y() - reach - lo.y()) / step))), j1 = std::min(ny - 1, int(std::floor((b.y() + reach - lo.y()) / step)));
      for(int j = j0; j <= j1; ++j)
        for(int i = i0; i <= i1; ++i) {
          double& d = sample[std::size_t(j) * std::size_t(nx) + std::size_t(i)];
          d = std::min(d, distance_to_triangle(lo + step * Eigen::Vector2d(i + 0.5, j + 0.5), T.p));
        }
    }
  }
  // at most the distance from x to the chart
  double lower(const Eigen::Vector2d& x) const
  {
    const double to_box = (x - x.cwiseMax(box_lo).cwiseMin(box_hi)).norm();
    const double d = cell_sample(x);
    return std::isfinite(d) ? std::max(to_box, d - half_diagonal()) : std::max(to_box, known());
  }
  // the distance within which the grid knows it
  double known() const { return 1.5 * margin; }
  // at least the distance from x to the chart (infinity where it is not known to be within known())
  double upper(const Eigen::Vector2d& x) const { return cell_sample(x) + half_diagonal(); }

private:
  double half_diagonal() const { return 0.7071067811865476 * step; }
  double cell_sample(const Eigen::Vector2d& x) const
  {
    const double fi = (x.x() - lo.x()) / step, fj = (x.y() - lo.y()) / step;
    if(!(fi >= 0 && fj >= 0 && fi < nx && fj < ny)) return std::numeric_limits<double>::infinity();
    return sample[std::size_t(int(fj)) * std::size_t(nx) + std::size_t(int(fi))];
  }
  static double distance_to_triangle(const Eigen::Vector2d& x, const std::array<Eigen::Vector2d, 3>& p)
  {
    const Eigen::Vector3d b = barycentric_2(p, x);
    if(b.minCoeff() >= 0) return 0;
    double d = 1e300;
    for(int k = 0; k < 3; ++k) {
      const Eigen::Vector2d e = p[std::size_t((k + 1) % 3)] - p[std::size_t(k)];
      const double t = std::clamp(e.dot(x - p[std::size_t(k)]) / std::max(e.squaredNorm(), 1e-300), 0.0, 1.0);
      d = std::min(d, (x - p[std::size_t(k)] - t * e).norm());
    }
    return d;
  }
};

// whether the Delaunay triangle t of a chart's sites and copies (`points`, `own` of them the chart's own
// sites) keeps the chart complete: its circle, if the triangle is at an own site or centred within a third
// of the band of the chart (where the cells of copies that reach into the chart have their vertices), lies
// within `width` of the chart (`dist`), so that no site left out of the band can lie in it
inline bool chart_circle_in_band(const Cone_chart_distance& dist, const std::vector<Eigen::Vector2d>& points, std::size_t own,
                                 const std::array<int, 3>& t, double width)
{
  typedef Indexed_delaunay_2::K K;
  const bool at_own = std::size_t(t[0]) < own || std::size_t(t[1]) < own || std::size_t(t[2]) < own;
  const auto P = [&](int i) { return K::Point_2(points[std::size_t(i)].x(), points[std::size_t(i)].y()); };
  const K::Point_2 c = K::Construct_circumcenter_2()(P(t[0]), P(t[1]), P(t[2]));
  const Eigen::Vector2d cc(c.x(), c.y());
  if(!at_own && dist.lower(cc) > width / 3) return true;
  return dist.upper(cc) + (cc - points[std::size_t(t[0])]).norm() <= width;
}

// `true` if the Delaunay triangulation of a chart's sites and copies (`cp`) is complete over the chart:
// no own site on its convex hull and every circle that matters within `width` of the chart
// (chart_circle_in_band()); from the CGAL triangulation `cp.dt`, or from `flips` when that is valid
inline bool chart_is_complete(const Cone_chart_distance& dist, const Cone_chart_points& cp, const Planar_flip_triangulation& flips, double width)
{
  if(cp.points.size() < 3) return false;
  if(flips.valid()) {
    for(std::size_t t = 0; t < flips.number_of_triangles(); ++t) {
      const std::array<int, 3>& T = flips.triangle(t);
      for(int k = 0; k < 3; ++k)
        if(flips.across(t, k) < 0 && (std::size_t(T[std::size_t((k + 1) % 3)]) < cp.own || std::size_t(T[std::size_t((k + 2) % 3)]) < cp.own))
          return false;
      if(!chart_circle_in_band(dist, cp.points, cp.own, T, width)) return false;
    }
    return true;
  }
  for(auto f = cp.dt.dt.all_faces_begin(); f != cp.dt.dt.all_faces_end(); ++f) {
    std::array<int, 3> T;
    bool infinite = false;
    for(int k = 0; k < 3; ++k) {
      if(cp.dt.dt.is_infinite(f->vertex(k))) {
        infinite = true;
        continue;
      }
      T[std::size_t(k)] = f->vertex(k)->info();
      if(std::size_t(T[std::size_t(k)]) < cp.own && cp.dt.dt.is_infinite(f)) return false;
    }
    if(!infinite && !chart_circle_in_band(dist, cp.points, cp.own, T, width)) return false;
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
