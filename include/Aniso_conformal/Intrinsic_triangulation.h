// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTRINSIC_TRIANGULATION_H
#define ANISO_CONFORMAL_INTRINSIC_TRIANGULATION_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Surface_point.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

/// \file Intrinsic_triangulation.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalStages
 * the background triangulation the pipeline works on: a triangulation whose vertices are points of
 * the input surface (input vertices, or points inserted by edge splits), with per-vertex metric square
 * roots `Q = M^{1/2}` and per-edge lengths measured in the metric.
 *
 * It starts as a copy of the input's connectivity; `adjust_edge_lengths()` flips and splits it.
 * Halfedges are implicit: halfedge `h = 3 f + k` runs from corner `k` to corner `k + 1` of face `f`,
 * `twin(h)` is the opposite halfedge or `-1` on the boundary (geometry-central's compact layout).
 * Faces keep a consistent orientation. `validate()` checks every invariant.
 */
class Intrinsic_triangulation {
public:
  /// \name Creation
  /// @{

  /// copies the connectivity and positions of `surface`; `Q[i]` is the metric square root at input vertex `i`
  Intrinsic_triangulation(const Input_surface& surface, std::vector<Eigen::Matrix3d> Q) : m_Q(std::move(Q))
  {
    const std::size_t nv = surface.number_of_vertices();
    m_points.reserve(nv);
    for(std::size_t i = 0; i < nv; ++i) m_points.push_back(Surface_point::at_vertex(i, surface.points()[i]));
    m_input_vertex.resize(nv);
    for(std::size_t i = 0; i < nv; ++i) m_input_vertex[i] = int(i);
    m_corner.assign(nv, 0);
    for(const auto& f : surface.faces()) m_faces.push_back({{int(f[0]), int(f[1]), int(f[2])}});
    // the input's own angle sums (Euclidean, from the positions): what the boundary of a planar layout
    // that keeps the input's shape is built from (conformal_embedding())
    m_input_angle_sum.assign(nv, 0.0);
    for(const auto& f : surface.faces())
      for(int k = 0; k < 3; ++k) {
        const Eigen::Vector3d& p = surface.points()[f[std::size_t(k)]];
        const Eigen::Vector3d a = surface.points()[f[std::size_t((k + 1) % 3)]] - p, b = surface.points()[f[std::size_t((k + 2) % 3)]] - p;
        m_input_angle_sum[f[std::size_t(k)]] += std::atan2(a.cross(b).norm(), a.dot(b));
      }
    m_twin.assign(3 * m_faces.size(), -1);
    m_length.assign(3 * m_faces.size(), std::numeric_limits<double>::quiet_NaN());
    // twins through the halfedges grouped by tail (linear; the input is a validated manifold, so each
    // directed edge occurs once)
    std::vector<int> start(nv + 1, 0), by_tail(m_twin.size());
    for(int h = 0; h < int(m_twin.size()); ++h) ++start[std::size_t(tail(h)) + 1];
    for(std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    {
      std::vector<int> fill(start.begin(), start.end() - 1);
      for(int h = 0; h < int(m_twin.size()); ++h) by_tail[std::size_t(fill[std::size_t(tail(h))]++)] = h;
    }
    for(int h = 0; h < int(m_twin.size()); ++h) {
      const int t = tail(h), b = head(h);
      for(int i = start[std::size_t(b)]; i < start[std::size_t(b) + 1]; ++i)
        if(head(by_tail[std::size_t(i)]) == t) m_twin[h] = by_tail[std::size_t(i)];
    }
    m_out.assign(nv, -1);
    for(int h = 0; h < int(m_twin.size()); ++h) m_out[tail(h)] = h;
  }
  /// @}

  /// \name Connectivity
  /// @{
  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }                     ///< next halfedge in the face
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }                     ///< previous halfedge in the face
  static int face(int h) { return h / 3; }                                          ///< face of a halfedge
  int tail(int h) const { return m_faces[h / 3][h % 3]; }                           ///< vertex the halfedge leaves
  int head(int h) const { return m_faces[h / 3][(h % 3 + 1) % 3]; }                 ///< vertex the halfedge enters
  int opposite_vertex(int h) const { return m_faces[h / 3][(h % 3 + 2) % 3]; }       ///< third vertex of h's face
  int twin(int h) const { return m_twin[h]; }                                       ///< opposite halfedge, -1 on the boundary
  bool is_boundary_edge(int h) const { return m_twin[h] < 0; }                      ///< `true` if h has no twin
  std::size_t number_of_vertices() const { return m_points.size(); }                ///< vertex count
  std::size_t number_of_faces() const { return m_faces.size(); }                    ///< face count
  std::size_t number_of_halfedges() const { return m_twin.size(); }                 ///< 3 x face count
  const std::array<int, 3>& face_vertices(std::size_t f) const { return m_faces[f]; } ///< corners of a face
  /// one halfedge per edge (the one with the larger index is skipped)
  bool is_edge_representative(int h) const { return m_twin[h] < 0 || m_twin[h] > h; }
  /// the outgoing halfedges of `v` in counterclockwise order; for a boundary vertex the first one is on the boundary
  std::vector<int> outgoing_halfedges(int v) const
  {
    std::vector<int> out;
    first_outgoing(v, [&out](int h) {
      out.push_back(h);
      return false;
    });
    return out;
  }
  /// `true` if `v` lies on the boundary
  bool is_boundary_vertex(int v) const
  {
    for(int h : outgoing_halfedges(v))
      if(m_twin[h] < 0 || m_twin[prev(h)] < 0) return true;
    return false;
  }
  /// `true` if a halfedge goes from `a` to `b` (`find_halfedge(a, b) >= 0`, one walk around `a` instead of two:
  /// the intrinsic Delaunay flips ask it of every edge they would make, a fifth of the time of CGAL's blade
  /// through the sphere)
  bool has_edge(int a, int b) const
  {
    const int h0 = m_out[a];
    int h = h0;
    std::size_t visited = 0;
    do {  // counterclockwise from h0, to the boundary or once around
      if(head(h) == b) return true;
      const int p = m_twin[prev(h)];
      if(p < 0) break;
      h = p;
    } while(h != h0 && ++visited <= m_twin.size());
    if(h == h0 && visited > 0) return false;  // once around an interior vertex
    for(h = h0; m_twin[h] >= 0 && visited++ <= m_twin.size();) {  // clockwise from h0, to the boundary
      h = next(m_twin[h]);
      if(head(h) == b) return true;
    }
    return false;
  }
  /// the halfedge from `a` to `b`, or -1
  int find_halfedge(int a, int b) const
  {
    return first_outgoing(a, [&](int h) { return head(h) == b; });  // with a double edge, the first in that order
  }
  /// @}

  /// \name Geometry and metric
  /// @{
  const Surface_point& point(int v) const { return m_points[v]; }                   ///< where the vertex lies on the input
  const Eigen::Vector3d& position(int v) const { return m_points[v].position; }     ///< its position in space
  const Eigen::Matrix3d& Q(int v) const { return m_Q[v]; }                          ///< metric square root at the vertex
  /// index of the input vertex this vertex copies, or -1 for an inserted vertex
  int input_vertex(int v) const { return m_input_vertex[v]; }
  double length(int h) const { return m_length[h]; }                                ///< metric length of the edge of h
  /// `true` if every edge has a finite positive length: a new triangulation's lengths are NaN until
  /// `compute_metric_edge_lengths()` or `adjust_edge_lengths()` sets them (the embeddings need them)
  bool has_edge_lengths() const
  {
    return std::all_of(m_length.begin(), m_length.end(), [](double l) { return std::isfinite(l) && l > 0; });
  }
  /// sets the length of the edge of `h` (both halfedges)
  void set_length(int h, double l)
  {
    m_length[h] = l;
    if(m_twin[h] >= 0) m_length[m_twin[h]] = l;
  }
  /*!
   * the sum of the input triangles' angles (Euclidean, in radians) at the point of vertex `v`, measured
   * on the input surface, not in the metric: at a boundary vertex, the input's interior angle there, so
   * that `pi - input_angle_sum(v)` is the turning angle of the input's boundary (its geodesic curvature,
   * concentrated at the vertex). A vertex inserted by a split gets `pi` on a boundary edge and `2 pi`
   * inside (a point of an input edge or face).
   */
  double input_angle_sum(int v) const { return m_input_angle_sum[std::size_t(v)]; }
  /// marks `v` as a boundary corner (kept as an output vertex)
  void set_corner(int v, bool c) { m_corner[v] = c; }
  bool is_corner(int v) const { return m_corner[v] != 0; }                           ///< `true` for a boundary corner
  /// @}

  /// \name Hole patches
  /// A surface with boundary loops is remeshed in a closed domain after each hole is closed by a virtual
  /// patch (`internal::close_holes()`): the patch's faces carry no CVT density, and the loop's edges (the
  /// seams between the surface and a patch) are never flipped, so that every face stays on one side of a
  /// seam. Nothing is tagged on a surface without patches.
  /// @{

  /// tags vertex `v` as on seam `loop` (0, 1, ...) at parameter `t` along it (input vertex `k` of a loop of
  /// `size` vertices at `t = k`; a split of a seam edge at the mean of its ends' parameters)
  void set_seam_vertex(int v, int loop, double t, std::size_t size)
  {
    if(m_seam.empty()) m_seam.assign(m_points.size(), -1), m_seam_t.assign(m_points.size(), 0.0);
    if(m_seam_size.size() <= std::size_t(loop)) m_seam_size.resize(std::size_t(loop) + 1, 0);
    m_seam[v] = loop;
    m_seam_t[v] = t;
    m_seam_size[std::size_t(loop)] = size;
  }
  /// the seam of vertex `v`, -1 if none
  int seam(int v) const { return m_seam.empty() ? -1 : m_seam[std::size_t(v)]; }
  /// the parameter of seam vertex `v` along its seam (in `[0, size)`)
  double seam_parameter(int v) const { return m_seam_t[std::size_t(v)]; }
  /// `true` if the edge of `h` is a piece of a seam (its ends consecutive on one seam): it is never flipped
  bool is_seam_edge(int h) const { return seam_neighbours(tail(h), head(h)); }
  /// `true` if the edge of `h` lies on its input loop: a seam edge whose ends are on one input loop edge
  /// (no input vertex strictly between their parameters). A seam edge that is not (a chord cutting a
  /// corner of the loop, from `k - 1/2` to `k + 1/2`, which the refinement's splits make next to a sharp
  /// turn) is never flipped either, but a split of it is not on the loop and is not tagged as a seam vertex
  bool is_seam_piece(int h) const
  {
    if(!is_seam_edge(h)) return false;
    double ta = m_seam_t[std::size_t(tail(h))], tb = m_seam_t[std::size_t(head(h))];
    const double L = double(m_seam_size[std::size_t(m_seam[std::size_t(tail(h))])]);
    if(std::abs(ta - tb) > 0.5 * L) (ta < tb ? ta : tb) += L;  // the piece across t = 0
    const double lo = std::min(ta, tb), hi = std::max(ta, tb);
    return !(std::floor(lo) + 1 < hi - 1e-12);  // no integer k with lo < k < hi
  }
  /// `true` if flipping the edge of `h` would join two vertices of one seam no farther apart along it
  /// than an input loop edge: that edge would count as a seam piece, and the triangle between it and
  /// the seam pieces it spans, all on the straight input edge, would be flat for good (a spoke of a
  /// patch flipped next to a split seam edge did this: issue 15, item 3). Such an edge is never flipped.
  bool flip_joins_seam_neighbours(int h) const
  {
    if(m_seam.empty() || twin(h) < 0) return false;
    return seam_neighbours(head(next(h)), head(next(twin(h))));
  }
  /// tags face `f` as a face of a hole's patch
  void set_patch_face(int f)
  {
    if(m_patch.empty()) m_patch.assign(m_faces.size(), 0);
    m_patch[std::size_t(f)] = 1;
  }
  /// `true` if face `f` lies in a hole's patch (no CVT density there, no output triangle)
  bool is_patch_face(std::size_t f) const { return !m_patch.empty() && m_patch[f] != 0; }
  /// `true` if some face is a patch's
  bool has_patches() const { return !m_patch.empty(); }
  /// @}

  /// \name Modification
  /// @{
  /*!
   * flips the interior edge of `h`: the two triangles `(a,b,c)` and `(b,a,d)` become `(c,a,d)` and
   * `(d,b,c)`. Returns the halfedge from `d` to `c`. The new edge length is left to the caller.
   */
  int flip(int h)
  {
    const int t = m_twin[h];
    if(t < 0) throw Internal_error("Intrinsic_triangulation::flip(): boundary edge");
    const int f0 = face(h), f1 = face(t);
    const int a = tail(h), b = head(h), c = opposite_vertex(h), d = opposite_vertex(t);
    const int hbc = next(h), hca = prev(h), had = next(t), hdb = prev(t);
    const int Tbc = m_twin[hbc], Tca = m_twin[hca], Tad = m_twin[had], Tdb = m_twin[hdb];
    const double Lbc = m_length[hbc], Lca = m_length[hca], Lad = m_length[had], Ldb = m_length[hdb];
    m_faces[f0] = {{c, a, d}};
    m_faces[f1] = {{d, b, c}};
    link(3 * f0 + 0, Tca, Lca);
    link(3 * f0 + 1, Tad, Lad);
    link(3 * f1 + 0, Tdb, Ldb);
    link(3 * f1 + 1, Tbc, Lbc);
    link(3 * f0 + 2, 3 * f1 + 2, std::numeric_limits<double>::quiet_NaN());
    m_out[c] = 3 * f0 + 0;
    m_out[a] = 3 * f0 + 1;
    m_out[d] = 3 * f1 + 0;
    m_out[b] = 3 * f1 + 1;
    return 3 * f0 + 2;
  }

  /*!
   * splits the edge of `h` at the new vertex `p` (with metric square root `Q`), splitting its one or two
   * triangles in two. Returns the new vertex. The lengths of the new edges are left to the caller.
   */
  int split(int h, const Surface_point& p, const Eigen::Matrix3d& Q)
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const int t = m_twin[h];
    const int m = int(m_points.size());
    m_points.push_back(p);
    m_Q.push_back(Q);
    m_input_vertex.push_back(-1);
    m_corner.push_back(0);
    m_input_angle_sum.push_back(t >= 0 ? 2 * 3.14159265358979323846 : 3.14159265358979323846);
    m_out.push_back(-1);
    if(!m_seam.empty()) {  // a split seam piece: the new vertex is on the seam, halfway in parameter
      const bool on_seam = is_seam_piece(h);
      const int a = tail(h), b = head(h);
      double ta = m_seam_t[std::size_t(a)], tb = m_seam_t[std::size_t(b)];
      if(on_seam) {
        const double L = double(m_seam_size[std::size_t(m_seam[std::size_t(a)])]);
        if(std::abs(ta - tb) > 0.5 * L) (ta < tb ? ta : tb) += L;  // the piece across t = 0
        double t = 0.5 * (ta + tb);
        if(t >= L) t -= L;
        m_seam.push_back(m_seam[std::size_t(a)]);
        m_seam_t.push_back(t);
      } else {
        m_seam.push_back(-1);
        m_seam_t.push_back(0.0);
      }
    }
    const int f0 = face(h);
    const int a = tail(h), b = head(h), c = opposite_vertex(h);
    const int f2 = split_face(h, m);  // f0 = (a, m, c), f2 = (m, b, c)
    m_length[3 * f0 + 0] = m_length[3 * f2 + 0] = nan;
    if(t >= 0) {
      const int f1 = face(t), d = opposite_vertex(t);
      const int f3 = split_face(t, m);  // f1 = (b, m, d), f3 = (m, a, d)
      link(3 * f1 + 0, 3 * f2 + 0, nan);  // b->m / m->b
      link(3 * f3 + 0, 3 * f0 + 0, nan);  // m->a / a->m
      m_out[d] = 3 * f3 + 2;
    } else {
      m_twin[3 * f0 + 0] = -1;
      m_twin[3 * f2 + 0] = -1;
    }
    m_out[a] = 3 * f0 + 0;
    m_out[b] = 3 * f2 + 1;
    m_out[c] = 3 * f0 + 2;
    m_out[m] = 3 * f2 + 0;
    return m;
  }
  /// @}

  /// \name Checks
  /// @{

  /// a 64-bit hash (FNV-1a) of the whole state, bit for bit: vertices (surface points, metric tensors,
  /// input vertices, corners, angle sums, seams), faces, twins, edge lengths and patches. Equal
  /// triangulations have equal fingerprints; the pipeline's runs reuse a conformal embedding computed from
  /// a background with the same fingerprint (internal/remesh/embedding_memo.h)
  std::uint64_t fingerprint() const
  {
    std::uint64_t h = 14695981039346656037ULL;
    auto bytes = [&h](const void* data, std::size_t size) {
      const unsigned char* c = static_cast<const unsigned char*>(data);
      for(std::size_t i = 0; i < size; ++i) h = (h ^ c[i]) * 1099511628211ULL;
    };
    auto array = [&](const auto& v) {
      const std::uint64_t n = v.size();
      bytes(&n, sizeof n);
      if(!v.empty()) bytes(v.data(), v.size() * sizeof(v[0]));
    };
    for(const Surface_point& p : m_points) {
      bytes(p.position.data(), 3 * sizeof(double));
      bytes(p.vertices.data(), 3 * sizeof(std::size_t));
      bytes(p.barycentric.data(), 3 * sizeof(double));
    }
    for(const Eigen::Matrix3d& q : m_Q) bytes(q.data(), 9 * sizeof(double));
    array(m_input_vertex);
    array(m_corner);
    array(m_input_angle_sum);
    array(m_faces);
    array(m_twin);
    array(m_length);
    array(m_out);
    array(m_seam);
    array(m_seam_t);
    array(m_seam_size);
    array(m_patch);
    return h;
  }

  /// throws `Internal_error` if an invariant is broken (twins, orientation, vertex halfedges, lengths if `with_lengths`)
  void validate(bool with_lengths = false) const
  {
    for(int h = 0; h < int(m_twin.size()); ++h) {
      int t = m_twin[h];
      if(t >= 0) {
        if(m_twin[t] != h) throw Internal_error("twin(twin(h)) != h at halfedge " + std::to_string(h));
        if(tail(t) != head(h) || head(t) != tail(h))
          throw Internal_error("twins with inconsistent ends at halfedge " + std::to_string(h));
        if(with_lengths && m_length[t] != m_length[h])
          throw Internal_error("twins with different lengths at halfedge " + std::to_string(h));
      }
      if(with_lengths && !(m_length[h] > 0)) throw Internal_error("invalid length at halfedge " + std::to_string(h));
    }
    for(int v = 0; v < int(m_points.size()); ++v)
      if(m_out[v] < 0 || tail(m_out[v]) != v)
        throw Internal_error("vertex " + std::to_string(v) + " has no valid outgoing halfedge");
  }
  /// @}

