// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_REMESH_LOOP_SITES_H
#define ANISO_CONFORMAL_INTERNAL_REMESH_LOOP_SITES_H

#include <Aniso_conformal/Remeshing_result.h>
#include <Aniso_conformal/internal/remesh/hole_patches.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <deque>
#include <iterator>
#include <map>
#include <queue>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

// The boundary loops of a surface closed by hole_patches.h, in the CVT and the dual mesh: the fixed
// sites along each loop's seam (place_loop_sites()), the output edges between consecutive loop sites
// (recover_loop_edges()) and the removal of the dual triangles on the patches' side of the loops
// (remove_patch_triangles()). Issue 15, item 3; the design is described at the top of hole_patches.h.

namespace Aniso_conformal {
namespace internal {

// The fixed sites along the loops: for each loop, background vertices on its seam in loop order
struct Loop_sites {
  std::vector<std::vector<int>> vertices;  // per loop, the background vertices of its sites, in the loop's order
  std::size_t size() const
  {
    std::size_t k = 0;
    for(const auto& l : vertices) k += l.size();
    return k;
  }
};

// A stretch of a boundary loop's chain of seam vertices (place_loop_sites()): between two kept corners, or
// the whole loop when it has none
struct Loop_stretch {
  std::size_t loop;
  std::vector<double> s;  // arc length at each chain vertex from the stretch's start (its last entry the end)
  std::vector<int> v;
  bool closed;            // a whole loop without corner
  std::size_t count;      // sites strictly inside (closed: all of them)
};

// The sites of place_loop_sites() from its stretches (a loop's chain between two kept corners, or a whole
// loop without corner) and their site counts: each stretch's corner at its start, then its sites at equal
// arc length on the nearest chain vertex (never its ends nor the previous site's vertex); per loop, in order.
// \throws Remeshing_failure if a loop's seam has too few background vertices for its sites, or a loop
// would keep fewer than 3
inline Loop_sites loop_sites_on_stretches(const std::vector<Loop_stretch>& stretches, std::size_t nl)
{
  Loop_sites out;
  out.vertices.resize(nl);
  for(const auto& st : stretches) {
    std::vector<int>& sites = out.vertices[st.loop];
    if(!st.closed) sites.push_back(st.v.front());
    const double len = st.s.back();
    const std::size_t m = st.count;
    const double step = len / double(st.closed ? m : m + 1);
    std::size_t i = 0;
    for(std::size_t k = 0; k < m; ++k) {
      const double target = st.closed ? (double(k) + 0.5) * step : double(k + 1) * step;
      while(i + 1 < st.s.size() && st.s[i + 1] <= target) ++i;
      std::size_t best = (i + 1 < st.s.size() && st.s[i + 1] - target < target - st.s[i]) ? i + 1 : i;
      // never the stretch's ends (corners) nor the vertex of the previous site
      if(!st.closed && best == 0) best = 1;
      if(!st.closed && best + 1 >= st.s.size()) best = st.s.size() - 2;
      if(best >= st.v.size() || (!sites.empty() && sites.back() == st.v[best]))
        throw Remeshing_failure("remesh(): boundary loop " + std::to_string(st.loop) +
                                " has too few background vertices for its sites (its seam is not refined enough)");
      sites.push_back(st.v[best]);
    }
  }
  for(std::size_t l = 0; l < nl; ++l) {
    std::vector<int> sorted = out.vertices[l];
    std::sort(sorted.begin(), sorted.end());
    if(std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw Remeshing_failure("remesh(): two sites of boundary loop " + std::to_string(l) +
                              " fall on the same background vertex (its seam is not refined enough)");
  }
  for(std::size_t l = 0; l < nl; ++l)
    if(out.vertices[l].size() < 3)
      throw Remeshing_failure("remesh(): boundary loop " + std::to_string(l) + " would keep " + std::to_string(out.vertices[l].size()) +
                              " output vertices; at least 3 are needed");
  return out;
}

// Places the sites of every loop: its seam's background vertices in order, the loop's corners (input
// vertices where the loop turns by more than `corner_angle_deg`; with `pinch_corners` false, none of the
// two copies of a point where a loop split at its pinches passes twice, Hole_patches::pinch_vertices:
// the sites at equal arc length then pass by it, as a scan's holes of removed triangles that meet at
// vertices need, CGAL's elephant-with-holes, where a site on each copy let the output join the copies)
// kept, and between two corners (or
// around a loop without one) evenly spaced points at about `h` of metric arc length, each at the seam
// vertex nearest in arc length (the seams are refined to a quarter of `h`). At least 3 sites a loop; in
// all at most `budget` (the longest stretches lose sites first).
inline Loop_sites place_loop_sites(const Intrinsic_triangulation& itri, const Hole_patches& patches, double h, double corner_angle_deg,
                                   std::size_t budget, bool pinch_corners = true)
{
  const std::size_t nl = patches.loops.size();
  std::vector<std::vector<int>> chain(nl);
  for(int v = 0; v < int(itri.number_of_vertices()); ++v)
    if(itri.seam(v) >= 0) chain[std::size_t(itri.seam(v))].push_back(v);
  const double limit = corner_angle_deg * 3.14159265358979323846 / 180.0;
  std::vector<Loop_stretch> stretches;
  std::vector<std::vector<int>> corners(nl);
  for(std::size_t l = 0; l < nl; ++l) {
    auto& c = chain[l];
    std::sort(c.begin(), c.end(), [&](int a, int b) { return itri.seam_parameter(a) < itri.seam_parameter(b); });
    const auto& loop = patches.loops[l];
    std::vector<char> is_corner(c.size(), 0);
    for(std::size_t i = 0; i < c.size(); ++i) {
      if(itri.input_vertex(c[i]) < 0) continue;
      const std::size_t k = std::size_t(itri.seam_parameter(c[i]));
      if(!pinch_corners && std::binary_search(patches.pinch_vertices.begin(), patches.pinch_vertices.end(), loop[k])) continue;
      const Eigen::Vector3d& p = patches.closed.points()[loop[(k + loop.size() - 1) % loop.size()]];
      const Eigen::Vector3d& v = patches.closed.points()[loop[k]];
      const Eigen::Vector3d& q = patches.closed.points()[loop[(k + 1) % loop.size()]];
      const Eigen::Vector3d a = v - p, b = q - v;
      if(std::atan2(a.cross(b).norm(), a.dot(b)) > limit) is_corner[i] = 1;
    }
    // a corner closer than half the spacing (in arc length) to the corner kept before it, or to the first
    // one around the loop, is not kept: the turns of a jagged (scanned) loop would crowd the fixed sites
    std::vector<double> arc(c.size() + 1, 0.0);
    for(std::size_t i = 1; i <= c.size(); ++i) {
      const int u = c[i - 1], v = c[i % c.size()];
      arc[i] = arc[i - 1] + metric_segment_length(itri.position(u), itri.position(v), itri.Q(u), itri.Q(v));
    }
    std::vector<std::size_t> starts;
    for(std::size_t i = 0; i < c.size(); ++i)
      if(is_corner[i] && (starts.empty() || (arc[i] - arc[starts.back()] >= 0.5 * h && arc[c.size()] - arc[i] + arc[starts.front()] >= 0.5 * h)))
        starts.push_back(i);
    const bool none = starts.empty();
    if(none) starts.push_back(0);
    for(std::size_t i : starts)
      if(!none) corners[l].push_back(c[i]);
    for(std::size_t j = 0; j < starts.size(); ++j) {
      Loop_stretch st;
      st.loop = l;
      st.closed = none;
      const std::size_t i0 = starts[j], i1 = j + 1 < starts.size() ? starts[j + 1] : starts[0] + c.size();
      double s = 0;
      for(std::size_t i = i0; i <= i1; ++i) {
        const int v = c[i % c.size()];
        if(i > i0) {
          const int u = c[(i - 1) % c.size()];
          s += metric_segment_length(itri.position(u), itri.position(v), itri.Q(u), itri.Q(v));
        }
        st.s.push_back(s);
        st.v.push_back(v);
      }
      const double m = std::round(s / h) - (none ? 0 : 1);
      st.count = std::size_t(std::max(0.0, m));
      if(none) st.count = std::max<std::size_t>(st.count, 3);
      stretches.push_back(std::move(st));
    }
  }
  // at least 3 sites a loop: a short loop between few corners gets sites in its longest stretches
  for(std::size_t l = 0; l < nl; ++l) {
    std::size_t k = corners[l].size();
    for(const auto& st : stretches)
      if(st.loop == l) k += st.count;
    for(; k < 3; ++k) {
      Loop_stretch* longest = nullptr;
      for(auto& st : stretches)
        if(st.loop == l && (!longest || st.s.back() / double(st.count + 1) > longest->s.back() / double(longest->count + 1))) longest = &st;
      ++longest->count;
    }
  }
  std::size_t total = 0;
  for(const auto& c : corners) total += c.size();
  for(const auto& st : stretches) total += st.count;
  while(total > budget) {
    Loop_stretch* longest = nullptr;
    for(auto& st : stretches)
      if(st.count > (st.closed ? 3u : 0u) && (!longest || st.count > longest->count)) longest = &st;
    if(!longest) break;
    --longest->count;
    --total;
  }
  if(total > budget)
    throw Invalid_input("remesh(): the input's " + std::to_string(nl) + " boundary loops need at least " + std::to_string(total) +
                        " output vertices (3 a loop and its corners) and more inside; only " + std::to_string(budget) +
                        " are available: ask for more vertices");
  return loop_sites_on_stretches(stretches, nl);
}

// Joins the consecutive sites of every loop that the dual left unjoined (`first[l]`: the index of loop
// l's first site, as remove_patch_triangles() reads it): a free site, or the loop's own sites across a
// spike of the surface narrower than their spacing (CGAL's mech-holes-shark.off, a loop turning by 153
// degrees), can stand between them in the Delaunay triangulation of the sites. Each missing edge is
// recovered by a sequence of edge flips along the segment between its sites (recover_edge_by_flips(), the
// flip-based edge recovery of constrained Delaunay triangulation): with `sphere` (the sites on the unit
// sphere, the domain of genus 0) in the gnomonic projection of the domain about the segment's middle,
// where the dual is a planar triangulation and a flip of a convex quadrilateral keeps it one; else, or if
// that fails, on the surface (`closed`: the input with its holes closed, which the output's surface
// points refer to), the input's normals guarding every flip. The edges joining consecutive sites of a
// loop are never flipped. At most 64 flips an edge, no angle bound (the alternative is no output).
// Returns the number of edges recovered; the output is unchanged where none was missing.
inline std::size_t recover_loop_edges(const Input_surface& closed, Remeshed_surface& out, const Loop_sites& loops,
                                      const std::vector<std::size_t>& first, const std::vector<Eigen::Vector3d>* sphere)
{
  Directed_edge_faces face_of;
  for(std::size_t f = 0; f < out.faces.size(); ++f)
    for(int k = 0; k < 3; ++k) face_of[{out.faces[f][std::size_t(k)], out.faces[f][std::size_t((k + 1) % 3)]}] = f;
  auto joined = [&](std::size_t a, std::size_t b) { return face_of.count({a, b}) && face_of.count({b, a}); };
  std::vector<std::array<std::size_t, 2>> pairs, missing;
  for(std::size_t l = 0; l < loops.vertices.size(); ++l) {
    const std::size_t k = loops.vertices[l].size();
    for(std::size_t j = 0; j < k; ++j) {
      const std::size_t a = first[l] + j, b = first[l] + (j + 1) % k;
      pairs.push_back({{std::min(a, b), std::max(a, b)}});
      if(!joined(a, b)) missing.push_back({{a, b}});
    }
  }
  if(missing.empty()) return 0;
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::size_t> valence(out.points.size(), 0);  // neighbours
  for(const auto& e : face_of)
    if(e.first.first < e.first.second || !face_of.count({e.first.second, e.first.first})) {
      ++valence[e.first.first];
      ++valence[e.first.second];
    }
  auto is_pair = [&](std::size_t a, std::size_t b) {
    return std::binary_search(pairs.begin(), pairs.end(), std::array<std::size_t, 2>{{std::min(a, b), std::max(a, b)}});
  };
  if(sphere && sphere->size() != out.points.size()) sphere = nullptr;
  std::size_t recovered = 0;
  for(const auto& ab : missing) {
    if(joined(ab[0], ab[1])) continue;  // joined by the flips of an earlier pair
    bool ok = sphere && recover_edge_by_flips(closed, out, face_of, valence, ab[0], ab[1], 0.0, is_pair, 64, 0.0, sphere);
    if(!ok) ok = recover_edge_by_flips(closed, out, face_of, valence, ab[0], ab[1], 0.0, is_pair, 64, 0.0);
    if(ok) ++recovered;
  }
  return recovered;
}

// The end of the message of remove_patch_triangles() when two consecutive sites of a loop are not joined:
// a free site sits on the chain so close that no flip recovers the edge past it.
constexpr const char* blocked_loop_reason = "a site came too close to the loop";

// The failure of remove_patch_triangles() when two consecutive sites of boundary loop `loop` (an index
// into the input's Input_surface::boundary_loops()) are not joined by an output edge
class Blocked_loop_failure : public Convergence_failure {
public:
  Blocked_loop_failure(const std::string& what, std::size_t loop) : Convergence_failure(what, 0), loop(loop) {}
  std::size_t loop;
};

// Runs `run(false)`; when `loops` and it fails because a free site blocks a loop's chain edge (the
// Convergence_failure of remove_patch_triangles()), runs `run(true)` once (the caller draws the CVT's
// initial sites with the next seed: another CVT, whose sites leave the chain alone), with the first
// failure's message in `why` and its wall time in `discarded`. Any other failure, or a second one, is
// thrown on; but with `any_failure` (an input whose loops pass twice through a point, whose second run
// closes its holes otherwise) every Remeshing_failure of the first run leads to the second. (A repair of
// the dual, moving the blocking site off the chain, would spare the second CVT.)
template <typename Run>
auto run_again_if_a_loop_is_blocked(bool loops, const Run& run, std::string& why, double& discarded, bool any_failure = false)
  -> decltype(run(false))
{
  if(!loops) return run(false);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    return run(false);
  } catch(const Remeshing_failure& e) {
    if(!any_failure && !dynamic_cast<const Blocked_loop_failure*>(&e))
      throw;
    why = e.what();
  }
  discarded = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run(true);
}

// Runs `run(false)`; when it fails because a free site blocks a loop's chain edge (the Blocked_loop_failure
// of remove_patch_triangles(), after every run of run_pipeline()) and that loop of `surface` runs along
// both faces of a part thinner than the output's edge length for `n` vertices (thin_loop_pairs()), runs
// `run(true)` (the caller closes those loops by a collar first, close_holes()), the first failure's wall
// time added to `result.discarded_seconds` (which the second run starts afresh). Otherwise, or if the
// second run fails too, the failure is thrown on. (Always closing thin loops so changed outputs that
// stood: CGAL's blade.off with the isotropic metric lost its first crease run; elephant-with-holes
// failed in the cone domain.)
template <typename Run>
auto run_again_with_collars_if_a_loop_is_blocked(const Input_surface& surface, std::size_t n, Remeshing_result& result,
                                                 const Run& run) -> decltype(run(false))
{
  const auto t0 = std::chrono::steady_clock::now();
  try {
    return run(false);
  } catch(const Blocked_loop_failure& e) {
    const auto& loops = surface.boundary_loops();
    if(e.loop >= loops.size() ||
       thin_loop_pairs(surface.points(), surface.vertex_normals(), loops[e.loop], estimated_output_edge_length(surface, n), 1).empty())
      throw;
  }
  const double discarded = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  auto out = run(true);
  result.discarded_seconds += discarded;
  return out;
}

// Removes from `out` the dual triangles on the patch side of every loop's chain of sites (`first[l]`,
// the index of loop l's first site among the sites, its sites following in order; `first.back()` the
// first of the `apexes` apex sites, one a loop or none (run_pipeline_once()), removed too), and checks
// what is left: consecutive sites of a loop joined by an output edge (those the dual did not join first
// recovered by flips, recover_loop_edges() with `closed`, the input with its holes closed, and `sphere`,
// the sites on the sphere or none), no other site inside a patch, every surface point on the input's own
// vertices. A free site left on the patch side of its loop's chain (all its triangles removed: it sat in a
// part of the surface that the chain's chords cut off, such as the tip of a spike narrower than the
// spacing) is moved to the midpoint, projected onto `input`, of the longest edge of the output left whose
// ends are both free sites, and that edge is split there: the output keeps its number of vertices.
// Returns the number of loop edges recovered and of free sites so moved. Throws Convergence_failure
// otherwise (a fixed site inside a patch, a free site on both sides of a chain, no edge to split).
inline std::pair<std::size_t, std::size_t> remove_patch_triangles(Remeshed_surface& out, const Loop_sites& loops,
                                                                  const std::vector<std::size_t>& first, std::size_t apexes,
                                                                  std::size_t input_vertices, const Input_surface& closed,
                                                                  const Input_surface& input, const std::vector<Eigen::Vector3d>* sphere)
{
  const std::size_t recovered = recover_loop_edges(closed, out, loops, first, sphere);
  const std::size_t apex_first = first.back(), apex_end = apex_first + apexes;
  const std::size_t nf = out.faces.size();
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> face_of;  // directed edge -> face
  for(std::size_t f = 0; f < nf; ++f)
    for(int k = 0; k < 3; ++k) face_of[{out.faces[f][std::size_t(k)], out.faces[f][std::size_t((k + 1) % 3)]}] = f;
  std::vector<std::size_t> loop_of(out.points.size(), std::size_t(-1));
  std::map<std::pair<std::size_t, std::size_t>, char> seam;  // undirected site-chain edges
  std::vector<std::size_t> seeds;
  for(std::size_t l = 0; l < loops.vertices.size(); ++l) {
    const std::size_t k = loops.vertices[l].size();
    for(std::size_t j = 0; j < k; ++j) loop_of[first[l] + j] = l;
    for(std::size_t j = 0; j < k; ++j) {
      const std::size_t a = first[l] + j, b = first[l] + (j + 1) % k;
      const auto inside = face_of.find({a, b}), outside = face_of.find({b, a});
      if(inside == face_of.end() || outside == face_of.end())
        throw Blocked_loop_failure("remesh(): the output does not join sites " + std::to_string(j) + " and " +
                                       std::to_string((j + 1) % k) + " of boundary loop " + std::to_string(l) +
                                       " by an edge (" + blocked_loop_reason + ")",
                                   l);
      seam[{std::min(a, b), std::max(a, b)}] = 1;
      seeds.push_back(outside->second);
    }
  }
  // flood the patch side from the triangles beyond each chain edge, never across a chain edge
  std::vector<char> removed(nf, 0);
  std::vector<std::size_t> stack;
  for(std::size_t f : seeds)
    if(!removed[f]) {
      removed[f] = 1;
      stack.push_back(f);
    }
  while(!stack.empty()) {
    const std::size_t f = stack.back();
    stack.pop_back();
    for(int k = 0; k < 3; ++k) {
      const std::size_t a = out.faces[f][std::size_t(k)], b = out.faces[f][std::size_t((k + 1) % 3)];
      if(seam.count({std::min(a, b), std::max(a, b)})) continue;
      const auto g = face_of.find({b, a});
      if(g != face_of.end() && !removed[g->second]) {
        removed[g->second] = 1;
        stack.push_back(g->second);
      }
    }
  }
  std::vector<std::array<std::size_t, 3>> kept;
  std::vector<char> used(out.points.size(), 0);
  std::vector<std::size_t> stray;  // free sites in a removed triangle
  for(std::size_t f = 0; f < nf; ++f) {
    if(removed[f]) {
      for(std::size_t v : out.faces[f])
        if(loop_of[v] == std::size_t(-1) && (v < apex_first || v >= apex_end)) {
          if(v < apex_end) throw Convergence_failure("remesh(): output vertex " + std::to_string(v) + " lies inside the patch of a hole", 0);
          stray.push_back(v);
        }
      continue;
    }
    kept.push_back(out.faces[f]);
    for(std::size_t v : out.faces[f]) used[v] = 1;
  }
  std::sort(stray.begin(), stray.end());
  stray.erase(std::unique(stray.begin(), stray.end()), stray.end());
  for(std::size_t v : stray) {
    if(used[v]) throw Convergence_failure("remesh(): output vertex " + std::to_string(v) + " lies inside the patch of a hole", 0);
    // the longest edge between two free sites, inside the output left (two triangles), split at v
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> kept_of;
    for(std::size_t f = 0; f < kept.size(); ++f)
      for(int k = 0; k < 3; ++k) kept_of[{kept[f][std::size_t(k)], kept[f][std::size_t((k + 1) % 3)]}] = f;
    double longest = 0;
    std::pair<std::size_t, std::size_t> edge(0, 0);
    for(const auto& e : kept_of) {
      const std::size_t a = e.first.first, b = e.first.second;
      if(a > b || a < apex_end || b < apex_end || !kept_of.count({b, a})) continue;
      const double length = (out.points[a] - out.points[b]).norm();
      if(length > longest) longest = length, edge = e.first;
    }
    if(!(longest > 0))
      throw Convergence_failure("remesh(): output vertex " + std::to_string(v) + " lies inside the patch of a hole", 0);
    const std::size_t a = edge.first, b = edge.second, f = kept_of[{a, b}], g = kept_of[{b, a}];
    const std::size_t c = kept[f][0] + kept[f][1] + kept[f][2] - a - b, d = kept[g][0] + kept[g][1] + kept[g][2] - a - b;
    const Surface_point sp = input.project(0.5 * (out.points[a] + out.points[b]));
    out.points[v] = sp.position;
    out.surface_points[v] = sp;
    // (a, b, c) and (b, a, d) become (a, v, c), (v, b, c), (b, v, d), (v, a, d)
    kept[f] = {{a, v, c}};
    kept[g] = {{b, v, d}};
    kept.push_back({{v, b, c}});
    kept.push_back({{v, a, d}});
    used[v] = 1;
  }
  for(std::size_t v = 0; v < used.size(); ++v) {
    const bool apex = v >= apex_first && v < apex_end;
    if(apex && used[v]) throw Convergence_failure("remesh(): the apex of a hole's patch is joined to the output outside the patch", 0);
    if(!apex && !used[v])
      throw Convergence_failure("remesh(): output vertex " + std::to_string(v) + " is left without a triangle by the holes' patches", 0);
  }
  // the apex sites out, the vertices after them renumbered
  const std::size_t na = apex_end - apex_first;
  for(auto& f : kept)
    for(std::size_t& v : f)
      if(v >= apex_end) v -= na;
  out.points.erase(out.points.begin() + std::ptrdiff_t(apex_first), out.points.begin() + std::ptrdiff_t(apex_end));
  out.surface_points.erase(out.surface_points.begin() + std::ptrdiff_t(apex_first), out.surface_points.begin() + std::ptrdiff_t(apex_end));
  out.fixed_vertices -= std::min(out.fixed_vertices, na);
  for(const Surface_point& sp : out.surface_points)
    for(std::size_t w : sp.vertices)
      if(w >= input_vertices) throw Internal_error("remesh(): an output vertex maps onto a hole's patch");
  out.faces = std::move(kept);
  return {recovered, stray.size()};
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_REMESH_LOOP_SITES_H
