// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_OPTIMIZE_SURFACE_OPTIMIZER_H
#define ANISO_CONFORMAL_INTERNAL_OPTIMIZE_SURFACE_OPTIMIZER_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/Surface_point.h>
#include <Aniso_conformal/extract_dual_mesh.h>
#include <Aniso_conformal/internal/optimize/local_score.h>
#include <Aniso_conformal/internal/optimize/settled_marks.h>
#include <Aniso_conformal/internal/optimize/triangle_orientation.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/internal/tensor.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

// The final optimisation of the output on the input surface, in the metric (optimize_surface_mesh()):
// metric-Delaunay edge flips and vertex relocation along the surface on a CGAL::Surface_mesh holding the
// connectivity, each operation accepted only when it makes the triangles it touches no worse by any
// figure of the quality report (Local_score), or when it repairs inverted triangles.

namespace Aniso_conformal {
namespace internal {

// the optimiser's state: the mesh's connectivity in a Surface_mesh whose vertex i is output vertex i,
// and per vertex its position, its point on the input, the square root of the metric there and whether
// it is fixed (on the output's boundary)
template <typename AnisotropicMetric>
class Surface_optimizer {
public:
  typedef CGAL::Surface_mesh<CGAL::Simple_cartesian<double>::Point_3> Mesh;
  typedef Mesh::Vertex_index V;
  typedef Mesh::Halfedge_index H;
  typedef Mesh::Face_index F;

  // `angle_pass_everywhere` (Surface_optimization::ALWAYS): boundary vertices on a straight piece of the
  // input's boundary may slide along it (slides()); angle_pass() runs on every output either way
  Surface_optimizer(const Input_surface& surface, const AnisotropicMetric& metric, Remeshed_surface& out,
                    bool angle_pass_everywhere = false)
    : m_surface(surface), m_metric(metric), m_out(out), m_side(planar_side(surface)), m_angle_pass_everywhere(angle_pass_everywhere)
  {}

  // builds the connectivity and the metric at the vertices; `false` if the faces are not a 2-manifold
  // (the output check of stage 6 then refuses the output as it would have without this stage)
  bool build()
  {
    const std::size_t n = m_out.points.size();
    if(m_out.surface_points.size() != n) throw Internal_error("surface optimisation: one surface point per vertex is needed");
    for(std::size_t i = 0; i < n; ++i) m_mesh.add_vertex();
    for(const auto& f : m_out.faces) {
      for(int k = 0; k < 3; ++k)
        if(f[k] >= n) throw Internal_error("surface optimisation: a face refers to a vertex out of range");
      if(m_mesh.add_face(V(Mesh::size_type(f[0])), V(Mesh::size_type(f[1])), V(Mesh::size_type(f[2]))) == Mesh::null_face())
        return false;
    }
    m_Q.resize(n);
    // serial: a user's metric model need not be safe for concurrent calls
    for(std::size_t i = 0; i < n; ++i) m_Q[i] = symmetric_sqrt(m_metric.tensor(m_out.surface_points[i]));
    m_kept = m_out.kept_edges;
    std::sort(m_kept.begin(), m_kept.end());
    m_fixed.assign(n, 0);
    for(V v : m_mesh.vertices())
      if(m_mesh.is_isolated(v) || m_mesh.is_border(v, false) || std::size_t(v.idx()) < m_out.fixed_vertices) m_fixed[v.idx()] = 1;
    // the fixed sites the dual needed and the output does not (the cone domain's cones): moved like any
    // vertex (CGAL's man through cones at 3000 vertices: theta_min 22.2 -> 27.7 degrees, the one angle
    // below 30 was at a cone of valence 10)
    for(std::size_t v : m_out.released_vertices)
      if(v < n && !m_mesh.is_isolated(V(Mesh::size_type(v))) && !m_mesh.is_border(V(Mesh::size_type(v)), false)) m_fixed[v] = 0;
    if(m_angle_pass_everywhere) find_sliding_vertices();
    m_start = m_out.points;
    m_marks.reset(n, m_mesh.number_of_edges());
    return true;
  }

