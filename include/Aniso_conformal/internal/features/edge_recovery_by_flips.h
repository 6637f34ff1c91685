// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_FEATURES_EDGE_RECOVERY_BY_FLIPS_H
#define ANISO_CONFORMAL_INTERNAL_FEATURES_EDGE_RECOVERY_BY_FLIPS_H

#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/extract_dual_mesh.h>
#include <Aniso_conformal/internal/optimize/triangle_orientation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <deque>
#include <map>
#include <utility>
#include <vector>

// The output-mesh edits of the crease edge recovery (crease_sites.h, recover_crease_edges()): the
// directed-edge map they keep, and the recovery of one edge by a sequence of flips.

namespace Aniso_conformal {
namespace internal {

// directed edge (u, v) of an output triangle -> that triangle's index
using Directed_edge_faces = std::map<std::pair<std::size_t, std::size_t>, std::size_t>;

// the smallest angle, in degrees, of the triangle `T` of `points` (in space)
inline double smallest_angle_in_space(const std::vector<Eigen::Vector3d>& points, const std::array<std::size_t, 3>& T)
{
  double m = 180;
  for(int i = 0; i < 3; ++i) {
    const Eigen::Vector3d u = points[T[std::size_t((i + 1) % 3)]] - points[T[std::size_t(i)]],
                          v = points[T[std::size_t((i + 2) % 3)]] - points[T[std::size_t(i)]];
    m = std::min(m, std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / 3.14159265358979323846);
  }
  return m;
}

// The faces of `faces` with a corner at `v`, in increasing index, from `face_of` (directed edge -> face, as
// recover_crease_edges() keeps it): those of the directed edges leaving `v`, contiguous in the map's order.
// O(log F + valence of v).
inline std::vector<std::size_t> faces_at(const Directed_edge_faces& face_of, std::size_t v)
{
  std::vector<std::size_t> around;
  for(auto it = face_of.lower_bound({v, 0}); it != face_of.end() && it->first.first == v; ++it) around.push_back(it->second);
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  return around;
}

// Makes the faces `which[i]` of `faces` the triangles `with[i]` (an edge flip, or the undo of several), the
// directed edges of `face_of` (directed edge -> face) updated: all the old faces' erased, then the new
// ones' set.
inline void replace_faces(std::vector<std::array<std::size_t, 3>>& faces, Directed_edge_faces& face_of,
                          const std::vector<std::size_t>& which, const std::vector<std::array<std::size_t, 3>>& with)
{
  for(const std::size_t h : which)
    for(int k = 0; k < 3; ++k) face_of.erase({faces[h][std::size_t(k)], faces[h][std::size_t((k + 1) % 3)]});
  for(std::size_t i = 0; i < which.size(); ++i) faces[which[i]] = with[i];
  for(const std::size_t h : which)
    for(int k = 0; k < 3; ++k) face_of[{faces[h][std::size_t(k)], faces[h][std::size_t((k + 1) % 3)]}] = h;
}

// One recovery of the edge (a, b) by flips, in steps (recover_edge_by_flips() below says what it does):
// the projection plane, the walk listing the crossed edges, their flips, the angle improvement, and the
// acceptance, with the undo of everything changed.
template <typename Kept>
class Flip_edge_recovery {
public:
  using Edge = std::pair<std::size_t, std::size_t>;

  Flip_edge_recovery(const Input_surface& surface, Remeshed_surface& out, Directed_edge_faces& face_of,
                     std::vector<std::size_t>& valence, std::size_t a, std::size_t b, double side, const Kept& is_kept,
                     const std::vector<Eigen::Vector3d>* sphere = nullptr)
    : m_surface(surface), m_out(out), m_face_of(face_of), m_valence(valence), m_a(a), m_b(b), m_side(side), m_is_kept(is_kept),
      m_sphere(sphere)
  {}