private:
  // The walk of outgoing_halfedges(v): clockwise from v's halfedge to the boundary (or once around), then
  // counterclockwise from there, until `stop(h)`; returns that h, or -1 when none stops it. find_halfedge()
  // walks without building the list.
  template <typename Stop>
  int first_outgoing(int v, const Stop& stop) const
  {
    const int h0 = m_out[v];
    int h = h0;
    while(true) {
      const int t = m_twin[h];
      if(t < 0) break;
      const int g = next(t);
      if(g == h0) break;
      h = g;
    }
    const int start = h;
    std::size_t visited = 0;
    do {
      if(stop(h)) return h;
      ++visited;
      const int p = m_twin[prev(h)];
      if(p < 0) break;
      h = p;
    } while(h != start && visited <= m_twin.size());
    return -1;
  }
  // makes halfedges x and y twins (y may be -1: a boundary), both of length `length`
  // splits the face of halfedge `e` = (x, y), opposite corner z, at the new vertex `m` on `e`: the face
  // becomes (x, m, z) in place and (m, y, z) is added (returned), joined by the edge m-z (length NaN);
  // the outer edges y-z and z-x keep their twins and lengths. The halves of `e` are left to the caller.
  int split_face(int e, int m)
  {
    const int f = face(e), x = tail(e), y = head(e), z = opposite_vertex(e);
    const int Tyz = m_twin[next(e)], Tzx = m_twin[prev(e)];
    const double Lyz = m_length[next(e)], Lzx = m_length[prev(e)];
    m_faces[f] = {{x, m, z}};
    const int g = add_face({{m, y, z}});
    if(!m_patch.empty()) m_patch.push_back(m_patch[std::size_t(f)]);
    link(3 * f + 1, 3 * g + 2, std::numeric_limits<double>::quiet_NaN());  // m->z / z->m
    link(3 * f + 2, Tzx, Lzx);
    link(3 * g + 1, Tyz, Lyz);
    return g;
  }
  void link(int x, int y, double length)
  {
    m_twin[x] = y;
    m_length[x] = length;
    if(y >= 0) {
      m_twin[y] = x;
      m_length[y] = length;
    }
  }
  // appends the face with corners c, its halfedges without twins or lengths; returns its index
  int add_face(const std::array<int, 3>& c)
  {
    m_faces.push_back(c);
    m_twin.resize(3 * m_faces.size(), -1);
    m_length.resize(3 * m_faces.size(), std::numeric_limits<double>::quiet_NaN());
    return int(m_faces.size()) - 1;
  }

  std::vector<Surface_point> m_points;
  std::vector<Eigen::Matrix3d> m_Q;
  std::vector<int> m_input_vertex;
  std::vector<char> m_corner;
  std::vector<double> m_input_angle_sum;
  std::vector<std::array<int, 3>> m_faces;
  std::vector<int> m_twin;
  std::vector<double> m_length;
  std::vector<int> m_out;
  // `true` if `a` and `b` lie on one seam no farther apart along it than an input loop edge
  bool seam_neighbours(int a, int b) const
  {
    if(m_seam.empty()) return false;
    if(m_seam[std::size_t(a)] < 0 || m_seam[std::size_t(a)] != m_seam[std::size_t(b)]) return false;
    const double L = double(m_seam_size[std::size_t(m_seam[std::size_t(a)])]);
    const double d = std::abs(m_seam_t[std::size_t(a)] - m_seam_t[std::size_t(b)]);
    return std::min(d, L - d) <= 1.0 + 1e-12;
  }

  std::vector<int> m_seam;                // per vertex: its seam, -1 (empty: no seam)
  std::vector<double> m_seam_t;           // per vertex: its parameter along its seam
  std::vector<std::size_t> m_seam_size;   // per seam: its number of input vertices
  std::vector<char> m_patch;              // per face: 1 in a hole's patch (empty: no patch)
};

namespace internal {
// the precondition of the conformal embeddings: `itri`'s edge lengths are set (`who` names the caller)
inline void require_edge_lengths(const Intrinsic_triangulation& itri, const std::string& who)
{
  if(!itri.has_edge_lengths())
    throw Invalid_input(who + ": the background's edge lengths are not set (or not all finite and positive): compute them "
                              "first with compute_metric_edge_lengths() or adjust_edge_lengths()");
}
} // namespace internal

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTRINSIC_TRIANGULATION_H