  // the number of boundary vertices that may slide along a straight piece of the input's boundary
  std::size_t sliding_vertices() const { return m_sliding; }
  // the vertex visits of the passes so far (a vertex skipped as settled is not visited)
  std::size_t visits() const { return m_visits; }
  // `true`: the passes visit every vertex and test every edge, none skipped as settled (for the tests:
  // the output must be the same)
  void visit_every_vertex(bool on) { m_exhaustive = on; }

  const std::vector<Eigen::Matrix3d>& metric_square_roots() const { return m_Q; }
  // the vertices that never move (the sliding ones are not counted)
  std::size_t fixed_vertices() const { return std::size_t(std::count(m_fixed.begin(), m_fixed.end(), 1)) - m_sliding; }
  double side() const { return m_side; }

  // one pass of metric-Delaunay flips over every edge; returns the number of flips
  std::size_t flip_pass()
  {
    std::size_t flips = 0;
    const double pi = 3.14159265358979323846;
    for(auto e : m_mesh.edges()) {
      if(m_mesh.is_border(e)) continue;
      const H h = m_mesh.halfedge(e);
      const V a = m_mesh.source(h), b = m_mesh.target(h), c = m_mesh.target(m_mesh.next(h)),
              d = m_mesh.target(m_mesh.next(m_mesh.opposite(h)));
      // an edge kept at its last test, its quad unchanged since, is kept again (settled_marks.h)
      if(!m_exhaustive && m_marks.edge_settled(e.idx(), a.idx(), b.idx(), c.idx(), d.idx())) continue;
      m_marks.edge_tested(e.idx());  // kept unless flipped below
      if(c == d || m_mesh.halfedge(c, d) != Mesh::null_halfedge()) continue;  // the flip would duplicate an edge
      if(!m_out.kept_edges.empty() &&
         std::binary_search(m_kept.begin(), m_kept.end(), std::array<std::size_t, 2>{{std::min<std::size_t>(a.idx(), b.idx()), std::max<std::size_t>(a.idx(), b.idx())}}))
        continue;  // a crease edge (Remeshed_surface::kept_edges)
      // faces (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c)
      Local_score before, after;
      before.add(figures(a, b, c));
      before.add(figures(b, a, d));
      after.add(figures(a, d, c));
      after.add(figures(d, b, c));
      const bool repairs = after.inverted < before.inverted;
      if(!repairs) {
        // the metric-Delaunay test, in the mean metric of the four corners
        const Eigen::Matrix3d Qq = (Q(a) + Q(b) + Q(c) + Q(d)) / 4.0;
        auto angle_at = [&](V x) {
          const Eigen::Vector3d u = Qq * (P(a) - P(x)), v = Qq * (P(b) - P(x));
          return std::atan2(u.cross(v).norm(), u.dot(v));
        };
        if(!(angle_at(c) + angle_at(d) > pi * (1 + 1e-10))) continue;
        if(!improves(after, before)) continue;
      }
      if(!keeps_the_shape(a, b, c, d, repairs)) continue;
      CGAL::Euler::flip_edge(h, m_mesh);
      m_marks.changed({a.idx(), b.idx(), c.idx(), d.idx()});
      ++flips;
    }
    m_flipped = m_flipped || flips > 0;
    return flips;
  }

  // moves free vertex `i` to the projection of `y` onto the input (z = 0 on a planar input), with its
  // metric; `false` (nothing moved) if `y` is not finite or the projection lies on another sheet of a
  // thin part (its interpolated normal against `old_normal`, the vertex's before any move): the
  // closest point there is no move along the surface
  bool move_onto_input(std::size_t i, const Eigen::Vector3d& y, const Eigen::Vector3d& old_normal)
  {
    if(!y.allFinite()) return false;
    Surface_point sp = m_surface.project(y, m_out.surface_points[i]);
    if(m_surface.is_planar()) sp.position.z() = 0;
    if(!m_surface.is_planar() && !(interpolated_normal(sp).dot(old_normal) > 0)) return false;
    m_out.surface_points[i] = sp;
    m_out.points[i] = sp.position;
    m_Q[i] = symmetric_sqrt(m_metric.tensor(sp));
    return true;
  }

