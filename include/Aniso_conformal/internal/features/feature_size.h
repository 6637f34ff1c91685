// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_FEATURES_FEATURE_SIZE_H
#define ANISO_CONFORMAL_INTERNAL_FEATURES_FEATURE_SIZE_H

#include <Aniso_conformal/Feature_graph.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Remeshing_result.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/internal/features/curvature_size.h>
#include <Aniso_conformal/internal/features/ragged_creases.h>
#include <Aniso_conformal/internal/remesh/canonical_parameters.h>
#include <Aniso_conformal/refine_background.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

// The size of the output where two crease curves run close (issue 15: "cells and quality on each side of
// a crease"): two creases a gap w apart (a chamfer, the two rims of a thin flange, the sides of a slot)
// are both kept by the output, so the triangles between them are at most w high; with edges of length h >> w along the curves they are flat (CGAL's spool at 2000 vertices: creases
// 0.01 apart under edges of 0.045, triangles of 137 degrees, and the sites of one curve left out where
// they fell within half an edge of the other's: theta_min 17.8, 88 % of the crease length covered).
// Meshers that keep features size the elements by the local feature size there (Ruppert's and Shewchuk's
// lfs, CGAL Mesh_3's protecting balls, MMG's geometric approximation); here the metric's lengths are
// multiplied near each narrow gap so that the output's edges there are about 1.3 w long (an equilateral
// row across the gap would have 2 w / sqrt(3) = 1.15 w; 1.3 measured better on rotor_small and spool),
// and the size grows away from the gap by (grading - 1) per unit of metric length in space (Borouchaki,
// Hecht and Frey, "Mesh gradation control", 1998, MMG's -hgrad, in its isotropic form; grading 1.2: 1.3
// and 1.5 measured worse). The number of output vertices stays the one asked for: the rest of the surface
// gets coarser by the square root of the area factor. Boundary loops are not measured: their sites come
// from their own 1D CVT (the plane) or loop sites, which no crease rule drops, and a narrow annulus
// measured worse with them (CGAL-like annulus_slit_ccw.off at 600: G_avg 0.945 -> 0.929, theta_min
// 37.7 -> 33.3).

