// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_OPTIMIZE_CROWDED_VERTICES_H
#define ANISO_CONFORMAL_INTERNAL_OPTIMIZE_CROWDED_VERTICES_H

#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Surface_point.h>
#include <Aniso_conformal/extract_dual_mesh.h>
#include <Aniso_conformal/internal/optimize/local_score.h>
#include <Aniso_conformal/internal/optimize/triangle_orientation.h>
#include <Aniso_conformal/internal/tensor.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <map>
#include <cstddef>
#include <utility>
#include <vector>

// Thin triangles next to fixed vertices, cured by moving a free vertex from where vertices are crowded
// to where they are missing (optimize_surface_mesh()). The CVT keeps the input's corners and crease
// sites fixed, and next to them it can leave a gap (a band between two crease chains with one free
// vertex in it, joined to both chains by long edges: CGAL's spool at 2000 vertices, theta_min 14
// degrees) that no move of a vertex fills, since the count of vertices there is what is wrong. The
// cure keeps the vertex count: a free vertex where the mesh is densest is removed (its star polygon
// retriangulated with the largest smallest angle) and put back at the midpoint of the longest edge of a
// thin triangle, split in two, followed by max-min angle edge flips around it: the vertex removal, edge
// split and edge flips of local remeshing (Hoppe et al. 1993 "Mesh optimization", Botsch and Kobbelt
// 2004 "A remeshing approach to multiresolution modeling"), as one count-preserving move. Lengths are
// measured in the metric (the mean of the two ends' square roots), triangles judged by Local_score as
// the quality report measures them.

namespace Aniso_conformal {
namespace internal {

// What relocate_crowded_vertices() did
struct Crowded_vertices_report {
  std::size_t candidates = 0;  // triangles with an angle below 30 degrees (in the metric) at the start
  std::size_t moved = 0;       // vertices moved from a crowded place to a split edge
};

// The state of relocate_crowded_vertices(): the mesh's faces around each vertex, its boundary vertices,
// and the steps of a move as members.
template <typename AnisotropicMetric>
class Crowded_vertex_mover {
public:
  typedef std::array<std::size_t, 3> Face;

  Crowded_vertex_mover(const Input_surface& surface, const AnisotropicMetric& metric, Remeshed_surface& mesh,
                       std::vector<Eigen::Matrix3d>& Q, double side, double min_gain)
    : surface(surface), metric(metric), mesh(mesh), Q(Q), side(side), min_gain(min_gain), nv(mesh.points.size())
  {}