  // the faces around `v` (its one-ring), into `ring` (cleared first)
  void one_ring(V v, std::vector<F>& ring) const
  {
    ring.clear();
    for(H h : CGAL::halfedges_around_target(m_mesh.halfedge(v), m_mesh))
      if(!m_mesh.is_border(h)) ring.push_back(m_mesh.face(h));
  }

  // one pass of relocation of every free vertex toward the metric-weighted centroid of its one-ring,
  // projected onto the input; returns the number of vertices moved. `relaxed` (the second phase of
  // Surface_optimization::ALWAYS): the vertex first tries its metric ideal point (metric_ideal_point(), and
  // 1/2 and 1/4 of the way to it), and moves are judged by improves_above_floors() with `G_floor` and
  // `angle_floor` (degrees)
  std::size_t relocation_pass(bool relaxed = false, double G_floor = 0, double angle_floor = 0)
  {
    if(relaxed && (G_floor != m_relaxed_floors[0] || angle_floor != m_relaxed_floors[1])) {
      m_marks.forget(Settled_marks::RELAXED_RELOCATION);  // other floors: another pass
      m_relaxed_floors[0] = G_floor, m_relaxed_floors[1] = angle_floor;
    }
    return for_each_movable_vertex(relaxed ? Settled_marks::RELAXED_RELOCATION : Settled_marks::RELOCATION, [&](V v, const std::vector<F>& ring, const Local_score& before) {
      const std::size_t i = v.idx();
      // the centroid of the ring's triangles weighted by their area in the metric, and the plain mean of
      // the neighbours as a fallback
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), mean = Eigen::Vector3d::Zero();
      double weight = 0;
      std::size_t neighbours = 0;
      for(F f : ring) {
        const auto t = corners(f);
        const double w = figures(t[0], t[1], t[2]).area;
        centroid += w * (P(t[0]) + P(t[1]) + P(t[2])) / 3.0;
        weight += w;
      }
      for(V u : CGAL::vertices_around_target(m_mesh.halfedge(v), m_mesh)) {
        mean += P(u);
        ++neighbours;
      }
      std::vector<Eigen::Vector3d> targets;
      const Eigen::Vector3d p = P(v);
      Eigen::Vector3d ideal;
      if(relaxed && metric_ideal_point(v, ring, ideal))
        for(double step : {1.0, 0.5, 0.25}) targets.push_back(p + step * (ideal - p));
      if(weight > 0 && centroid.allFinite())
        for(double step : {1.0, 0.5, 0.25}) targets.push_back(p + step * (centroid / weight - p));
      if(neighbours > 0) targets.push_back(mean / double(neighbours));
      if(before.inverted > 0) {
        // a folded ring: also half way to the mean and toward each neighbour
        if(neighbours > 0) targets.push_back(0.5 * (p + mean / double(neighbours)));
        for(V u : CGAL::vertices_around_target(m_mesh.halfedge(v), m_mesh))
          for(double step : {0.5, 0.25}) targets.push_back(p + step * (P(u) - p));
      }
      const Vertex_state old = state(i);
      const Eigen::Vector3d old_normal = interpolated_normal(old.sp);
      for(const Eigen::Vector3d& y : targets) {
        if(!try_move(v, y, old_normal, before.inverted > 0)) continue;
        const Local_score after = ring_score(ring);
        if(relaxed ? improves_above_floors(after, before, G_floor, angle_floor) : improves(after, before)) return true;
        restore(i, old);
      }
      return false;
    });
  }

