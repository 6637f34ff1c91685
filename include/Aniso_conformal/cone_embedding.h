// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_CONE_EMBEDDING_H
#define ANISO_CONFORMAL_CONE_EMBEDDING_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/cone_metric.h>
#include <Aniso_conformal/internal/conformal/euclidean_geometry.h>
#include <Aniso_conformal/internal/intrinsic/midpoint_split.h>
#include <Aniso_conformal/internal/parameter_defaults.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <deque>
#include <string>
#include <utility>
#include <unordered_map>
#include <vector>

/// \file cone_embedding.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * a rigid motion of the plane `x -> R x + t` (`R` a rotation): how the chart of one face of a cone
 * surface's atlas sits in the chart of its neighbour
 */
struct Rigid_motion_2 {
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();  ///< the rotation
  Eigen::Vector2d t = Eigen::Vector2d::Zero();      ///< the translation (units of the flat metric)
  /// the image of the point `x`
  Eigen::Vector2d operator()(const Eigen::Vector2d& x) const { return R * x + t; }
  /// `this` after `m`: `x -> this(m(x))`
  Rigid_motion_2 operator*(const Rigid_motion_2& m) const { return {R * m.R, R * m.t + t}; }
  /// the inverse motion
  Rigid_motion_2 inverse() const { return {R.transpose(), -(R.transpose() * t)}; }
  /// `true` for the identity (exactly)
  bool is_identity() const { return R == Eigen::Matrix2d::Identity() && t == Eigen::Vector2d::Zero(); }
};

/*!
 * \ingroup PkgAnisoConformalStages
 * the output of `cone_embedding()`: a flat metric with cone singularities conformal to the metric of the
 * background, and an atlas of planar charts of it (issue 16; Ben-Chen, Gotsman and Bunin 2008).
 *
 * Every face lies in one chart, laid out in the flat metric (edge of `i, j`: `exp((u_i + u_j) / 2) l_ij`).
 * A chart is a patch of faces grown breadth first that never closes around a cone and covers less than
 * `2 pi` at each cone, so it is one sheet of the plane; neighbouring faces in different charts (or across
 * a chart's own seam) are related by the rigid motion `transition[h]` of their shared halfedge.
 */
struct Cone_embedding {
  std::vector<int> cones;           ///< vertices of the background carrying a cone
  std::vector<double> cone_angles;  ///< each cone's angle sum in the flat metric (radians)
  std::vector<double> u;            ///< per background vertex, the log scale factor (flat length = exp(u) x metric length)
  std::vector<double> conformal_factor;  ///< per background vertex, `exp(-u)`: metric length over flat length (the CVT density is its square)
  double u_range = 0;        ///< max u - min u: the area distortion is `exp(2 u_range)`
  double start_u_range = 0;  ///< the range of u with the starting cones only (four extreme points on genus 0), of the linearised problem
  int genus = 0;             ///< of the closed surface
  std::size_t iterations = 0;  ///< Newton iterations over every solve of the cone placement
  std::size_t solves = 0;      ///< Newton solves of the cone placement (the nonlinear rounds)
  std::size_t linearised_cones = 0;  ///< cones placed by the linearised rounds, before the Newton solves
  std::size_t flips = 0;       ///< intrinsic Delaunay flips
  double residual = 0;         ///< max |target - angle sum| (radians)
  bool double_edges = false;   ///< the placement's flips could double an edge (its first try ended with flat triangles)
  std::size_t edge_splits = 0; ///< edges split at their midpoints after a placement that flattened a triangle next to a hole's loop (new vertices of the triangulation)
  std::vector<int> chart_of_face;                          ///< per face, its chart
  std::vector<std::array<Eigen::Vector2d, 3>> corner_uv;   ///< per face, its corners in its chart (counterclockwise)
  std::vector<Rigid_motion_2> transition;                  ///< per halfedge h: the twin's face chart -> h's face chart
  std::size_t number_of_charts = 0;                        ///< charts of the atlas
  double flat_area = 0;                                    ///< area of the flat metric (that of the background)
};

