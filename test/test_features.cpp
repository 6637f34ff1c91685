// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Sharp features (issue 15): the feature graph of an input (detect_features(): creases by the angle between
// face normals, corners, curves and loops), its measurement on an output (measure_features(): corners
// kept, crease length covered by output edges) on meshes whose answer is known by hand, and the whole
// pipeline on a cube through the sphere and on a disk through the plane (the only domains this module
// compiles): corners kept as output vertices, creases as chains of output edges (test/data/cases:
// cube_grid.off, capped_cylinder.off, pyramid_grid.off, hip_roof.off), and the crowded vertices next to the
// crease sites moved by the surface optimisation (CGAL's part.off).

#ifndef ANISO_CONFORMAL_TEST_UNITY  // else compiled with other modules in one translation unit (CMakeLists.txt)
#define BOOST_TEST_MODULE Aniso_conformal_features
#endif
#include <boost/test/unit_test.hpp>

#include <Aniso_conformal/Feature_graph.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/IO/write_report.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/features/curvature_size.h>
#include <Aniso_conformal/internal/features/fixed_corner_sites.h>
#include <Aniso_conformal/internal/features/ragged_creases.h>
#include <Aniso_conformal/internal/optimize/crowded_vertices.h>
#include <Aniso_conformal/internal/optimize/triangle_orientation.h>
#include <Aniso_conformal/internal/tensor.h>
#include <Aniso_conformal/mesh_quality.h>
#include <Aniso_conformal/Default_visitor.h>
#include <Aniso_conformal/Planar_domain.h>
#include <Aniso_conformal/Spherical_domain.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/make_ellipsoid.h>
#include <Aniso_conformal/measure_features.h>
#include <Aniso_conformal/remesh_in_domain.h>

#include <Eigen/Core>

#include "grid_cube.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

BOOST_AUTO_TEST_SUITE(features)  // also a namespace: keeps the helpers apart from other modules in one unit

namespace AC = Aniso_conformal;