namespace Aniso_conformal {
namespace internal {

// the smallest eigenvalue of a metric square root on the tangent plane (the second of three: the normal's
// is 0), at least 1e-300: a Euclidean length r is at least r times it in the metric
inline double smallest_tangent_eigenvalue(const Eigen::Matrix3d& q)
{
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (q + q.transpose()), Eigen::EigenvaluesOnly);
  return std::max(es.eigenvalues()[1], 1e-300);
}

// The size field of the feature sizing: narrow points p (on a feature curve, across a gap) with their size
// sigma_p (in the metric), graded in space: D(x) = min_p sigma_p + (grading - 1) |Q_p (x - p)|; the metric's
// lengths are multiplied by scale(x) = clamp(h_s / D(x), 1, cap), h_s the output edge length in the scaled
// metric (feature_size_field() finds it). Each point is filed in the grid cells its reach (where D < h_s)
// overlaps, so scale(x) reads one cell.
class Feature_size_field {
public:
  struct Source {
    Eigen::Vector3d p;
    Eigen::Matrix3d Q;
    double sigma;
  };
  // `largest_h`: the largest h_s the field will be given (the sources' reach); `vertex_size`: the
  // curvature's sizes at the input vertices (curvature_size.h; empty: none), interpolated in the faces
  Feature_size_field(std::vector<Source> sources, double largest_h, double grading, double cap, std::vector<double> vertex_size = {})
      : m_sources(std::move(sources)), m_vertex_size(std::move(vertex_size)), m_largest_h(largest_h), m_g(grading - 1), m_cap(cap)
  {
    // the Euclidean reach of each source: where sigma + g |Q (x - p)| < h, within (h - sigma) / (g lambda_min)
    std::vector<double> reach(m_sources.size());
    for(std::size_t i = 0; i < reach.size(); ++i)
      reach[i] = std::max(0.0, largest_h - m_sources[i].sigma) / (m_g * smallest_tangent_eigenvalue(m_sources[i].Q));
    std::vector<double> sorted = reach;
    std::sort(sorted.begin(), sorted.end());
    m_cell = std::max(sorted.empty() ? 1.0 : sorted[sorted.size() / 2], sorted.empty() ? 1.0 : sorted.back() / 8);
    if(!(m_cell > 0) || !std::isfinite(m_cell)) m_cell = 1;
    for(std::size_t i = 0; i < m_sources.size(); ++i) {
      const Eigen::Vector3d r = Eigen::Vector3d::Constant(reach[i]);
      const Grid_cell lo = grid_cell(m_sources[i].p - r, m_cell), hi = grid_cell(m_sources[i].p + r, m_cell);
      for(std::int64_t x = lo[0]; x <= hi[0]; ++x)
        for(std::int64_t y = lo[1]; y <= hi[1]; ++y)
          for(std::int64_t z = lo[2]; z <= hi[2]; ++z) m_grid[{{x, y, z}}].push_back(i);
    }
  }
  // the graded size D(x), in the metric (infinite where no source reaches)
  double size(const Eigen::Vector3d& x) const
  {
    double d = std::numeric_limits<double>::infinity();
    const auto it = m_grid.find(grid_cell(x, m_cell));
    if(it != m_grid.end())
      for(std::size_t i : it->second) d = std::min(d, m_sources[i].sigma + m_g * (m_sources[i].Q * (x - m_sources[i].p)).norm());
    return d;
  }
  // the graded size at a point of the input: the crease gaps' (size(x)) or the curvature's, the smaller
  // (a point of a hole's patch, its vertices past the input's: the gaps' only)
  double size(const Surface_point& p) const
  {
    double d = size(p.position);
    if(m_vertex_size.empty()) return d;
    double c = 0;
    for(int k = 0; k < 3; ++k) {
      if(p.vertices[k] >= m_vertex_size.size()) return d;
      c += p.barycentric[k] * m_vertex_size[p.vertices[k]];
    }
    return std::min(d, c);
  }
  double scale(const Surface_point& p) const { return scale_at_size(size(p)); }
  // the scale where the graded size is `d` (size() does not depend on h_s: a fixed point on h_s reads
  // the sizes it stored)
  double scale_at_size(double d) const { return std::clamp(m_scaled_h / d, 1.0, m_cap); }
  // h_s, at most largest_h
  void set_scaled_edge_length(double hs) { m_scaled_h = std::min(hs, m_largest_h); }
  bool reaches(const Eigen::Vector3d& x) const { return m_grid.count(grid_cell(x, m_cell)) > 0; }
  // the curvature asks for a size below largest_h at input vertex v
  bool reaches_vertex(std::size_t v) const { return v < m_vertex_size.size() && m_vertex_size[v] < m_largest_h; }
  double cell() const { return m_cell; }

private:
  std::vector<Source> m_sources;
  std::vector<double> m_vertex_size;
  double m_largest_h, m_g, m_cap, m_cell = 1, m_scaled_h = 0;
  std::unordered_map<Grid_cell, std::vector<std::size_t>, Grid_cell_hash> m_grid;
};

// what feature_size_field() found: the field (none when no gap is held) and its figures
struct Feature_sizing {
  std::shared_ptr<const Feature_size_field> field;
  Feature_sizing_report report;  // `applied` is set by feature_size_field() with the field
};

// the feature polylines: the crease curves, each with its arc length at every
// vertex (Euclidean) and its vertices' arc lengths
struct Feature_polyline {
  std::vector<std::size_t> v;  // closed: v.front() == v.back()
  std::vector<double> arc;
  bool closed = false;
  std::unordered_map<std::size_t, double> at;  // vertex -> arc length (a closed line's start: 0)
};

inline std::vector<Feature_polyline> feature_polylines(const Input_surface& surface, const Feature_graph& g,
                                                       const std::vector<Eigen::Matrix3d>& Q, double h)
{
  std::vector<Feature_polyline> out;
  // the crease components shorter than h in the metric, which the remeshing leaves out
  // (without_short_crease_components()): not measured either
  const auto& P = surface.points();
  Crease_components components(P.size(), g, {}, {});
  std::vector<double> component_length(P.size(), 0.0);
  for(const Feature_curve& c : g.curves)
    for(std::size_t i = 0; i + 1 < c.vertices.size(); ++i) {
      const std::size_t a = c.vertices[i], b = c.vertices[i + 1];
      component_length[components.root(a)] += metric_segment_length(P[a], P[b], Q[a], Q[b]);
    }
  auto add = [&](std::vector<std::size_t> v, bool closed) {
    Feature_polyline l;
    if(closed && v.front() != v.back()) v.push_back(v.front());
    l.v = std::move(v);
    l.closed = closed;
    l.arc.assign(l.v.size(), 0.0);
    for(std::size_t i = 1; i < l.v.size(); ++i) l.arc[i] = l.arc[i - 1] + (surface.points()[l.v[i]] - surface.points()[l.v[i - 1]]).norm();
    for(std::size_t i = 0; i < l.v.size(); ++i) l.at.emplace(l.v[i], l.arc[i]);
    if(l.v.size() >= 2) out.push_back(std::move(l));
  };
  for(const Feature_curve& c : g.curves)
    if(!(component_length[components.root(c.vertices.front())] < h)) add(c.vertices, c.closed);
  return out;
}

// arc distance along `l` between arc lengths a and b
inline double arc_distance(const Feature_polyline& l, double a, double b)
{
  const double d = std::abs(a - b);
  return l.closed ? std::min(d, l.arc.back() - d) : d;
}

// The samples of the feature curves `lines` (every quarter of the output edge length h) across a gap
// narrower than an output triangle's height, as feature_size_field() defines the gap, each with its gap;
// `too_narrow` those whose size would be below h / cap, and the other points of the gaps between the
// same two lines; `gap_min` the narrowest (infinite if none).
struct Narrow_feature_points {
  std::vector<std::pair<double, Feature_size_field::Source>> points;  // (gap, source) within the cap
  std::size_t too_narrow = 0;
  double gap_min = std::numeric_limits<double>::infinity();
};

// Keeps the narrow points of `out` whose gap is resolved whole (their pairs of lines in `pair_of`; the
// pairs with a point below the cap in `unresolved`); the others are counted in `too_narrow`.
inline void keep_whole_gaps(Narrow_feature_points& out, const std::vector<std::pair<std::size_t, std::size_t>>& pair_of,
                            const std::set<std::pair<std::size_t, std::size_t>>& unresolved)
{
  // a gap is resolved whole or not at all: refining the wider part of a gap whose narrowest part stays
  // as it is only moves the flat triangles; and only a gap along which the two lines run for 1.5 output
  // edges or more (12 samples on the two) is one: two lines that come close at a point make a flat
  // triangle or two, which a refinement around them does not mend (CGAL's hand, its scanned creases a
  // few hundredths of an output edge apart here and there: theta_min 33.7 -> 27.1 with them refined)
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> samples;
  for(const auto& pr : pair_of) ++samples[pr];
  std::size_t kept = 0;
  for(std::size_t j = 0; j < out.points.size(); ++j)
    if(unresolved.count(pair_of[j]) || samples[pair_of[j]] < 12)
      ++out.too_narrow;
    else
      out.points[kept++] = out.points[j];
  out.points.resize(kept);
}

inline Narrow_feature_points narrow_feature_points(const Input_surface& surface, const std::vector<Feature_polyline>& lines,
                                                   const std::vector<Eigen::Matrix3d>& Q, double h, double cap, double gap_to_size)
{
  const auto& P = surface.points();
  Narrow_feature_points out;
  const double reach = 0.5 * std::sqrt(3.0) * h;  // gaps up to an equilateral row's height
  // the segments in a grid of cell `cell` (the median Euclidean search radius)
  struct Segment {
    std::size_t line, i;
  };
  std::vector<Segment> segments;
  std::vector<double> radius;
  for(std::size_t l = 0; l < lines.size(); ++l)
    for(std::size_t i = 0; i + 1 < lines[l].v.size(); ++i) {
      segments.push_back({l, i});
      radius.push_back(reach / smallest_tangent_eigenvalue(Q[lines[l].v[i]]));
    }
  std::vector<double> sorted = radius;
  std::sort(sorted.begin(), sorted.end());
  const double cell = std::max(sorted[sorted.size() / 2], sorted.back() / 8);
  if(!(cell > 0) || !std::isfinite(cell)) return out;
  std::unordered_map<Grid_cell, std::vector<std::size_t>, Grid_cell_hash> grid;
  for(std::size_t s = 0; s < segments.size(); ++s) {
    const Eigen::Vector3d& a = P[lines[segments[s].line].v[segments[s].i]];
    const Eigen::Vector3d& b = P[lines[segments[s].line].v[segments[s].i + 1]];
    // filed in the cells of its points at every half cell (a cell it only clips has a filed neighbour)
    const int steps = int(std::min(1e6, std::ceil(2 * (b - a).norm() / cell)));
    Grid_cell last = {{0, 0, 0}};
    for(int k = 0; k <= steps; ++k) {
      const Grid_cell c = grid_cell(a + (double(k) / std::max(steps, 1)) * (b - a), cell);
      if(k > 0 && c == last) continue;
      auto& here = grid[c];
      if(here.empty() || here.back() != s) here.push_back(s);
      last = c;
    }
  }
  // the gap at a point x of line l at arc length `arc` (Q there: `q`), over the segments near it
  auto gap = [&](std::size_t l, const Eigen::Vector3d& x, double arc, const Eigen::Matrix3d& q) {
    const Feature_polyline& line = lines[l];
    const double r = reach / smallest_tangent_eigenvalue(q);
    const int span = 1 + int(std::min(2.0, std::ceil(r / cell)));
    const Grid_cell k = grid_cell(x, cell);
    double best = std::numeric_limits<double>::infinity();
    std::size_t across = l;  // the line of the nearest point
    for(int dx = -span; dx <= span; ++dx)
      for(int dy = -span; dy <= span; ++dy)
        for(int dz = -span; dz <= span; ++dz) {
          const auto it = grid.find({{k[0] + dx, k[1] + dy, k[2] + dz}});
          if(it == grid.end()) continue;
          for(std::size_t s : it->second) {
            const Feature_polyline& m = lines[segments[s].line];
            const std::size_t j = segments[s].i;
            const Eigen::Vector3d& a = P[m.v[j]];
            const Eigen::Vector3d ab = P[m.v[j + 1]] - a;
            const double t = std::clamp((x - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
            const Eigen::Vector3d y = a + t * ab;
            const double d = (y - x).norm();
            if(!(d > 1e-9 * r) || d > r) continue;  // the point itself, to rounding
            const double arc_y = m.arc[j] + t * (m.arc[j + 1] - m.arc[j]);
            if(segments[s].line == l) {
              if(arc_distance(line, arc, arc_y) < 3 * d + 1e-9 * r) continue;
            } else {  // lines that share a vertex e: a gap only if the path through e is 6 |p - q| or longer
              double along = std::numeric_limits<double>::infinity();
              for(std::size_t e : {line.v.front(), line.v.back()}) {
                const auto f = m.at.find(e);
                if(f != m.at.end()) along = std::min(along, arc_distance(line, arc, line.at.at(e)) + arc_distance(m, f->second, arc_y));
              }
              for(std::size_t e : {m.v.front(), m.v.back()}) {
                const auto f = line.at.find(e);
                if(f != line.at.end()) along = std::min(along, arc_distance(line, arc, f->second) + arc_distance(m, m.at.at(e), arc_y));
              }
              if(along < 6 * d) continue;
            }
            const double g = (q * (y - x)).norm();
            if(g < best) {
              best = g;
              across = segments[s].line;
            }
          }
        }
    return std::make_pair(best, across);
  };
  std::vector<std::pair<std::size_t, std::size_t>> pair_of;  // per narrow point, its two lines (smaller first)
  std::set<std::pair<std::size_t, std::size_t>> unresolved;   // pairs of lines with a point below h / cap
  for(std::size_t l = 0; l < lines.size(); ++l) {
    const Feature_polyline& line = lines[l];
    for(std::size_t i = 0; i + 1 < line.v.size(); ++i) {
      const std::size_t a = line.v[i], b = line.v[i + 1];
      const double len = metric_segment_length(P[a], P[b], Q[a], Q[b]);
      const int pieces = int(std::clamp(std::ceil(len / (0.25 * h)), 1.0, 1024.0));
      for(int k = 0; k < pieces; ++k) {  // the samples of the segment, its end b left to the next one (or to the last sample)
        const double t = double(k) / pieces;
        const Eigen::Vector3d x = (1 - t) * P[a] + t * P[b];
        const Eigen::Matrix3d q = (1 - t) * Q[a] + t * Q[b];
        const auto [w, m] = gap(l, x, line.arc[i] + t * (line.arc[i + 1] - line.arc[i]), q);
        if(!(w < reach)) continue;
        out.gap_min = std::min(out.gap_min, w);
        const auto lines_pair = std::make_pair(std::min(l, m), std::max(l, m));
        if(gap_to_size * w * cap < h) {
          ++out.too_narrow;  // a size below h / cap: left as it is, with the rest of that pair's gap
          unresolved.insert(lines_pair);
        } else {
          out.points.push_back({w, {x, q, gap_to_size * w}});
          pair_of.push_back(lines_pair);
        }
      }
    }
  }
  keep_whole_gaps(out, pair_of, unresolved);
  return out;
}

// The feature sizing (see above) of the input with the feature graph `g`, `Q` the metric's square roots at
// the input vertices, `n` the output vertices asked for, `grading` the size's growth per unit of metric
// length (> 1; MMG's default -hgrad is 1.3), `cap` the largest scale. The crease curves are sampled at a quarter of the output edge length; at each sample p a point q of
// another line is a gap of |Q_p (q - p)|, unless q is near p along the lines: on the same line, closer
// along it than 3 |p - q| (a U-turn, the two sides of a slot, are gaps); on a line sharing a vertex e with
// p's, closer than 6 |p - q| through e (near a corner whose sector is wider than 19 degrees: the sector's
// angle bounds the triangle there whatever the size, and refining toward it made fandisk's 21-degree
// corner worse, 21.4 -> 16.6 degrees). A gap w below an output triangle's height (sqrt(3) h / 2) makes p
// a source of size `gap_to_size` w, unless that is below h / cap. The output's edge length h_s in the
// scaled metric grows with the scaled area: when the area factor would pass `area_budget` (6: at most
// 5/6 of the output's vertices in the refined zones), no field (a thin coin at 600 vertices, its rims
// 0.27 h apart: a factor of 12.6, and G_avg 0.930 -> 0.853 for nothing, the rims' sites still too close
// for both to stay); `gaps_left` counts the narrow points left as they are. `gaps` false: no gap measured;
// `radius_to_size` > 0: the curvature's sizes too (curvature_size.h; 0: none).
// The gaps and the curvature share one field (the smaller size wins) and one budget: past it, the gaps
// alone, else the curvature alone. No field when none is held. In two steps: measure_feature_gaps(), what
// the sizings with and without the curvature share (Feature_sizing_measure: the feature graph, the metric's square roots at the input vertices, the faces' metric areas, the output
// edge length h (0 when there is none) and the narrow gaps of the crease curves, none unless `gaps`), then
// feature_size_field() from it.
struct Feature_sizing_measure {
  Feature_graph g;
  std::vector<Eigen::Matrix3d> Q;
  std::vector<double> face_area;
  double area = 0, h = 0;
  Narrow_feature_points found;
};

inline Feature_sizing_measure measure_feature_gaps(const Input_surface& surface, Feature_graph g, std::vector<Eigen::Matrix3d> Q,
                                                   std::size_t n, bool gaps = true, double cap = 6.0, double gap_to_size = 1.3)
{
  Feature_sizing_measure m;
  m.g = std::move(g);
  m.Q = std::move(Q);
  if(n == 0) return m;
  const auto& P = surface.points();
  // the metric area (Heron on the metric lengths of each face) and the output edge length
  m.face_area.assign(surface.number_of_faces(), 0.0);
  for(std::size_t f = 0; f < m.face_area.size(); ++f) {
    const auto& t = surface.faces()[f];
    const double a = metric_segment_length(P[t[0]], P[t[1]], m.Q[t[0]], m.Q[t[1]]);
    const double b = metric_segment_length(P[t[1]], P[t[2]], m.Q[t[1]], m.Q[t[2]]);
    const double c = metric_segment_length(P[t[2]], P[t[0]], m.Q[t[2]], m.Q[t[0]]);
    m.face_area[f] = heron_area(a, b, c);
    m.area += m.face_area[f];
  }
  const double h = std::sqrt(2 * m.area / (std::sqrt(3.0) * double(n)));
  if(!(h > 0) || !std::isfinite(h)) return m;
  m.h = h;
  // the crease gaps
  if(gaps) {
    const std::vector<Feature_polyline> lines = feature_polylines(surface, m.g, m.Q, h);
    if(!lines.empty()) m.found = narrow_feature_points(surface, lines, m.Q, h, cap, gap_to_size);
  }
  return m;
}

// The field (see above) from the measure `m`; `radius_to_size` > 0: with the curvature's sizes
inline Feature_sizing feature_size_field(const Input_surface& surface, const Feature_sizing_measure& m, std::size_t n,
                                         double radius_to_size = 1.25, double grading = 1.2, double cap = 6.0,
                                         double area_budget = 6.0)
{
  Feature_sizing out;
  if(n == 0 || !(m.h > 0)) return out;
  const auto& P = surface.points();
  const Feature_graph& g = m.g;
  const std::vector<Eigen::Matrix3d>& Q = m.Q;
  const std::vector<double>& face_area = m.face_area;
  const double area = m.area, h = m.h;
  const double largest_h = std::sqrt(area_budget) * h;
  const Narrow_feature_points& found = m.found;
  const auto& narrow = found.points;
  out.report.narrow_points = narrow.size() + found.too_narrow;
  if(out.report.narrow_points > 0) out.report.gap_min = found.gap_min / h;
  out.report.gaps_left = out.report.narrow_points;
  // the curvature (curvature_size.h)
  Curvature_sizes curved;
  if(radius_to_size > 0) curved = curvature_sizes(surface, g, Q, h, largest_h, radius_to_size);
  out.report.curved_points = curved.points;
  if(std::isfinite(curved.radius_min)) out.report.radius_min = curved.radius_min;
  if(narrow.empty() && curved.size.empty()) return out;
  // A field of the gaps and/or the curvature, and its h_s (the output edge length in the scaled metric, by
  // fixed-point steps on the scaled area: each face's mean of scale^2 over a barycentric grid of spacing
  // at most a quarter of the gaps' cell, or of half the face for the curvature's sizes, which are linear
  // in a face; only on the faces the field reaches); its area factor (infinite past the budget)
  auto field_of = [&](bool with_gaps, bool with_curvature) {
    std::vector<Feature_size_field::Source> sources;
    if(with_gaps)
      for(const auto& x : narrow) sources.push_back(x.second);
    auto field = std::make_shared<Feature_size_field>(std::move(sources), largest_h, grading, cap,
                                                      with_curvature ? curved.size : std::vector<double>());
    // the faces the field reaches, with the graded sizes at their quadrature points, once: the fixed
    // point below only changes h_s (`first[k]` .. `first[k + 1]`: the points of face reached[k])
    std::vector<std::size_t> reached;
    double unreached_area = 0;
    std::vector<double> sizes;
    std::vector<std::size_t> first(1, 0);
    field->set_scaled_edge_length(largest_h);
    for(std::size_t f = 0; f < face_area.size(); ++f) {
      const auto& t = surface.faces()[f];
      const Eigen::Vector3d c = (P[t[0]] + P[t[1]] + P[t[2]]) / 3;
      const double diam = std::max({(P[t[0]] - P[t[1]]).norm(), (P[t[1]] - P[t[2]]).norm(), (P[t[2]] - P[t[0]]).norm()});
      bool near_gap = with_gaps && diam > 0.25 * field->cell();
      for(const Eigen::Vector3d& x : {P[t[0]], P[t[1]], P[t[2]], c}) near_gap = near_gap || (with_gaps && field->reaches(x));
      bool near = near_gap;
      for(int k = 0; k < 3; ++k) near = near || field->reaches_vertex(t[k]);
      if(!near) {
        unreached_area += face_area[f];
        continue;
      }
      reached.push_back(f);
      const int m = near_gap ? int(std::clamp(std::ceil(4 * diam / field->cell()), 1.0, 16.0)) : 2;
      Surface_point x;
      x.vertices = {{t[0], t[1], t[2]}};
      for(int i = 0; i <= m; ++i)
        for(int j = 0; i + j <= m; ++j) {
          x.barycentric = Eigen::Vector3d(double(m - i - j), double(i), double(j)) / double(m);
          x.position = x.barycentric[0] * P[t[0]] + x.barycentric[1] * P[t[1]] + x.barycentric[2] * P[t[2]];
          sizes.push_back(field->size(x));
        }
      first.push_back(sizes.size());
    }
    double hs = h, scaled = area;
    for(int it = 0; it < 5; ++it) {
      field->set_scaled_edge_length(std::min(hs, largest_h));
      scaled = unreached_area;
      for(std::size_t k = 0; k < reached.size(); ++k) {
        double sum = 0;
        for(std::size_t q = first[k]; q < first[k + 1]; ++q) {
          const double s = field->scale_at_size(sizes[q]);
          sum += s * s;
        }
        scaled += face_area[reached[k]] * sum / double(first[k + 1] - first[k]);
      }
      hs = std::sqrt(2 * scaled / (std::sqrt(3.0) * double(n)));
    }
    field->set_scaled_edge_length(std::min(hs, largest_h));
    const double factor = hs > largest_h * (1 + 1e-9) ? std::numeric_limits<double>::infinity() : scaled / area;
    return std::make_pair(std::move(field), factor);
  };
  // all the gaps or none: a field of the widest gaps only leaves the narrowest, those that need it most,
  // between refined zones (CGAL's spool at 2000 vertices with 3/4 of its narrow points held: theta_min 18.6,
  // 96.6 % of the crease length covered; with none 17.8 and 88 %; with all 25.6 and 99.6 %); both
  // the gaps and the curvature, or else the gaps alone, or else the curvature alone, within the budget
  const bool with[3][2] = {{true, true}, {true, false}, {false, true}};
  for(const auto& w : with) {
    if((w[0] && narrow.empty()) || (w[1] && curved.size.empty())) continue;
    auto [best, factor] = field_of(w[0], w[1]);
    if(!(factor <= area_budget)) continue;  // past the budget: the next choice, or no field
    out.report.area_factor = factor;
    if(w[0]) out.report.gaps_left = found.too_narrow;
    out.report.curvature_applied = w[1];
    for(std::size_t v = 0; v < P.size(); ++v) {
      const double s = best->scale(Surface_point::at_vertex(v, P[v]));
      if(s > 1) ++out.report.vertices_scaled;
      out.report.scale_max = std::max(out.report.scale_max, s);
    }
    if(w[0])
      for(const auto& x : narrow) out.report.scale_max = std::max(out.report.scale_max, best->scale_at_size(best->size(x.second.p)));
    if(out.report.scale_max > 1) {
      out.field = std::move(best);
      out.report.applied = true;
    }
    break;
  }
  return out;
}

// The feature sizing of `metric` for the request: the input's feature graph as remesh_in_domain.h's
// start_pipeline() detects it, the metric at the input vertices, the scales of the narrow gaps (when
// `options.feature_sizing`) and of the curvature (when `curvature`; none without either).
// With `shared`, the measure (graph, metric, gaps) is taken from there, or stored there when this call
// measures it: the sizings with and without the curvature measure it once.
template <typename AnisotropicMetric>
Feature_sizing feature_sizing(const Input_surface& surface, const AnisotropicMetric& metric, const Remeshing_options& options,
                              bool curvature = false, std::shared_ptr<const Feature_sizing_measure>* shared = nullptr)
{
  if(options.number_of_vertices < 3) return {};
  std::shared_ptr<const Feature_sizing_measure> m = shared ? *shared : nullptr;
  if(!m) {
    Feature_graph g = detect_features(surface, options.feature_angle, options.corner_angle, options.feature_edges, options.feature_vertices);
    if(options.drop_ragged_creases) {
      Ragged_creases ragged;
      g = without_ragged_crease_components(surface, g, options.number_of_vertices, options.feature_angle, options.corner_angle,
                                           options.feature_edges, options.feature_vertices, ragged);
    }
    if((g.curves.empty() || !options.feature_sizing) && !curvature) return {};  // nothing to measure
    m = std::make_shared<const Feature_sizing_measure>(measure_feature_gaps(
        surface, std::move(g), compute_metric_square_roots(surface, metric), options.number_of_vertices, options.feature_sizing));
    if(shared) *shared = m;
  }
  if((m->g.curves.empty() || !options.feature_sizing) && !curvature) return {};
  return feature_size_field(surface, *m, options.number_of_vertices, curvature ? 1.25 : 0.0);
}

// The feature sizing of one input, metric and options (above), computed at most once
// for the runs of several domains (the automatic choice's fallback to cones: CGAL's cheese, 979 crease
// curves, spends 0.6 s on it), without and with the curvature's sizes (`sizing[curvature]`)
struct Feature_sizing_once {
  std::optional<Feature_sizing> sizing[2];
  std::shared_ptr<const Feature_sizing_measure> measure;  // what both share (feature_sizing())
  double seconds[2] = {0, 0};  // what computing each took
  // the sizing, computed by `compute` if it was not yet (its time then added to `spent`)
  const Feature_sizing& get(bool curvature, const std::function<Feature_sizing()>& compute, double& spent)
  {
    if(!sizing[curvature]) {
      const auto start = std::chrono::steady_clock::now();
      sizing[curvature] = compute();
      seconds[curvature] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      spent += seconds[curvature];
    }
    return *sizing[curvature];
  }
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_FEATURES_FEATURE_SIZE_H