  // the moves, at most `max_moves` (relocate_crowded_vertices())
  Crowded_vertices_report run(std::size_t max_moves)
  {
    Crowded_vertices_report report;
    build();
    std::vector<char> moved(nv, 0);
    const std::size_t donors_tried = 32;
    std::vector<Face> failed;  // thin triangles (sorted corners) whose split found no move: not tried again
    for(std::size_t attempt = 0; report.moved < max_moves && attempt < 4 * max_moves + 16; ++attempt) {
      // the thin triangles, worst first
      std::vector<std::pair<double, std::size_t>> thin;
      for(std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Triangle_figures t = existing(mesh.faces[f]);
        if(!t.inverted && t.smallest_angle < 30) thin.emplace_back(t.smallest_angle, f);
      }
      std::sort(thin.begin(), thin.end());
      if(attempt == 0) report.candidates = thin.size();
      // the donors: free vertices inside, the most crowded first
      const std::vector<Donor> donors = crowded_donors(moved, 4 * donors_tried);
      bool done = false;
      for(const auto& th : thin) {
        if(done) break;
        const Face t = mesh.faces[th.second];
        // the thin triangle's longest edge in the metric
        std::size_t ka = 0;
        for(std::size_t k = 1; k < 3; ++k)
          if(metric_length(t[k], t[(k + 1) % 3]) > metric_length(t[ka], t[(ka + 1) % 3])) ka = k;
        const std::size_t a = t[ka], b = t[(ka + 1) % 3];
        Face key = t;
        std::sort(key.begin(), key.end());
        if(std::find(failed.begin(), failed.end(), key) != failed.end()) continue;
        Split split;  // with the new vertex numbered nv until a donor gives its number
        // the split alone must do better than the triangles it replaces (the donors' stars are good): at
        // the edge's midpoint, else (a cap: its third vertex c all but on the edge, as between three crease
        // sites, the midpoint next to c) the better of two points across the edge
        auto good = [&](const Split& s) { return s.after.angle_min >= s.before.angle_min + min_gain && !(s.after.G_min < s.before.G_min); };
        bool found = evaluate_split(a, b, nv, split, Split_point::MIDPOINT) && good(split);
        if(!found)
          for(Split_point where : {Split_point::ACROSS_MIDPOINT, Split_point::ACROSS_INCENTRE}) {
            Split other;
            if(evaluate_split(a, b, nv, other, where) && good(other) && (!found || other.after.angle_min > split.after.angle_min)) {
              split = std::move(other);
              found = true;
            }
          }
        if(!found) {
          failed.push_back(key);
          continue;
        }
        // the donor's star and its retriangulation stay apart from the split's region (3 rings of a and b)
        const std::vector<char> near = rings_around(a, b, 3);
        std::size_t tries = 0;
        for(const Donor& dn : donors) {
          if(tries >= donors_tried) break;
          const std::size_t v = dn.v;
          if(near[v]) continue;
          ++tries;
          const std::vector<std::size_t> ring_faces = faces_at[v];
          const std::vector<Face>& hole = dn.hole;
          const Local_score &ring = dn.ring, &removal = dn.removal;
          const Local_score replaced = merged(ring, split.before), made = merged(removal, split.after);
          if(made.inverted > 0 || !(made.angle_min >= replaced.angle_min + min_gain) || made.G_min < replaced.G_min ||
             made.below_30 > replaced.below_30)
            continue;
          // the move: v's k faces become the k - 2 of its star's retriangulation and the split's two added
          // faces (the face count stays), the split's region its new faces; the new vertex is v
          auto renumbered = [&](Face t) {
            for(auto& x : t)
              if(x == nv) x = v;
            return t;
          };
          for(std::size_t j = 0; j < hole.size(); ++j) mesh.faces[ring_faces[j]] = hole[j];
          mesh.faces[ring_faces[hole.size()]] = renumbered(split.added[0]);
          mesh.faces[ring_faces[hole.size() + 1]] = renumbered(split.added[1]);
          for(const auto& cf : split.changed) mesh.faces[cf.first] = renumbered(cf.second);
          mesh.points[v] = split.sp.position;
          mesh.surface_points[v] = split.sp;
          Q[v] = split.Q;
          moved[v] = 1;
          ++report.moved;
          build();
          done = true;
          break;
        }
        if(!done) failed.push_back(key);
      }
      if(!done) break;
    }
    return report;
  }

private:
  static constexpr std::size_t none = std::size_t(-1);

  // a crowded vertex that may give its number to a split: its star without it (`hole`), and the scores of
  // its star (`ring`) and of that retriangulation (`removal`)
  struct Donor {
    std::size_t v;
    std::vector<Face> hole;   // its star without it
    Local_score ring, removal;
  };

  // The donors: free vertices inside not `moved` yet, the most crowded (shortest edge in the metric)
  // first, each with its star retriangulated without it; at most `most`, those whose removal is admissible
  // (no inverted triangle in the star, not the one vertex at a tip, a retriangulation found).
  std::vector<Donor> crowded_donors(const std::vector<char>& moved, std::size_t most) const
  {
    std::vector<std::pair<double, std::size_t>> crowd;
    for(std::size_t v = mesh.fixed_vertices; v < nv; ++v) {
      if(border[v] || moved[v]) continue;
      double shortest = 1e300;
      for(std::size_t w : neighbours(v)) shortest = std::min(shortest, metric_length(v, w));
      crowd.emplace_back(shortest, v);
    }
    std::sort(crowd.begin(), crowd.end());
    std::vector<Donor> donors;
    for(const auto& c : crowd) {
      if(donors.size() >= most) break;
      Donor d;
      d.v = c.second;
      std::vector<std::pair<std::size_t, std::size_t>> opposite;
      for(std::size_t f : faces_at[d.v]) {
        d.ring.add(existing(mesh.faces[f]));
        const Face& t = mesh.faces[f];
        const int k = t[0] == d.v ? 0 : t[1] == d.v ? 1 : 2;
        opposite.push_back({t[std::size_t((k + 1) % 3)], t[std::size_t((k + 2) % 3)]});
      }
      if(d.ring.inverted > 0) continue;
      // not the one vertex at a tip: its star without it would cut the tip off
      if(!surface.is_planar() &&
         angle_deficit(mesh.points[d.v], opposite, [&](std::size_t x) -> const Eigen::Vector3d& { return mesh.points[x]; }) > tip_angle_deficit)
        continue;
      d.hole = retriangulate_star(d.v, faces_at[d.v]);
      if(d.hole.empty()) continue;
      for(const Face& h : d.hole) d.removal.add(existing(h));
      donors.push_back(std::move(d));
    }
    return donors;
  }