  // whether the mesh has fixed vertices inside (corners and crease sites of the input's features, issue
  // 15): only then are crowded vertices moved (optimize_surface_mesh())
  bool has_interior_fixed_vertices() const
  {
    for(V v : m_mesh.vertices())
      if(std::size_t(v.idx()) < m_out.fixed_vertices && !m_mesh.is_isolated(v) && !m_mesh.is_border(v, false)) return true;
    return false;
  }

  // one pass of max-min angle relocation (optimisation-based smoothing, Freitag and Plassmann 2000: a
  // vertex moves where the smallest angle of its one-ring grows) of every free vertex whose one-ring has
  // an angle below 30 degrees in the metric (next to fixed vertices inside, corners and crease sites,
  // such angles are common: a fixed site the CVT could not move leaves its free neighbours where its Voronoi cell ended,
  // and a short fixed edge, two corners closer than the output edge length, gets a free vertex at the
  // usual distance across it, a thin triangle the centroid moves of relocation_pass() do not cure: CGAL's
  // three_peaks at 2000 vertices, theta_min 20.6 degrees). Targets: for each triangle (v, a, b) of the
  // ring whose smallest angle is the ring's, the apex of the equilateral triangle on (a, b) on v's side
  // and the points 1/2, 1/4, 1/8 and 1/16 of the way there, both the triangle equilateral in space and
  // the one equilateral in the metric (the mean Q of v, a, b; metric_equilateral_apex()), projected onto
  // the input (two obtuse triangles on one edge, the torus at stretch 30, need the short steps), and the
  // steps along the steepest ascent of the ring's smallest angle (ascent_targets()). A move is accepted when it
  // makes no triangle of the ring inverted that was not, raises the ring's smallest angle and lowers
  // neither its G_min nor its count below 30 degrees (G_avg may drop a little: the smallest angle is what
  // this pass is for). Returns the number of vertices moved. It ran only next to fixed vertices inside
  // and with Surface_optimization::ALWAYS (the image metric's thin triangles across colour edges, issue
  // 17 item 4; chelsea at 3000 vertices, theta_min 24.1 -> 29.4 degrees after the other passes) until
  // it was found to lift the thin triangles of smooth outputs as well (bear at 2000: 17.1 -> 30.4).
  std::size_t angle_pass()
  {
    static constexpr double angle_pass_steps[] = {1.0, 0.5, 0.25, 0.125, 0.0625};  // of the way to each apex
    return for_each_movable_vertex(Settled_marks::ANGLE, [&](V v, const std::vector<F>& ring, const Local_score& before) {
      const std::size_t i = v.idx();
      if(before.inverted > 0 || !(before.angle_min < 30)) return false;
      const Eigen::Vector3d p = P(v);
      std::vector<Eigen::Vector3d> targets;
      for(F f : ring) {
        const auto t = corners(f);
        if(!(figures(t[0], t[1], t[2]).smallest_angle <= before.angle_min)) continue;
        const auto [a, b] = opposite_edge(t, v);
        const Eigen::Vector3d m = 0.5 * (P(a) + P(b)), e = P(b) - P(a);
        const double len = e.norm();
        if(!(len > 0)) continue;
        Eigen::Vector3d d = (p - m) - (p - m).dot(e) / (len * len) * e;
        if(!(d.norm() > 0)) continue;
        const Eigen::Vector3d apex = m + (0.5 * std::sqrt(3.0) * len / d.norm()) * d;
        for(double step : angle_pass_steps) targets.push_back(p + step * (apex - p));
        // the same apex in the metric: equilateral for the triangle's mean Q, which is where an
        // anisotropic metric wants v (the Euclidean apex is the same point when the metric is isotropic)
        Eigen::Vector3d metric_apex;
        if(metric_equilateral_apex(p, P(a), P(b), (Q(v) + Q(a) + Q(b)) / 3.0, metric_apex))
          for(double step : angle_pass_steps) targets.push_back(p + step * (metric_apex - p));
      }
      const Vertex_state old = state(i);
      const Eigen::Vector3d old_normal = interpolated_normal(old.sp);
      ascent_targets(v, ring, old_normal, targets);
      Local_score best = before;
      Vertex_state best_state = old;
      for(const Eigen::Vector3d& y : targets) {
        if(!try_move(v, y, old_normal, false)) continue;
        const Local_score s = ring_score(ring);
        if(s.inverted == 0 && s.angle_min > best.angle_min + 1e-9 && s.G_min >= before.G_min && s.below_30 <= before.below_30) {
          best = s;
          best_state = state(i);
        }
      }
      restore(i, best_state);
      return best.angle_min > before.angle_min;
    });
  }