namespace {

using test::make_grid_cube;  // grid_cube.h

// A closed prism over a regular k-gon (radius 1, height 2), its sides split into `rows` rows of quads, its
// caps fans around a centre vertex: 2 closed crease loops (the rims, turning by 360/k degrees at each
// vertex) and k vertical creases between them when the sides are flat enough to be creases.
AC::Input_surface make_capped_prism(int k, int rows)
{
  std::vector<Eigen::Vector3d> points;
  const double pi = 3.14159265358979323846;
  for(int r = 0; r <= rows; ++r)
    for(int i = 0; i < k; ++i)
      points.push_back(Eigen::Vector3d(std::cos(2 * pi * i / k), std::sin(2 * pi * i / k), -1 + 2.0 * r / rows));
  const std::size_t bottom = points.size(), top = bottom + 1;
  points.push_back(Eigen::Vector3d(0, 0, -1));
  points.push_back(Eigen::Vector3d(0, 0, 1));
  std::vector<AC::Input_surface::Face> faces;
  auto at = [k](int r, int i) { return std::size_t(r * k + (i % k)); };
  for(int r = 0; r < rows; ++r)
    for(int i = 0; i < k; ++i) {
      faces.push_back({{at(r, i), at(r, i + 1), at(r + 1, i + 1)}});
      faces.push_back({{at(r, i), at(r + 1, i + 1), at(r + 1, i)}});
    }
  for(int i = 0; i < k; ++i) {
    faces.push_back({{bottom, at(0, i + 1), at(0, i)}});
    faces.push_back({{top, at(rows, i), at(rows, i + 1)}});
  }
  return AC::Input_surface(points, faces);
}

const AC::Input_surface cube12({{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
                               {{{0, 2, 1}}, {{0, 3, 2}}, {{4, 5, 6}}, {{4, 6, 7}}, {{0, 1, 5}}, {{0, 5, 4}}, {{1, 2, 6}}, {{1, 6, 5}},
                                {{2, 3, 7}}, {{2, 7, 6}}, {{3, 0, 4}}, {{3, 4, 7}}});

} // namespace

BOOST_AUTO_TEST_CASE(the_cube_has_twelve_creases_and_eight_corners)
{
  for(int n : {1, 4}) {
    const AC::Input_surface cube = make_grid_cube(n);
    const AC::Feature_graph g = AC::detect_features(cube, 60, 30);
    BOOST_TEST(g.crease_edges.size() == std::size_t(12 * n));  // the face diagonals are flat
    BOOST_TEST(g.corners.size() == 8u);
    BOOST_TEST(g.curves.size() == 12u);
    for(const AC::Feature_curve& c : g.curves) {
      BOOST_TEST(!c.closed);
      BOOST_TEST(c.vertices.size() == std::size_t(n + 1));
      BOOST_TEST(std::abs(c.length - 2) < 1e-12);
      BOOST_TEST(cube.points()[c.vertices.front()].cwiseAbs().minCoeff() == 1.0);  // from corner to corner
      BOOST_TEST(cube.points()[c.vertices.back()].cwiseAbs().minCoeff() == 1.0);
    }
    BOOST_TEST(std::abs(g.crease_length() - 24) < 1e-12);
    // the normals differ by 90 degrees across the cube's edges: creases up to a feature angle of 90
    BOOST_TEST(AC::detect_features(cube, 89, 30).corners.size() == 8u);
    BOOST_TEST(AC::detect_features(cube, 91, 30).empty());
    BOOST_TEST(AC::detect_features(cube, 180, 30).empty());  // feature_angle(180): no feature
  }
}

BOOST_AUTO_TEST_CASE(the_rims_of_a_capped_prism_are_closed_loops_or_chains_of_corners)
{
  // 24 sides: the sides' normals differ by 15 degrees (no crease between them), the rims turn by 15
  // degrees at each vertex (no corner under the default 30): two closed loops of length 48 sin(7.5 deg)
  const AC::Feature_graph g = AC::detect_features(make_capped_prism(24, 3), 60, 30);
  BOOST_TEST(g.curves.size() == 2u);
  BOOST_TEST(g.corners.empty());
  const double rim = 24 * 2 * std::sin(3.14159265358979323846 / 24);
  for(const AC::Feature_curve& c : g.curves) {
    BOOST_TEST(c.closed);
    BOOST_TEST(c.vertices.size() == 25u);
    BOOST_TEST(c.vertices.front() == c.vertices.back());
    BOOST_TEST(std::abs(c.length - rim) < 1e-12);
  }
  // a corner angle of 10 degrees makes every rim vertex a corner: 2 x 24 curves of one edge
  const AC::Feature_graph h = AC::detect_features(make_capped_prism(24, 3), 60, 10);
  BOOST_TEST(h.corners.size() == 48u);
  BOOST_TEST(h.curves.size() == 48u);
  // 4 sides: the box's vertical edges are creases too, the rims turn by 90 degrees: 8 corners, 12 curves
  const AC::Feature_graph box = AC::detect_features(make_capped_prism(4, 2), 60, 30);
  BOOST_TEST(box.corners.size() == 8u);
  BOOST_TEST(box.curves.size() == 12u);
  BOOST_TEST(box.crease_edges.size() == 16u);  // 8 rim edges, 4 vertical creases of 2 edges
}

BOOST_AUTO_TEST_CASE(bad_angles_are_refused)
{
  BOOST_CHECK_THROW(AC::detect_features(cube12, -1, 30), AC::Invalid_input);
  BOOST_CHECK_THROW(AC::detect_features(cube12, 181, 30), AC::Invalid_input);
  BOOST_CHECK_THROW(AC::detect_features(cube12, std::nan(""), 30), AC::Invalid_input);
  BOOST_CHECK_THROW(AC::detect_features(cube12, 60, 180), AC::Invalid_input);
  const AC::Feature_graph g = AC::detect_features(cube12, 60, 30);
  BOOST_CHECK_THROW(AC::measure_features(cube12, g, cube12.points(), {{{0, 1, 8}}}), AC::Invalid_input);
}

BOOST_AUTO_TEST_CASE(measurement_of_known_outputs)
{
  const AC::Input_surface cube = make_grid_cube(4);
  const AC::Feature_graph g = AC::detect_features(cube, 60, 30);
  // the 12-triangle cube as an output of the fine one: every corner kept, every crease one output edge
  const AC::Feature_report all = AC::measure_features(cube, g, cube12.points(), cube12.faces());
  BOOST_TEST(all.curves == 12u);
  BOOST_TEST(all.corners == 8u);
  BOOST_TEST(all.crease_edges == 48u);
  BOOST_TEST(all.corners_kept == 8u);
  BOOST_TEST(std::abs(all.crease_length - 24) < 1e-12);
  BOOST_TEST(std::abs(all.covered_share - 1) < 1e-12);
  // the fine cube as its own output: the same, each crease covered by 4 edges
  const AC::Feature_report self = AC::measure_features(cube, g, cube.points(), cube.faces());
  BOOST_TEST(self.corners_kept == 8u);
  BOOST_TEST(std::abs(self.covered_length - 24) < 1e-12);
  // corner 0 of the coarse cube moved inside: 7 corners kept, its 3 edges (6 of the 24) no longer cover
  std::vector<Eigen::Vector3d> moved = cube12.points();
  moved[0] = Eigen::Vector3d(-0.99, -0.99, -0.99);
  const AC::Feature_report seven = AC::measure_features(cube, g, moved, cube12.faces());
  BOOST_TEST(seven.corners_kept == 7u);
  BOOST_TEST(std::abs(seven.covered_length - 18) < 1e-12);
  BOOST_TEST(std::abs(seven.covered_share - 0.75) < 1e-12);
  // a corner missed by 1e-6 is not kept (the tolerance is 1e-9 of the diagonal)
  moved[0] = Eigen::Vector3d(-1 + 1e-6, -1, -1);
  BOOST_TEST(AC::measure_features(cube, g, moved, cube12.faces()).corners_kept == 7u);
  // an output edge between two points of one crease covers the piece between them, once however many
  // edges cover it: the crease from (-1, -1, -1) to (1, -1, -1) carries the points x = -0.5 and x = 0.25
  const std::vector<Eigen::Vector3d> pts = {{-0.5, -1, -1}, {0.25, -1, -1}, {0, 0, 0}};
  const AC::Feature_report piece = AC::measure_features(cube, g, pts, {{{0, 1, 2}}, {{1, 0, 2}}});
  BOOST_TEST(std::abs(piece.covered_length - 0.75) < 1e-12);
  BOOST_TEST(piece.corners_kept == 0u);
  // an edge between two crease points across a face of the cube covers nothing (not on one curve)
  const std::vector<Eigen::Vector3d> across = {{-0.5, -1, -1}, {-0.5, 1, -1}, {0, 0, 0}};
  BOOST_TEST(AC::measure_features(cube, g, across, {{{0, 1, 2}}}).covered_length == 0.0);
  // nothing to measure on a surface without features
  const AC::Feature_report none = AC::measure_features(cube, AC::detect_features(cube, 180, 30), cube.points(), cube.faces());
  BOOST_TEST(none.curves == 0u);
  BOOST_TEST(none.corners_kept == 0u);
  BOOST_TEST(none.covered_share == 0.0);
}

BOOST_AUTO_TEST_CASE(a_chord_across_a_closed_rim_covers_only_what_it_follows)
{
  // the rim of the 24-gon prism: output edges between consecutive rim vertices cover it; one between
  // opposite rim vertices (through the cap) covers nothing
  const AC::Input_surface prism = make_capped_prism(24, 3);
  const AC::Feature_graph g = AC::detect_features(prism, 60, 30);
  const AC::Feature_curve& rim = g.curves[0];
  std::vector<Eigen::Vector3d> pts;
  for(std::size_t i = 0; i < 24; ++i) pts.push_back(prism.points()[rim.vertices[i]]);
  std::vector<std::array<std::size_t, 3>> faces;
  for(std::size_t i = 0; i + 2 < 24; ++i) faces.push_back({{0, i + 1, i + 2}});  // a fan: 0-i chords, and the rim
  const AC::Feature_report r = AC::measure_features(prism, g, pts, faces);
  // the rim once: the short chords of the fan follow it (they cover nothing new), the long ones cut across
  BOOST_TEST(std::abs(r.covered_length - rim.length) < 1e-12);
  BOOST_TEST(std::abs(r.covered_share - 0.5) < 1e-12);  // of two rims
  // one triangle 0, 6, 12 on the rim: its edges span 90 and 180 degrees of it (1.107 and 1.571 times their
  // length): they cut across the cap and cover nothing
  const AC::Feature_report across = AC::measure_features(prism, g, pts, {{{0, 6, 12}}});
  BOOST_TEST(across.covered_length == 0.0);
}

BOOST_AUTO_TEST_CASE(remeshing_a_cube_keeps_its_eight_corners)
{
  // the corners are fixed sites of the CVT, mapped back exactly onto the input's corners (issue 15, item 2)
  const AC::Input_surface cube = make_grid_cube(4);
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(cube, AC::Uniform_metric(), r,
                                                                               AC::parameters::number_of_vertices(std::size_t(500)));
  BOOST_TEST(out.points.size() == 500u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.features.curves == 12u);
  BOOST_TEST(r.features.corners == 8u);
  BOOST_TEST(r.features.crease_edges == 48u);
  BOOST_TEST(std::abs(r.features.crease_length - 24) < 1e-12);
  BOOST_TEST(r.features.corners_kept == 8u);
  BOOST_TEST(r.cvt.energy.size() > 1u);
  // exactly: each corner is an output vertex, bit for bit, and its surface point is the input vertex
  std::size_t exact = 0;
  for(std::size_t i = 0; i < out.points.size(); ++i)
    if(out.points[i].cwiseAbs() == Eigen::Vector3d(1, 1, 1)) {
      ++exact;
      BOOST_TEST(out.surface_points[i].vertices[0] == out.surface_points[i].vertices[1]);
      BOOST_TEST((cube.points()[out.surface_points[i].vertices[0]] == out.points[i]));
    }
  BOOST_TEST(exact == 8u);
  // the report agrees with a measurement made apart
  const AC::Feature_report check = AC::measure_features(cube, AC::detect_features(cube, 60, 30), out.points, out.faces);
  BOOST_TEST(check.corners_kept == 8u);
  BOOST_TEST(check.covered_length == r.features.covered_length);
  BOOST_TEST(r.quality.G_avg >= 0.85);
  BOOST_TEST_MESSAGE("cube to 500: " << r.features.corners_kept << " of 8 corners kept, " << 100 * r.features.covered_share
                                     << " % of the crease length covered, Hausdorff " << r.hausdorff_distance_relative << ", G_avg "
                                     << r.quality.G_avg << ", theta_min " << r.quality.theta_min);
}

BOOST_AUTO_TEST_CASE(the_surface_optimisation_keeps_the_corners)
{
  // the surface optimisation moves vertices along the input: never the CVT's fixed sites (the corners),
  // which are the first Remeshed_surface::fixed_vertices vertices
  const AC::Input_surface cube = make_grid_cube(4);
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(
    cube, AC::Uniform_metric(), r,
    AC::parameters::number_of_vertices(std::size_t(500)).surface_optimization(AC::Surface_optimization::ALWAYS));
  BOOST_TEST(r.surface_optimization.ran);
  BOOST_TEST(r.surface_optimization.relocations > 0u);  // it did move vertices
  // the corners first, then the crease sites (issue 15, item 2)
  BOOST_TEST(r.crease_sites > 0u);
  BOOST_TEST(out.fixed_vertices == 8u + r.crease_sites);
  BOOST_TEST(r.surface_optimization.fixed_vertices == out.fixed_vertices);
  BOOST_TEST(r.features.corners_kept == 8u);
  for(std::size_t i = 0; i < 8; ++i) BOOST_TEST((out.points[i].cwiseAbs() == Eigen::Vector3d(1, 1, 1)));
  // a crease site is on a cube edge: two of its coordinates are +-1 exactly
  for(std::size_t i = 8; i < out.fixed_vertices; ++i)
    BOOST_TEST((out.points[i].array().abs() == 1.0).count() >= 2);
  // the crease edges are still output edges after the flips of the optimisation
  BOOST_TEST(!out.kept_edges.empty());
  for(const auto& e : out.kept_edges) {
    bool found = false;
    for(const auto& f : out.faces)
      for(int k = 0; k < 3; ++k) found = found || (std::min(f[k], f[(k + 1) % 3]) == e[0] && std::max(f[k], f[(k + 1) % 3]) == e[1]);
    BOOST_TEST(found);
  }
  BOOST_TEST(r.inverted_triangles == 0u);
}

BOOST_AUTO_TEST_CASE(the_default_optimisation_runs_both_phases_on_an_output_that_follows_creases)
{
  // Surface_optimization::REPAIR runs as ALWAYS when the output follows creases (since 2026-12-07): the
  // crease sites are fixed, the CVT's cells beside them irregular, and the second phase's moves toward
  // each vertex's ideal point in the metric lift G_avg (CGAL's crease meshes at 2000 vertices: +0.014 to
  // +0.018, benchmark/features.md). Without creases, on an output with no triangle to repair, REPAIR stays
  // REPAIR.
  const AC::Input_surface cube = make_grid_cube(4);
  AC::Remeshing_result r, always, smooth;
  const auto np = AC::parameters::number_of_vertices(std::size_t(500));
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(cube, AC::Uniform_metric(), r, np);
  BOOST_TEST(!out.kept_edges.empty());
  BOOST_TEST(r.surface_optimization.ran);
  BOOST_TEST(r.surface_optimization.second_phase);
  BOOST_TEST(r.surface_optimization.G_avg_after > r.surface_optimization.G_avg_before);
  BOOST_TEST(r.surface_optimization.theta_min_after >= r.surface_optimization.theta_min_before);
  const AC::Remeshed_surface out_always = AC::remesh_in_domain<AC::Spherical_domain>(
    cube, AC::Uniform_metric(), always, AC::parameters::number_of_vertices(std::size_t(500)).surface_optimization(AC::Surface_optimization::ALWAYS));
  BOOST_TEST((out_always.points == out.points));
  BOOST_TEST((out_always.faces == out.faces));
  // the same cube without its creases: no kept edge, and the second phase only if asked for
  const AC::Remeshed_surface out_smooth =
    AC::remesh_in_domain<AC::Spherical_domain>(cube, AC::Uniform_metric(), smooth, AC::parameters::number_of_vertices(std::size_t(500)).feature_angle(180.0));
  BOOST_TEST(out_smooth.kept_edges.empty());
  BOOST_TEST(!smooth.surface_optimization.second_phase);
  BOOST_TEST_MESSAGE("cube to 500, default optimisation: G_avg " << r.surface_optimization.G_avg_before << " -> "
                                                                  << r.surface_optimization.G_avg_after << ", theta_min "
                                                                  << r.surface_optimization.theta_min_before << " -> "
                                                                  << r.surface_optimization.theta_min_after);
}

BOOST_AUTO_TEST_CASE(corners_closer_than_half_an_output_edge_are_not_all_fixed)
{
  // the cube's corners are 2 apart along an edge, 2.83 across a face, 3.46 across the cube (identity metric)
  const AC::Input_surface cube = make_grid_cube(2);
  const AC::Intrinsic_triangulation t(cube, std::vector<Eigen::Matrix3d>(cube.number_of_vertices(), Eigen::Matrix3d::Identity()));
  const AC::Feature_graph g = AC::detect_features(cube, 60, 30);
  BOOST_TEST(AC::internal::corners_to_fix(g, t, 3.9).size() == 8u);  // 2 >= 3.9 / 2: all
  for(double h : {4.2, 6.0, 8.0}) {
    const std::vector<std::size_t> fixed = AC::internal::corners_to_fix(g, t, h);
    BOOST_TEST(!fixed.empty());
    // the fixed corners are at least h / 2 apart, and every other corner is closer than that to one of them
    for(std::size_t a : fixed)
      for(std::size_t b : fixed)
        if(a != b) BOOST_TEST((cube.points()[a] - cube.points()[b]).norm() >= h / 2);
    for(std::size_t c : g.corners) {
      double nearest = 1e300;
      for(std::size_t a : fixed) nearest = std::min(nearest, (cube.points()[a] - cube.points()[c]).norm());
      BOOST_TEST(nearest < h / 2);  // 0 for a fixed one
    }
    if(h == 8.0) BOOST_TEST(fixed.size() == 1u);  // every corner within 4 of every other
  }
}

namespace {

// The disk [-1, 1]^2 as an m x m grid cut by diagonals, its centre vertex raised by `height`: a spike whose
// ring of edges (its link, about 6 / m long) is a crease component, with corners where the ring turns
AC::Input_surface make_plate_with_a_spike(int m, double height)
{
  std::vector<Eigen::Vector3d> points;
  for(int j = 0; j <= m; ++j)
    for(int i = 0; i <= m; ++i)
      points.push_back(Eigen::Vector3d(-1 + 2.0 * i / m, -1 + 2.0 * j / m, i == m / 2 && j == m / 2 ? height : 0.0));
  auto at = [m](int i, int j) { return std::size_t(j * (m + 1) + i); };
  std::vector<AC::Input_surface::Face> faces;
  for(int j = 0; j < m; ++j)
    for(int i = 0; i < m; ++i) {
      faces.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}});
      faces.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}});
    }
  return AC::Input_surface(std::move(points), std::move(faces));
}

} // namespace