  bool run(std::size_t max_flips, double least_angle)
  {
    if(!set_projection_plane()) return false;
    std::vector<Edge> crossed;
    if(!walk(max_flips, crossed) || m_far) return false;
    if(!flip_crossed(crossed, max_flips) || !has_edge(m_a, m_b) || m_far) return restore();
    improve_angles();
    if(!has_edge(m_a, m_b) || m_far) return restore();
    double before = 180, after = 180;
    for(const auto& T : m_before_faces) before = std::min(before, smallest_angle(T));
    for(const std::size_t h : m_touched) after = std::min(after, smallest_angle(m_out.faces[h]));
    if(after < std::min(before, least_angle)) return restore();
    return true;
  }

private:
  // the plane normal to the area-weighted mean normal of the triangles at a and b (the xy plane, or its
  // mirror, for a planar input); false when a and b coincide in it or the normal vanishes
  bool set_projection_plane()
  {
    m_at_a = faces_at(m_face_of, m_a);  // in increasing index (the sum of the normals in that order)
    if(m_sphere) {
      // the sites on the unit sphere, seen from its centre on the plane tangent at the middle of a and b
      // (gnomonic projection: the Delaunay triangles' great-circle arcs are straight lines there)
      if(m_a >= m_sphere->size() || m_b >= m_sphere->size()) return false;
      const Eigen::Vector3d m = (*m_sphere)[m_a] + (*m_sphere)[m_b];
      if(!(m.norm() > 1e-9)) return false;
      m_centre = m.normalized();
      m_e1 = m_centre.unitOrthogonal();
      m_e2 = m_centre.cross(m_e1);
      const double ab2 = (xy(m_b) - xy(m_a)).squaredNorm();
      if(!(ab2 > 0)) return false;
      m_eps = 1e-12 * ab2;
      return true;
    }
    Eigen::Vector3d n(0, 0, m_side < 0 ? -1 : 1);
    if(!m_surface.is_planar()) {
      std::vector<std::size_t> around = faces_at(m_face_of, m_b);
      around.insert(around.end(), m_at_a.begin(), m_at_a.end());
      std::sort(around.begin(), around.end());
      around.erase(std::unique(around.begin(), around.end()), around.end());
      n = Eigen::Vector3d::Zero();
      for(const std::size_t f : around) {
        const auto& F = m_out.faces[f];
        n += (m_out.points[F[1]] - m_out.points[F[0]]).cross(m_out.points[F[2]] - m_out.points[F[0]]);
      }
    }
    if(!(n.norm() > 0)) return false;
    n.normalize();
    m_e1 = n.unitOrthogonal();
    m_e2 = n.cross(m_e1);
    const double ab2 = xy(m_b).squaredNorm();
    if(!(ab2 > 0)) return false;
    m_eps = 1e-12 * ab2;
    return true;
  }

  Eigen::Vector2d xy(std::size_t v) const
  {
    if(m_sphere) {
      // a site on the far side of the tangent plane's hemisphere (never near a and b in practice) has no
      // image: it marks the recovery as failed
      const Eigen::Vector3d& d = (*m_sphere)[v];
      const double w = d.dot(m_centre);
      if(!(w > 0.1)) {
        m_far = true;
        return Eigen::Vector2d::Zero();
      }
      return Eigen::Vector2d(d.dot(m_e1) / w, d.dot(m_e2) / w);
    }
    const Eigen::Vector3d d = m_out.points[v] - m_out.points[m_a];
    return Eigen::Vector2d(d.dot(m_e1), d.dot(m_e2));
  }
  // sign of the turn p -> q -> r in the plane: +1 left, -1 right, 0 within eps
  int orient(std::size_t p, std::size_t q, std::size_t r) const
  {
    const Eigen::Vector2d P = xy(p), u = xy(q) - P, w = xy(r) - P;
    const double o = u.x() * w.y() - u.y() * w.x();
    return o > m_eps ? 1 : (o < -m_eps ? -1 : 0);
  }
  std::size_t third(std::size_t f, std::size_t p, std::size_t q) const
  {
    const auto& F = m_out.faces[f];
    return F[0] + F[1] + F[2] - p - q;
  }
  bool has_edge(std::size_t p, std::size_t q) const { return m_face_of.count({p, q}) || m_face_of.count({q, p}); }
  // does the edge (p, q) cross the open segment (a, b)?
  bool crosses(std::size_t p, std::size_t q) const
  {
    if(p == m_a || p == m_b || q == m_a || q == m_b) return false;
    return orient(m_a, m_b, p) * orient(m_a, m_b, q) < 0 && orient(p, q, m_a) * orient(p, q, m_b) < 0;
  }
  double smallest_angle(const std::array<std::size_t, 3>& T) const { return smallest_angle_in_space(m_out.points, T); }