  // Targets of angle_pass() along the steepest ascent of the smallest angle of `v`'s one-ring `ring` (the
  // gradient of Freitag and Plassmann 2000, of the one angle that is smallest): the gradient by central
  // differences in the plane normal to `normal`, steps 1/2 to 1/32 of the mean length of v's edges, into
  // `targets`. What the apexes of angle_pass() miss: a vertex next to a tip of the surface (a horn's end,
  // where one vertex has three or four triangles of apex angles summing to far less than 2 pi) that
  // leaves one of them thin, as on CGAL's triceratops through cones (14.8 degrees where the three apex
  // angles at the tip could each be 28): the apex of the equilateral triangle asks the tip for 60 degrees
  // it does not have, while turning the vertex around the tip evens the apex angles out. v is put back.
  void ascent_targets(V v, const std::vector<F>& ring, const Eigen::Vector3d& normal, std::vector<Eigen::Vector3d>& targets)
  {
    const std::size_t i = v.idx();
    const Eigen::Vector3d p = P(v);
    double length = 0;
    std::size_t edges = 0;
    for(V u : CGAL::vertices_around_target(m_mesh.halfedge(v), m_mesh)) length += (P(u) - p).norm(), ++edges;
    const Eigen::Vector3d n = normal.normalized();
    if(edges == 0 || !(length > 0) || !n.allFinite()) return;
    length /= double(edges);
    const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    const Vertex_state old = state(i);
    const double delta = 1e-4 * length;
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
    for(const Eigen::Vector3d& t : {t1, t2}) {
      double side[2];
      for(int k = 0; k < 2; ++k) {
        if(!try_move(v, p + (k == 0 ? delta : -delta) * t, normal, false)) {
          restore(i, old);
          return;
        }
        side[k] = ring_score(ring).angle_min;
        restore(i, old);
      }
      gradient += (side[0] - side[1]) / (2 * delta) * t;
    }
    if(!(gradient.norm() > 0) || !gradient.allFinite()) return;
    const Eigen::Vector3d d = gradient.normalized();
    for(double step : {0.5, 0.25, 0.125, 0.0625, 0.03125}) targets.push_back(p + step * length * d);
  }

  // writes the faces back into the output (positions and surface points are updated in place); the faces
  // are left untouched when no edge was flipped
  void write_faces()
  {
    if(!m_flipped) return;
    m_out.faces.clear();
    for(F f : m_mesh.faces()) {
      const auto t = corners(f);
      m_out.faces.push_back({{std::size_t(t[0].idx()), std::size_t(t[1].idx()), std::size_t(t[2].idx())}});
    }
  }

private:
  // what a trial move of a vertex changes, to put it back
  struct Vertex_state {
    Surface_point sp;
    Eigen::Matrix3d Q;
  };
  Vertex_state state(std::size_t i) const { return {m_out.surface_points[i], m_Q[i]}; }
  void restore(std::size_t i, const Vertex_state& s)
  {
    m_out.surface_points[i] = s.sp;
    m_out.points[i] = s.sp.position;
    m_Q[i] = s.Q;
  }

