// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Surfaces with several boundary loops, or a boundary and a genus (issue 15, item 3): each hole closed by a
// virtual patch, the surface remeshed in the closed domain of its genus (the sphere, the flat torus: the
// two domains this module compiles), every loop a chain of fixed sites. An annulus, an open tube, a plate
// with two square holes and a torus with a hole keep their topology, exactly N vertices, every output
// vertex on an output boundary on the input's loops, no inverted triangle.

#ifndef ANISO_CONFORMAL_TEST_UNITY  // else compiled with other modules in one translation unit (CMakeLists.txt)
#define BOOST_TEST_MODULE Aniso_conformal_boundaries
#endif
#include <boost/test/unit_test.hpp>

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Flat_torus_domain.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Spherical_domain.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/remesh_in_domain.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <set>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "mesh_checks.h"

BOOST_AUTO_TEST_SUITE(boundaries)  // also a namespace: keeps the helpers apart from other modules in one unit

namespace AC = Aniso_conformal;

namespace {

AC::Input_surface read_case(const std::string& name)
{
  return AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cases/" + name);
}

// The surface of `faces` over `points` without the points of no face (those inside the holes)
AC::Input_surface without_unused_points(const std::vector<Eigen::Vector3d>& points, std::vector<AC::Input_surface::Face> faces)
{
  std::vector<long> index(points.size(), -1);
  for(const auto& f : faces)
    for(std::size_t v : f) index[v] = 0;
  std::vector<Eigen::Vector3d> kept;
  for(std::size_t v = 0; v < points.size(); ++v)
    if(index[v] == 0) {
      index[v] = long(kept.size());
      kept.push_back(points[v]);
    }
  for(auto& f : faces)
    for(std::size_t& v : f) v = std::size_t(index[v]);
  return AC::Input_surface(std::move(kept), std::move(faces));
}

// The grid of a unit square plate of m x m quads, (m + 1)^2 points (point (i, j) at j (m + 1) + i), two
// triangles a cell but for the cells (i, j) where hole(i, j)
template <typename Hole>
void plate_grid(int m, const Hole& hole, std::vector<Eigen::Vector3d>& points, std::vector<AC::Input_surface::Face>& faces)
{
  for(int j = 0; j <= m; ++j)
    for(int i = 0; i <= m; ++i) points.push_back(Eigen::Vector3d(double(i) / m, double(j) / m, 0));
  auto at = [m](int i, int j) { return std::size_t(j * (m + 1) + i); };
  for(int j = 0; j < m; ++j)
    for(int i = 0; i < m; ++i) {
      if(hole(i, j)) continue;
      faces.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}});
      faces.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}});
    }
}

// A unit square plate of m x m quads without the cells (i, j) where hole(i, j)
template <typename Hole>
AC::Input_surface make_plate(int m, const Hole& hole)
{
  std::vector<Eigen::Vector3d> points;
  std::vector<AC::Input_surface::Face> faces;
  plate_grid(m, hole, points, faces);
  return without_unused_points(points, std::move(faces));
}

// A unit square plate of m x m quads with the quads of two rectangles of cells removed: 3 loops (the
// outline and two holes), each with 4 corners
AC::Input_surface make_plate_with_two_holes(int m)
{
  return make_plate(m, [m](int i, int j) {
    return (i >= m / 6 && i < m / 6 + m / 4 && j >= m / 6 && j < m / 6 + m / 4) ||
           (i >= m / 2 + m / 12 && i < m / 2 + m / 12 + m / 4 && j >= m / 2 && j < m / 2 + m / 3);
  });
}

using test::segment_distance;