/*!
 * \ingroup PkgAnisoConformalDomains
 * one chart of a `Cone_embedding`'s atlas with the Voronoi cells of the CVT's sites over it, for pictures
 * (`Cone_domain_traits::voronoi_cells()`, `IO::write_cone_cvt_svg()`); all coordinates are the chart's
 * own, in units of the flat metric
 */
struct Cone_chart_cells {
  std::vector<std::array<Eigen::Vector2d, 3>> triangles;  ///< the chart's background faces (counterclockwise)
  std::vector<std::array<Eigen::Vector2d, 2>> outline;    ///< the edges along which the chart meets another chart (or itself)
  std::vector<Eigen::Vector2d> points;  ///< the sites in the chart's faces (the first `own`), then the copies of the sites around it
  std::vector<std::size_t> sites;       ///< per point, the site it stands for
  std::size_t own = 0;                  ///< number of the chart's own sites, at the front of `points`
  /// per point, its Voronoi cell among the chart's points (counterclockwise, not clipped to the chart:
  /// only its part inside the chart's triangles is a cell of the cone surface); empty when unknown
  std::vector<std::vector<Eigen::Vector2d>> cells;
  std::vector<Eigen::Vector2d> cones;   ///< the cone singularities at corners of the chart's faces
  std::vector<double> cone_angles;      ///< their angle sums in the flat metric (radians; `2 pi` is flat)
};