  // calls `visit(v, ring, before)` for every vertex that may move (free, or sliding along the boundary)
  // with its one-ring and the ring's score; `visit` tries its moves and returns whether v moved, leaving
  // it exactly as it was if not. Returns the number of vertices moved. A vertex that the last visit of
  // pass `kind` left in place is skipped while its one-ring is unchanged (settled_marks.h): the output
  // is the one of visiting every vertex (CGAL's hand at 2000 vertices, one thread: the stage 0.247 ->
  // 0.130 s, the same output).
  template <typename Visit>
  std::size_t for_each_movable_vertex(std::size_t kind, Visit visit)
  {
    std::size_t moved = 0;
    std::vector<F> ring;
    for(V v : m_mesh.vertices()) {
      const std::size_t i = v.idx();
      if(m_fixed[i] && !slides(i)) continue;
      if(!m_exhaustive && m_marks.settled(kind, i, CGAL::vertices_around_target(m_mesh.halfedge(v), m_mesh))) continue;
      ++m_visits;
      one_ring(v, ring);
      const Local_score before = ring_score(ring);
      if(visit(v, ring, before)) {
        ++moved;
        m_marks.changed(i);
      } else {
        m_marks.left_in_place(kind, i);
      }
    }
    return moved;
  }

  // whether boundary vertex `i` may slide along the input's boundary (find_sliding_vertices())
  bool slides(std::size_t i) const { return !m_slide.empty() && m_slide[i]; }

  // the output's boundary vertices that may slide along the input's boundary: those with their
  // two boundary neighbours on a straight line through them (to 1e-12 of the edge lengths: a corner of
  // the boundary, or a curved boundary, keeps its vertices fixed) and on an input boundary edge. A move
  // keeps such a vertex on that line between its neighbours (try_move()), so the output's boundary, as a
  // set, does not change (its area in the plane neither).
  void find_sliding_vertices()
  {
    for(const auto& loop : m_surface.boundary_loops())
      for(std::size_t k = 0; k < loop.size(); ++k) {
        const std::size_t a = loop[k], b = loop[(k + 1) % loop.size()];
        m_input_border.push_back({{std::min(a, b), std::max(a, b)}});
      }
    std::sort(m_input_border.begin(), m_input_border.end());
    m_slide.assign(m_fixed.size(), 0);
    m_sliding = 0;
    for(V v : m_mesh.vertices()) {
      const std::size_t i = v.idx();
      if(m_mesh.is_isolated(v) || !m_mesh.is_border(v, false)) continue;
      Eigen::Vector3d u, w;
      if(!boundary_neighbours(v, u, w) || !on_input_border(m_out.surface_points[i])) continue;
      const Eigen::Vector3d e1 = u - P(v), e2 = w - P(v);
      if(!(e1.cross(e2).norm() <= 1e-12 * e1.norm() * e2.norm()) || !(e1.dot(e2) < 0)) continue;
      m_slide[i] = 1;
      ++m_sliding;
    }
  }

  // the positions of the boundary neighbours of boundary vertex `v` (before and after it along the
  // boundary); `false` if `v` is on the boundary more than once
  bool boundary_neighbours(V v, Eigen::Vector3d& u, Eigen::Vector3d& w) const
  {
    const H h = m_mesh.halfedge(v);  // the border halfedge into v
    if(!m_mesh.is_border(h)) return false;
    std::size_t border = 0;
    for(H g : CGAL::halfedges_around_target(h, m_mesh)) border += m_mesh.is_border(g) ? 1 : 0;
    if(border != 1) return false;
    u = P(m_mesh.source(h));
    w = P(m_mesh.target(m_mesh.next(h)));
    return true;
  }

  // whether `sp` lies on an edge of the input's boundary (a barycentric coordinate of at most 1e-12)
  bool on_input_border(const Surface_point& sp) const
  {
    for(int j = 0; j < 3; ++j) {
      if(!(std::abs(sp.barycentric[j]) <= 1e-12)) continue;
      const std::size_t a = sp.vertices[(j + 1) % 3], b = sp.vertices[(j + 2) % 3];
      if(std::binary_search(m_input_border.begin(), m_input_border.end(), std::array<std::size_t, 2>{{std::min(a, b), std::max(a, b)}}))
        return true;
    }
    return false;
  }