double diagonal(const AC::Input_surface& s)
{
  Eigen::Vector3d lo = s.points().front(), hi = lo;
  for(const auto& p : s.points()) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

// Remeshes `input` in `Domain` with n vertices and checks the output: n vertices, the input's genus and
// number of loops, each output loop's vertices on one input loop (within 1e-9 of the diagonal), no
// inverted triangle; prints the quality
template <typename Domain>
AC::Remeshing_result check_remesh(const std::string& name, const AC::Input_surface& input, std::size_t n,
                                  AC::Remeshed_surface* output = nullptr)
{
  AC::Remeshing_result result;
  const AC::Remeshed_surface out =
    AC::remesh_in_domain<Domain>(input, AC::Uniform_metric(), result, AC::parameters::number_of_vertices(n).random_seed(0));
  BOOST_TEST(out.points.size() == n);
  std::vector<AC::Input_surface::Face> faces(out.faces.begin(), out.faces.end());
  const AC::Input_surface s(out.points, std::move(faces));
  BOOST_TEST(s.genus() == input.genus());
  BOOST_TEST(s.boundary_loops().size() == input.boundary_loops().size());
  BOOST_TEST(result.inverted_triangles == 0u);
  const double tolerance = 1e-9 * diagonal(input);
  std::size_t on_loops = 0;
  for(const auto& out_loop : s.boundary_loops()) {
    // the input loop nearest to the output loop's first vertex holds all of it
    double worst = 0;
    std::size_t best_loop = 0;
    double best = 1e300;
    for(std::size_t l = 0; l < input.boundary_loops().size(); ++l) {
      const auto& loop = input.boundary_loops()[l];
      for(std::size_t i = 0; i < loop.size(); ++i) {
        const double d = segment_distance(out.points[out_loop.front()], input.points()[loop[i]], input.points()[loop[(i + 1) % loop.size()]]);
        if(d < best) best = d, best_loop = l;
      }
    }
    const auto& loop = input.boundary_loops()[best_loop];
    for(std::size_t v : out_loop) {
      double d = 1e300;
      for(std::size_t i = 0; i < loop.size(); ++i)
        d = std::min(d, segment_distance(out.points[v], input.points()[loop[i]], input.points()[loop[(i + 1) % loop.size()]]));
      worst = std::max(worst, d);
    }
    BOOST_TEST(worst < tolerance);
    on_loops += out_loop.size();
  }
  BOOST_TEST(on_loops == result.boundary_sites);
  std::printf("%-16s n=%zu loops=%zu genus=%d boundary vertices=%zu G_avg=%.3f theta_min=%.1f %%<30=%.1f hausdorff=%.2e\n",
              name.c_str(), n, s.boundary_loops().size(), s.genus(), on_loops, result.quality.G_avg, result.quality.theta_min,
              result.quality.percent_below_30, result.hausdorff_distance_relative);
  if(output) *output = out;
  return result;
}

// The length of a shortest path from `from` to `to` along the edges of `s`
double graph_distance(const AC::Input_surface& s, std::size_t from, std::size_t to)
{
  const auto& pts = s.points();
  std::vector<std::vector<std::size_t>> adjacent(pts.size());
  for(const auto& f : s.faces())
    for(std::size_t k = 0; k < 3; ++k) adjacent[f[k]].push_back(f[(k + 1) % 3]);
  std::vector<double> d(pts.size(), 1e300);
  std::vector<std::pair<double, std::size_t>> heap{{0.0, from}};
  d[from] = 0;
  while(!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), std::greater<>());
    const auto [dv, v] = heap.back();
    heap.pop_back();
    if(v == to) return dv;
    if(dv > d[v]) continue;
    for(const std::size_t w : adjacent[v])
      if(dv + (pts[v] - pts[w]).norm() < d[w]) {
        d[w] = dv + (pts[v] - pts[w]).norm();
        heap.push_back({d[w], w});
        std::push_heap(heap.begin(), heap.end(), std::greater<>());
      }
  }
  return d[to];
}

} // namespace

BOOST_AUTO_TEST_CASE(annulus_keeps_both_loops)
{
  const AC::Input_surface annulus = read_case("annulus.off");
  BOOST_TEST_REQUIRE(annulus.boundary_loops().size() == 2u);
  // 200 and 300 failed with one flat triangle per edge of a loop, until a patch's spokes next to a split
  // seam edge were no longer flipped into a flat triangle on the seam (Intrinsic_triangulation::
  // flip_joins_seam_neighbours())
  for(std::size_t n : {200u, 300u, 400u}) check_remesh<AC::Spherical_domain>("annulus", annulus, n);
}