BOOST_AUTO_TEST_CASE(crease_components_shorter_than_an_output_edge_are_left_out)
{
  // the spike's creases: one component of length about 0.39 (m = 64); the cube's twelve edges: one of 24
  const AC::Input_surface plate = make_plate_with_a_spike(64, 0.1);
  const AC::Feature_graph g = AC::detect_features(plate, 60, 30);
  BOOST_TEST_REQUIRE(!g.crease_edges.empty());
  BOOST_TEST_REQUIRE(!g.corners.empty());
  const AC::Intrinsic_triangulation t(plate, std::vector<Eigen::Matrix3d>(plate.number_of_vertices(), Eigen::Matrix3d::Identity()));
  const double length = g.crease_length();
  BOOST_TEST_MESSAGE("spike: " << g.crease_edges.size() << " crease edges of total length " << length << ", " << g.corners.size() << " corners");
  std::size_t dropped = 0;
  double dropped_length = 0;
  // longer than the output edge: kept as it is
  AC::Feature_graph kept = AC::internal::without_short_crease_components(plate, g, t, 0.9 * length, 30, {}, {}, dropped, dropped_length);
  BOOST_TEST(kept.crease_edges == g.crease_edges);
  BOOST_TEST(kept.corners == g.corners);
  BOOST_TEST(dropped == 0u);
  // shorter: left out, with its corners, and counted
  kept = AC::internal::without_short_crease_components(plate, g, t, 1.1 * length, 30, {}, {}, dropped, dropped_length);
  BOOST_TEST(kept.empty());
  BOOST_TEST(kept.curves.empty());
  BOOST_TEST(dropped == 1u);
  BOOST_TEST(std::abs(dropped_length - length) <= 1e-12 * length);
  // one of its edges marked by the user: kept whole
  dropped = 0;
  kept = AC::internal::without_short_crease_components(plate, g, t, 1.1 * length, 30, {g.crease_edges.front()}, {}, dropped, dropped_length);
  BOOST_TEST(kept.crease_edges == g.crease_edges);
  BOOST_TEST(kept.corners == g.corners);
  BOOST_TEST(dropped == 0u);
  // the length is measured in the metric: scaled by 2, the component is twice as long
  const AC::Intrinsic_triangulation t2(plate, std::vector<Eigen::Matrix3d>(plate.number_of_vertices(), 2.0 * Eigen::Matrix3d::Identity()));
  kept = AC::internal::without_short_crease_components(plate, g, t2, 1.1 * length, 30, {}, {}, dropped, dropped_length);
  BOOST_TEST(kept.crease_edges == g.crease_edges);
  // the cube keeps its twelve creases and eight corners below an output edge of 24
  const AC::Input_surface cube = make_grid_cube(4);
  const AC::Feature_graph gc = AC::detect_features(cube, 60, 30);
  const AC::Intrinsic_triangulation tc(cube, std::vector<Eigen::Matrix3d>(cube.number_of_vertices(), Eigen::Matrix3d::Identity()));
  kept = AC::internal::without_short_crease_components(cube, gc, tc, 23.0, 30, {}, {}, dropped, dropped_length);
  BOOST_TEST(kept.crease_edges.size() == gc.crease_edges.size());
  BOOST_TEST(kept.corners.size() == 8u);
  // through remesh(): at 20 vertices (output edge about 0.48) the spike's creases are left out and the
  // report says so; at 2000 (0.05) they are followed
  for(std::size_t n : {std::size_t(20), std::size_t(2000)}) {
    AC::Remeshing_result r;
    // (ragged creases kept: at 20 vertices the spike's edges are finer than the output, and its creases,
    // whose triangles bend at other edges too, would be left out as ragged before their length counts)
    const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Planar_domain>(
      plate, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n).drop_ragged_creases(false));
    BOOST_TEST(out.points.size() == n);
    BOOST_TEST_MESSAGE("spike plate -> " << n << ": " << r.features.short_components_dropped << " dropped, " << r.features.corners << " corners, "
                                         << r.features.crease_edges << " crease edges; theta_min " << r.quality.theta_min);
    if(n == 20) {
      BOOST_TEST(r.features.short_components_dropped == 1u);
      BOOST_TEST(std::abs(r.features.short_length_dropped - length) <= 1e-9 * length);
      BOOST_TEST(r.features.crease_edges == 0u);
      BOOST_TEST(r.features.corners == 0u);
      BOOST_TEST(AC::IO::report_json(r).at("features").at("short_components_dropped") == 1);
    } else {
      BOOST_TEST(r.features.short_components_dropped == 0u);
      BOOST_TEST(r.features.crease_edges == g.crease_edges.size());
      BOOST_TEST(r.features.corners == g.corners.size());
    }
  }
}

namespace {
// make_grid_cube(n) made rough: each vertex at least `margin` grid steps from the cube's edges moved along
// its face's normal by a fixed pseudo-random multiple of `amplitude` grid steps, in [-amplitude, amplitude]
// (a noisy scan of a box, its edges clean)
AC::Input_surface make_rough_cube(int n, int margin, double amplitude)
{
  const AC::Input_surface cube = make_grid_cube(n);
  std::vector<Eigen::Vector3d> p = cube.points();
  const double step = 2.0 / n;
  for(auto& x : p) {
    int axis = 0;
    x.cwiseAbs().maxCoeff(&axis);
    double from_edge = n;
    for(int k = 0; k < 3; ++k)
      if(k != axis) from_edge = std::min(from_edge, (1 - std::abs(x[k])) / step);
    if(from_edge < margin - 1e-9) continue;
    const long g = std::lround((x.x() + 1) / step) * 73856093L ^ std::lround((x.y() + 1) / step) * 19349663L ^
                   std::lround((x.z() + 1) / step) * 83492791L;
    x[axis] += (x[axis] > 0 ? 1 : -1) * amplitude * step * (double(((g % 9) + 9) % 9) / 4 - 1);
  }
  return AC::Input_surface(p, cube.faces());
}
} // namespace

BOOST_AUTO_TEST_CASE(ragged_crease_components_are_left_out)
{
  using AC::internal::without_ragged_crease_components;
  AC::internal::Ragged_creases left_out;
  // a clean box: no crease edge is ragged, whatever the output's size
  const AC::Input_surface box = make_grid_cube(10);
  const AC::Feature_graph gb = AC::detect_features(box, 60, 30);
  for(std::size_t n : {std::size_t(20), std::size_t(2000)}) {
    const AC::Feature_graph kept = without_ragged_crease_components(box, gb, n, 60, 30, {}, {}, left_out);
    BOOST_TEST(kept.crease_edges == gb.crease_edges);
    BOOST_TEST(left_out.components == 0u);
    BOOST_TEST(!left_out.rough);
  }
  // a box whose faces are bumpy three steps away from its edges: the crease fragments there whose
  // triangles bend by more than 30 degrees at other edges are left out, the twelve edges stay
  const AC::Input_surface bumpy = make_rough_cube(10, 3, 0.5);
  const AC::Feature_graph g = AC::detect_features(bumpy, 60, 30);
  BOOST_TEST_MESSAGE("bumpy box: " << g.crease_edges.size() << " crease edges, " << g.curves.size() << " curves, " << g.corners.size()
                                   << " corners, crease length " << g.crease_length());
  BOOST_TEST_REQUIRE(g.crease_edges.size() > gb.crease_edges.size());
  AC::Feature_graph kept = without_ragged_crease_components(bumpy, g, 200, 60, 30, {}, {}, left_out);
  for(const auto& e : gb.crease_edges)  // the same vertex indices: only positions moved
    BOOST_TEST(std::binary_search(kept.crease_edges.begin(), kept.crease_edges.end(), e));
  BOOST_TEST(left_out.components > 0u);
  BOOST_TEST(!left_out.rough);  // under a quarter of the crease length
  BOOST_TEST(std::abs(left_out.length + kept.crease_length() - g.crease_length()) <= 1e-9 * g.crease_length());
  BOOST_TEST(left_out.length < 0.25 * g.crease_length());
  // a ragged component with an edge the user marked is kept whole
  std::vector<std::array<std::size_t, 2>> fragment;
  for(const auto& e : g.crease_edges)
    if(!std::binary_search(kept.crease_edges.begin(), kept.crease_edges.end(), e)) fragment.push_back(e);
  BOOST_TEST_REQUIRE(!fragment.empty());
  const std::size_t before = left_out.components;
  kept = without_ragged_crease_components(bumpy, g, 200, 60, 30, {fragment.front()}, {}, left_out);
  BOOST_TEST(left_out.components == before - 1);
  BOOST_TEST(std::binary_search(kept.crease_edges.begin(), kept.crease_edges.end(), fragment.front()));
  // output edges shorter than the noise (10^7 vertices): nothing is ragged at that resolution
  kept = without_ragged_crease_components(bumpy, g, 10000000, 60, 30, {}, {}, left_out);
  BOOST_TEST(kept.crease_edges == g.crease_edges);
  BOOST_TEST(left_out.components == 0u);
  // rough up to one step from the edges: ragged fragments are most of the crease length, so the surface is
  // rough and every detected crease goes, the twelve edges too (rough faces make their creases suspect)
  const AC::Input_surface rough = make_rough_cube(8, 1, 1.0);
  const AC::Feature_graph gr = AC::detect_features(rough, 60, 30);
  BOOST_TEST_REQUIRE(!gr.crease_edges.empty());
  kept = without_ragged_crease_components(rough, gr, 200, 60, 30, {}, {}, left_out);
  BOOST_TEST(kept.empty());
  BOOST_TEST(left_out.rough);
  BOOST_TEST(std::abs(left_out.length - gr.crease_length()) <= 1e-9 * gr.crease_length());
  // at feature angle 180 every crease is the user's: kept
  kept = without_ragged_crease_components(rough, gr, 200, 180, 30, {}, {}, left_out);
  BOOST_TEST(kept.crease_edges == gr.crease_edges);

  // through remesh(): counted in the result and the report, and drop_ragged_creases(false) keeps them
  for(bool drop : {true, false}) {
    AC::Remeshing_result r;
    const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(
      rough, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(300)).drop_ragged_creases(drop));
    BOOST_TEST(out.points.size() == 300u);
    BOOST_TEST_MESSAGE("rough box, drop " << drop << ": " << r.features.ragged_components_dropped << " ragged components left out, "
                                          << r.features.crease_edges << " crease edges kept; G_avg " << r.quality.G_avg << ", theta_min "
                                          << r.quality.theta_min);
    if(drop) {
      BOOST_TEST(r.features.rough_surface);
      BOOST_TEST(r.features.ragged_components_dropped > 0u);
      BOOST_TEST(r.features.crease_edges == 0u);
      BOOST_TEST(r.features.corners == 0u);
      const nlohmann::json j = AC::IO::report_json(r);
      BOOST_TEST(j.at("features").at("rough_surface") == true);
      BOOST_TEST(j.at("features").at("ragged_components_dropped") == r.features.ragged_components_dropped);
    } else {
      BOOST_TEST(!r.features.rough_surface);
      BOOST_TEST(r.features.ragged_components_dropped == 0u);
      BOOST_TEST(r.features.crease_edges > 0u);
    }
  }
}

BOOST_AUTO_TEST_CASE(without_features_nothing_is_kept_or_counted)
{
  // feature_angle(180), the tool's --no-features: no feature, no fixed site, the corners rounded off
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(
    make_grid_cube(4), AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(500)).feature_angle(180.0));
  BOOST_TEST(r.features.curves == 0u);
  BOOST_TEST(r.features.corners == 0u);
  BOOST_TEST(r.features.crease_length == 0.0);
  std::size_t at_corner = 0;
  for(const auto& p : out.points) at_corner += p.cwiseAbs() == Eigen::Vector3d(1, 1, 1);
  BOOST_TEST(at_corner == 0u);
  // measured against the cube's features, that output keeps none of them
  BOOST_TEST(AC::measure_features(make_grid_cube(4), AC::detect_features(make_grid_cube(4), 60, 30), out.points, out.faces).corners_kept == 0u);
}

namespace {
// the edges of `s` whose two ends satisfy `on`, as (smaller, larger) pairs, sorted
template <typename Predicate>
std::vector<std::array<std::size_t, 2>> edges_where(const AC::Input_surface& s, Predicate on)
{
  std::vector<std::array<std::size_t, 2>> e;
  for(const auto& f : s.faces())
    for(int k = 0; k < 3; ++k) {
      const std::size_t a = f[k], b = f[(k + 1) % 3];
      if(a < b && on(s.points()[a]) && on(s.points()[b])) e.push_back({{a, b}});
    }
  std::sort(e.begin(), e.end());
  return e;
}
std::size_t vertex_at(const AC::Input_surface& s, const Eigen::Vector3d& p)
{
  for(std::size_t v = 0; v < s.number_of_vertices(); ++v)
    if(s.points()[v] == p) return v;
  return s.number_of_vertices();
}
} // namespace