  // moves vertex `v` toward `y` (move_onto_input()); a sliding vertex (slides()) goes instead to the
  // projection of `y` onto the line through its boundary neighbours, kept within 90 % of the way to each,
  // and the move is refused (nothing moved) unless it lands on an input boundary edge, at most 1e-9 of the
  // input's diagonal from that line. Unless it `repairs` an inverted triangle, a move on a curved input
  // is refused if it cuts off the shape the vertex held (keeps_the_shape_at()).
  bool try_move(V v, const Eigen::Vector3d& y, const Eigen::Vector3d& old_normal, bool repairs)
  {
    const std::size_t i = v.idx();
    if(!slides(i)) {
      const Vertex_state old = state(i);
      if(!move_onto_input(i, y, old_normal)) return false;
      if(repairs || m_surface.is_planar() || keeps_the_shape_at(v)) return true;
      restore(i, old);
      return false;
    }
    Eigen::Vector3d u, w;
    if(!boundary_neighbours(v, u, w)) return false;
    const Eigen::Vector3d p = P(v), d = (w - u).normalized();
    const double su = (u - p).dot(d), sw = (w - p).dot(d);  // su < 0 < sw
    if(!(su < 0 && sw > 0) || !d.allFinite()) return false;
    const double s_y = std::clamp((y - p).dot(d), 0.9 * su, 0.9 * sw);
    const Eigen::Vector3d z = p + s_y * d;
    const Vertex_state old = state(i);
    if(!move_onto_input(i, z, old_normal)) return false;
    if(on_input_border(m_out.surface_points[i]) &&
       (m_out.points[i] - z).norm() <= 1e-9 * m_surface.bounding_box_diagonal())
      return true;
    restore(i, old);
    return false;
  }

  const Eigen::Vector3d& P(V v) const { return m_out.points[v.idx()]; }
  const Eigen::Matrix3d& Q(V v) const { return m_Q[v.idx()]; }

  std::array<V, 3> corners(F f) const
  {
    const H h = m_mesh.halfedge(f);
    return {{m_mesh.source(h), m_mesh.target(h), m_mesh.target(m_mesh.next(h))}};
  }

  // the edge (a, b) of triangle `t` opposite its corner `v`, in the triangle's order (v, a, b)
  static std::pair<V, V> opposite_edge(const std::array<V, 3>& t, V v)
  {
    const int k = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
    return {t[(k + 1) % 3], t[(k + 2) % 3]};
  }

  Triangle_figures figures(V a, V b, V c) const
  {
    Triangle_figures t = triangle_figures(P(a), P(b), P(c), Q(a), Q(b), Q(c));
    t.inverted = triangle_is_inverted(m_surface, P(a), P(b), P(c), m_out.surface_points[a.idx()],
                                      m_out.surface_points[b.idx()], m_out.surface_points[c.idx()], m_side);
    return t;
  }

  // the mean, over the triangles (v, a, b) of v's one-ring `ring`, of the apex of the triangle on (a, b)
  // equilateral in that triangle's mean metric (metric_equilateral_apex()): where each triangle of the
  // ring wants v (the "ideal point" of the smoothing of Vartziotis and Wipper's GETMe, here in the
  // metric); `false` if one of them is degenerate
  bool metric_ideal_point(V v, const std::vector<F>& ring, Eigen::Vector3d& ideal) const
  {
    ideal = Eigen::Vector3d::Zero();
    for(F f : ring) {
      const auto t = corners(f);
      const auto [a, b] = opposite_edge(t, v);
      Eigen::Vector3d apex;
      if(!metric_equilateral_apex(P(v), P(a), P(b), (Q(v) + Q(a) + Q(b)) / 3.0, apex)) return false;
      ideal += apex;
    }
    if(ring.empty()) return false;
    ideal /= double(ring.size());
    return ideal.allFinite();
  }