BOOST_AUTO_TEST_CASE(open_tube_keeps_both_loops_at_several_sizes)
{
  const AC::Input_surface tube = read_case("tube_lowpoly.off");
  BOOST_TEST_REQUIRE(tube.boundary_loops().size() == 2u);
  for(std::size_t n : {60u, 100u, 300u}) check_remesh<AC::Spherical_domain>("tube", tube, n);
}

BOOST_AUTO_TEST_CASE(plate_with_two_holes_keeps_three_loops)
{
  const AC::Input_surface plate = make_plate_with_two_holes(24);
  BOOST_TEST_REQUIRE(plate.boundary_loops().size() == 3u);
  check_remesh<AC::Spherical_domain>("plate 2 holes", plate, 500);
}

// a 24 x 24 plate with a hole of 2 x 2 cells in the middle: the outline's patch covers more than half of
// the sphere, so the patches hold apex sites (the sphere's dual needs sites all around it), but the small
// hole's apex, which sees an edge of its loop's few sites under more than 60 degrees at 60 to 200
// vertices, is left out (remesh_in_domain.h; at 400 it is kept): both paths, with the same outputs as
// when every apex was kept
BOOST_AUTO_TEST_CASE(plate_with_a_small_hole_keeps_both_loops)
{
  const AC::Input_surface plate = make_plate(24, [](int i, int j) { return i >= 11 && i < 13 && j >= 11 && j < 13; });
  BOOST_TEST_REQUIRE(plate.boundary_loops().size() == 2u);
  for(std::size_t n : {100u, 400u}) check_remesh<AC::Spherical_domain>("plate small hole", plate, n);
}

// A 24 x 24 plate with a U-shaped hole two cells wide (cells 4..19 x 4..5 and the arms 4..5 and 18..19 up
// to row 19): the hole's loop is not star-shaped about its centroid, which lies on the plate between the
// arms. The cone over it folded (40 of its 92 fan triangles turned the other way round; apex angle sum
// 531 degrees), the seam carried singularities of the flat metric of that strength, and the spherical
// embedding at 300 vertices found a triangle flat on the seam (exit 3, also after the seam splits). Such a
// hole is now filled by Liepa's method (close_holes()): the plate being planar, so is its fill, and every
// vertex of the hole's loop has an angle sum of 2 pi on the closed surface. (At 600 and 1000 vertices this
// plate still fails on its outline, whose cone keeps 172 degrees of curvature at each corner, with or
// without the fill.)
BOOST_AUTO_TEST_CASE(plate_with_a_hole_not_star_shaped_keeps_both_loops)
{
  const AC::Input_surface plate = make_plate(24, [](int i, int j) {
    return (i >= 4 && i < 20 && j >= 4 && j < 6) || (i >= 4 && i < 6 && j >= 4 && j < 20) || (i >= 18 && i < 20 && j >= 4 && j < 20);
  });
  BOOST_TEST_REQUIRE(plate.boundary_loops().size() == 2u);
  const AC::internal::Hole_patches patches = AC::internal::close_holes(plate);
  const double pi = 3.14159265358979323846;
  std::vector<double> angle_sum(patches.closed.number_of_vertices(), 0.0);
  for(const auto& f : patches.closed.faces())
    for(std::size_t k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = patches.closed.points()[f[k]];
      const Eigen::Vector3d a = patches.closed.points()[f[(k + 1) % 3]] - p, b = patches.closed.points()[f[(k + 2) % 3]] - p;
      angle_sum[f[k]] += std::atan2(a.cross(b).norm(), a.dot(b));
    }
  // the outline (96 vertices) keeps its cone, one apex; the U (92 vertices) is filled, flat
  const std::size_t u = plate.boundary_loops()[0].size() < plate.boundary_loops()[1].size() ? 0 : 1;
  double worst = 0;
  for(std::size_t v : plate.boundary_loops()[u]) worst = std::max(worst, std::abs(angle_sum[v] - 2 * pi));
  BOOST_TEST(worst < 1e-9);
  BOOST_TEST(patches.closed.number_of_vertices() > plate.number_of_vertices() + 2);
  check_remesh<AC::Spherical_domain>("plate U hole", plate, 300);
}