BOOST_AUTO_TEST_CASE(marked_edges_and_vertices_are_features_whatever_their_angle)
{
  // a user's features (issue 15, item 1): with feature_angle 180 only they count; a marked vertex is a corner
  const AC::Input_surface cube = make_grid_cube(4);
  const auto vertical = edges_where(cube, [](const Eigen::Vector3d& p) { return p.x() == 1 && p.y() == 1; });
  BOOST_REQUIRE(vertical.size() == 4u);  // one of the cube's edges, 4 grid edges long
  const std::size_t centre = vertex_at(cube, Eigen::Vector3d(1, 0, 0));
  BOOST_REQUIRE(centre < cube.number_of_vertices());
  const AC::Feature_graph g = AC::detect_features(cube, 180, 30, vertical, {centre});
  BOOST_TEST(g.crease_edges == vertical);
  BOOST_REQUIRE(g.curves.size() == 1u);
  BOOST_TEST(g.curves[0].vertices.size() == 5u);
  BOOST_TEST(std::abs(g.curves[0].length - 2) < 1e-12);
  BOOST_TEST(g.corners.size() == 3u);  // the curve's two ends and the marked vertex
  BOOST_TEST(std::count(g.corners.begin(), g.corners.end(), centre) == 1);
  // on top of the detected ones: marking a crease again changes nothing, a flat edge is added
  const auto flat = edges_where(cube, [](const Eigen::Vector3d& p) { return p.x() == 1 && p.z() == 0; });
  BOOST_REQUIRE(flat.size() == 4u);
  const AC::Feature_graph all = AC::detect_features(cube, 60, 30, vertical);
  BOOST_TEST(all.crease_edges == AC::detect_features(cube, 60, 30).crease_edges);
  const AC::Feature_graph more = AC::detect_features(cube, 60, 30, flat);
  BOOST_TEST(more.crease_edges.size() == 48u + 4u);
  BOOST_TEST(more.corners.size() == 8u + 2u);  // the flat line ends on two crease midpoints, where 3 creases now meet

  // marks that name no edge or no vertex of the input are bad input, named
  auto message = [&](const std::vector<std::array<std::size_t, 2>>& e, const std::vector<std::size_t>& v) {
    try {
      AC::detect_features(cube, 60, 30, e, v);
    } catch(const AC::Invalid_input& x) {
      return std::string(x.what());
    }
    return std::string("(no Invalid_input)");
  };
  const std::size_t far = vertex_at(cube, Eigen::Vector3d(-1, -1, -1));
  BOOST_TEST(message({{{centre, far}}}, {}).find("is not an edge of the input") != std::string::npos);
  BOOST_TEST(message({{{centre, centre}}}, {}).find("is not an edge of the input") != std::string::npos);
  BOOST_TEST(message({{{0, 100000}}}, {}).find("names a vertex the input does not have") != std::string::npos);
  BOOST_TEST(message({}, {100000}).find("marked feature vertex 100000") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_marked_vertex_is_kept_as_an_output_vertex)
{
  // feature_vertices through remesh(): a fixed site mapped back exactly onto the marked vertex
  const AC::Input_surface cube = make_grid_cube(4);
  const std::size_t centre = vertex_at(cube, Eigen::Vector3d(1, 0, 0));
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(
    cube, AC::Uniform_metric(), r,
    AC::parameters::number_of_vertices(std::size_t(300)).feature_angle(180.0).feature_vertices(std::vector<std::size_t>{centre}));
  BOOST_TEST(out.points.size() == 300u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.features.corners == 1u);
  BOOST_TEST(r.features.corners_kept == 1u);
  BOOST_TEST(std::count(out.points.begin(), out.points.end(), Eigen::Vector3d(1, 0, 0)) == 1);
}

BOOST_AUTO_TEST_CASE(too_few_vertices_for_the_corners_or_a_bad_angle_are_refused)
{
  AC::Remeshing_result r;
  std::string message;
  try {
    AC::remesh_in_domain<AC::Spherical_domain>(make_grid_cube(4), AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(6)));
  } catch(const AC::Invalid_input& e) {
    message = e.what();
  }
  BOOST_TEST(message.find("8 corners") != std::string::npos);
  BOOST_TEST(message.find("at least 8") != std::string::npos);
  BOOST_TEST(message.find("feature angle") != std::string::npos);
  // the same request without features is valid (whether 6 vertices can then be built is another question)
  bool invalid = false;
  try {
    AC::remesh_in_domain<AC::Spherical_domain>(make_grid_cube(4), AC::Uniform_metric(), r,
                                               AC::parameters::number_of_vertices(std::size_t(6)).feature_angle(180.0));
  } catch(const AC::Invalid_input&) {
    invalid = true;
  } catch(const AC::Remeshing_failure&) {
  }
  BOOST_TEST(!invalid);
  BOOST_CHECK_THROW(AC::remesh_in_domain<AC::Spherical_domain>(make_grid_cube(4), AC::Uniform_metric(), r,
                                                              AC::parameters::number_of_vertices(std::size_t(500)).feature_angle(200.0)),
                    AC::Invalid_input);
}

namespace {
// the distance from `p` to the nearest crease edge of `g` on `s`
double distance_to_creases(const AC::Input_surface& s, const AC::Feature_graph& g, const Eigen::Vector3d& p)
{
  double d = 1e300;
  for(const auto& e : g.crease_edges) {
    const Eigen::Vector3d a = s.points()[e[0]], b = s.points()[e[1]];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    d = std::min(d, (a + t * (b - a) - p).norm());
  }
  return d;
}
AC::Input_surface read_case(const std::string& name)
{
  return AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cases/" + name);
}
} // namespace

BOOST_AUTO_TEST_CASE(creases_of_a_cube_and_a_capped_cylinder_are_chains_of_output_edges)
{
  // issue 15, item 2: fixed sites along each crease curve at the output edge length, on background
  // vertices of the crease, so every such output vertex lies on the input crease; consecutive ones joined
  // by an output edge (before: 0 % of the crease length on output edges for both)
  struct Case {
    const char* file;
    std::size_t n;
    double least_share;  // measured 1.0 for both at 150 and 600 vertices; a margin below
    std::size_t corners;
  };
  // (cube_grid at 150 once stopped in the spherical embedding, its crease edges split in 4: pipeline_steps.h)
  for(const Case& c : {Case{"cube_grid.off", 150, 0.9, 8}, Case{"cube_grid.off", 600, 0.9, 8}, Case{"capped_cylinder.off", 150, 0.85, 0},
                       Case{"capped_cylinder.off", 600, 0.85, 0}}) {
    const AC::Input_surface in = read_case(c.file);
    const AC::Feature_graph g = AC::detect_features(in, 60, 30);
    AC::Remeshing_result r;
    const AC::Remeshed_surface out =
      AC::remesh_in_domain<AC::Spherical_domain>(in, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(c.n));
    BOOST_TEST_MESSAGE(c.file << " to " << c.n << ": " << r.crease_sites << " crease sites, " << r.crease_edges_recovered
                              << " crease edges recovered by a flip, " << r.crease_edges_missing << " missing, "
                              << 100 * r.features.covered_share << " % of the crease length covered, corners kept "
                              << r.features.corners_kept << " of " << r.features.corners << ", G_avg " << r.quality.G_avg
                              << ", theta_min " << r.quality.theta_min << ", %<30 " << r.quality.percent_below_30);
    BOOST_TEST(out.points.size() == c.n);
    BOOST_TEST(r.inverted_triangles == 0u);
    BOOST_TEST(r.features.corners == c.corners);
    BOOST_TEST(r.features.corners_kept == c.corners);
    BOOST_TEST(r.crease_sites > 0u);
    BOOST_TEST(r.features.covered_share >= c.least_share);
    // every crease site (after the corners) is on the input's creases, up to the rounding of the midpoints
    const double tol = 1e-9 * in.bounding_box_diagonal();
    BOOST_TEST(out.fixed_vertices == c.corners + r.crease_sites);
    for(std::size_t i = 0; i < out.fixed_vertices; ++i) BOOST_TEST(distance_to_creases(in, g, out.points[i]) < tol);
    // the crease edges joined join such vertices
    for(const auto& e : out.kept_edges) BOOST_TEST((e[0] < out.fixed_vertices && e[1] < out.fixed_vertices));
    // and a measurement made apart agrees
    BOOST_TEST(AC::measure_features(in, g, out.points, out.faces).covered_length == r.features.covered_length);
  }
}

BOOST_AUTO_TEST_CASE(without_features_no_crease_site_is_placed)
{
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(
    read_case("cube_grid.off"), AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(150)).feature_angle(180.0));
  BOOST_TEST(r.crease_sites == 0u);
  BOOST_TEST(out.fixed_vertices == 0u);
  BOOST_TEST(out.kept_edges.empty());
}

BOOST_AUTO_TEST_CASE(a_crease_edge_the_dual_missed_is_recovered_by_one_flip_or_counted)
{
  // a 3 x 3 grid of the unit square's points (vertex i + 3 j at (i, j)), each cell cut along its diagonal
  // from (i, j) to (i + 1, j + 1); as input and as "output"
  std::vector<Eigen::Vector3d> points;
  for(int j = 0; j < 3; ++j)
    for(int i = 0; i < 3; ++i) points.push_back(Eigen::Vector3d(i, j, 0));
  std::vector<AC::Input_surface::Face> faces;
  for(std::size_t j = 0; j < 2; ++j)
    for(std::size_t i = 0; i < 2; ++i) {
      const std::size_t v = i + 3 * j;
      faces.push_back({{v, v + 1, v + 4}});
      faces.push_back({{v, v + 4, v + 3}});
    }
  const AC::Input_surface grid(points, faces);
  AC::Remeshed_surface out;
  out.points = points;
  out.faces.assign(faces.begin(), faces.end());
  for(std::size_t v = 0; v < points.size(); ++v) out.surface_points.push_back(AC::Surface_point::at_vertex(v, points[v]));
  // 2 -> 4 crosses the one edge (1, 5): flipped; 4 -> 5 is an edge already; 0 -> 8 crosses two edges: counted
  const auto joined = AC::internal::recover_crease_edges(grid, out, {{2, 4, 5}, {0, 8}}, {0, 0});
  BOOST_TEST(joined.first == 1u);
  BOOST_TEST(joined.second == 1u);
  std::vector<std::array<std::size_t, 2>> kept = out.kept_edges;
  std::sort(kept.begin(), kept.end());
  BOOST_TEST((kept == std::vector<std::array<std::size_t, 2>>{{{2, 4}}, {{4, 5}}}));
  // still a valid surface of 8 triangles, none inverted, with the edge (2, 4) and without (1, 5)
  BOOST_TEST(out.faces.size() == 8u);
  std::vector<AC::Input_surface::Face> after(out.faces.begin(), out.faces.end());
  const AC::Input_surface flipped(out.points, after);
  BOOST_TEST(flipped.is_disk());
  bool has24 = false, has15 = false;
  for(const auto& f : out.faces) {
    BOOST_TEST(((out.points[f[1]] - out.points[f[0]]).cross(out.points[f[2]] - out.points[f[0]]).z() > 0));
    for(int k = 0; k < 3; ++k) {
      const std::size_t a = std::min(f[k], f[(k + 1) % 3]), b = std::max(f[k], f[(k + 1) % 3]);
      has24 = has24 || (a == 2 && b == 4);
      has15 = has15 || (a == 1 && b == 5);
    }
  }
  BOOST_TEST(has24);
  BOOST_TEST(!has15);
}