namespace internal {

// the flat length of halfedge h under the log scale factors u
inline double cone_flat_length(const Intrinsic_triangulation& itri, int h, const std::vector<double>& u)
{
  return itri.length(h) * std::exp(0.5 * (u[std::size_t(itri.tail(h))] + u[std::size_t(itri.head(h))]));
}

// the angle of the wedge of face corners `p` at corner k (radians)
inline double corner_wedge_angle(const std::array<Eigen::Vector2d, 3>& p, int k)
{
  const Eigen::Vector2d a = p[std::size_t((k + 1) % 3)] - p[std::size_t(k)], b = p[std::size_t((k + 2) % 3)] - p[std::size_t(k)];
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

// The motion taking the twin face's copy of edge (a, b) (positions ta of a, tb of b) to this face's (fa, fb).
inline Rigid_motion_2 motion_between_edges(const Eigen::Vector2d& ta, const Eigen::Vector2d& tb, const Eigen::Vector2d& fa,
                                           const Eigen::Vector2d& fb)
{
  const Eigen::Vector2d e = tb - ta, g = fb - fa;
  const double angle = std::atan2(e.x() * g.y() - e.y() * g.x(), e.dot(g));
  Rigid_motion_2 m;
  m.R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  // the midpoints coincide (the lengths agree to rounding)
  m.t = 0.5 * (fa + fb) - m.R * (0.5 * (ta + tb));
  return m;
}

// Grows the charts of the atlas (see Cone_embedding): breadth first from a seed, each face laid out from
// the chart face it is reached from, refused if one of its vertices is already in the chart elsewhere
// (the chart would close around a cone) or if it would make the chart's wedges at a cone non-contiguous
// or wider than 1.9 pi; a chart stops growing at `target_area` of metric area (the CVT's mass: charts then
// hold about as many sites each).
inline void grow_cone_charts(const Intrinsic_triangulation& itri, const std::vector<double>& u, const std::vector<char>& is_cone,
                             double target_area, Cone_embedding& emb)
{
  const double pi = 3.14159265358979323846;
  const std::size_t nf = itri.number_of_faces();
  emb.chart_of_face.assign(nf, -1);
  emb.corner_uv.assign(nf, {});
  std::vector<std::array<double, 3>> L(nf);
  double scale = 0;
  for(std::size_t f = 0; f < nf; ++f)
    for(int k = 0; k < 3; ++k) {
      L[f][std::size_t(k)] = cone_flat_length(itri, int(3 * f + k), u);
      scale = std::max(scale, L[f][std::size_t(k)]);
    }
  const double tol = 1e-7 * scale;
  std::deque<int> seeds;  // faces next to finished charts: the next seeds, so that charts stay compact
  std::size_t next_unassigned = 0;
  int chart = 0;
  while(true) {
    int seed = -1;
    while(!seeds.empty() && seed < 0) {
      if(emb.chart_of_face[std::size_t(seeds.front())] < 0) seed = seeds.front();
      seeds.pop_front();
    }
    while(seed < 0 && next_unassigned < nf) {
      if(emb.chart_of_face[next_unassigned] < 0) seed = int(next_unassigned);
      ++next_unassigned;
    }
    if(seed < 0) break;
    std::unordered_map<int, Eigen::Vector2d> where;  // the chart's vertex positions
    std::unordered_map<int, double> wedge;           // the chart's total wedge angle at each cone
    auto place = [&](int f, const std::array<Eigen::Vector2d, 3>& p) {
      emb.chart_of_face[std::size_t(f)] = chart;
      emb.corner_uv[std::size_t(f)] = p;
      const auto& c = itri.face_vertices(std::size_t(f));
      for(int k = 0; k < 3; ++k) {
        where[c[std::size_t(k)]] = p[std::size_t(k)];
        if(is_cone[std::size_t(c[std::size_t(k)])]) wedge[c[std::size_t(k)]] += corner_wedge_angle(p, k);
      }
    };
    {
      const Eigen::Vector2d p0(0, 0), p1(L[std::size_t(seed)][0], 0);
      place(seed, {{p0, p1, third_point(p0, p1, L[std::size_t(seed)][2], L[std::size_t(seed)][1])}});
    }
    double area = 0;
    std::deque<int> queue{seed};
    while(!queue.empty()) {
      const int f = queue.front();
      queue.pop_front();
      const auto& pf = emb.corner_uv[std::size_t(f)];
      area += heron_area(itri.length(3 * f), itri.length(3 * f + 1), itri.length(3 * f + 2));
      for(int k = 0; k < 3; ++k) {
        const int t = itri.twin(3 * f + k);
        if(t < 0) continue;
        const int g = t / 3;
        if(emb.chart_of_face[std::size_t(g)] >= 0) continue;
        if(area >= target_area) {
          seeds.push_back(g);
          continue;
        }
        // g's corners: t leaves head(h) = corner (k + 1) of f and enters its tail = corner k
        std::array<Eigen::Vector2d, 3> q;
        const int kt = t % 3;
        q[std::size_t(kt)] = pf[std::size_t((k + 1) % 3)];
        q[std::size_t((kt + 1) % 3)] = pf[std::size_t(k)];
        q[std::size_t((kt + 2) % 3)] = third_point(q[std::size_t(kt)], q[std::size_t((kt + 1) % 3)],
                                                   L[std::size_t(g)][std::size_t((kt + 2) % 3)], L[std::size_t(g)][std::size_t((kt + 1) % 3)]);
        const auto& cg = itri.face_vertices(std::size_t(g));
        bool ok = true;
        for(int j = 0; j < 3 && ok; ++j) {
          const int v = cg[std::size_t(j)];
          const auto w = where.find(v);
          if(w != where.end() && (w->second - q[std::size_t(j)]).norm() > tol) ok = false;
          if(ok && is_cone[std::size_t(v)]) {
            // contiguous: g shares a spoke of v with a face of the chart (f shares edge t only)
            const bool via_spoke = v == itri.tail(t) || v == itri.head(t);
            const auto a = wedge.find(v);
            if(a != wedge.end() && !via_spoke) ok = false;
            if(ok && (a != wedge.end() ? a->second : 0.0) + corner_wedge_angle(q, j) > 1.9 * pi) ok = false;
          }
        }
        if(!ok) {
          seeds.push_back(g);
          continue;
        }
        place(g, q);
        queue.push_back(g);
      }
    }
    ++chart;
  }
  emb.number_of_charts = std::size_t(chart);
  // the transitions
  emb.transition.assign(3 * nf, Rigid_motion_2());
  for(std::size_t f = 0; f < nf; ++f)
    for(int k = 0; k < 3; ++k) {
      const int h = int(3 * f + k), t = itri.twin(h);
      if(t < 0) continue;
      const std::size_t g = std::size_t(t / 3);
      const int kt = t % 3;
      const Eigen::Vector2d& fa = emb.corner_uv[f][std::size_t(k)];
      const Eigen::Vector2d& fb = emb.corner_uv[f][std::size_t((k + 1) % 3)];
      const Eigen::Vector2d& ta = emb.corner_uv[g][std::size_t((kt + 1) % 3)];  // a = tail(h) = head(t)
      const Eigen::Vector2d& tb = emb.corner_uv[g][std::size_t(kt)];
      if(emb.chart_of_face[f] == emb.chart_of_face[g] && (fa - ta).norm() <= tol && (fb - tb).norm() <= tol) continue;
      emb.transition[std::size_t(h)] = motion_between_edges(ta, tb, fa, fb);
    }
}

// place_cones() on `itri`; on a triangulation with seams (the loops of the holes' patches, which never
// flip) that ends with triangles flat in the cone metric, their longest edges are split at their
// midpoints in the triangulation as it was given and the placement runs again, at most 3 more times
// (`splits` counts the splits). Found on CGAL's blade.off with its two holes closed: a boundary ear (an
// input triangle with two edges on the loop) whose angle between the loop edges reached 180 degrees,
// the only surface triangle at its loop vertex, so no flip could open it; the split of its third edge
// gives that vertex a second triangle and a vertex of its own scale. Without seams, no split. After the
// splits (or none), on any surface, a placement that ends with flat triangles is tried once more with flips
// that may double an edge (`Cone_placement_options::double_edges`, cone_metric_geometry(); not by
// default, as it changes the limb models' cones: camel at 3000 theta_min 20.5 -> 12.2, triceratops 20.9 ->
// 29.3): CGAL's cheese (genus 133) and the femur with the curvature metric needed it.
template <typename NamedParameters>
Cone_metric place_cones_splitting_flat_edges(Intrinsic_triangulation& itri, const Cone_placement_options& options, const NamedParameters& np,
                                             std::size_t& splits)
{
  bool seams = false;
  for(int v = 0; v < int(itri.number_of_vertices()) && !seams; ++v) seams = itri.seam(v) >= 0;
  Intrinsic_triangulation entry = itri;  // the triangulation as given: each attempt flips `itri`
  Cone_placement_options with_double_edges = options;
  with_double_edges.double_edges = true;
  for(int attempt = 0;; ++attempt) {
    std::vector<std::pair<int, int>> flat;
    try {
      return place_cones(itri, options, np, &flat);
    } catch(const Convergence_failure& e) {
      std::size_t made = 0;
      if(seams && attempt < 3) {
        std::sort(flat.begin(), flat.end(), [](std::pair<int, int> x, std::pair<int, int> y) {
          return std::minmax(x.first, x.second) < std::minmax(y.first, y.second);
        });
        made = split_edges_at_midpoints(entry, flat, [](int) { return true; });
      }
      if(made > 0) {
        splits += made;
        itri = entry;
        continue;
      }
      // no split (no seams, or none helps): flat triangles whose opening flip would double an edge get
      // one more try with such flips, whose failure is the one reported
      if(!flat.empty()) {
        itri = entry;
        return place_cones(itri, with_double_edges, np);
      }
      if(splits == 0) throw;
      throw Convergence_failure(std::string(e.what()) + " (after " + std::to_string(splits) +
                                    " edges of triangles flattened next to the holes' loops were split)",
                                e.residual());
    }
  }
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalStages
 * conformally maps the closed background `itri` (edge lengths of the metric, as after
 * `adjust_edge_lengths()`) to a flat metric with cone singularities (stage 3 of the cone domain, issue 16):
 * cones are placed greedily where the log scale factor is extreme until its range is at most 2 (area
 * distortion at most `e^4`; Ben-Chen, Gotsman and Bunin 2008, section 4: `internal::place_cones()`, with
 * Newton's method and intrinsic Delaunay flips, Gillespie, Springborn and Crane 2021), then the faces are
 * laid out in an atlas of planar charts glued by rigid motions (`Cone_embedding`). The CVT runs on that
 * atlas (`Cone_domain_traits`). Unlike the sphere, the conformal factor stays representable however long
 * the surface's limbs are.
 *
 * `itri`'s edges are flipped (Ptolemy flips, same conformal class). Named parameters: `number_of_vertices`
 * (sizes the charts), `max_conformal_iterations`, `conformal_tolerance`, `max_flips_per_edge` and `visitor`;
 * at most 160 cones are placed, whatever the genus (CGAL's cheese, genus 133, with the curvature metric is
 * still 5.9 above the range's bound there; 426 cones made its solve's flips run out after almost 5 minutes).
 * \throws Invalid_input if `itri` has a boundary, or its edge lengths are not set (`Intrinsic_triangulation::has_edge_lengths()`)
 * \throws Convergence_failure if 160 cones do not bound the range of u by 4 (with the range reached; between 2
 *         and 4 the metric is accepted once 160 cones are placed), or a
 *         Newton solve fails
 */
template <typename NamedParameters>
Cone_embedding cone_embedding(Intrinsic_triangulation& itri, const NamedParameters& np)
{
  internal::require_edge_lengths(itri, "cone_embedding()");
  std::size_t emb_splits = 0;
  internal::Cone_placement_options options;
  options.max_cones = 160;
  internal::Cone_metric m = internal::place_cones_splitting_flat_edges(itri, options, np, emb_splits);
  Cone_embedding emb;
  emb.edge_splits = emb_splits;
  emb.double_edges = m.double_edges;
  emb.cones = m.cones;
  emb.cone_angles = m.cone_angles;
  emb.u = m.u;
  emb.u_range = m.u_range;
  emb.start_u_range = m.start_u_range;
  emb.genus = m.genus;
  emb.iterations = m.iterations;
  emb.solves = m.solves;
  emb.linearised_cones = m.linearised_cones;
  emb.flips = m.flips;
  emb.residual = m.residual;
  emb.conformal_factor.resize(emb.u.size());
  for(std::size_t v = 0; v < emb.u.size(); ++v) emb.conformal_factor[v] = std::exp(-emb.u[v]);
  std::vector<char> is_cone(itri.number_of_vertices(), 0);
  for(int c : emb.cones) is_cone[std::size_t(c)] = 1;
  emb.flat_area = internal::scaled_area(itri, emb.u);
  // a chart holds about 64 output cells; its band of copies then holds four to five times its own sites
  // (cow, 3000 sites: 16k points in 89 charts). Larger charts need fewer copies but change their points
  // (and are triangulated anew) at more of the CVT's evaluations, and came out worse (cow: 256 cells, 39
  // charts, 12.6k points, G_avg 0.9319; 1024 cells, 17 charts, 9.5k points, 0.9274; 64 cells: 0.9347)
  const std::size_t n = std::max<std::size_t>(1, internal::number_of_vertices(np));
  internal::grow_cone_charts(itri, emb.u, is_cone, 64.0 * internal::scaled_area(itri, std::vector<double>(emb.u.size(), 0.0)) / double(n), emb);
  return emb;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_CONE_EMBEDDING_H