  // 1 for the vertices within `rings` rings of a or b (a and b included)
  std::vector<char> rings_around(std::size_t a, std::size_t b, int rings) const
  {
    std::vector<char> near(nv, 0);
    std::vector<std::size_t> layer{a, b};
    near[a] = near[b] = 1;
    for(int r = 0; r < rings; ++r) {
      std::vector<std::size_t> next;
      for(std::size_t x : layer)
        for(std::size_t f : faces_at[x])
          for(std::size_t y : mesh.faces[f])
            if(!near[y]) {
              near[y] = 1;
              next.push_back(y);
            }
      layer.swap(next);
    }
    return near;
  }

    // where a split puts its vertex (then projected onto the input): the edge's midpoint; across the edge
    // (for a cap), the midpoint of the two vertices opposite it or the incentre of the larger of its two
    // triangles (its angles bisected)
    enum class Split_point { MIDPOINT, ACROSS_MIDPOINT, ACROSS_INCENTRE };

    // the split of edge (a, b) at `where` on the input, the new vertex numbered `m` (a number no vertex has):
    // the faces (a, b, c) and (b, a, d) become (a, m, c), (m, b, c), (b, m, d), (m, a, d);
    // then edge flips that raise the smallest angle of their two triangles (Lawson's flips with the
    // max-min angle test, as after a point insertion in a Delaunay triangulation), among the faces at the
    // vertices of the faces at a and b, never of a kept or a boundary edge, never onto an edge that exists,
    // never folding a triangle nor cutting through the solid (the new edge's midpoint as close to the
    // input as the old one's, as the optimiser's flips), at most 64. `changed`: the region's faces that
    // changed (index, new face); `added`: the two faces more; `before`, `after`: their figures.
    struct Split {
      std::vector<std::pair<std::size_t, Face>> changed;
      std::array<Face, 2> added;
      Local_score before, after;
      Surface_point sp;
      Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
    };