// A 24 x 24 plate with a square hole (cells 6..17 x 6..17) into which a tongue of the plate one cell wide
// reaches (cells 12 x 6..6 + length - 1), narrower than the output spacing. Before this round every run
// below failed: with a tongue of 8 cells at 600 and 700 vertices "the output does not join sites 28 and 29
// (26 and 27) of boundary loop 0 by an edge", with 6 cells at 400 "output vertex 393 lies inside the
// patch of a hole". The cause: a background edge from k - 1/2 to k + 1/2 along a loop, cutting the
// corner at input vertex k, counted as a seam edge, and its splits were tagged as seam vertices although
// they lie inside the surface, so loop sites were placed off the loop near the plate's and the tongue's
// corners (up to 6e-3 of the diagonal) and the chain zigzagged (Intrinsic_triangulation::is_seam_piece()).
// At 400 with 6 cells, a free site was still cut off with the tongue's tip into the patch and moved
// (remove_patch_triangles()) while the initial sites were drawn by rho; drawn by rho^(1/2), the CVT
// leaves none there (the count is printed, no longer asserted: no test input of ours reaches that
// mending now); loop edges the dual misses are recovered by flips (recover_loop_edges(),
// needed by CGAL's mech-holes-shark.off, benchmark/boundaries.md). Measured: G_avg 0.91, 0.91 and 0.89,
// theta_min 32.6, 32.1 and 33.4 degrees.
namespace {
AC::Input_surface make_plate_with_tongue(int length)
{
  return make_plate(24, [length](int i, int j) { return i >= 6 && i < 18 && j >= 6 && j < 18 && !(i == 12 && j < 6 + length); });
}
} // namespace

BOOST_AUTO_TEST_CASE(plate_with_a_thin_tongue_into_its_hole_keeps_both_loops)
{
  const AC::Input_surface plate = make_plate_with_tongue(8);
  BOOST_TEST_REQUIRE(plate.boundary_loops().size() == 2u);
  for(std::size_t n : {600u, 700u}) {
    const AC::Remeshing_result r = check_remesh<AC::Spherical_domain>("plate tongue 8", plate, n);
    BOOST_TEST(r.quality.G_avg > 0.88);
    BOOST_TEST(r.quality.theta_min > 25.0);
  }
  const AC::Input_surface shorter = make_plate_with_tongue(6);
  const AC::Remeshing_result r = check_remesh<AC::Spherical_domain>("plate tongue 6", shorter, 400);
  BOOST_TEST_MESSAGE("plate tongue 6 at 400: " << r.patch_sites_moved << " sites moved out of the patch");
  BOOST_TEST(r.quality.theta_min > 25.0);
}

BOOST_AUTO_TEST_CASE(the_shark_loop_edges_the_dual_misses_are_recovered_by_flips)
{
  // CGAL's mech-holes-shark.off (4 boundary loops, a narrow spike on loop 0): at 1500 vertices the sites of
  // the spike's two sides were joined across it, leaving consecutive loop sites unjoined ("the output does
  // not join sites 3 and 4 of boundary loop 0 by an edge"); the missing loop edges are now recovered by
  // flips. Measured when written: 3 edges recovered, G_avg 0.927, theta_min 25.9 degrees; on 2026-12-07 (the
  // tool, --domain sphere, seed 0) G_avg 0.934, theta_min 22.2: the smallest angle moved with later changes
  // to the CVT's set-up, still above the bound of 20
  const AC::Input_surface shark = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cgal/mech-holes-shark.off");
  BOOST_TEST_REQUIRE(shark.boundary_loops().size() == 4u);
  const AC::Remeshing_result r = check_remesh<AC::Spherical_domain>("shark", shark, 1500);
  BOOST_TEST(r.loop_edges_recovered > 0u);
  BOOST_TEST(r.quality.G_avg > 0.9);
  BOOST_TEST(r.quality.theta_min > 20.0);
}