BOOST_AUTO_TEST_CASE(a_crease_edge_that_crosses_three_edges_is_recovered_by_a_sequence_of_flips)
{
  // a regular hexagon of side 1 (0 and 1 its opposite corners on the x axis, 2, 3 above, 4, 5 below) with
  // a vertex above (6) and below (7), cut so that the segment from 0 to 1 crosses the edges (2, 4), (2, 5)
  // and (3, 5): one flip cannot join 0 and 1, three in turn do
  const double h = std::sqrt(3.0) / 2;
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0},      {2, 0, 0},  {0.5, h, 0}, {1.5, h, 0},
                                               {0.5, -h, 0},   {1.5, -h, 0}, {1, 1.8, 0}, {1, -1.8, 0}};
  const std::vector<AC::Input_surface::Face> faces = {{{0, 4, 2}}, {{2, 4, 5}}, {{2, 5, 3}}, {{3, 5, 1}}, {{2, 3, 6}}, {{5, 4, 7}}};
  const AC::Input_surface hexagon(points, faces);
  auto make = [&] {
    AC::Remeshed_surface out;
    out.points = points;
    out.faces.assign(faces.begin(), faces.end());
    for(std::size_t v = 0; v < points.size(); ++v) out.surface_points.push_back(AC::Surface_point::at_vertex(v, points[v]));
    return out;
  };
  auto has_edge = [](const AC::Remeshed_surface& out, std::size_t a, std::size_t b) {
    for(const auto& f : out.faces)
      for(int k = 0; k < 3; ++k)
        if(std::min(f[k], f[(k + 1) % 3]) == std::min(a, b) && std::max(f[k], f[(k + 1) % 3]) == std::max(a, b)) return true;
    return false;
  };
  AC::Remeshed_surface out = make();
  const auto joined = AC::internal::recover_crease_edges(hexagon, out, {{0, 1}}, {0});
  BOOST_TEST(joined.first == 1u);
  BOOST_TEST(joined.second == 0u);
  BOOST_TEST(has_edge(out, 0, 1));
  BOOST_TEST((out.kept_edges == std::vector<std::array<std::size_t, 2>>{{{0, 1}}}));
  // still a disk of 6 triangles, none inverted, none with an angle below 30 degrees (the old smallest)
  BOOST_TEST(out.faces.size() == 6u);
  std::vector<AC::Input_surface::Face> after(out.faces.begin(), out.faces.end());
  BOOST_TEST(AC::Input_surface(out.points, after).is_disk());
  for(const auto& f : out.faces) {
    const Eigen::Vector3d u = out.points[f[1]] - out.points[f[0]], v = out.points[f[2]] - out.points[f[0]];
    BOOST_TEST(u.cross(v).z() > 0);
    for(int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = out.points[f[(k + 1) % 3]] - out.points[f[k]], q = out.points[f[(k + 2) % 3]] - out.points[f[k]];
      BOOST_TEST(std::atan2(p.cross(q).norm(), p.dot(q)) * 180 / std::acos(-1.0) > 30 - 1e-9);
    }
  }
  // with the middle crossed edge kept (a crease already joined), nothing is flipped and the pair is missing
  AC::Remeshed_surface locked = make();
  locked.kept_edges.push_back({{2, 5}});
  const auto none = AC::internal::recover_crease_edges(hexagon, locked, {{0, 1}}, {0});
  BOOST_TEST(none.first == 0u);
  BOOST_TEST(none.second == 1u);
  BOOST_TEST((locked.faces == make().faces));
}

BOOST_AUTO_TEST_CASE(creases_and_corners_of_a_disk_are_kept_in_the_plane)
{
  // issue 15, item 2, in the plane: pyramid_grid.off (scripts/make_pyramid_grid.py), a disk with 4 creases
  // from its apex (an interior corner) to the 4 corners of its boundary. Before: 0 % of the crease length
  // covered, 4 of 5 corners (the apex lost); measured 96.9 % at 150 and 98.4 % at 600 vertices, 5 of 5
  const AC::Input_surface in = read_case("pyramid_grid.off");
  const AC::Feature_graph g = AC::detect_features(in, 60, 30);
  BOOST_TEST(g.curves.size() == 4u);
  BOOST_TEST(g.corners.size() == 5u);
  const double tol = 1e-9 * in.bounding_box_diagonal();
  for(std::size_t n : {std::size_t(150), std::size_t(600)}) {
    AC::Remeshing_result r;
    const AC::Remeshed_surface out =
      AC::remesh_in_domain<AC::Planar_domain>(in, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n));
    BOOST_TEST_MESSAGE("pyramid_grid to " << n << ": " << r.crease_sites << " crease sites, " << r.crease_edges_missing << " missing, "
                                          << 100 * r.features.covered_share << " % covered, corners kept " << r.features.corners_kept
                                          << " of " << r.features.corners << ", G_avg " << r.quality.G_avg << ", theta_min "
                                          << r.quality.theta_min << ", %<30 " << r.quality.percent_below_30);
    BOOST_TEST(r.creases_not_followed.empty());
    BOOST_TEST((r.crease_run == AC::Crease_run::REFINED));
    BOOST_TEST(std::string(AC::crease_run_name(r.crease_run)) == "refined");
    BOOST_TEST(out.points.size() == n);
    BOOST_TEST(r.inverted_triangles == 0u);
    BOOST_TEST(r.features.corners_kept == 5u);
    BOOST_TEST(r.features.covered_share >= 0.9);
    BOOST_TEST(r.crease_sites > 0u);
    // the fixed sites: the boundary's, then the apex, then the crease sites
    BOOST_TEST(out.fixed_vertices == r.boundary_sites + 1 + r.crease_sites);
    for(std::size_t i = r.boundary_sites; i < out.fixed_vertices; ++i) BOOST_TEST(distance_to_creases(in, g, out.points[i]) < tol);
    // every vertex of a crease edge kept lies on the input's creases (the boundary corners included)
    BOOST_TEST(!out.kept_edges.empty());
    for(const auto& e : out.kept_edges)
      for(std::size_t v : e) BOOST_TEST(distance_to_creases(in, g, out.points[v]) < tol);
    // no two sites at one place: the boundary's corner sites are the creases' ends, not placed twice
    for(std::size_t i = 0; i < out.fixed_vertices; ++i)
      for(std::size_t j = i + 1; j < out.fixed_vertices; ++j) BOOST_TEST((out.points[i] - out.points[j]).norm() > tol);
    BOOST_TEST(AC::measure_features(in, g, out.points, out.faces).covered_length == r.features.covered_length);
  }
}

BOOST_AUTO_TEST_CASE(a_short_edge_between_two_fixed_corners_gets_no_thin_triangle)
{
  // issue 15, the smallest angle next to fixed sites: hip_roof.off (scripts/make_hip_roof.py), a disk whose
  // ridge (length 0.24, under half the output edge at 150 vertices) joins two interior corners, each the
  // end of 3 creases. Both corners are fixed sites, and the free vertices across their short edge were
  // left at the usual output edge length from it by the CVT and the centroid moves of the surface
  // optimisation: theta_min 24.95 degrees, %<30 0.37 (the tool, seed 0). The max-min angle moves of the
  // optimisation (Surface_optimizer::angle_pass()) bring them in: 35.5 degrees, every crease and corner kept
  const AC::Input_surface in = read_case("hip_roof.off");
  const AC::Feature_graph g = AC::detect_features(in, 60, 30);
  BOOST_TEST(g.curves.size() == 5u);
  BOOST_TEST(g.corners.size() == 6u);
  AC::Remeshing_result r;
  const AC::Remeshed_surface out =
    AC::remesh_in_domain<AC::Planar_domain>(in, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(150)));
  BOOST_TEST_MESSAGE("hip_roof to 150: " << 100 * r.features.covered_share << " % covered, corners kept " << r.features.corners_kept
                                         << " of " << r.features.corners << ", G_avg " << r.quality.G_avg << ", theta_min "
                                         << r.quality.theta_min << ", %<30 " << r.quality.percent_below_30 << ", surface optimisation "
                                         << r.surface_optimization.theta_min_before << " -> " << r.surface_optimization.theta_min_after);
  BOOST_TEST(r.creases_not_followed.empty());
  BOOST_TEST((r.crease_run == AC::Crease_run::REFINED));
  BOOST_TEST(out.points.size() == 150u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.features.corners_kept == 6u);
  BOOST_TEST(r.features.covered_share >= 0.99);
  BOOST_TEST(r.surface_optimization.ran);
  BOOST_TEST(r.quality.theta_min >= 30.0);  // 24.95 before, 35.5 measured
  BOOST_TEST(r.quality.percent_below_30 == 0.0);
  // the fixed vertices did not move: the corners and crease sites are still on the creases
  const double tol = 1e-9 * in.bounding_box_diagonal();
  for(std::size_t i = r.boundary_sites; i < out.fixed_vertices; ++i) BOOST_TEST(distance_to_creases(in, g, out.points[i]) < tol);
  BOOST_TEST(AC::measure_features(in, g, out.points, out.faces).covered_length == r.features.covered_length);
}

BOOST_AUTO_TEST_CASE(without_features_the_plane_is_unchanged)
{
  // feature angle 180 (the tool's --no-features) follows nothing, and its output is the pipeline's run
  // without the creases (the retry's path, finish_pipeline(..., false)) bit for bit
  const AC::Input_surface in = read_case("pyramid_grid.off");
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Planar_domain>(
    in, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(150)).feature_angle(180.0));
  BOOST_TEST(r.crease_sites == 0u);
  BOOST_TEST((r.crease_run == AC::Crease_run::NONE));
  BOOST_TEST(std::string(AC::crease_run_name(r.crease_run)) == "none");
  BOOST_TEST(out.fixed_vertices == r.boundary_sites);
  BOOST_TEST(out.kept_edges.empty());
  BOOST_TEST(r.features.curves == 0u);
  AC::Default_visitor visitor;
  AC::internal::Visitor_handle handle(visitor);
  const AC::internal::Remeshing_options options =
    AC::internal::Remeshing_options::from(AC::parameters::number_of_vertices(std::size_t(150)));
  AC::Remeshing_result r2;
  AC::internal::Pipeline_start start = AC::internal::start_pipeline<AC::Planar_domain>(in, AC::Uniform_metric(), r2, options, handle);
  BOOST_TEST(start.features.curves.size() == 4u);  // found, not followed
  const AC::Remeshed_surface plain =
    AC::internal::finish_pipeline<AC::Planar_domain>(in, AC::Uniform_metric(), start, *start.itri, r2, options, handle, false, nullptr);
  BOOST_TEST(plain.points == out.points);
  BOOST_TEST(plain.faces == out.faces);
  BOOST_TEST(r2.features.covered_share < 0.5);  // rounded off, as before
}

namespace {
// counts the stages started
struct Stage_counter : AC::Default_visitor {
  std::map<AC::Stage, int> started, finished;
  void on_stage_started(AC::Stage s) { ++started[s]; }
  void on_stage_finished(AC::Stage s, double) { ++finished[s]; }
};
} // namespace