  bool evaluate_split(std::size_t a, std::size_t b, std::size_t m, Split& out, Split_point where) const
  {
    if(is_kept(a, b)) return false;
    std::vector<std::size_t> region;
    for(std::size_t x : {a, b})
      for(std::size_t f : faces_at[x])
        for(std::size_t y : mesh.faces[f]) region.insert(region.end(), faces_at[y].begin(), faces_at[y].end());
    std::sort(region.begin(), region.end());
    region.erase(std::unique(region.begin(), region.end()), region.end());
    std::vector<Face> F;
    for(std::size_t f : region) F.push_back(mesh.faces[f]);
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> at;  // directed edge -> local face
    for(std::size_t i = 0; i < F.size(); ++i)
      for(int k = 0; k < 3; ++k) at[{F[i][std::size_t(k)], F[i][std::size_t((k + 1) % 3)]}] = i;
    const auto ab = at.find({a, b}), ba = at.find({b, a});
    if(ab == at.end() || ba == at.end()) return false;  // a boundary edge
    const std::size_t fab = ab->second, fba = ba->second;
    auto third = [&](const Face& t, std::size_t x, std::size_t y) {
      for(std::size_t z : t)
        if(z != x && z != y) return z;
      return none;
    };
    const std::size_t c = third(F[fab], a, b), d = third(F[fba], a, b);
    if(c == d) return false;
    // across the edge: x, the apex of the larger of the triangles (a, b, c), (a, b, d)
    const Eigen::Vector3d &pa = mesh.points[a], &pb = mesh.points[b];
    const std::size_t x = (pb - pa).cross(mesh.points[c] - pa).norm() >= (pb - pa).cross(mesh.points[d] - pa).norm() ? c : d;
    Eigen::Vector3d mid = 0.5 * (pa + pb);
    if(where == Split_point::ACROSS_MIDPOINT) mid = 0.5 * (mesh.points[c] + mesh.points[d]);
    if(where == Split_point::ACROSS_INCENTRE) {
      const Eigen::Vector3d& px = mesh.points[x];
      const double la = (px - pb).norm(), lb = (px - pa).norm(), lx = (pb - pa).norm();
      if(!(la + lb + lx > 0)) return false;
      mid = (la * pa + lb * pb + lx * px) / (la + lb + lx);
    }
    Surface_point sp = surface.project(mid);
    if(surface.is_planar()) sp.position.z() = 0;
    if(!surface.is_planar()) {  // not onto another sheet of a thin part: the normal there agrees with the
      // edge's ends', or across the edge with x's (a cap's three vertices may lie on the rim of a thin fin,
      // whose normals, averaged over both its sheets, tell neither)
      const Eigen::Vector3d n = surface.interpolated_normal(sp);
      auto agrees = [&](std::size_t v) { return n.dot(surface.interpolated_normal(mesh.surface_points[v])) > 0; };
      if(where == Split_point::MIDPOINT ? !(agrees(a) && agrees(b)) : !agrees(x)) return false;
    }
    const Eigen::Matrix3d Qm = symmetric_sqrt(metric.tensor(sp));
    if(!Qm.allFinite()) return false;
    auto fig = [&](const Face& t) { return figures(t[0], t[1], t[2], sp.position, sp, Qm, m); };
    auto point = [&](std::size_t x) -> const Eigen::Vector3d& { return x == m ? sp.position : mesh.points[x]; };
    auto set_face = [&](std::size_t i, const Face& t) {
      for(int k = 0; k < 3; ++k) {
        const auto it = at.find({F[i][std::size_t(k)], F[i][std::size_t((k + 1) % 3)]});
        if(it != at.end() && it->second == i) at.erase(it);
      }
      F[i] = t;
      for(int k = 0; k < 3; ++k) at[{t[std::size_t(k)], t[std::size_t((k + 1) % 3)]}] = i;
    };
    const std::size_t n_region = F.size();
    F.push_back(Face{{none, none, none}});
    F.push_back(Face{{none, none, none}});
    set_face(fab, Face{{a, m, c}});
    set_face(n_region, Face{{m, b, c}});
    set_face(fba, Face{{b, m, d}});
    set_face(n_region + 1, Face{{m, a, d}});
    std::vector<std::pair<std::size_t, std::size_t>> stack{{c, a}, {b, c}, {d, b}, {a, d}};
    for(int flips = 0; !stack.empty() && flips < 64;) {
      const auto [x, y] = stack.back();
      stack.pop_back();
      const auto f1 = at.find({x, y}), f2 = at.find({y, x});
      if(f1 == at.end() || f2 == at.end() || is_kept(x, y)) continue;
      const std::size_t i1 = f1->second, i2 = f2->second;
      const std::size_t p = third(F[i1], x, y), q = third(F[i2], x, y);
      if(p == q || at.count({p, q}) || at.count({q, p})) continue;
      if(p != m && q != m) {
        const std::vector<std::size_t> np = neighbours(p);
        if(std::binary_search(np.begin(), np.end(), q)) continue;  // an edge of the mesh already
      }
      const Face n1{{x, q, p}}, n2{{q, y, p}};
      const Triangle_figures o1 = fig(F[i1]), o2 = fig(F[i2]), t1 = fig(n1), t2 = fig(n2);
      if(t1.inverted || t2.inverted) continue;
      if(!(std::min(t1.smallest_angle, t2.smallest_angle) > std::min(o1.smallest_angle, o2.smallest_angle) + 1e-9)) continue;
      if(!flip_keeps_the_shape(surface, point(x), point(y), point(p), point(q), false)) continue;
      set_face(i1, n1);
      set_face(i2, n2);
      ++flips;
      for(const auto& e : {std::make_pair(x, q), std::make_pair(p, x), std::make_pair(q, y), std::make_pair(y, p)}) stack.push_back(e);
    }
    out = Split();
    for(std::size_t i = 0; i < n_region; ++i)
      if(F[i] != mesh.faces[region[i]]) {
        out.before.add(existing(mesh.faces[region[i]]));
        out.after.add(fig(F[i]));
        out.changed.push_back({region[i], F[i]});
      }
    out.added = {{F[n_region], F[n_region + 1]}};
    out.after.add(fig(F[n_region]));
    out.after.add(fig(F[n_region + 1]));
    out.sp = sp;
    out.Q = Qm;
    return out.after.inverted == 0;
  }
  // the figures of a move over all the triangles it replaces: those of `x` and `y` together (the sums are
  // not needed)
  static Local_score merged(Local_score x, const Local_score& y)
  {
    x.inverted += y.inverted;
    x.below_30 += y.below_30;
    x.G_min = std::min(x.G_min, y.G_min);
    x.angle_min = std::min(x.angle_min, y.angle_min);
    return x;
  }
  // the faces at each vertex, and which vertices are on the boundary (an edge with one face) or isolated
  void build()
  {
    faces_at.assign(nv, {});
    for(std::size_t f = 0; f < mesh.faces.size(); ++f)
      for(std::size_t v : mesh.faces[f]) faces_at[v].push_back(f);
    // a vertex is on the boundary when one of its edges has one face only
    border.assign(nv, 0);
    for(std::size_t v = 0; v < nv; ++v) {
      std::vector<std::size_t> around;  // the other ends of v's edges, once per face side
      for(std::size_t f : faces_at[v])
        for(std::size_t w : mesh.faces[f])
          if(w != v) around.push_back(w);
      std::sort(around.begin(), around.end());
      for(std::size_t k = 0; k < around.size();) {
        std::size_t j = k;
        while(j < around.size() && around[j] == around[k]) ++j;
        if(j - k != 2) border[v] = 1;
        k = j;
      }
      if(faces_at[v].empty()) border[v] = 1;  // isolated: never moved
    }
  }
  // the figures of triangle (a, b, c) where vertex `m`, if it is a corner, is at `pm` (`sm` on the
  // input, metric square root `Qm`): the split's new vertex before it has a number
  Triangle_figures figures(std::size_t a, std::size_t b, std::size_t c, const Eigen::Vector3d& pm, const Surface_point& sm,
                           const Eigen::Matrix3d& Qm, std::size_t m) const
  {
    auto p = [&](std::size_t x) -> const Eigen::Vector3d& { return x == m ? pm : mesh.points[x]; };
    auto s = [&](std::size_t x) -> const Surface_point& { return x == m ? sm : mesh.surface_points[x]; };
    auto q = [&](std::size_t x) -> const Eigen::Matrix3d& { return x == m ? Qm : Q[x]; };
    Triangle_figures t = triangle_figures(p(a), p(b), p(c), q(a), q(b), q(c));
    t.inverted = triangle_is_inverted(surface, p(a), p(b), p(c), s(a), s(b), s(c), side);
    return t;
  }
  Triangle_figures existing(const Face& t) const
  {
    static const Surface_point no_surface_point;
    return figures(t[0], t[1], t[2], Eigen::Vector3d::Zero(), no_surface_point, Eigen::Matrix3d::Zero(), none);
  }
  bool is_kept(std::size_t a, std::size_t b) const
  {
    const std::array<std::size_t, 2> e{{std::min(a, b), std::max(a, b)}};
    return std::find(mesh.kept_edges.begin(), mesh.kept_edges.end(), e) != mesh.kept_edges.end();
  }
  double metric_length(std::size_t a, std::size_t b) const { return (0.5 * (Q[a] + Q[b]) * (mesh.points[b] - mesh.points[a])).norm(); }
  // the neighbours of v, sorted
  std::vector<std::size_t> neighbours(std::size_t v) const
  {
    std::vector<std::size_t> r;
    for(std::size_t f : faces_at[v])
      for(std::size_t w : mesh.faces[f])
        if(w != v) r.push_back(w);
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    return r;
  }
  // the triangles of the star polygon of interior vertex v (faces `ring`, a closed fan) without v, with
  // the largest smallest angle in the metric: dynamic programme over the polygon's triangulations
  // (best[i][j]: the best triangulation of the polygon's vertices i..j, through the triangle (i, m, j));
  // a triangle is admitted if it is not inverted and its diagonals are not edges of the mesh already.
  // Empty if the fan is not a cycle or no triangulation is admissible. O(k^3) for k neighbours.
  std::vector<Face> retriangulate_star(std::size_t v, const std::vector<std::size_t>& ring) const
  {
    const std::size_t k = ring.size();
    std::vector<std::size_t> next_of(nv, none), poly;
    for(std::size_t f : ring) {
      const Face& t = mesh.faces[f];
      for(int j = 0; j < 3; ++j)
        if(t[std::size_t(j)] == v) next_of[t[std::size_t((j + 1) % 3)]] = t[std::size_t((j + 2) % 3)];
    }
    std::size_t x = mesh.faces[ring[0]][0] == v ? mesh.faces[ring[0]][1] : mesh.faces[ring[0]][0];
    for(std::size_t j = 0; j < k; ++j) {
      if(x == none) return {};
      poly.push_back(x);
      x = next_of[x];
    }
    if(x != poly[0]) return {};
    std::vector<std::vector<std::size_t>> adjacent(k);
    for(std::size_t j = 0; j < k; ++j) adjacent[j] = neighbours(poly[j]);
    auto is_edge = [&](std::size_t i, std::size_t j) {  // poly[i] and poly[j] joined outside the star
      return std::binary_search(adjacent[i].begin(), adjacent[i].end(), poly[j]);
    };
    const double lowest = -1e300;
    std::vector<double> best(k * k, lowest);
    std::vector<std::size_t> via(k * k, none);
    for(std::size_t i = 0; i + 1 < k; ++i) best[i * k + i + 1] = 1e300;
    for(std::size_t span = 2; span < k; ++span)
      for(std::size_t i = 0; i + span < k; ++i) {
        const std::size_t j = i + span;
        if(!(i == 0 && j == k - 1) && is_edge(i, j)) continue;  // a diagonal already an edge
        for(std::size_t m = i + 1; m < j; ++m) {
          const double inner = std::min(best[i * k + m], best[m * k + j]);
          if(!(inner > lowest)) continue;
          const Triangle_figures t = existing(Face{{poly[i], poly[m], poly[j]}});
          if(t.inverted) continue;
          const double q = std::min(inner, t.smallest_angle);
          if(q > best[i * k + j]) {
            best[i * k + j] = q;
            via[i * k + j] = m;
          }
        }
      }
    if(via[k - 1] == none) return {};
    std::vector<Face> out;
    std::vector<std::pair<std::size_t, std::size_t>> stack{{0, k - 1}};
    while(!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      if(j < i + 2) continue;
      const std::size_t m = via[i * k + j];
      out.push_back({{poly[i], poly[m], poly[j]}});
      stack.push_back({i, m});
      stack.push_back({m, j});
    }
    return out;
  }