// A necklace of `beads` square holes of k x k cells along the diagonal of a 24 x 24 plate, each touching
// the next at a corner, every such corner vertex duplicated (one copy in the faces of each of the two
// plate cells that touch it), so that the surface is manifold and the holes are one boundary loop that
// passes twice through each of the beads - 1 pinch points, as the jagged holes of a scan where removed
// triangles meet at a vertex (CGAL's elephant-with-holes.off: 38 such loops, 65 pinches;
// benchmark/boundaries.md). Two beads: a figure-of-eight hole of 8 k edges, pinched at (12, 12).
namespace {
AC::Input_surface make_plate_with_necklace_hole(int beads, int k)
{
  const int m = 24, c = 12 - beads * k / 2;
  std::vector<Eigen::Vector3d> points;
  std::vector<AC::Input_surface::Face> faces;
  plate_grid(m, [&](int i, int j) { return i >= c && j >= c && (i - c) / k == (j - c) / k && (i - c) / k < beads; }, points, faces);
  for(int b = 1; b < beads; ++b) {
    const int q = c + b * k;  // the pinch (q, q): the faces below it take the copy
    const std::size_t pinch = std::size_t(q * (m + 1) + q), copy = points.size();
    points.push_back(points[pinch]);
    for(auto& f : faces)
      if(std::count(f.begin(), f.end(), pinch) && std::any_of(f.begin(), f.end(), [&](std::size_t v) { return v < std::size_t(q * (m + 1)); }))
        std::replace(f.begin(), f.end(), pinch, copy);
  }
  return without_unused_points(points, std::move(faces));
}
} // namespace

// A figure-of-eight hole keeps its loop and both copies of the pinch point. Measured here: G_avg
// 0.937-0.955, theta_min 34.6-39.9; with the tool (seed 0) at 300 to 1500 vertices for k = 1, 2 and 4
// through the sphere, and at 300 and 800 through cones: G_avg 0.938-0.958, theta_min 34.7-40.0.
BOOST_AUTO_TEST_CASE(plate_with_a_pinched_hole_keeps_its_loop_through_the_pinch_twice)
{
  for(int k : {1, 4}) {
    const AC::Input_surface plate = make_plate_with_necklace_hole(2, k);
    BOOST_TEST_REQUIRE(plate.boundary_loops().size() == 2u);  // the outline and the figure-of-eight hole
    const std::size_t hole = plate.boundary_loops()[0].size() < plate.boundary_loops()[1].size() ? 0 : 1;
    BOOST_TEST_REQUIRE(plate.boundary_loops()[hole].size() == std::size_t(8 * k));
    for(std::size_t n : {300u, 800u}) {
      AC::Remeshed_surface out;
      const AC::Remeshing_result checked = check_remesh<AC::Spherical_domain>("plate pinched hole", plate, n, &out);
      std::size_t at_pinch = 0;
      for(const Eigen::Vector3d& p : out.points) at_pinch += (p - Eigen::Vector3d(0.5, 0.5, 0)).norm() < 1e-12;
      BOOST_TEST(at_pinch == 2u);  // both copies: the output's loop passes twice through the pinch too
      BOOST_TEST(checked.quality.G_avg > 0.9);
      BOOST_TEST(checked.quality.theta_min > 25.0);
    }
  }
}

// The necklaces of 4 holes of one cell and of 3 of two cells. Measured here: G_avg 0.905-0.956,
// theta_min 34.0-36.7. Three of the four cases (all but 3 beads at 600) are remeshed by the second run,
// lobe by lobe: in the first, the single patch over the necklace made 8 to 16 triangles flat on the
// sphere (the tool of 32a67b9 refused them with --domain sphere; its automatic choice fell back to
// cones).
BOOST_AUTO_TEST_CASE(plate_with_a_necklace_hole_keeps_its_loop)
{
  for(const auto& bk : {std::array<int, 2>{{4, 1}}, std::array<int, 2>{{3, 2}}}) {
    const AC::Input_surface plate = make_plate_with_necklace_hole(bk[0], bk[1]);
    BOOST_TEST_REQUIRE(plate.boundary_loops().size() == 2u);  // the outline and the necklace
    const std::size_t hole = plate.boundary_loops()[0].size() < plate.boundary_loops()[1].size() ? 0 : 1;
    BOOST_TEST_REQUIRE(plate.boundary_loops()[hole].size() == std::size_t(4 * bk[0] * bk[1]));
    for(std::size_t n : {150u, 600u}) {
      const AC::Remeshing_result r = check_remesh<AC::Spherical_domain>("plate necklace", plate, n);
      BOOST_TEST(r.quality.G_avg > 0.85);
      BOOST_TEST(r.quality.theta_min > 20.0);
      if(!r.reseeded.empty()) std::printf("  second run, lobe by lobe, after: %.100s\n", r.reseeded.c_str());
    }
  }
}