BOOST_AUTO_TEST_CASE(a_run_whose_refined_creases_fail_follows_them_on_the_input_vertices)
{
  // pillow_005.off at 150: splitting its rim's pieces (a crease) makes the spherical embedding fail (89
  // triangles turned over); the second run, from the background kept after the refinement (the metric
  // stage is not run again), places the crease sites on the rim's own vertices, unsplit, and follows it
  // (the run without creases: 0 % covered, theta_min 12.4, Hausdorff 3.3 % of the diagonal)
  const AC::Input_surface in = read_case("pillow_005.off");
  Stage_counter counter;
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(
    in, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(150)).visitor(std::ref(counter)));
  BOOST_TEST(r.creases_not_followed.empty());
  BOOST_TEST((r.crease_run == AC::Crease_run::INPUT_VERTICES));
  BOOST_TEST_MESSAGE("pillow_005: the refined run failed: " << r.crease_refinement_failed);
  BOOST_TEST(r.crease_refinement_failed.find("inverted") != std::string::npos);  // the sphere's reason, kept
  BOOST_TEST(r.crease_sites > 10u);
  BOOST_TEST(out.points.size() == 150u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.features.covered_share >= 0.9);  // measured 1.0
  BOOST_TEST(r.quality.theta_min > 25.0);       // measured 37.0
  BOOST_TEST(counter.started[AC::Stage::METRIC] == 1);
  BOOST_TEST(counter.started[AC::Stage::EDGE_LENGTHS] == 2);
  BOOST_TEST(counter.finished[AC::Stage::EDGE_LENGTHS] == 2);
  BOOST_TEST(counter.started[AC::Stage::EMBEDDING] == 2);
}

namespace {
// a visitor whose first `failures` embeddings fail as a stage of this library fails on a valid input
struct Failing_embeddings : Stage_counter {
  int failures = 0;
  void on_stage_started(AC::Stage s)
  {
    Stage_counter::on_stage_started(s);
    if(s == AC::Stage::EMBEDDING && started[s] <= failures) throw AC::Remeshing_failure("injected failure " + std::to_string(started[s]));
  }
};
} // namespace

BOOST_AUTO_TEST_CASE(creases_that_fail_twice_give_the_run_without_them)
{
  // cube_grid.off at 150 (its crease pieces are split: the second run differs from the first), the
  // embedding made to fail by the visitor: once, and the second run (crease sites on the input's
  // vertices) follows the creases; twice, and the third run, without creases (its corners kept), stands
  // with the first run's reason; three times, and the fourth, without any feature site, stands with the
  // third's reason too; four times, and the third run's failure is thrown
  const AC::Input_surface in = read_case("cube_grid.off");
  const auto np = AC::parameters::number_of_vertices(std::size_t(150));
  Failing_embeddings once;
  once.failures = 1;
  AC::Remeshing_result r1;
  AC::remesh_in_domain<AC::Spherical_domain>(in, AC::Uniform_metric(), r1, np.visitor(std::ref(once)));
  BOOST_TEST(once.started[AC::Stage::EMBEDDING] == 2);
  BOOST_TEST(r1.creases_not_followed.empty());
  BOOST_TEST(r1.crease_refinement_failed == "injected failure 1");  // why the first run did not stand
  BOOST_TEST(AC::IO::report_json(r1).at("features").at("crease_refinement_failed") == "injected failure 1");
  BOOST_TEST((r1.crease_run == AC::Crease_run::INPUT_VERTICES));
  BOOST_TEST(std::string(AC::crease_run_name(r1.crease_run)) == "input-vertices");
  BOOST_TEST(AC::IO::report_json(r1).at("features").at("crease_run") == "input-vertices");  // the report says which run stood
  BOOST_TEST(r1.crease_sites > 0u);
  BOOST_TEST(r1.features.covered_share >= 0.9);
  BOOST_TEST(r1.features.corners_kept == 8u);
  BOOST_TEST(r1.inverted_triangles == 0u);

  Failing_embeddings twice;
  twice.failures = 2;
  AC::Remeshing_result r2;
  const AC::Remeshed_surface out = AC::remesh_in_domain<AC::Spherical_domain>(in, AC::Uniform_metric(), r2, np.visitor(std::ref(twice)));
  BOOST_TEST(twice.started[AC::Stage::EMBEDDING] == 3);
  BOOST_TEST(twice.started[AC::Stage::METRIC] == 1);
  BOOST_TEST(r2.creases_not_followed == "injected failure 1");
  BOOST_TEST(r2.crease_refinement_failed.empty());  // said by creases_not_followed
  BOOST_TEST(!AC::IO::report_json(r2).at("features").contains("crease_refinement_failed"));
  BOOST_TEST((r2.crease_run == AC::Crease_run::NOT_FOLLOWED));
  BOOST_TEST(std::string(AC::crease_run_name(r2.crease_run)) == "not-followed");
  BOOST_TEST(AC::IO::report_json(r2).at("features").at("crease_run") == "not-followed");
  BOOST_TEST(AC::IO::report_json(r2).at("features").at("creases_not_followed") == "injected failure 1");
  BOOST_TEST(r2.crease_sites == 0u);
  BOOST_TEST(out.points.size() == 150u);
  BOOST_TEST(r2.inverted_triangles == 0u);
  BOOST_TEST(r2.features.corners_kept == 8u);  // the corners are still kept, the creases not
  BOOST_TEST_MESSAGE("cube_grid without its creases followed: " << r2.features.covered_share << " covered");
  BOOST_TEST(r2.features.covered_share < 0.5);

  Failing_embeddings thrice;
  thrice.failures = 3;
  AC::Remeshing_result r3;
  const AC::Remeshed_surface bare = AC::remesh_in_domain<AC::Spherical_domain>(in, AC::Uniform_metric(), r3, np.visitor(std::ref(thrice)));
  BOOST_TEST(thrice.started[AC::Stage::EMBEDDING] == 4);
  BOOST_TEST((r3.crease_run == AC::Crease_run::FEATURES_DROPPED));
  BOOST_TEST(std::string(AC::crease_run_name(r3.crease_run)) == "features-dropped");
  BOOST_TEST(r3.creases_not_followed == "injected failure 1");
  BOOST_TEST(r3.corners_not_kept == "injected failure 3");
  BOOST_TEST(AC::IO::report_json(r3).at("features").at("corners_not_kept") == "injected failure 3");
  BOOST_TEST(r3.crease_sites == 0u);
  BOOST_TEST(bare.points.size() == 150u);
  BOOST_TEST(bare.fixed_vertices == 0u);   // no feature site at all
  BOOST_TEST(r3.features.corners == 8u);   // the input's features, still measured on the output
  BOOST_TEST(r3.discarded_seconds > 0);    // the three runs thrown away

  Failing_embeddings always;
  always.failures = 4;
  AC::Remeshing_result r4;
  try {
    AC::remesh_in_domain<AC::Spherical_domain>(in, AC::Uniform_metric(), r4, np.visitor(std::ref(always)));
    BOOST_ERROR("four failed runs must throw");
  } catch(const AC::Remeshing_failure& e) {
    BOOST_TEST(std::string(e.what()) == "injected failure 3");  // the run with the corners' failure, as it was
  }
  BOOST_TEST(always.started[AC::Stage::EMBEDDING] == 4);
}

BOOST_AUTO_TEST_CASE(a_crease_refinement_that_fails_keeps_its_split_count)
{
  // issue 15 review: when refine_creases() itself fails (more background vertices than its bound), the
  // splits it made were lost with the exception, and run_pipeline() skipped the second run (the crease
  // sites on the unsplit background), which it takes when the first run split pieces. A strip 1000 x 1 in
  // z = 0 whose middle line is a crease, for 1 output vertex: output edge length about 34, so the crease
  // needs about 88 pieces of a third of it, but the bound is 64 n + 4 V_before + V = 64 + 0 + 6 vertices.
  // (Through remesh() the background's own refinement refuses such an input first: the 1000 x 1 strip, a
  // band under a metric 30 to 1600 times longer along its crease, at 3 to 30 vertices, all stop there.)
  const double W = 1000;
  const AC::Input_surface strip({{0, 0, 0}, {W, 0, 0}, {0, 0.5, 0}, {W, 0.5, 0}, {0, 1, 0}, {W, 1, 0}},
                                {{{0, 1, 3}}, {{0, 3, 2}}, {{2, 3, 5}}, {{2, 5, 4}}});
  const AC::Feature_graph g = AC::detect_features(strip, 180, 30, {{{2, 3}}}, {});
  BOOST_REQUIRE(g.curves.size() == 1u);
  AC::Intrinsic_triangulation itri(strip, std::vector<Eigen::Matrix3d>(6, Eigen::Matrix3d::Identity()));
  AC::compute_metric_edge_lengths(itri);
  AC::Default_visitor visitor;
  AC::Remeshing_result r;  // refinement.vertices_before 0: the bound is 64 + 6
  std::size_t splits = 0;
  std::string message;
  try {
    AC::internal::finish_edge_lengths(itri, strip, 1, AC::parameters::default_values(), visitor, r, 0.0, nullptr, nullptr, nullptr, &g,
                                      &splits);
  } catch(const AC::Remeshing_failure& e) {
    message = e.what();
  }
  BOOST_TEST(message.find("the creases need more than 70 background vertices") != std::string::npos, message);
  BOOST_TEST(itri.number_of_vertices() == 70u);
  BOOST_TEST(splits == 64u);  // 0 before: the second run was skipped
}