  Local_score ring_score(const std::vector<F>& ring) const
  {
    Local_score s;
    for(F f : ring) {
      const auto t = corners(f);
      s.add(figures(t[0], t[1], t[2]));
    }
    return s;
  }

  Eigen::Vector3d interpolated_normal(const Surface_point& sp) const { return m_surface.interpolated_normal(sp); }

  // `true` unless vertex `v` was at a tip when the stage started and its one-ring now cuts the tip off:
  // at a tip (an angle deficit above `tip_angle_deficit` at its starting position `p0` with its
  // neighbours now) and with no fixed neighbour (a corner or a crease site holds the shape there), `p0`
  // must lie within a tenth of the mean length of the edges from `p0` to the neighbours of the one-ring
  // the vertex has now. Moved along the surface, the one vertex the CVT left at the tip of a thin part
  // would otherwise cut the tip off, a little more at each round (the cow through cones at 3000
  // vertices: Hausdorff distance 1.3 -> 2.5 % of its diagonal); away from tips nothing changes (the 35
  // runs of the regression set give the same output)
  bool keeps_the_shape_at(V v) const
  {
    typedef CGAL::Simple_cartesian<double> SK;
    const Eigen::Vector3d& p0 = m_start[v.idx()];
    double length = 0;
    std::size_t k = 0;
    std::vector<std::pair<V, V>> opposite;
    for(V u : CGAL::vertices_around_target(m_mesh.halfedge(v), m_mesh)) {
      if(m_fixed[u.idx()]) return true;  // a fixed neighbour (a corner, a crease site) holds the shape
      length += (P(u) - p0).norm(), ++k;
    }
    for(F f : CGAL::faces_around_target(m_mesh.halfedge(v), m_mesh)) {
      if(f == Mesh::null_face()) return true;
      opposite.push_back(opposite_edge(corners(f), v));
    }
    if(k == 0 || angle_deficit(p0, opposite, [&](V x) { return P(x); }) <= tip_angle_deficit) return true;
    const double tolerance = 0.1 * length / double(k);
    auto point = [](const Eigen::Vector3d& x) { return SK::Point_3(x.x(), x.y(), x.z()); };
    const SK::Point_3 q = point(p0);
    for(const auto& e : opposite) {
      const SK::Triangle_3 tri(point(P(v)), point(P(e.first)), point(P(e.second)));
      if(!tri.is_degenerate() && CGAL::squared_distance(q, tri) <= tolerance * tolerance) return true;
    }
    return false;
  }

  bool keeps_the_shape(V a, V b, V c, V d, bool repairs) const
  {
    return flip_keeps_the_shape(m_surface, P(a), P(b), P(c), P(d), repairs);
  }

  const Input_surface& m_surface;
  const AnisotropicMetric& m_metric;
  Remeshed_surface& m_out;
  double m_side;  // planar_side(m_surface)
  Mesh m_mesh;
  std::vector<Eigen::Matrix3d> m_Q;
  std::vector<char> m_fixed;
  std::vector<Eigen::Vector3d> m_start;  // the positions when the stage started (keeps_the_shape_at())
  std::vector<char> m_slide;  // per vertex: slides along the input's boundary (find_sliding_vertices())
  std::size_t m_sliding = 0;
  std::vector<std::array<std::size_t, 2>> m_input_border;  // the input's boundary edges, sorted
  std::vector<std::array<std::size_t, 2>> m_kept;  // Remeshed_surface::kept_edges, sorted: never flipped
  bool m_angle_pass_everywhere;  // Surface_optimization::ALWAYS: sliding boundary vertices
  bool m_flipped = false;
  Settled_marks m_marks;  // what the passes may skip
  double m_relaxed_floors[2] = {-1, -1};
  std::size_t m_visits = 0;
  bool m_exhaustive = false;
};

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_OPTIMIZE_SURFACE_OPTIMIZER_H