// The second run after a blocked loop closes a pinched loop lobe by lobe (hole_patches.h,
// split_loop_at_pinches(); CGAL's elephant-with-holes remeshes that way, benchmark/boundaries.md): the
// closed surface keeps the genus, one bridge vertex a pinch, and no patch edge joins a copy of a pinch
// point to the other copy or to one of its loop neighbours (so the copies are at least two edges apart
// through the patches); the first run's single patch does not guarantee that
BOOST_AUTO_TEST_CASE(a_pinched_loop_split_into_lobes_keeps_the_copies_apart)
{
  for(const auto& bk : {std::array<int, 2>{{2, 1}}, std::array<int, 2>{{4, 1}}, std::array<int, 2>{{3, 2}}}) {
    const AC::Input_surface plate = make_plate_with_necklace_hole(bk[0], bk[1]);
    BOOST_TEST(AC::internal::has_pinched_loop(plate));
    const AC::internal::Hole_patches whole = AC::internal::close_holes(plate);
    BOOST_TEST(whole.pinch_vertices.empty());
    const AC::internal::Hole_patches split = AC::internal::close_holes(plate, true);
    BOOST_TEST(split.closed.genus() == 0);
    BOOST_TEST(split.closed.boundary_loops().empty());
    BOOST_TEST(split.pinch_vertices.size() == std::size_t(2 * (bk[0] - 1)));
    std::size_t bridges = 0;
    for(const auto& pv : split.patch_vertices) bridges += pv.bridge;
    BOOST_TEST(bridges == std::size_t(bk[0] - 1));
    // the copies, and the loop neighbours of each
    const std::vector<std::size_t>& loop = split.loops[0].size() < split.loops[1].size() ? split.loops[0] : split.loops[1];
    std::set<std::array<std::size_t, 2>> apart;  // pairs that no patch edge may join
    for(std::size_t a : split.pinch_vertices)
      for(std::size_t b : split.pinch_vertices)
        if(a != b && (plate.points()[a] - plate.points()[b]).norm() < 1e-12) {
          apart.insert({{a, b}});
          const std::size_t k = std::size_t(std::find(loop.begin(), loop.end(), b) - loop.begin());
          BOOST_TEST_REQUIRE(k < loop.size());
          apart.insert({{a, loop[(k + 1) % loop.size()]}});
          apart.insert({{a, loop[(k + loop.size() - 1) % loop.size()]}});
        }
    BOOST_TEST(apart.size() == std::size_t(6 * (bk[0] - 1)));
    for(std::size_t f = split.input_faces; f < split.closed.number_of_faces(); ++f)
      for(int i = 0; i < 3; ++i) {
        const std::size_t a = split.closed.faces()[f][std::size_t(i)], b = split.closed.faces()[f][std::size_t((i + 1) % 3)];
        BOOST_TEST((!apart.count({{a, b}}) && !apart.count({{b, a}})));
      }
  }
}

BOOST_AUTO_TEST_CASE(torus_with_a_hole_keeps_its_genus_and_loop)
{
  const AC::Input_surface torus = read_case("torus_with_hole.off");
  BOOST_TEST_REQUIRE(torus.genus() == 1);
  BOOST_TEST_REQUIRE(torus.boundary_loops().size() == 1u);
  check_remesh<AC::Flat_torus_domain>("torus with hole", torus, 600);
}

BOOST_AUTO_TEST_CASE(torus_with_a_hole_keeps_its_loop_at_100_and_300_vertices)
{
  // the hole is small: 3 sites on its loop at 100 and 300 vertices, 4 at 1000. A fixed site at the apex of
  // the hole's patch, close to the loop's chords, made the dual miss an edge between consecutive loop
  // sites at 100, 150, 300 and 1000 ("a site came too close to the loop"); the flat torus now puts no
  // site in a patch. Quality bounds with margin: measured G_avg 0.920 and 0.930, theta_min 11.7 and 21.2
  // degrees (the smallest angles next to the 3-site loop at 100)
  const AC::Input_surface torus = read_case("torus_with_hole.off");
  for(std::size_t n : {100u, 300u}) {
    const AC::Remeshing_result r = check_remesh<AC::Flat_torus_domain>("torus with hole", torus, n);
    BOOST_TEST(r.boundary_sites >= 3u);
    BOOST_TEST(r.quality.G_avg > 0.88);
    BOOST_TEST(r.quality.theta_min > 8.0);
  }
}