BOOST_AUTO_TEST_CASE(crowded_vertices_move_to_split_edges_and_no_figure_gets_worse)
{
  // CGAL's part.off (175 vertices, flat faces and sharp creases) at 1000 vertices, the dual mesh of a CVT
  // stopped after 3 iterations (no surface optimisation): thin triangles remain next to the crease sites,
  // where the fixed sites left a free vertex crowded or a gap. (After 100 iterations none is left crowded
  // since the initial sites follow the optimal density of sites; with sites drawn by rho, 3 were.) relocate_crowded_vertices() moves some free vertices to the
  // midpoints of the thin triangles' longest edges (crowded_vertices.h): the vertex and face counts stay,
  // the fixed sites do not move, the faces still form a closed 2-manifold with the crease edges, every
  // moved vertex lies on the input, and none of G_min, theta_min, %<30 gets worse.
  const AC::Input_surface s = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cgal/part.off");
  AC::Remeshing_result r;
  const AC::Uniform_metric metric;
  const AC::Remeshed_surface dual = AC::remesh_in_domain<AC::Spherical_domain>(
      s, metric, r, AC::parameters::number_of_vertices(std::size_t(1000)).number_of_iterations(3u).surface_optimization(AC::Surface_optimization::OFF));
  BOOST_TEST_REQUIRE(r.crease_sites > 0u);
  AC::Remeshed_surface out = dual;
  std::vector<Eigen::Matrix3d> Q(out.points.size());
  for(std::size_t i = 0; i < Q.size(); ++i) Q[i] = AC::internal::symmetric_sqrt(metric.tensor(out.surface_points[i]));
  const std::vector<Eigen::Matrix3d> Q_before = Q;
  const AC::internal::Crowded_vertices_report moved =
      AC::internal::relocate_crowded_vertices(s, metric, out, Q, AC::internal::planar_side(s), 10);
  BOOST_TEST_MESSAGE("part.off at 1000: " << moved.candidates << " thin triangles, " << moved.moved << " vertices moved");
  BOOST_TEST(moved.moved > 0u);
  BOOST_TEST(moved.moved <= 10u);
  BOOST_TEST(out.points.size() == dual.points.size());
  BOOST_TEST(out.faces.size() == dual.faces.size());
  for(std::size_t i = 0; i < out.fixed_vertices; ++i) BOOST_TEST((out.points[i] == dual.points[i]));
  // a closed 2-manifold: every directed edge once, with its opposite
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  for(const auto& f : out.faces)
    for(int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  for(const auto& e : directed) {
    BOOST_TEST(e.second == 1);
    BOOST_TEST(directed.count({e.first.second, e.first.first}) == 1u);
  }
  for(const auto& e : out.kept_edges) BOOST_TEST(directed.count({e[0], e[1]}) + directed.count({e[1], e[0]}) == 2u);
  // the moved vertices are points of the input, with the metric there
  const double diagonal = s.bounding_box_diagonal();
  std::size_t changed = 0;
  for(std::size_t i = 0; i < out.points.size(); ++i) {
    if(out.points[i] == dual.points[i]) continue;
    ++changed;
    BOOST_TEST((s.project(out.points[i]).position - out.points[i]).norm() < 1e-9 * diagonal);
    BOOST_TEST((Q[i] - AC::internal::symmetric_sqrt(metric.tensor(out.surface_points[i]))).norm() < 1e-12);
  }
  BOOST_TEST(changed == moved.moved);
  const AC::Quality_report before = AC::compute_mesh_quality(dual.points, dual.faces, Q_before, 1);
  const AC::Quality_report after = AC::compute_mesh_quality(out.points, out.faces, Q, 1);
  BOOST_TEST_MESSAGE("G_min " << before.G_min << " -> " << after.G_min << ", theta_min " << before.theta_min << " -> "
                              << after.theta_min << ", %<30 " << before.percent_below_30 << " -> " << after.percent_below_30);
  BOOST_TEST(after.G_min >= before.G_min);
  BOOST_TEST(after.theta_min >= before.theta_min);
  BOOST_TEST(after.percent_below_30 < before.percent_below_30);  // each move replaces a thin triangle
  // the pipeline runs it after its flips and moves, and reports it
  AC::Remeshing_result full;
  AC::remesh_in_domain<AC::Spherical_domain>(s, metric, full, AC::parameters::number_of_vertices(std::size_t(1000)).number_of_iterations(3u));
  BOOST_TEST(full.surface_optimization.crowded_vertices > 0u);
  BOOST_TEST(full.inverted_triangles == 0u);
  BOOST_TEST(full.quality.theta_min >= r.quality.theta_min);
}

BOOST_AUTO_TEST_CASE(a_cap_between_three_crease_sites_is_split_across_its_long_edge)
{
  // A cap: three fixed crease sites all but on one line (a, c, b, the crease a -> c -> b kept), joined by
  // the long edge a b that the CVT's dual put there (CGAL's dino at 3000 vertices: 175.5 degrees at c,
  // theta_min 2.0). Its flip cannot be taken on a curved surface (the new edge leaves the input) and the
  // midpoint of a b lies next to c, so a split there leaves the same needle. relocate_crowded_vertices()
  // then splits it between c and the vertex d across a b (crowded_vertices.h). Here on a 12 x 12 planar
  // grid (the cell at (2, 2) holds the cap), one free vertex crowded near (9, 9) to give.
  const int n = 12;
  std::vector<Eigen::Vector3d> in_pts;
  std::vector<std::array<std::size_t, 3>> in_faces;
  auto grid = [&](std::vector<Eigen::Vector3d>& pts, std::vector<std::array<std::size_t, 3>>& faces) {
    pts.clear();
    faces.clear();
    for(int j = 0; j < n; ++j)
      for(int i = 0; i < n; ++i) pts.emplace_back(double(i), double(j), 0.0);
    auto id = [&](int i, int j) { return std::size_t(j * n + i); };
    for(int j = 0; j + 1 < n; ++j)
      for(int i = 0; i + 1 < n; ++i) {
        faces.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
        faces.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
      }
  };
  grid(in_pts, in_faces);
  const AC::Input_surface s(in_pts, in_faces);
  // the output: the same grid, the vertex (3, 2) moved to c = (2.55, 2.45) next to the diagonal from
  // a = (2, 2) to b = (3, 3), the vertex (9, 9) moved to (9.35, 9); a, c, b renumbered 0, 1, 2 (fixed)
  AC::Remeshed_surface out;
  grid(out.points, out.faces);
  const std::size_t a = 2 * n + 2, c = 2 * n + 3, b = 3 * n + 3, crowded = 9 * n + 9;
  out.points[c] = Eigen::Vector3d(2.55, 2.45, 0.0);
  out.points[crowded] = Eigen::Vector3d(9.35, 9.0, 0.0);
  out.points[3 * n + 2] = Eigen::Vector3d(1.6, 3.4, 0.0);  // d: (a, b, d) of angles 61, 61, 58 degrees
  std::vector<std::size_t> order(out.points.size());
  for(std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::swap(order[0], order[a]);  // order[new] = old: a, c, b first
  std::swap(order[1], order[std::size_t(std::find(order.begin(), order.end(), c) - order.begin())]);
  std::swap(order[2], order[std::size_t(std::find(order.begin(), order.end(), b) - order.begin())]);
  std::vector<std::size_t> new_of(order.size());
  for(std::size_t i = 0; i < order.size(); ++i) new_of[order[i]] = i;
  std::vector<Eigen::Vector3d> points(order.size());
  for(std::size_t i = 0; i < order.size(); ++i) points[i] = out.points[order[i]];
  out.points = points;
  for(auto& f : out.faces)
    for(auto& x : f) x = new_of[x];
  for(const auto& p : out.points) out.surface_points.push_back(s.project(p));
  out.fixed_vertices = 3;
  out.kept_edges = {{{0, 1}}, {{1, 2}}};
  const AC::Remeshed_surface dual = out;
  const AC::Uniform_metric metric;
  std::vector<Eigen::Matrix3d> Q(out.points.size(), Eigen::Matrix3d::Identity());
  const AC::Quality_report before = AC::compute_mesh_quality(out.points, out.faces, Q, 1);
  const AC::internal::Crowded_vertices_report moved =
    AC::internal::relocate_crowded_vertices(s, metric, out, Q, AC::internal::planar_side(s), 1);
  const AC::Quality_report after = AC::compute_mesh_quality(out.points, out.faces, Q, 1);
  BOOST_TEST_MESSAGE("cap on a grid: theta_min " << before.theta_min << " -> " << after.theta_min << ", " << moved.moved << " moved");
  BOOST_TEST_REQUIRE(moved.moved == 1u);
  BOOST_TEST(before.theta_min < 6.0);  // the cap: 5.7 degrees at a and b
  BOOST_TEST(after.theta_min > 11.0);   // measured 11.3: the triangle (1, 3), d, (2, 4) left by moving d
  // the cap is gone, the crease edges and the fixed sites stay, the counts too
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  for(const auto& f : out.faces) {
    std::array<std::size_t, 3> t = f;
    std::sort(t.begin(), t.end());
    BOOST_TEST(!(t[0] == 0 && t[1] == 1 && t[2] == 2));
    for(int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  }
  BOOST_TEST(directed.count({0, 1}) + directed.count({1, 0}) == 2u);
  BOOST_TEST(directed.count({1, 2}) + directed.count({2, 1}) == 2u);
  BOOST_TEST(out.points.size() == dual.points.size());
  BOOST_TEST(out.faces.size() == dual.faces.size());
  for(std::size_t i = 0; i < 3; ++i) BOOST_TEST((out.points[i] == dual.points[i]));
  // the new vertex is off the line a b (at the incentre of a, b, d), not at its midpoint
  std::size_t changed = 0;
  for(std::size_t i = 3; i < out.points.size(); ++i) {
    if(out.points[i] == dual.points[i]) continue;
    ++changed;
    const Eigen::Vector3d& m = out.points[i];
    // its triangles (where the cap was): measured 30.4 degrees at least (the midpoint of a b would give 5.7)
    for(const auto& f : out.faces) {
      if(f[0] != i && f[1] != i && f[2] != i) continue;
      for(int k = 0; k < 3; ++k) {
        const Eigen::Vector3d u = out.points[f[(k + 1) % 3]] - out.points[f[k]], v = out.points[f[(k + 2) % 3]] - out.points[f[k]];
        BOOST_TEST(std::atan2(u.cross(v).norm(), u.dot(v)) * 180 / 3.14159265358979323846 > 29.0);
      }
    }
    BOOST_TEST(std::abs(m.y() - m.x()) / std::sqrt(2.0) > 0.2);  // its distance to the line through a and b
  }
  BOOST_TEST(changed == 1u);
}

namespace {

// A coin: a closed prism over a regular k-gon of radius 1 and height `thickness` (one row of quads on the
// side, each cap a fan around its centre): its two rims are closed crease loops `thickness` apart.
AC::Input_surface make_coin(int k, double thickness)
{
  std::vector<Eigen::Vector3d> points;
  const double pi = 3.14159265358979323846;
  for(double z : {-0.5 * thickness, 0.5 * thickness})
    for(int i = 0; i < k; ++i) points.push_back(Eigen::Vector3d(std::cos(2 * pi * i / k), std::sin(2 * pi * i / k), z));
  const std::size_t bottom = points.size(), top = bottom + 1;
  points.push_back(Eigen::Vector3d(0, 0, -0.5 * thickness));
  points.push_back(Eigen::Vector3d(0, 0, 0.5 * thickness));
  std::vector<AC::Input_surface::Face> faces;
  for(int i = 0; i < k; ++i) {
    const std::size_t a = std::size_t(i), b = std::size_t((i + 1) % k);
    faces.push_back({{a, b, b + std::size_t(k)}});
    faces.push_back({{a, b + std::size_t(k), a + std::size_t(k)}});
    faces.push_back({{bottom, b, a}});
    faces.push_back({{top, a + std::size_t(k), b + std::size_t(k)}});
  }
  return AC::Input_surface(points, faces);
}

} // namespace

BOOST_AUTO_TEST_CASE(two_creases_closer_than_an_output_edge_are_both_kept_with_the_metric_scaled_between_them)
{
  // issue 15 (features/feature_size.h): the rims of a coin 0.03 thick, at 2000 vertices (output edges
  // about 0.06): without the feature sizing the second rim's sites fall within half an edge of the first's
  // and are left out (measured: 50 % of the crease length covered); with it the metric is scaled up along
  // the side band and both rims are chains of output edges (measured 100 %, theta_min 34.6, G_avg 0.883)
  const AC::Input_surface coin = make_coin(96, 0.03);
  const std::size_t n = 2000;
  AC::Remeshing_result off;
  AC::remesh_in_domain<AC::Spherical_domain>(coin, AC::Uniform_metric(), off, AC::parameters::number_of_vertices(n).feature_sizing(false));
  BOOST_TEST_MESSAGE("coin without the sizing: " << 100 * off.features.covered_share << " % covered, G_avg " << off.quality.G_avg
                                                 << ", theta_min " << off.quality.theta_min);
  BOOST_TEST(!off.feature_sizing.applied);
  BOOST_TEST(off.feature_sizing.narrow_points == 0u);  // not even measured
  BOOST_TEST(off.features.covered_share < 0.75);
  AC::Remeshing_result r;
  AC::internal::Feature_sizing_once once;  // as remesh_in_domain() does
  const AC::Remeshed_surface out = AC::internal::remesh_in_domain_with_sizing<AC::Spherical_domain>(
      coin, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n), once);
  const AC::Feature_sizing_report& s = r.feature_sizing;
  BOOST_TEST_MESSAGE("coin with the sizing: " << 100 * r.features.covered_share << " % covered, G_avg " << r.quality.G_avg
                                              << ", theta_min " << r.quality.theta_min << "; gap " << s.gap_min << " h, scale up to "
                                              << s.scale_max << ", area x " << s.area_factor << ", " << s.narrow_points << " narrow points");
  BOOST_TEST(s.applied);
  BOOST_TEST(s.narrow_points > 0u);
  BOOST_TEST(s.gaps_left == 0u);
  BOOST_TEST((s.gap_min > 0.3 && s.gap_min < 0.7));  // 0.03 over an output edge of about 0.06 (0.49 measured)
  BOOST_TEST((s.scale_max > 1.5 && s.scale_max <= 6.0));
  BOOST_TEST((s.area_factor > 1.0 && s.area_factor <= 6.0));
  BOOST_TEST(s.vertices_scaled == 192u);  // the rims' vertices, and not the caps' centres
  BOOST_TEST(out.points.size() == n);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.features.covered_share >= 0.99);
  BOOST_TEST(r.quality.theta_min >= 25.0);
  // the JSON report says it
  const nlohmann::json j = AC::IO::report_json(r);
  BOOST_TEST(j.at("feature_sizing").at("applied").get<bool>());
  BOOST_TEST(j.at("feature_sizing").at("narrow_points").get<std::size_t>() == s.narrow_points);
  // a second run with the same sizing (as the automatic choice's cone run after the sphere's) reuses it:
  // the same field, not computed again (its time is the first run's), and the same output
  BOOST_TEST_REQUIRE(once.sizing[0].has_value());
  BOOST_TEST(!once.sizing[1].has_value());  // the sphere is not sized by curvature by default
  const AC::internal::Feature_size_field* field = once.sizing[0]->field.get();
  const double seconds = once.seconds[0];
  BOOST_TEST(r.seconds[int(AC::Stage::METRIC)] >= seconds);
  AC::Remeshing_result r2;
  const AC::Remeshed_surface out2 = AC::internal::remesh_in_domain_with_sizing<AC::Spherical_domain>(
      coin, AC::Uniform_metric(), r2, AC::parameters::number_of_vertices(n), once);
  BOOST_TEST(once.sizing[0]->field.get() == field);
  BOOST_TEST(once.seconds[0] == seconds);
  BOOST_TEST(r2.feature_sizing.narrow_points == s.narrow_points);
  BOOST_TEST((out2.points == out.points));
}

BOOST_AUTO_TEST_CASE(feature_sizing_leaves_alone_corners_wide_gaps_and_what_it_cannot_afford)
{
  // the cube's creases meet at its corners (not a gap: the path through the corner is short), so no
  // sizing; the coin at 600 vertices would need more than 5/6 of the vertices near its rims: measured,
  // not applied, and the output is the one without the sizing
  AC::Remeshing_result cube;
  AC::remesh_in_domain<AC::Spherical_domain>(make_grid_cube(4), AC::Uniform_metric(), cube,
                                             AC::parameters::number_of_vertices(std::size_t(500)));
  BOOST_TEST(cube.feature_sizing.narrow_points == 0u);
  BOOST_TEST(!cube.feature_sizing.applied);
  const AC::Input_surface coin = make_coin(96, 0.03);
  AC::Remeshing_result small, plain;
  const AC::Remeshed_surface a =
    AC::remesh_in_domain<AC::Spherical_domain>(coin, AC::Uniform_metric(), small, AC::parameters::number_of_vertices(std::size_t(600)));
  const AC::Remeshed_surface b = AC::remesh_in_domain<AC::Spherical_domain>(
    coin, AC::Uniform_metric(), plain, AC::parameters::number_of_vertices(std::size_t(600)).feature_sizing(false));
  BOOST_TEST(small.feature_sizing.narrow_points > 0u);
  BOOST_TEST(!small.feature_sizing.applied);
  BOOST_TEST(small.feature_sizing.gaps_left == small.feature_sizing.narrow_points);
  BOOST_TEST(small.feature_sizing.area_factor == 1.0);
  BOOST_TEST((a.points == b.points));
  const nlohmann::json j = AC::IO::report_json(small);
  BOOST_TEST(!j.at("feature_sizing").at("applied").get<bool>());
}

namespace {

// the sphere of radius 1 (make_ellipsoid at `level`), each vertex moved along its radius by up to
// `noise` (a deterministic pseudo-random pattern of either sign: a scan's noise at the input's own scale)
AC::Input_surface make_noisy_sphere(int level, double noise)
{
  const AC::Input_surface sphere = AC::make_ellipsoid(level, 1, 1, 1);
  std::vector<Eigen::Vector3d> points = sphere.points();
  std::uint32_t state = 12345;
  for(Eigen::Vector3d& p : points) {
    state = state * 1664525u + 1013904223u;
    p *= 1 + noise * (2 * double(state >> 8) / double(1u << 24) - 1);
  }
  return AC::Input_surface(points, sphere.faces());
}

// the output vertices within `r` of either end (x = +-a) of an ellipsoid along x
std::size_t vertices_near_the_tips(const AC::Remeshed_surface& out, double a, double r)
{
  std::size_t k = 0;
  for(const Eigen::Vector3d& p : out.points)
    if((p - Eigen::Vector3d(a, 0, 0)).norm() < r || (p + Eigen::Vector3d(a, 0, 0)).norm() < r) ++k;
  return k;
}

} // namespace

BOOST_AUTO_TEST_CASE(curvature_sizes_read_a_spheres_radius_through_noise)
{
  // features/curvature_size.h: on the unit sphere the largest principal curvature is 1 everywhere; where
  // an output edge h is longer than the radius (h = 2) every vertex asks for radius_to_size (1.25) times
  // it, and where it is much shorter (h = 0.1) none asks for anything
  const std::vector<Eigen::Matrix3d> I(AC::make_ellipsoid(4, 1, 1, 1).number_of_vertices(), Eigen::Matrix3d::Identity());
  const AC::Feature_graph none;
  for(double noise : {0.0, 0.005}) {
    // the noise: at level 4 the input's edges are about 0.08 long, so +-0.005 bends them by up to 7
    // degrees, a curvature of up to 1.5 at the input's own scale: averaged over cells of at least the
    // input's median edge it cancels
    const AC::Input_surface sphere = make_noisy_sphere(4, noise);
    const AC::internal::Curvature_sizes big = AC::internal::curvature_sizes(sphere, none, I, 2.0, std::sqrt(6.0) * 2.0);
    BOOST_TEST_MESSAGE("noise " << noise << ": " << big.points << " of " << sphere.number_of_vertices()
                                << " vertices, smallest radius " << big.radius_min * 2.0);
    BOOST_TEST(big.points == sphere.number_of_vertices());
    BOOST_TEST_REQUIRE(big.size.size() == sphere.number_of_vertices());
    BOOST_TEST((big.radius_min * 2.0 > 0.8 && big.radius_min * 2.0 <= 1.02));
    for(double d : big.size) BOOST_TEST((d > 0.8 * 1.25 && d < 1.2 * 1.25));
    const AC::internal::Curvature_sizes small = AC::internal::curvature_sizes(sphere, none, I, 0.1, std::sqrt(6.0) * 0.1);
    BOOST_TEST(small.points == 0u);
    BOOST_TEST(small.size.empty());
  }
  // a planar input has no curvature
  AC::Input_surface square({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(0, 1, 0)},
                           {{{0, 1, 2}}, {{0, 2, 3}}});
  const std::vector<Eigen::Matrix3d> I4(4, Eigen::Matrix3d::Identity());
  BOOST_TEST(AC::internal::curvature_sizes(square, none, I4, 10.0, 25.0).size.empty());
}

BOOST_AUTO_TEST_CASE(the_curvature_sizing_refines_the_tips_of_a_needle)
{
  // an ellipsoid 1 x 0.12 x 0.12 at 400 vertices: output edges of about 0.06, the tips' radius of
  // curvature 0.0144 (b^2 / a), the middle's 0.12: with Curvature_sizing::ALWAYS on the sphere the metric
  // is scaled up at the tips, so the output has more vertices there and follows them closer; by default
  // (Curvature_sizing::CONES) the sphere's run is not sized by curvature
  const AC::Input_surface needle = AC::make_ellipsoid(5, 1.0, 0.12, 0.12);
  const std::size_t n = 400;
  AC::Remeshing_result with, without;
  const AC::Remeshed_surface a = AC::remesh_in_domain<AC::Spherical_domain>(
    needle, AC::Uniform_metric(), with, AC::parameters::number_of_vertices(n).curvature_sizing(AC::Curvature_sizing::ALWAYS));
  const AC::Remeshed_surface b =
    AC::remesh_in_domain<AC::Spherical_domain>(needle, AC::Uniform_metric(), without, AC::parameters::number_of_vertices(n));
  const AC::Feature_sizing_report& s = with.feature_sizing;
  BOOST_TEST_MESSAGE("needle: " << s.curved_points << " curved points, radius down to " << s.radius_min << " h, scale up to "
                                << s.scale_max << ", area x " << s.area_factor << "; near the tips " << vertices_near_the_tips(a, 1.0, 0.1)
                                << " vertices (without: " << vertices_near_the_tips(b, 1.0, 0.1) << "), Hausdorff "
                                << with.hausdorff_distance << " (without: " << without.hausdorff_distance << "), G_avg " << with.quality.G_avg
                                << " (" << without.quality.G_avg << "), theta_min " << with.quality.theta_min << " (" << without.quality.theta_min << ")");
  BOOST_TEST(s.applied);
  BOOST_TEST(s.curvature_applied);
  BOOST_TEST(s.curved_points > 0u);
  BOOST_TEST(s.narrow_points == 0u);  // no crease
  BOOST_TEST((s.radius_min > 0.2 && s.radius_min < 0.8));  // 0.47 measured
  BOOST_TEST((s.scale_max > 1.2 && s.scale_max <= 3.0));    // 1.72 measured
  BOOST_TEST((s.area_factor > 1.0 && s.area_factor <= 6.0));
  BOOST_TEST(without.feature_sizing.curved_points == 0u);  // not even measured
  BOOST_TEST(!without.feature_sizing.applied);
  BOOST_TEST(a.points.size() == n);
  BOOST_TEST(with.inverted_triangles == 0u);
  BOOST_TEST(vertices_near_the_tips(a, 1.0, 0.1) >= vertices_near_the_tips(b, 1.0, 0.1) + 6);  // 21 and 11 measured
  BOOST_TEST(with.hausdorff_distance < 0.8 * without.hausdorff_distance);                       // 0.0088 and 0.0128
  BOOST_TEST(with.quality.theta_min >= 25.0);
  BOOST_TEST(with.quality.G_avg >= 0.85);
  const nlohmann::json j = AC::IO::report_json(with);
  BOOST_TEST(j.at("feature_sizing").at("curvature_applied").get<bool>());
  BOOST_TEST(j.at("feature_sizing").at("curved_points").get<std::size_t>() == s.curved_points);
}

BOOST_AUTO_TEST_SUITE_END()  // features