  const Input_surface& surface;
  const AnisotropicMetric& metric;
  Remeshed_surface& mesh;
  std::vector<Eigen::Matrix3d>& Q;
  double side, min_gain;
  std::size_t nv;
  std::vector<std::vector<std::size_t>> faces_at;  // per vertex: its faces
  std::vector<char> border;                        // per vertex: on the boundary (or isolated)
};

// The count-preserving moves on `mesh` (positions, faces, surface points), with `Q` the square roots of
// `metric` at the vertices (3 x 3, one per vertex; updated for the moved ones) and `side` the
// orientation of a planar input (planar_side()). The thin triangles (smallest angle below 30 degrees in
// the metric, none inverted) are taken worst first; for each, its longest edge in the metric is split
// at its midpoint projected onto the input (not onto another sheet of a thin part: the projection's
// normal must agree with the edge's ends'), or when that does not do (a cap, whose third vertex lies all
// but on the edge) at the better of the midpoint of the two vertices opposite the edge and the incentre
// of the larger of its two triangles (the normal there must agree with that triangle's apex), then
// flipped around with the max-min angle test among the faces at the vertices of the faces at its ends
// (evaluate_split, below). The split alone must raise
// the smallest angle of the triangles it replaces by `min_gain` degrees without lowering their G_min;
// then the donor: among the 4 x 32 free vertices inside with the shortest edges in the metric whose star
// retriangulates without them (the polygon's triangulation with the largest smallest angle: the dynamic
// programme of Klincsek 1980, no triangle inverted, no diagonal that is an edge already), the first of
// up to 32 that are three rings away from the split's ends and make the move good: over all the
// triangles the move replaces (the donor's star and the split's region), no new one inverted
// (triangle_is_inverted()), the smallest angle raised by `min_gain`, G_min not lowered and no more
// triangles below 30 degrees. So none of the report's G_min, theta_min and %<30 gets worse (G_avg and
// theta_avg may, though measured they rose). The donor's number becomes the new vertex's. Never moved:
// the first `mesh.fixed_vertices` vertices and the boundary's; never split: an edge of
// `mesh.kept_edges` or of the boundary; never flipped: those edges. Faces keep their orientation, the
// vertex and face counts, the genus and the boundary are kept, each vertex moves at most once, at most
// `max_moves` move. A thin triangle without a good move is not tried again. Time O(max_moves (F log F +
// thin triangles x region)), serial (the metric is evaluated at the split points). Returns the counts.
template <typename AnisotropicMetric>
Crowded_vertices_report relocate_crowded_vertices(const Input_surface& surface, const AnisotropicMetric& metric, Remeshed_surface& mesh,
                                                  std::vector<Eigen::Matrix3d>& Q, double side, std::size_t max_moves,
                                                  double min_gain = 0.1)
{
  return Crowded_vertex_mover<AnisotropicMetric>(surface, metric, mesh, Q, side, min_gain).run(max_moves);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_OPTIMIZE_CROWDED_VERTICES_H