// An open tube of k x m quads whose cross-section is an ellipse of semi-axes 1 and `b`, `length` long
// (a hollow blade when b is small): two boundary loops, each along both faces of the tube
AC::Input_surface make_flat_tube(int m, int k, double b, double length)
{
  std::vector<Eigen::Vector3d> points;
  std::vector<AC::Input_surface::Face> faces;
  for(int j = 0; j <= k; ++j)
    for(int i = 0; i < m; ++i) {
      const double t = 2 * 3.14159265358979323846 * i / m;
      points.push_back(Eigen::Vector3d(std::cos(t), b * std::sin(t), length * j / k));
    }
  auto at = [m](int i, int j) { return std::size_t(j * m + (i % m)); };
  for(int j = 0; j < k; ++j)
    for(int i = 0; i < m; ++i) {
      faces.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}});
      faces.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}});
    }
  return AC::Input_surface(std::move(points), std::move(faces));
}

BOOST_AUTO_TEST_CASE(a_loop_along_both_faces_of_a_thin_part_gets_a_collar_that_opens_them)
{
  // 0.06 thick where the output's edges are about 0.25 long at 300 vertices: a flat patch over a loop
  // puts its sites on one face 0.06 from those on the other (CGAL's blade.off, a hollow blade: "a site
  // came too close to the loop" with the curvature metric); the collar (patch_collars.h) opens them
  const AC::Input_surface tube = make_flat_tube(64, 40, 0.03, 4.0);
  BOOST_TEST_REQUIRE(tube.boundary_loops().size() == 2u);
  const double h = AC::internal::estimated_output_edge_length(tube, 300);
  BOOST_TEST(h > 0.2);
  BOOST_TEST(h < 0.3);
  for(const auto& loop : tube.boundary_loops())
    BOOST_TEST(!AC::internal::thin_loop_pairs(tube.points(), tube.vertex_normals(), loop, h).empty());
  // a round tube's loops, and a flat tube's at a scale below its thickness, are not thin
  const AC::Input_surface round = make_flat_tube(64, 40, 1.0, 4.0);
  for(const auto& loop : round.boundary_loops())
    BOOST_TEST(AC::internal::thin_loop_pairs(round.points(), round.vertex_normals(), loop, h).empty());
  for(const auto& loop : tube.boundary_loops())
    BOOST_TEST(AC::internal::thin_loop_pairs(tube.points(), tube.vertex_normals(), loop, 0.01).empty());
  BOOST_TEST(AC::internal::close_holes(tube, false).collared_loops == 0u);  // no scale given: no collar
  const AC::internal::Hole_patches patches = AC::internal::close_holes(tube, false, h);
  BOOST_TEST(patches.collared_loops == 2u);
  BOOST_TEST(patches.closed.genus() == 0);
  BOOST_TEST(patches.closed.boundary_loops().empty());
  // through the closed surface (shortest paths along its edges), the loop vertices at angles t and -t
  // (2 * 0.03 sin t apart in space) are at least about the shorter of their distance along the loop and
  // twice the collar's height (2 h) apart
  const std::size_t m = 64;
  const double step = 2 * 3.14159265358979323846 / m;
  for(std::size_t i : {8u, 16u, 24u}) {  // angles 45, 90 and 135 degrees, on the loop at z = 0
    double along = 0;                    // the loop's length from angle -t to t through angle 0 or pi
    const std::size_t k = std::min(i, m / 2 - i);
    for(std::size_t j = 0; j < 2 * k; ++j) {
      const double t0 = (i <= m / 4 ? -double(i) : double(m / 2 - k)) * step + double(j) * step;
      along += (Eigen::Vector2d(std::cos(t0 + step), 0.03 * std::sin(t0 + step)) - Eigen::Vector2d(std::cos(t0), 0.03 * std::sin(t0))).norm();
    }
    BOOST_TEST(graph_distance(patches.closed, i, m - i) > 0.9 * std::min(along, 4 * h));
    // the flat cone's edges join the two faces through its apex, half the loop's mean radius away
    if(i == 16) BOOST_TEST(graph_distance(AC::internal::close_holes(tube, false).closed, i, m - i) < 0.9 * std::min(along, 4 * h));
  }
}

