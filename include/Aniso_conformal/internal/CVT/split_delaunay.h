// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_CVT_SPLIT_DELAUNAY_H
#define ANISO_CONFORMAL_INTERNAL_CVT_SPLIT_DELAUNAY_H

#include <Aniso_conformal/internal/domains/indexed_delaunay_2.h>
#include <Aniso_conformal/internal/parallel_for.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

// The Delaunay graph of a planar point set built as two triangulations, one per half, on two threads
// (the CVT rebuilds it at every evaluation of its energy, and one CGAL triangulation of the sites was a
// third of the CVT's time, serial).
//
// The points are split at the median m of their coordinate along the longer side of their bounding box
// (say x). Each half's triangulation holds the points of its side and those within a margin beyond it,
// i.e. every point of the set in its "held" half-plane (x < m + margin, resp. x > m - margin). A
// triangle of a half is a Delaunay triangle of the whole set if its circumscribed disk holds no point of
// the set: true when the disk lies inside the held half-plane, otherwise tested against the points
// beyond it (a bucket grid). A point whose finite triangles in its own half are all certified so has
// the Delaunay neighbours of the whole set (points in general position: a cocircular configuration may
// be triangulated either way, in a half as in one triangulation). The caller says which triangles
// matter (`matters`); a point with a triangle that matters and one not certified makes the split fail,
// and the caller builds one triangulation instead (whole_delaunay_fans()). Both give the graph with the
// neighbours of every point in increasing order, so that the integrals clipped against the cells do not
// depend on which one ran, nor on the number of threads.
//
// On the convex hull: the infinite triangles of a half are not tested. A point on the hull of its half
// that is not on the hull of the whole set (a point of the other side beyond the hull edge) misses the
// neighbours it has across that edge in the whole set, through triangles whose disks reach outside the
// hull: their Voronoi edges lie outside the point set. The flat torus' triangles that matter lie inside
// a band of copies three site spacings or more wider than the background, so the cells over the
// background are the same; the tests compare both constructions point by point.

namespace Aniso_conformal {
namespace internal {

// The Delaunay graph in CSR form (neighbours of point i: nbr[start[i] .. start[i+1]), increasing) and
// the finite Delaunay triangles that matter (vertex indices increasing, each once, in no particular
// order, with the centre and radius of their circumscribed circle). A point with no vertex of its own
// (it coincides with another point) has no neighbour.
struct Delaunay_fans {
  std::vector<int> start, nbr;
  std::vector<std::array<int, 3>> faces;
  std::vector<Eigen::Vector2d> centre;
  std::vector<double> radius;

