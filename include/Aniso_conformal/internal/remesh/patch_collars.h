// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_REMESH_PATCH_COLLARS_H
#define ANISO_CONFORMAL_INTERNAL_REMESH_PATCH_COLLARS_H

#include <Aniso_conformal/Input_surface.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

// Thin boundary loops (issue 15, item 3): a hole whose loop runs along both faces of a part thinner than
// the output's edges (the open ends of CGAL's blade.off, a hollow blade 0.46 thick where the output's
// edges are about 0.7 long at 2000 vertices) closed by a flat patch puts the loop's sites on one face one
// patch-width from those on the other: the CVT's free sites next to the loop then join, through the
// patch, the other face's loop sites, across the chain of the loop's own sites, and the output does not
// join two consecutive loop sites (remove_patch_triangles(): "a site came too close to the loop"). A
// thin loop is therefore closed by a collar first: rings of copies of the loop pushed along the surface's
// normals, which open the two faces apart, then the cone over the last ring (close_holes()). Through the
// collar, two loop points on opposite faces are at least twice its height apart; the collar's faces
// carry no CVT density and no output vertex, as every patch face.

namespace Aniso_conformal {
namespace internal {

// `true` if the cone of close_holes() over `loop` (points `pts`, centroid `c`, Newell vector `newell`)
// folds over itself: some fan triangle (centroid, loop[i], loop[i + 1]), seen along `newell`, turns the
// other way round the centroid than the loop as a whole, i.e. the loop is not star-shaped about its
// centroid in its mean plane. Such a cone closes the hole with a crumpled surface: the fan triangles of
// the folds add their angles at the apex and at the loop vertices where they should cancel (CGAL's
// lion.off: apex angle sum 647 degrees, loop vertices with 2 pi minus their angle sum from -163 to +284
// degrees, against at most 74 on the scans that embed), and the flat metric has singularities of that
// strength on the seam, whose edges cannot flip: its triangles there go flat whatever their size.
inline bool cone_folds(const std::vector<Eigen::Vector3d>& pts, const std::vector<std::size_t>& loop, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& newell)
{
  const Eigen::Vector3d n = newell.normalized();
  for(std::size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector3d a = pts[loop[i]] - c, b = pts[loop[(i + 1) % loop.size()]] - c;
    if(a.cross(b).dot(n) < -1e-12 * a.norm() * b.norm()) return true;  // a radial edge (0 up to rounding) is no fold
  }
  return false;
}

// The centroid, Newell vector (twice the vector area) and mean distance to the centroid of the points
// `pts` of `loop`, and its length: what close_holes() places a cone's apex by
struct Loop_frame {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), newell = Eigen::Vector3d::Zero();
  double radius = 0, length = 0;
};
inline Loop_frame loop_frame(const std::vector<Eigen::Vector3d>& pts, const std::vector<std::size_t>& loop)
{
  Loop_frame f;
  const std::size_t m = loop.size();
  if(m == 0) return f;
  for(std::size_t v : loop) f.centroid += pts[v];
  f.centroid /= double(m);
  for(std::size_t i = 0; i < m; ++i) {
    f.newell += pts[loop[i]].cross(pts[loop[(i + 1) % m]]);
    f.radius += (pts[loop[i]] - f.centroid).norm();
    f.length += (pts[loop[(i + 1) % m]] - pts[loop[i]]).norm();
  }
  f.radius /= double(m);
  return f;
}

// The edge length of an isotropic output of `n` vertices over the area of `s` (equilateral triangles,
// two per vertex): the scale against which close_holes() judges a loop thin. Length unit of the input.
inline double estimated_output_edge_length(const Input_surface& s, std::size_t n)
{
  double area = 0;
  for(const auto& f : s.faces())
    area += 0.5 * (s.points()[f[1]] - s.points()[f[0]]).cross(s.points()[f[2]] - s.points()[f[0]]).norm();
  return n > 0 ? std::sqrt(2 * area / (std::sqrt(3.0) * double(n))) : 0.0;
}

// The pairs (i, j), i < j, of positions on `loop` (points `pts`, unit vertex normals `normals`) closer
// than `h` in space but more than three times their distance apart along the loop (the shorter way
// round), whose normals face away from each other (at more than 120 degrees): the places where the loop
// runs along both faces of a part thinner than `h`. (A notch of a hole in a plate, whose two sides face
// the same way, is none: a collar there would only crumple.) A loop through one vertex twice (a pinch) has none
// (split_loop_at_pinches() handles those). A grid of cells of size h finds them in O(loop size) for
// loops that are not crowded; at most `most` pairs are returned.
inline std::vector<std::pair<std::size_t, std::size_t>> thin_loop_pairs(const std::vector<Eigen::Vector3d>& pts,
                                                                        const std::vector<Eigen::Vector3d>& normals,
                                                                        const std::vector<std::size_t>& loop, double h,
                                                                        std::size_t most = 4096)
{
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  const std::size_t m = loop.size();
  if(m < 4 || !(h > 0)) return pairs;
  {
    std::vector<std::size_t> sorted = loop;
    std::sort(sorted.begin(), sorted.end());
    if(std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return pairs;  // a pinch
  }
  std::vector<double> s(m + 1, 0.0);  // arc length at each position, s[m] the loop's length
  for(std::size_t i = 0; i < m; ++i) s[i + 1] = s[i] + (pts[loop[(i + 1) % m]] - pts[loop[i]]).norm();
  const double length = s[m];
  auto key = [&](const Eigen::Vector3d& p, int dx, int dy, int dz) {
    const auto c = [&](double x, int d) { return std::int64_t(std::floor(x / h)) + d; };
    return (std::uint64_t(c(p.x(), dx)) * 73856093u) ^ (std::uint64_t(c(p.y(), dy)) * 19349663u) ^ (std::uint64_t(c(p.z(), dz)) * 83492791u);
  };
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
  for(std::size_t i = 0; i < m; ++i) grid[key(pts[loop[i]], 0, 0, 0)].push_back(i);
  for(std::size_t i = 0; i < m && pairs.size() < most; ++i)
    for(int dx = -1; dx <= 1; ++dx)
      for(int dy = -1; dy <= 1; ++dy)
        for(int dz = -1; dz <= 1; ++dz) {
          const auto cell = grid.find(key(pts[loop[i]], dx, dy, dz));
          if(cell == grid.end()) continue;
          for(const std::size_t j : cell->second) {
            if(j <= i || pairs.size() >= most) continue;
            const double d = (pts[loop[i]] - pts[loop[j]]).norm(), along = std::min(s[j] - s[i], length - (s[j] - s[i]));
            if(d < h && along > 3 * d && normals[loop[i]].dot(normals[loop[j]]) < -0.5) pairs.emplace_back(i, j);
          }
        }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());  // hash collisions list a cell twice
  return pairs;
}

// Adds to `points` and `faces` the collar of `loop` (in the orientation of the surface's faces; `normals`
// the surface's unit vertex normals): `rings` rings of copies of the loop, ring k at k / rings of
// `height` along each loop vertex's normal, on the side that moves the `thin` pairs (thin_loop_pairs())
// farther apart, joined ring to ring by two triangles a loop edge, oriented as the surface. Returns the
// last ring (the indices of its vertices, in the loop's order), which the caller closes. `on_new_vertex(i)`
// is called for each new vertex, with the position on the loop it copies.
template <typename OnNewVertex>
std::vector<std::size_t> add_patch_collar(const std::vector<std::size_t>& loop, const std::vector<Eigen::Vector3d>& normals,
                                          const std::vector<std::pair<std::size_t, std::size_t>>& thin, double height, int rings,
                                          std::vector<Eigen::Vector3d>& points, std::vector<Input_surface::Face>& faces,
                                          const OnNewVertex& on_new_vertex)
{
  const std::size_t m = loop.size();
  // the side: the one whose last ring holds the thin pairs farther apart (their smallest distance)
  double sign = 1, best = -1;
  for(const double side : {1.0, -1.0}) {
    double closest = std::numeric_limits<double>::infinity();
    for(const auto& ij : thin) {
      const Eigen::Vector3d a = points[loop[ij.first]] + side * height * normals[loop[ij.first]],
                            b = points[loop[ij.second]] + side * height * normals[loop[ij.second]];
      closest = std::min(closest, (a - b).norm());
    }
    if(closest > best) best = closest, sign = side;
  }
  std::vector<std::size_t> below = loop, ring(m);
  for(int k = 1; k <= rings; ++k) {
    const double t = sign * height * double(k) / double(rings);
    for(std::size_t i = 0; i < m; ++i) {
      ring[i] = points.size();
      points.push_back(points[loop[i]] + t * normals[loop[i]]);
      on_new_vertex(i);
    }
    // the face (b, a, a') runs along the loop edge a -> b backwards, as the cone's (b, a, apex) does
    for(std::size_t i = 0; i < m; ++i) {
      const std::size_t a0 = below[i], b0 = below[(i + 1) % m], a1 = ring[i], b1 = ring[(i + 1) % m];
      faces.push_back({{b0, a0, a1}});
      faces.push_back({{b0, a1, b1}});
    }
    below = ring;
  }
  return ring;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_REMESH_PATCH_COLLARS_H