BOOST_AUTO_TEST_CASE(a_run_blocked_at_a_thin_loop_goes_again_with_collars)
{
  // run_again_with_collars_if_a_loop_is_blocked(): a second run only after a Blocked_loop_failure, and
  // only when the loop it names is thin: a tube flat (0.03) at one end and round at the other
  std::vector<Eigen::Vector3d> points;
  {
    const AC::Input_surface flat = make_flat_tube(64, 40, 0.03, 4.0);
    for(const auto& p : flat.points()) points.push_back(Eigen::Vector3d(p.x(), p.y() / 0.03 * (0.03 + 0.97 * p.z() / 4.0), p.z()));
    const AC::Input_surface tapered(points, std::vector<AC::Input_surface::Face>(flat.faces().begin(), flat.faces().end()));
    const double h = AC::internal::estimated_output_edge_length(tapered, 300);
    std::vector<std::size_t> thin_loops, round_loops;
    for(std::size_t l = 0; l < tapered.boundary_loops().size(); ++l)
      (AC::internal::thin_loop_pairs(tapered.points(), tapered.vertex_normals(), tapered.boundary_loops()[l], h).empty() ? round_loops
                                                                                                                         : thin_loops)
        .push_back(l);
    BOOST_TEST_REQUIRE(thin_loops.size() == 1u);
    BOOST_TEST_REQUIRE(round_loops.size() == 1u);
    AC::Remeshing_result result;
    std::vector<bool> calls;
    for(const std::size_t blocked : {thin_loops[0], round_loops[0]}) {
      calls.clear();
      auto run = [&](bool collars) {
        calls.push_back(collars);
        if(!collars)
          throw AC::internal::Blocked_loop_failure(std::string("remesh(): the output does not join sites 4 and 5 of boundary loop ") +
                                                       std::to_string(blocked) + " by an edge (" + AC::internal::blocked_loop_reason + ")",
                                                   blocked);
        return 7;
      };
      if(blocked == thin_loops[0]) {
        BOOST_TEST(AC::internal::run_again_with_collars_if_a_loop_is_blocked(tapered, 300, result, run) == 7);
        BOOST_TEST((calls == std::vector<bool>{false, true}));
        BOOST_TEST(result.discarded_seconds >= 0.0);
      } else {
        BOOST_CHECK_THROW(AC::internal::run_again_with_collars_if_a_loop_is_blocked(tapered, 300, result, run),
                          AC::internal::Blocked_loop_failure);
        BOOST_TEST((calls == std::vector<bool>{false}));
      }
    }
    // any other failure is thrown on without a second run
    calls.clear();
    auto other = [&](bool collars) -> int {
      calls.push_back(collars);
      throw AC::Convergence_failure("remesh(): the output has 1 inverted or degenerate triangles", 0);
    };
    BOOST_CHECK_THROW(AC::internal::run_again_with_collars_if_a_loop_is_blocked(tapered, 300, result, other), AC::Convergence_failure);
    BOOST_TEST((calls == std::vector<bool>{false}));
  }
}

BOOST_AUTO_TEST_CASE(a_domain_that_does_not_fit_is_refused)
{
  // the annulus is of genus 0: the flat torus does not fit it, even with its holes closed
  const AC::Input_surface annulus = read_case("annulus.off");
  AC::Remeshing_result result;
  BOOST_CHECK_THROW(AC::remesh_in_domain<AC::Flat_torus_domain>(annulus, AC::Uniform_metric(), result,
                                                                AC::parameters::number_of_vertices(200)),
                    AC::Invalid_input);
}

BOOST_AUTO_TEST_SUITE_END()  // boundaries