  // room for the triangles of a triangulation of about n points
  void reserve_faces(std::size_t n)
  {
    faces.reserve(2 * n + 64);
    centre.reserve(2 * n + 64);
    radius.reserve(2 * n + 64);
  }
};

namespace split_delaunay_detail {

// the centre of the circle through the points v[0] < v[1] < v[2], computed from them in that order, so
// that every triangulation holding the triangle gets the same bits
inline Eigen::Vector2d circumcentre(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c)
{
  const Eigen::Vector2d q = b - a, r = c - a;
  const double d = 2 * (q.x() * r.y() - q.y() * r.x());
  const double q2 = q.squaredNorm(), r2 = r.squaredNorm();
  return a + Eigen::Vector2d((r.y() * q2 - q.y() * r2) / d, (q.x() * r2 - r.x() * q2) / d);
}
inline Eigen::Vector2d circumcentre(const std::vector<Eigen::Vector2d>& pts, const std::array<int, 3>& v)
{
  return circumcentre(pts[std::size_t(v[0])], pts[std::size_t(v[1])], pts[std::size_t(v[2])]);
}

// The finite triangles of `dt` with a vertex `own(i)`: each is tested once, `trusted(centre, radius)`
// (else its vertices get flag bit 1) and `matters(v, centre)` (then its vertices get bit 2, and it goes
// to `out` if own(v[0]), v sorted). `flag` has one entry per point.
template <typename DT, typename Own, typename Matters, typename Trusted>
void test_faces(const DT& dt, const std::vector<Eigen::Vector2d>& pts, const Own& own, const Matters& matters, const Trusted& trusted,
                std::vector<unsigned char>& flag, Delaunay_fans& out)
{
  for(auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    std::array<int, 3> v{{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}};
    if(!own(v[0]) && !own(v[1]) && !own(v[2])) continue;
    std::sort(v.begin(), v.end());
    const Eigen::Vector2d c = circumcentre(pts, v);
    const double r = (c - pts[std::size_t(v[0])]).norm();
    const unsigned char bits = (trusted(c, r) ? 0 : 1) | (matters(v, c) ? 2 : 0);
    if(bits == 0) continue;
    for(int k = 0; k < 3; ++k) flag[std::size_t(v[k])] |= bits;
    if((bits & 2) && own(v[0])) {
      out.faces.push_back(v);
      out.centre.push_back(c);
      out.radius.push_back(r);
    }
  }
}

// The neighbours of the vertices of `dt` (vertex info: the point index, below n) whose point `want`s
// them, in CSR form over all n points (start has n + 1 entries; the others get none), each list in
// increasing order: the directed edges of every face, counterclockwise, the infinite faces giving their
// finite edge (a hull vertex's neighbour across the hull), bucketed by head then by tail (two counting
// sorts instead of a sort per list).
template <typename DT, typename Want>
void sorted_neighbour_lists(const DT& dt, std::size_t n, const Want& want, std::vector<int>& start, std::vector<int>& nbr)
{
  start.assign(n + 1, 0);
  nbr.clear();
  if(dt.dimension() < 2) {  // no faces: circulate
    std::vector<std::vector<int>> lists(n);
    for(auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
      if(!want(v->info())) continue;
      auto w = dt.incident_vertices(v), done = w;
      if(w != nullptr) do {
          if(!dt.is_infinite(w)) lists[std::size_t(v->info())].push_back(w->info());
        } while(++w != done);
      std::sort(lists[std::size_t(v->info())].begin(), lists[std::size_t(v->info())].end());
    }
    for(std::size_t i = 0; i < n; ++i) {
      start[i] = int(nbr.size());
      nbr.insert(nbr.end(), lists[i].begin(), lists[i].end());
    }
    start[n] = int(nbr.size());
    return;
  }
  std::vector<int> tail, head;
  tail.reserve(6 * n + 16);
  head.reserve(6 * n + 16);
  for(auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f)
    for(int k = 0; k < 3; ++k) {
      const auto a = f->vertex(DT::ccw(k)), b = f->vertex(DT::cw(k));
      if(dt.is_infinite(a) || dt.is_infinite(b) || !want(a->info())) continue;
      tail.push_back(a->info());
      head.push_back(b->info());
    }
  const std::size_t m = tail.size();
  std::vector<int> by_head_start(n + 1, 0), by_head(m);
  for(std::size_t e = 0; e < m; ++e) ++by_head_start[std::size_t(head[e]) + 1];
  for(std::size_t i = 0; i < n; ++i) by_head_start[i + 1] += by_head_start[i];
  {
    std::vector<int> fill(by_head_start.begin(), by_head_start.end() - 1);
    for(std::size_t e = 0; e < m; ++e) by_head[std::size_t(fill[std::size_t(head[e])]++)] = int(e);
  }
  for(std::size_t e = 0; e < m; ++e) ++start[std::size_t(tail[e]) + 1];
  for(std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  nbr.resize(m);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for(std::size_t k = 0; k < m; ++k) {
    const std::size_t e = std::size_t(by_head[k]);
    nbr[std::size_t(fill[std::size_t(tail[e])]++)] = head[e];
  }
}

// A uniform grid of bucketed points (about one per cell) that answers whether a disk holds a point of
// a given side of a vertical line.
class Point_buckets {
public:
  explicit Point_buckets(const std::vector<Eigen::Vector2d>& pts) : m_pts(pts)
  {
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for(const auto& p : pts) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const Eigen::Vector2d ext = (hi - lo).cwiseMax(1e-300);
    m_lo = lo;
    m_cell = std::max(std::sqrt(ext.x() * ext.y() / double(std::max<std::size_t>(1, pts.size()))), 1e-6 * std::max(ext.x(), ext.y()));
    m_nx = std::max(1, std::min(1 << 14, int(ext.x() / m_cell) + 1));
    m_ny = std::max(1, std::min(1 << 14, int(ext.y() / m_cell) + 1));
    m_start.assign(std::size_t(m_nx) * std::size_t(m_ny) + 1, 0);
    std::vector<std::size_t> cell_of(pts.size());
    for(std::size_t i = 0; i < pts.size(); ++i) {
      cell_of[i] = cell(pts[i]);
      ++m_start[cell_of[i] + 1];
    }
    for(std::size_t c = 1; c < m_start.size(); ++c) m_start[c] += m_start[c - 1];
    m_index.resize(pts.size());
    std::vector<std::size_t> fill(m_start.begin(), m_start.end() - 1);
    for(std::size_t i = 0; i < pts.size(); ++i) m_index[fill[cell_of[i]]++] = int(i);
  }

  // whether the disk (centre c, radius r; enlarged by a relative 1e-9, so that a point on the circle
  // counts as inside) holds a point p with p[axis] >= line (beyond = true) or p[axis] <= line (beyond =
  // false)
  bool disk_holds(const Eigen::Vector2d& c, double r, int axis, double line, bool beyond) const
  {
    const double r2 = r * r * (1 + 1e-9);
    Eigen::Vector2d a = c - Eigen::Vector2d(r, r), b = c + Eigen::Vector2d(r, r);
    if(beyond)
      a[axis] = std::max(a[axis], line);
    else
      b[axis] = std::min(b[axis], line);
    if(a[axis] > b[axis]) return false;
    const int i0 = clamp_x(a.x()), i1 = clamp_x(b.x()), j0 = clamp_y(a.y()), j1 = clamp_y(b.y());
    for(int j = j0; j <= j1; ++j)
      for(int i = i0; i <= i1; ++i) {
        const std::size_t k = std::size_t(j) * std::size_t(m_nx) + std::size_t(i);
        for(std::size_t e = m_start[k]; e < m_start[k + 1]; ++e) {
          const Eigen::Vector2d& p = m_pts[std::size_t(m_index[e])];
          if((beyond ? p[axis] >= line : p[axis] <= line) && (p - c).squaredNorm() <= r2) return true;
        }
      }
    return false;
  }

private:
  int clamp_x(double x) const { return std::max(0, std::min(m_nx - 1, int(std::floor((x - m_lo.x()) / m_cell)))); }
  int clamp_y(double y) const { return std::max(0, std::min(m_ny - 1, int(std::floor((y - m_lo.y()) / m_cell)))); }
  std::size_t cell(const Eigen::Vector2d& p) const { return std::size_t(clamp_y(p.y())) * std::size_t(m_nx) + std::size_t(clamp_x(p.x())); }

  const std::vector<Eigen::Vector2d>& m_pts;
  Eigen::Vector2d m_lo;
  double m_cell = 1;
  int m_nx = 1, m_ny = 1;
  std::vector<std::size_t> m_start;
  std::vector<int> m_index;
};

} // namespace split_delaunay_detail

/*
 * The Delaunay graph of `pts` from one CGAL triangulation of all of them (see the file comment);
 * `matters(v, centre)` says which finite triangles (v: vertex indices, centre: their circumcentre) go to
 * out.faces.
 */
template <typename Matters>
void whole_delaunay_fans(const std::vector<Eigen::Vector2d>& pts, const Matters& matters, Delaunay_fans& out)
{
  Indexed_delaunay_2 d;
  d.build(pts);
  out = Delaunay_fans();
  out.reserve_faces(pts.size());
  std::vector<unsigned char> flag(pts.size(), 0);
  split_delaunay_detail::test_faces(
      d.dt, pts, [](int) { return true; }, matters, [](const Eigen::Vector2d&, double) { return true; }, flag, out);
  split_delaunay_detail::sorted_neighbour_lists(d.dt, pts.size(), [](int) { return true; }, out.start, out.nbr);
}

/*
 * The Delaunay graph of `pts` from two triangulations, one per half (see the file comment), on up to
 * `threads` threads (0: every core; two are used, one builds the halves in turn): `margin` is how far
 * (in the points' units) each half reaches beyond the median, a few point spacings. Returns false, with
 * `out` unspecified, when a point with a triangle that matters has a triangle not certified (the margin
 * is too narrow there for the points' spacing), or for fewer than 64 points: the caller then calls
 * whole_delaunay_fans(). On success `out` is what whole_delaunay_fans() gives for points in general
 * position, up to the order of out.faces.
 */
template <typename Matters>
bool split_delaunay_fans(const std::vector<Eigen::Vector2d>& pts, double margin, unsigned threads, const Matters& matters,
                         Delaunay_fans& out)
{
  const std::size_t n = pts.size();
  if(n < 64 || !(margin > 0)) return false;
  // split across the longer side of the bounding box
  Eigen::Vector2d lo = pts[0], hi = pts[0];
  for(const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const int axis = hi.x() - lo.x() >= hi.y() - lo.y() ? 0 : 1;
  std::vector<double> xs(n);
  for(std::size_t i = 0; i < n; ++i) xs[i] = pts[i][axis];
  std::nth_element(xs.begin(), xs.begin() + std::ptrdiff_t(n / 2), xs.end());
  const double split = xs[n / 2];
  // point i belongs to half 0 if its coordinate is below the split, else to half 1
  struct Half {
    std::vector<int> owned;          // points of this side, increasing
    std::vector<int> start, nbr;     // CSR over all points: the neighbours of the owned ones
    Delaunay_fans faces;             // the triangles that matter found from this side
    bool ok = true;
  };
  std::array<Half, 2> half;
  for(std::size_t i = 0; i < n; ++i) half[pts[i][axis] < split ? 0 : 1].owned.push_back(int(i));
  if(half[0].owned.empty() || half[1].owned.empty()) return false;

  const split_delaunay_detail::Point_buckets buckets(pts);
  auto build_half = [&](std::size_t h) {
    Half& H = half[h];
    const bool left = h == 0;
    std::vector<std::pair<Indexed_delaunay_2::K::Point_2, int>> in;
    in.reserve(n / 2 + n / 8);
    for(std::size_t i = 0; i < n; ++i)
      if(left ? pts[i][axis] < split + margin : pts[i][axis] > split - margin)
        in.emplace_back(Indexed_delaunay_2::K::Point_2(pts[i].x(), pts[i].y()), int(i));
    Indexed_delaunay_2::Triangulation dt;
    dt.insert(in.begin(), in.end());
    H.faces.reserve_faces(H.owned.size());
    // a circle inside the half-plane of the points held is empty; one that leaves it, if no point
    // outside the half-plane lies in it
    const auto trusted = [&](const Eigen::Vector2d& c, double r) {
      if(left ? c[axis] + r < split + margin : c[axis] - r > split - margin) return true;
      return !buckets.disk_holds(c, r, axis, left ? split + margin : split - margin, left);
    };
    const auto own = [&](int i) { return (pts[std::size_t(i)][axis] < split) == left; };
    std::vector<unsigned char> flag(n, 0);
    split_delaunay_detail::test_faces(dt, pts, own, matters, trusted, flag, H.faces);
    for(int i : H.owned)
      if(flag[std::size_t(i)] == 3) {  // a triangle that matters, and one not certified
        H.ok = false;
        return;
      }
    split_delaunay_detail::sorted_neighbour_lists(dt, n, own, H.start, H.nbr);
  };
  parallel_blocks(
      2, threads,
      [&](std::size_t begin, std::size_t end, std::size_t) {
        for(std::size_t h = begin; h < end; ++h) build_half(h);
      },
      1);
  if(!half[0].ok || !half[1].ok) return false;

  // merge: the CSR in point order
  out = Delaunay_fans();
  out.start.assign(n + 1, 0);
  out.nbr.reserve(half[0].nbr.size() + half[1].nbr.size());
  for(std::size_t i = 0; i < n; ++i) {
    out.start[i] = int(out.nbr.size());
    const Half& H = half[pts[i][axis] < split ? 0 : 1];
    out.nbr.insert(out.nbr.end(), H.nbr.begin() + H.start[i], H.nbr.begin() + H.start[i + 1]);
  }
  out.start[n] = int(out.nbr.size());
  for(const Half& H : half) {
    out.faces.insert(out.faces.end(), H.faces.faces.begin(), H.faces.faces.end());
    out.centre.insert(out.centre.end(), H.faces.centre.begin(), H.faces.centre.end());
    out.radius.insert(out.radius.end(), H.faces.radius.begin(), H.faces.radius.end());
  }
  return true;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_CVT_SPLIT_DELAUNAY_H