  // 1. the walk from a toward b: the edges the segment crosses, in order (the first is opposite a in one
  //    of its triangles); false when it meets a vertex, a boundary edge or a kept edge, or crosses more
  //    than `max_flips` edges
  bool walk(std::size_t max_flips, std::vector<Edge>& crossed) const
  {
    const std::size_t none = m_out.points.size();
    std::size_t x = none, y = none;
    for(const std::size_t f : m_at_a) {
      const auto& F = m_out.faces[f];
      int k = 0;
      while(k < 3 && F[std::size_t(k)] != m_a) ++k;
      if(k == 3) continue;
      const std::size_t p = F[std::size_t((k + 1) % 3)], q = F[std::size_t((k + 2) % 3)];
      if(orient(m_a, m_b, p) == 0 || orient(m_a, m_b, q) == 0) {
        // a vertex on the way
        if(orient(m_a, m_b, p) == 0 && (xy(p) - xy(m_a)).dot(xy(m_b) - xy(m_a)) > 0) return false;
        if(orient(m_a, m_b, q) == 0 && (xy(q) - xy(m_a)).dot(xy(m_b) - xy(m_a)) > 0) return false;
        continue;
      }
      if(crosses(p, q)) {
        x = p;
        y = q;
        break;
      }
    }
    if(x == none) return false;
    for(;;) {
      if(crossed.size() >= max_flips || m_is_kept(x, y)) return false;
      crossed.emplace_back(x, y);
      const auto g = m_face_of.find({y, x});
      if(g == m_face_of.end()) return false;  // a boundary edge
      const std::size_t r = third(g->second, x, y);
      if(r == m_b) return true;
      const int sr = orient(m_a, m_b, r);
      if(sr == 0) return false;
      if(sr == orient(m_a, m_b, x)) x = r;
      else y = r;
    }
  }

  // flips (u, v) when allowed: a convex quadrilateral in the plane, both ends keep 3 neighbours or more,
  // neither new triangle inverted against the input's normals, not kept; `improve_only`: only when that
  // raises the smallest angle of the two triangles. Records what an undo needs.
  bool flip(std::size_t u, std::size_t v, bool improve_only)
  {
    const auto fi = m_face_of.find({u, v}), gi = m_face_of.find({v, u});
    if(fi == m_face_of.end() || gi == m_face_of.end()) return false;
    const std::size_t f = fi->second, g = gi->second;
    const std::size_t w1 = third(f, u, v), w2 = third(g, u, v);  // (u, v, w1) and (v, u, w2)
    if(w1 == w2 || has_edge(w1, w2) || m_valence[u] <= 3 || m_valence[v] <= 3 || m_is_kept(u, v)) return false;
    if(orient(u, v, w1) * orient(u, v, w2) >= 0 || orient(w1, w2, u) * orient(w1, w2, v) >= 0 || m_far) return false;
    const std::array<std::size_t, 3> T1 = {{w1, u, w2}}, T2 = {{w2, v, w1}};
    // on the sphere the flip of a convex quadrilateral keeps the sites' triangulation valid: the output
    // triangles are the dual's, mapped back as every other (stage 6 checks them against the input)
    for(const auto& T : {T1, T2})
      if(!m_sphere && triangle_is_inverted(m_surface, m_out.points[T[0]], m_out.points[T[1]], m_out.points[T[2]], m_out.surface_points[T[0]],
                              m_out.surface_points[T[1]], m_out.surface_points[T[2]], m_side))
        return false;
    if(improve_only && !(std::min(smallest_angle(T1), smallest_angle(T2)) >
                         std::min(smallest_angle(m_out.faces[f]), smallest_angle(m_out.faces[g]))))
      return false;
    for(const std::size_t h : {f, g})
      if(std::find(m_touched.begin(), m_touched.end(), h) == m_touched.end()) {
        m_touched.push_back(h);
        m_before_faces.push_back(m_out.faces[h]);  // not changed before: as it was
      }
    replace_faces(m_out.faces, m_face_of, {f, g}, {T1, T2});
    m_flipped.push_back({{u, v, w1, w2}});
    --m_valence[u];
    --m_valence[v];
    ++m_valence[w1];
    ++m_valence[w2];
    return true;
  }

  // 2. the crossed edges flipped in turn; one that cannot be flipped yet goes back to the end of the
  //    queue, a new edge that still crosses the segment too; false after `max_flips` flips or a whole
  //    round without one (stuck)
  bool flip_crossed(const std::vector<Edge>& crossed, std::size_t max_flips)
  {
    std::deque<Edge> queue(crossed.begin(), crossed.end());
    std::size_t flips = 0, idle = 0;
    while(!queue.empty()) {
      if(flips >= max_flips || idle > queue.size()) return false;
      const Edge e = queue.front();
      queue.pop_front();
      const auto fi = m_face_of.find({e.first, e.second});
      const std::size_t w1 = fi == m_face_of.end() ? 0 : third(fi->second, e.first, e.second);
      const auto gi = m_face_of.find({e.second, e.first});
      const std::size_t w2 = gi == m_face_of.end() ? 0 : third(gi->second, e.first, e.second);
      if(!flip(e.first, e.second, false)) {
        queue.push_back(e);
        ++idle;
        continue;
      }
      ++flips;
      idle = 0;
      if(crosses(w1, w2)) queue.emplace_back(w1, w2);
    }
    return true;
  }

  // 3. the edges of the triangles changed, but (a, b) and the kept ones: flipped where that raises the
  //    smallest angle of their two triangles (Lawson's local improvement, the same guards), 3 rounds
  void improve_angles()
  {
    for(int pass = 0; pass < 3; ++pass) {
      std::vector<Edge> edges;
      for(const std::size_t h : m_touched)
        for(int k = 0; k < 3; ++k) {
          const std::size_t u = m_out.faces[h][std::size_t(k)], v = m_out.faces[h][std::size_t((k + 1) % 3)];
          if(std::min(u, v) == std::min(m_a, m_b) && std::max(u, v) == std::max(m_a, m_b)) continue;
          edges.emplace_back(std::min(u, v), std::max(u, v));
        }
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      bool any = false;
      for(const auto& e : edges)
        if(m_face_of.count({e.first, e.second}) && flip(e.first, e.second, true)) any = true;
      if(!any) return;
    }
  }

  // the faces changed, their directed edges and the flips' valences as they were; returns false
  bool restore()
  {
    replace_faces(m_out.faces, m_face_of, m_touched, m_before_faces);
    for(const auto& e : m_flipped) {
      ++m_valence[e[0]];
      ++m_valence[e[1]];
      --m_valence[e[2]];
      --m_valence[e[3]];
    }
    return false;
  }

  const Input_surface& m_surface;
  Remeshed_surface& m_out;
  Directed_edge_faces& m_face_of;
  std::vector<std::size_t>& m_valence;
  const std::size_t m_a, m_b;
  const double m_side;
  const Kept& m_is_kept;
  const std::vector<Eigen::Vector3d>* m_sphere;  // the sites on the unit sphere (the domain), or none
  Eigen::Vector3d m_centre = Eigen::Vector3d::Zero();  // the gnomonic projection's centre
  mutable bool m_far = false;           // a site had no gnomonic image
  std::vector<std::size_t> m_at_a;      // the faces at a, in increasing index
  Eigen::Vector3d m_e1, m_e2;           // the projection plane's axes
  double m_eps = 0;                     // orientation tolerance, 1e-12 |ab|^2 in the plane
  std::vector<std::size_t> m_touched;   // faces changed, in the order first changed
  std::vector<std::array<std::size_t, 3>> m_before_faces;  // what they were
  std::vector<std::array<std::size_t, 4>> m_flipped;  // (u, v, w1, w2): u and v lost a neighbour, w1 and w2 gained one
};

// Joins the output vertices `a` and `b` of `out` by an edge through a sequence of edge flips, the
// flip-based edge recovery of constrained Delaunay triangulation (Sloan, "A fast algorithm for generating
// constrained Delaunay triangulations", Computers & Structures 47(3), 1993, section 3; Shewchuk's
// "Lecture notes on Delaunay mesh generation", 1999, section 2.5), on the surface: the triangles around the
// segment from a to b are projected onto the plane normal to the area-weighted mean normal of the
// triangles at a and b. The walk from a toward b lists the output edges the segment crosses (it fails when
// the segment meets a vertex, a boundary edge or an edge of `is_kept`); each is flipped in turn when its
// two triangles make a convex quadrilateral in that plane, both its ends keep 3 neighbours or more
// (`valence`) and neither new triangle is inverted (triangle_is_inverted(), the input's normals), else it
// goes back to the end of the list; a new edge that still crosses the segment goes back too. At most
// `max_flips` flips. Then the edges of the changed triangles other than (a, b) and the kept ones are
// flipped where that raises the smallest angle of their two triangles (Lawson's local improvement, same
// guards, 3 rounds), and the whole sequence is accepted only when the smallest angle of
// the triangles it changed is at least the old ones' or `least_angle` degrees. Returns whether (a, b) is an
// edge after; when not, `out.faces`, `face_of` and `valence` are as they were. Local: the faces at a and
// b come from `face_of` (faces_at()), and an undo restores only the faces changed, their directed edges
// and the valences of the flips' ends, so a call costs O((valence + flips) log F), not O(F).
template <typename Kept>
bool recover_edge_by_flips(const Input_surface& surface, Remeshed_surface& out, Directed_edge_faces& face_of,
                           std::vector<std::size_t>& valence, std::size_t a, std::size_t b, double side,
                           const Kept& is_kept, std::size_t max_flips, double least_angle,
                           const std::vector<Eigen::Vector3d>* sphere = nullptr)
{
  if(a == b || a >= out.points.size() || b >= out.points.size()) return false;
  Flip_edge_recovery<Kept> recovery(surface, out, face_of, valence, a, b, side, is_kept, sphere);
  return recovery.run(max_flips, least_angle);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_FEATURES_EDGE_RECOVERY_BY_FLIPS_H
