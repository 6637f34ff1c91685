// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The cone domain of issue 16 (a flat metric with cone singularities instead of the sphere's, for
// surfaces with limbs):
// - Cone_domain models ParametricDomain (the shared concept checks);
// - the intrinsic Delaunay triangulation of points on a cone surface (internal::Cone_surface_delaunay):
//   on the regular tetrahedron (four cones of angle pi) and its subdivision (six flat vertices more, which
//   must all be removed), a closed genus-0 triangulation of exactly the points, oriented like the faces,
//   whose volume approaches the tetrahedron's; coinciding points and an open surface are refused;
// - remesh() through the cones: a synthetic body with five long limbs and the bundled cow, which the
//   sphere cannot take, remesh to exactly the vertex count asked, closed, of genus 0, with no inverted
//   triangle and quality bounds; the automatic choice falls back to cones and says why; with the
//   defaults the cow's noisy creases end in the run without feature sites, which the report says;
// - surfaces with holes through cones (their holes closed by patches, as on the sphere): a long open
//   tube falls back to cones and keeps both loops, a short one goes there on request; a disk and bad
//   input are refused with Invalid_input.

#ifndef ANISO_CONFORMAL_TEST_UNITY
#define BOOST_TEST_MODULE Aniso_conformal_cones
#endif
#include <boost/test/unit_test.hpp>

#include <Aniso_conformal/Cone_domain.h>
#include <Aniso_conformal/Curvature_metric.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/IO/write_cone_cvt_svg.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/internal/domains/cone_charts.h>
#include <Aniso_conformal/internal/domains/cone_surface_delaunay.h>
#include <Aniso_conformal/make_ellipsoid.h>
#include <Aniso_conformal/make_square_background.h>
#include <Aniso_conformal/remesh.h>

#include "domain_concept_checks.h"
#include "mesh_checks.h"
#include "limb_body.h"
#include "message_checks.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

BOOST_AUTO_TEST_SUITE(cone_domain)  // also a namespace: keeps the helpers apart from other modules in one unit

namespace AC = Aniso_conformal;

namespace {

// every directed edge once with its opposite, every vertex's link one cycle, every vertex in a triangle;
// the genus from Euler's formula (-1 if not a closed manifold)
int closed_manifold_genus(std::size_t n, const std::vector<std::array<std::size_t, 3>>& tris)
{
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  std::vector<std::map<std::size_t, std::size_t>> link(n);
  for(const auto& t : tris)
    for(int k = 0; k < 3; ++k) {
      const std::size_t a = t[std::size_t(k)], b = t[std::size_t((k + 1) % 3)], c = t[std::size_t((k + 2) % 3)];
      if(a >= n || a == b || !link[a].emplace(b, c).second) return -1;
      ++directed[{a, b}];
    }
  for(const auto& e : directed)
    if(e.second != 1 || !directed.count({e.first.second, e.first.first})) return -1;
  for(std::size_t v = 0; v < n; ++v) {
    if(link[v].empty()) return -1;
    std::size_t steps = 0, x = link[v].begin()->first;
    do {
      const auto it = link[v].find(x);
      if(it == link[v].end()) return -1;
      x = it->second;
      ++steps;
    } while(x != link[v].begin()->first && steps <= link[v].size());
    if(steps != link[v].size()) return -1;
  }
  const long chi = long(n) - long(directed.size() / 2) + long(tris.size());
  return chi % 2 == 0 ? int((2 - chi) / 2) : -1;
}

// A regular tetrahedron of edge 1 (`subdivided`: each face cut into four, the six edge midpoints being flat
// vertices of the cone metric) as faces, twins, an equilateral layout per face, its cones and the
// vertices' positions in space.
struct Tetrahedron {
  std::vector<std::array<int, 3>> faces;
  std::vector<int> twin;
  std::vector<std::array<Eigen::Vector2d, 3>> layout;
  std::vector<char> is_cone;
  std::vector<Eigen::Vector3d> position;
};

void with_twins_and_layout(Tetrahedron& t);

Tetrahedron make_tetrahedron(bool subdivided)
{
  Tetrahedron t;
  const double s = 1 / std::sqrt(8.0);
  t.position = {Eigen::Vector3d(s, s, s), Eigen::Vector3d(s, -s, -s), Eigen::Vector3d(-s, s, -s), Eigen::Vector3d(-s, -s, s)};
  std::vector<std::array<int, 3>> coarse = {{{0, 1, 2}}, {{0, 3, 1}}, {{0, 2, 3}}, {{1, 3, 2}}};
  t.is_cone.assign(4, 1);
  if(!subdivided) t.faces = coarse;
  else {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if(it != mid.end()) return it->second;
      t.position.push_back(0.5 * (t.position[std::size_t(a)] + t.position[std::size_t(b)]));
      t.is_cone.push_back(0);
      return mid[key] = int(t.position.size()) - 1;
    };
    for(const auto& f : coarse) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      t.faces.push_back({{f[0], ab, ca}});
      t.faces.push_back({{ab, f[1], bc}});
      t.faces.push_back({{ca, bc, f[2]}});
      t.faces.push_back({{ab, bc, ca}});
    }
  }
  with_twins_and_layout(t);
  return t;
}

// the twins and each face's layout (by its own edge lengths, counterclockwise) of t's faces and positions
void with_twins_and_layout(Tetrahedron& t)
{
  std::map<std::pair<int, int>, int> half;
  for(std::size_t f = 0; f < t.faces.size(); ++f)
    for(int k = 0; k < 3; ++k) half[{t.faces[f][std::size_t(k)], t.faces[f][std::size_t((k + 1) % 3)]}] = int(3 * f) + k;
  t.twin.assign(3 * t.faces.size(), -1);
  for(const auto& h : half) t.twin[std::size_t(h.second)] = half.at({h.first.second, h.first.first});
  // each face laid out by its own edge lengths, counterclockwise
  for(const auto& f : t.faces) {
    const Eigen::Vector3d a = t.position[std::size_t(f[0])], b = t.position[std::size_t(f[1])], c = t.position[std::size_t(f[2])];
    const double ab = (b - a).norm(), x = (c - a).dot(b - a) / ab, y = ((c - a) - x * (b - a) / ab).norm();
    t.layout.push_back({{Eigen::Vector2d(0, 0), Eigen::Vector2d(ab, 0), Eigen::Vector2d(x, y)}});
  }
}

// A needle: a triangular bipyramid whose top apex (vertex 0, at height 10 over a base triangle of
// circumradius 1) is a cone of about 30 degrees, the bottom apex (vertex 4) 1 below the base; every
// vertex a cone, no flat vertex.
Tetrahedron make_needle()
{
  Tetrahedron t;
  t.position = {Eigen::Vector3d(0, 0, 10)};
  for(int i = 0; i < 3; ++i) t.position.push_back(Eigen::Vector3d(std::cos(2.0944 * i), std::sin(2.0944 * i), 0));
  t.position.push_back(Eigen::Vector3d(0, 0, -1));
  for(int i = 0; i < 3; ++i) {
    const int a = 1 + i, b = 1 + (i + 1) % 3;
    t.faces.push_back({{0, a, b}});
    t.faces.push_back({{4, b, a}});
  }
  t.is_cone.assign(5, 1);
  with_twins_and_layout(t);
  return t;
}

// the point of face f at barycentric coordinates (1 - a - b, a, b), and its position in space
AC::internal::Cone_surface_delaunay::Point_on_face point_in_face(const Tetrahedron& t, int f, double a, double b, Eigen::Vector3d& where)
{
  const auto& L = t.layout[std::size_t(f)];
  const auto& F = t.faces[std::size_t(f)];
  where = (1 - a - b) * t.position[std::size_t(F[0])] + a * t.position[std::size_t(F[1])] + b * t.position[std::size_t(F[2])];
  AC::internal::Cone_surface_delaunay::Point_on_face p;
  p.face = f;
  p.x = L[0] + a * (L[1] - L[0]) + b * (L[2] - L[0]);
  return p;
}

// `n` random points on the faces of `t` (uniform in each face, faces weighted by area), and their positions
std::vector<AC::internal::Cone_surface_delaunay::Point_on_face> random_points(const Tetrahedron& t, std::size_t n, unsigned seed,
                                                                             std::vector<Eigen::Vector3d>& where)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<AC::internal::Cone_surface_delaunay::Point_on_face> p(n);
  where.resize(n);
  for(std::size_t i = 0; i < n; ++i) {
    const int f = int(rng() % t.faces.size());
    double a = unit(rng), b = unit(rng);
    if(a + b > 1) a = 1 - a, b = 1 - b;
    const auto& L = t.layout[std::size_t(f)];
    p[i].face = f;
    p[i].x = L[0] + a * (L[1] - L[0]) + b * (L[2] - L[0]);
    const auto& F = t.faces[std::size_t(f)];
    where[i] = (1 - a - b) * t.position[std::size_t(F[0])] + a * t.position[std::size_t(F[1])] + b * t.position[std::size_t(F[2])];
  }
  return p;
}

} // namespace

BOOST_AUTO_TEST_CASE(cone_domain_models_its_concepts)
{
  // the cells hold the surface's mass to 1e-6, as in the other domains (measured 3e-16 on 2026-12-06). A
  // defect that left 6e-4 of it next to the four cones in no chart's cell had been bounded here at 1e-3;
  // a later change of the charts or their bands removed it (which one was not traced)
  test::check_domain_concept<AC::Cone_domain>(AC::make_ellipsoid(3), AC::make_square_background(AC::Uniform_metric(), 300), 200);
  // its fewest vertices are those of the genus (the tetrahedron on a sphere)
  BOOST_CHECK_NO_THROW(AC::Cone_domain::check_number_of_vertices(AC::make_ellipsoid(3), 4));
  BOOST_CHECK_THROW(AC::Cone_domain::check_number_of_vertices(AC::make_ellipsoid(3), 3), AC::Invalid_input);
}

BOOST_AUTO_TEST_CASE(delaunay_of_points_on_the_tetrahedron_is_a_closed_triangulation_of_them)
{
  const double tetrahedron_volume = 1 / (6 * std::sqrt(2.0));
  for(bool subdivided : {false, true})
    for(std::size_t n : {std::size_t(12), std::size_t(300)}) {
      const Tetrahedron t = make_tetrahedron(subdivided);
      std::vector<Eigen::Vector3d> where;
      const auto points = random_points(t, n, unsigned(n), where);
      AC::internal::Cone_surface_delaunay delaunay(t.faces, t.twin, t.layout, t.is_cone);
      const std::vector<std::array<std::size_t, 3>> tris = delaunay.triangulate(points);
      BOOST_TEST(tris.size() == 2 * n - 4);
      BOOST_TEST(closed_manifold_genus(n, tris) == 0);
      // the flat edge midpoints are all removed; the four cones are merged into a point each
      BOOST_TEST(delaunay.statistics().removed == (subdivided ? 6u : 0u));
      BOOST_TEST(delaunay.statistics().collapsed == 4u);
      // oriented like the faces (outwards): positive volume, close to the tetrahedron's with many points
      double volume = 0;
      for(const auto& f : tris) volume += where[f[0]].dot(where[f[1]].cross(where[f[2]])) / 6;
      BOOST_TEST_MESSAGE("tetrahedron" << (subdivided ? " subdivided" : "") << ", " << n << " points: volume " << volume / tetrahedron_volume
                                       << " of the tetrahedron's, " << delaunay.statistics().flips << " flips, "
                                       << delaunay.statistics().untangled << " untangled");
      BOOST_TEST(volume > 0);
      BOOST_TEST(volume <= tetrahedron_volume * (1 + 1e-9));
      if(n == 300) BOOST_TEST(volume >= 0.7 * tetrahedron_volume);
    }
}

// Sites exactly at background vertices (fixed sites: the input's corners, the cones of negative curvature
// kept as output vertices) become those vertices; a site a hair away from one makes needle-like triangles
// whose flips must keep every angle sum (they did not, with the law of cosines: 0.14 rad on CGAL's femur,
// and hundreds of flat vertices were left unremoved)
BOOST_AUTO_TEST_CASE(delaunay_on_a_cone_surface_with_sites_at_and_next_to_vertices)
{
  const Tetrahedron t = make_tetrahedron(true);
  std::vector<Eigen::Vector3d> where;
  auto points = random_points(t, 200, 11u, where);
  // a point at every cone (vertices 0 to 3) and at one flat midpoint (vertex 4), each given as a corner of
  // the first face at it
  auto first_face_at = [&](int v, int& corner) {
    for(std::size_t f = 0; f < t.faces.size(); ++f)
      for(int k = 0; k < 3; ++k)
        if(t.faces[f][std::size_t(k)] == v) {
          corner = k;
          return int(f);
        }
    return -1;
  };
  for(int v = 0; v < 5; ++v) {
    int k = 0;
    const int f = first_face_at(v, k);
    points[std::size_t(v)].face = f;
    points[std::size_t(v)].x = t.layout[std::size_t(f)][std::size_t(k)];
    where[std::size_t(v)] = t.position[std::size_t(v)];
  }
  // two points a hair (1e-9 of the edges) inside faces at two other midpoints (vertices 5 and 6)
  for(int j = 0; j < 2; ++j) {
    int k = 0;
    const int f = first_face_at(5 + j, k);
    const auto& L = t.layout[std::size_t(f)];
    const std::size_t i = std::size_t(10 + j), k0 = std::size_t(k), k1 = std::size_t((k + 1) % 3), k2 = std::size_t((k + 2) % 3);
    points[i].face = f;
    points[i].x = L[k0] + 1e-9 * ((L[k1] - L[k0]) + (L[k2] - L[k0]));
    where[i] = t.position[std::size_t(5 + j)];
  }
  AC::internal::Cone_surface_delaunay delaunay(t.faces, t.twin, t.layout, t.is_cone);
  const std::vector<std::array<std::size_t, 3>> tris = delaunay.triangulate(points);
  BOOST_TEST(tris.size() == 2 * points.size() - 4);
  BOOST_TEST(closed_manifold_genus(points.size(), tris) == 0);
  BOOST_TEST(delaunay.statistics().collapsed == 0u);  // every cone is a point
  BOOST_TEST(delaunay.statistics().removed == 5u);    // the other five midpoints, each flat: none left over
  double volume = 0;
  for(const auto& f : tris) volume += where[f[0]].dot(where[f[1]].cross(where[f[2]])) / 6;
  BOOST_TEST(volume > 0);
}

// A thin part narrower than the points' spacing: one point near the needle's tip (vertex 0, a cone of
// about 30 degrees), the next one 5 further down, whose cell wraps around the needle, and the others near
// the base. The cone's link is then a a b (a's loop edge around the tip, b of degree 2), which neither a
// collapse nor a fan over the cone's and one point's faces can mend (CGAL's triceratops and cow, at 3000
// with creases); the star of b over that region grown across its border joins b to the points beyond.
BOOST_AUTO_TEST_CASE(delaunay_on_a_cone_surface_meshes_a_needle_with_one_point_near_its_tip)
{
  const Tetrahedron t = make_needle();
  std::vector<Eigen::Vector3d> where(9);
  std::vector<AC::internal::Cone_surface_delaunay::Point_on_face> points;
  points.push_back(point_in_face(t, 0, 0.02, 0.02, where[0]));  // b: 0.4 from the tip
  points.push_back(point_in_face(t, 2, 0.25, 0.25, where[1]));  // a: 5 from the tip
  // near the base: on the top faces 9.5 from the tip, and on the bottom faces
  for(int i = 0; i < 3; ++i) points.push_back(point_in_face(t, 2 * i, 0.6, 0.35, where[std::size_t(2 + i)]));
  for(int i = 0; i < 3; ++i) points.push_back(point_in_face(t, 2 * i + 1, 0.3, 0.3, where[std::size_t(5 + i)]));
  points.push_back(point_in_face(t, 4, 0.45, 0.5, where[8]));
  AC::internal::Cone_surface_delaunay delaunay(t.faces, t.twin, t.layout, t.is_cone);
  const std::vector<std::array<std::size_t, 3>> tris = delaunay.triangulate(points);
  BOOST_TEST(delaunay.statistics().grown_fans >= 1u);  // the configuration above was met and mended
  BOOST_TEST(tris.size() == 2 * points.size() - 4);
  BOOST_TEST(closed_manifold_genus(points.size(), tris) == 0);
  std::size_t at_tip = 0;  // b has at least three neighbours
  for(const auto& f : tris) at_tip += f[0] == 0 || f[1] == 0 || f[2] == 0;
  BOOST_TEST(at_tip >= 3u);
  double volume = 0;
  for(const auto& f : tris) volume += where[f[0]].dot(where[f[1]].cross(where[f[2]])) / 6;
  BOOST_TEST(volume > 0);
}

// the angle of a triangle from its sides, also for needles and degenerate sides
BOOST_AUTO_TEST_CASE(triangle_angle_from_sides_is_accurate_for_needles)
{
  const double pi = 3.14159265358979323846;
  BOOST_TEST(std::abs(AC::internal::triangle_angle(1, 1, 1) - pi / 3) < 1e-15);
  BOOST_TEST(std::abs(AC::internal::triangle_angle(3, 4, 5) - pi / 2) < 1e-15);
  BOOST_TEST(std::abs(AC::internal::triangle_angle(4, 3, 5) - pi / 2) < 1e-15);
  // a needle: sides 1, 1 and 1e-9 (the law of cosines gives acos(1 - 5e-19) = 0)
  BOOST_TEST(std::abs(AC::internal::triangle_angle(1, 1, 1e-9) / (2 * std::asin(0.5e-9)) - 1) < 1e-12);
  // nearly flat the other way: sides 1, 1 and 2 - 1e-12, the angle opposite the long side near pi
  const double c = 2 - 1e-12;
  BOOST_TEST(std::abs(AC::internal::triangle_angle(1, 1, c) - 2 * std::asin(c / 2)) < 1e-9);
  BOOST_TEST(AC::internal::triangle_angle(1, 1, 3) == pi);  // c > a + b
  BOOST_TEST(AC::internal::triangle_angle(3, 1, 1) == 0);   // c < a - b
  BOOST_TEST(AC::internal::triangle_angle(1, 3, 1) == 0);
}

BOOST_AUTO_TEST_CASE(delaunay_on_a_cone_surface_refuses_what_it_cannot_triangulate)
{
  const Tetrahedron t = make_tetrahedron(false);
  std::vector<Eigen::Vector3d> where;
  auto points = random_points(t, 20, 5u, where);
  points[7] = points[3];  // two points at one place
  AC::internal::Cone_surface_delaunay delaunay(t.faces, t.twin, t.layout, t.is_cone);
  BOOST_CHECK_THROW(delaunay.triangulate(points), AC::Convergence_failure);
  points[7].face = 99;  // not a face
  BOOST_CHECK_THROW(delaunay.triangulate(points), AC::Convergence_failure);
  std::vector<int> open = t.twin;
  open[0] = -1;
  AC::internal::Cone_surface_delaunay not_closed(t.faces, open, t.layout, t.is_cone);
  BOOST_CHECK_THROW(not_closed.triangulate(random_points(t, 20, 5u, where)), AC::Invalid_input);
}

BOOST_AUTO_TEST_CASE(limb_body_remeshes_through_cones)
{
  // five limbs eight times longer than wide: the sphere shrinks each exponentially (test_sphere.cpp,
  // cone_metric); through cones every limb is meshed at the spacing asked for
  const AC::Input_surface s = limb_body::make_limb_body();
  for(std::size_t n : {std::size_t(400), std::size_t(1500)}) {
    AC::Remeshing_result r;
    const AC::Remeshed_surface out =
      AC::remesh(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n).parametric_domain(AC::Parametric_domain::CONE));
    BOOST_TEST_MESSAGE("limb body " << s.number_of_vertices() << " -> " << n << ": " << r.domain_diagnostics.summary << "; G_min "
                                    << r.quality.G_min << " G_avg " << r.quality.G_avg << " theta_min " << r.quality.theta_min
                                    << " Hausdorff " << r.hausdorff_distance_relative << ", " << r.total_seconds() << " s");
    BOOST_TEST(out.points.size() == n);
    BOOST_TEST(out.faces.size() == 2 * n - 4);
    BOOST_TEST(closed_manifold_genus(n, out.faces) == 0);
    BOOST_TEST(r.inverted_triangles == 0u);
    BOOST_TEST(r.domain_diagnostics.value("cones") >= 5);  // at least one per limb
    BOOST_TEST(r.domain_diagnostics.value("log_scale_factor_range") <= 2.0 + 1e-9);
    // the report's table of cones: each on the input, its angle within the range reported
    for(std::size_t c = 0; c < std::size_t(r.domain_diagnostics.value("cones")); ++c) {
      const Eigen::Vector3d x(r.domain_diagnostics.value("cone_table", 4 * c), r.domain_diagnostics.value("cone_table", 4 * c + 1),
                              r.domain_diagnostics.value("cone_table", 4 * c + 2));
      const double angle = r.domain_diagnostics.value("cone_table", 4 * c + 3);
      BOOST_TEST((s.project(x).position - x).norm() <= 1e-9 * s.bounding_box_diagonal());
      BOOST_TEST(angle >= r.domain_diagnostics.value("cone_angle_range", 0));
      BOOST_TEST(angle <= r.domain_diagnostics.value("cone_angle_range", 1));
    }
    BOOST_CHECK_THROW(r.domain_diagnostics.value("cone_table", 4 * std::size_t(r.domain_diagnostics.value("cones"))), AC::Invalid_input);
    // the surface optimisation runs by default in the cone domain (Cone_domain::optimizes_on_the_surface_by_default)
    BOOST_TEST(r.surface_optimization.ran);
    BOOST_TEST(r.quality.G_avg >= 0.87);      // measured 0.923 / 0.939 at 400 / 1500
    BOOST_TEST(r.quality.theta_min >= 18.0);  // measured 36.6 / 31.4 (23.7 / 24.9 before later changes)
    BOOST_TEST(r.hausdorff_distance_relative < (n < 1000 ? 0.05 : 0.02));
  }
}

BOOST_AUTO_TEST_CASE(the_cow_goes_to_cones_when_the_sphere_fails)
{
  // CGAL's cow (data/meshes/cow.off): its legs and tail are too long for the sphere in double precision
  const AC::Input_surface cow = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/cow.off");
  const std::size_t n = 2000;
  AC::Remeshing_result r;
  const AC::Remeshed_surface out =
    AC::remesh(cow, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n).feature_angle(180.0));
  BOOST_TEST_MESSAGE("cow -> " << n << ": " << r.domain_choice << "; " << r.domain_diagnostics.summary << "; G_avg " << r.quality.G_avg
                               << " theta_min " << r.quality.theta_min << " Hausdorff " << r.hausdorff_distance_relative << ", "
                               << r.total_seconds() << " s");
  BOOST_TEST(r.domain_choice.rfind("cones, because the sphere failed: ", 0) == 0u);
  // the sphere's failed run is counted in the total, apart from the stages of the cone run
  BOOST_TEST(r.discarded_seconds > 0);
  double stages = 0;
  for(double x : r.seconds) stages += x;
  // summed in another order than total_seconds() does: equal up to rounding, not bit for bit
  BOOST_TEST(std::abs(r.total_seconds() - (stages + r.discarded_seconds)) <= 1e-9 * (1.0 + r.total_seconds()));
  BOOST_TEST(out.points.size() == n);
  BOOST_TEST(closed_manifold_genus(n, out.faces) == 0);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.surface_optimization.ran);
  // the cones of negative curvature are fixed sites of the CVT (the dual needs a site on each) and no more
  // than vertices of the input after it: the surface optimisation moves them, and without features it
  // holds no vertex fixed
  BOOST_TEST(!out.released_vertices.empty());
  BOOST_TEST(out.released_vertices.size() == out.fixed_vertices);
  BOOST_TEST(r.surface_optimization.fixed_vertices == 0u);
  for(std::size_t v : out.released_vertices) {
    BOOST_TEST(v < out.fixed_vertices);
    BOOST_TEST((cow.project(out.points[v]).position - out.points[v]).norm() <= 1e-9 * cow.bounding_box_diagonal());
  }
  BOOST_TEST(r.quality.G_avg >= 0.90);      // measured 0.940 (an earlier version: 0.911 without the surface optimisation)
  BOOST_TEST(r.quality.theta_min >= 12.0);  // measured 35.0 (an earlier version: 11.9 without the surface optimisation)
  BOOST_TEST(r.hausdorff_distance_relative < 0.03);  // measured 0.0186 (the limb body at 1500: 0.0054)
}

// CGAL's camel (test/data/cgal) at 500 sites, seed 1: the sphere fails (its legs), and in the cone domain
// a chart expecting less than one site starts from a band three times the square root of its own area;
// 8 widenings by 1.6 did not reach the Voronoi cells around it and the remesh was refused ("the Voronoi
// cells of chart 7 are not complete within a band of width 0.0096 (too few sites for the surface)").
// The band now widens up to 24 times (build_band()'s bound on its copies stops it on a surface with
// really too few sites).
BOOST_AUTO_TEST_CASE(camel_at_500_sites_widens_the_bands_of_its_smallest_charts)
{
  const AC::Input_surface camel = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cgal/camel.off");
  const std::size_t n = 500;
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh(camel, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n).random_seed(1u));
  BOOST_TEST_MESSAGE("camel -> " << n << ": " << r.domain_choice << "; G_avg " << r.quality.G_avg << " theta_min " << r.quality.theta_min
                                 << " Hausdorff " << r.hausdorff_distance_relative);
  BOOST_TEST(r.domain_choice.rfind("cones, because the sphere failed: ", 0) == 0u, r.domain_choice);
  BOOST_TEST(out.points.size() == n);
  BOOST_TEST(closed_manifold_genus(n, out.faces) == 0);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.quality.G_avg >= 0.85);      // measured 0.894
  BOOST_TEST(r.quality.theta_min >= 12.0);  // measured 20.1
}

// CGAL's cactus (620 vertices, 31 crease curves, 47 corners; test/data/cgal) at 4000 vertices: the sphere's
// runs with crease sites fail (the sites on the creases of its arms make triangles too small on the sphere
// for double precision) and its run without them covered 1 % of the crease length. The automatic choice
// now also runs the cone domain, whose output follows the creases, and takes it (remesh.h,
// remesh_with_cones_if_it_fails(); measured: 100 % covered, 47 / 47 corners, G_avg 0.948, theta_min 31.0).
BOOST_AUTO_TEST_CASE(cactus_follows_its_creases_through_the_cones_where_the_sphere_cannot)
{
  const AC::Input_surface cactus = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cgal/cactus.off");
  const std::size_t n = 4000;
  AC::Remeshing_result r;
  const auto start = std::chrono::steady_clock::now();
  const AC::Remeshed_surface out = AC::remesh(cactus, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  BOOST_TEST_MESSAGE("cactus -> " << n << ": " << r.domain_choice << "; " << 100 * r.features.covered_share << " % covered, G_avg "
                                  << r.quality.G_avg << " theta_min " << r.quality.theta_min << "; " << r.total_seconds()
                                  << " s reported, " << wall << " s");
  BOOST_TEST((r.domain == AC::Parametric_domain::CONE));
  BOOST_TEST(r.domain_choice.rfind("cones, because the sphere kept the corners but not the creases: ", 0) == 0u, r.domain_choice);
  BOOST_TEST((r.crease_run == AC::Crease_run::REFINED || r.crease_run == AC::Crease_run::INPUT_VERTICES));
  BOOST_TEST(r.features.covered_share >= 0.99);
  BOOST_TEST(r.features.corners_kept == r.features.corners);
  BOOST_TEST(r.discarded_seconds > 0.0);  // the sphere's runs
  // the feature sizing of the cone run, with the curvature's sizes (Curvature_sizing::CONES), is the one
  // reported; each sizing's time counted once: the reported stages and runs thrown away are the call's time
  const AC::internal::Feature_sizing sizing = AC::internal::feature_sizing(
      cactus, AC::Uniform_metric(), AC::internal::Remeshing_options::from(AC::parameters::number_of_vertices(n)), true);
  BOOST_TEST(r.feature_sizing.applied == sizing.report.applied);
  BOOST_TEST(r.feature_sizing.narrow_points == sizing.report.narrow_points);
  BOOST_TEST(r.feature_sizing.scale_max == sizing.report.scale_max);
  BOOST_TEST(r.total_seconds() <= wall);
  BOOST_TEST(r.total_seconds() >= 0.9 * wall);
  BOOST_TEST(out.points.size() == n);
  BOOST_TEST(closed_manifold_genus(n, out.faces) == 0);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.quality.G_avg >= 0.90);      // measured 0.948
  BOOST_TEST(r.quality.theta_min >= 25.0);  // measured 31.0
  // at 2000 vertices the sphere follows the creases itself: no cone run
  AC::Remeshing_result r2;
  AC::remesh(cactus, AC::Uniform_metric(), r2, AC::parameters::number_of_vertices(std::size_t(2000)));
  BOOST_TEST((r2.domain == AC::Parametric_domain::SPHERE));
  BOOST_TEST(r2.domain_choice.empty());
  BOOST_TEST(r2.features.covered_share >= 0.99);
}

// CGAL's femur (genus 2, test/data/cgal): the hyperbolic disk cannot resolve its sites (the metric shrinks
// one end), so it goes to cones (108, up to 755 degrees). At 2000 sites one cone of 278 degrees lies on a
// part narrower than the sites' spacing, its link a b c c b: no site could be merged into it and the dual
// was refused ("1 cone ... cannot be merged"); at 1500 a cone merged into a site left two edges doubled
// and a loop. The dual now moves the nearest free site onto such a cone and triangulates again.
namespace {

// CGAL's femur (genus 2; test/data/cgal) and the curvature metric the corpus uses on it (stretch 5)
AC::Input_surface read_femur() { return AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cgal/femur.off"); }

AC::Curvature_metric stretch_5_curvature_metric(const AC::Input_surface& s)
{
  AC::Curvature_metric_options o;
  o.stretch_max = 5;
  return AC::Curvature_metric(s, o);
}

} // namespace

BOOST_AUTO_TEST_CASE(femur_goes_to_cones_with_free_sites_moved_onto_cones_at_its_thin_parts)
{
  const AC::Input_surface femur = read_femur();
  BOOST_REQUIRE(femur.genus() == 2);
  for(const std::size_t n : {std::size_t(1500), std::size_t(2000)}) {
    AC::Remeshing_result r;
    const AC::Remeshed_surface out =
      // seed 0: no such cone at 2000; without the curvature sizing (the default since stop 60), whose
      // refined tips give other cones, none of which needs a site moved onto it
      AC::remesh(femur, AC::Uniform_metric(), r,
                 AC::parameters::number_of_vertices(n).random_seed(1u).curvature_sizing(AC::Curvature_sizing::OFF));
    BOOST_TEST_MESSAGE("femur -> " << n << ": " << r.domain_diagnostics.summary << "; G_avg " << r.quality.G_avg << " theta_min "
                                   << r.quality.theta_min << " Hausdorff " << r.hausdorff_distance_relative);
    BOOST_TEST(r.domain_choice.rfind("cones, because the hyperbolic failed: ", 0) == 0u, r.domain_choice);
    BOOST_TEST(out.points.size() == n);
    BOOST_TEST(closed_manifold_genus(n, out.faces) == 2);
    BOOST_TEST(r.inverted_triangles == 0u);
    BOOST_REQUIRE(r.domain_diagnostics.has("dual_moved_sites"));  // the configurations above were met
    BOOST_TEST(r.domain_diagnostics.value("dual_moved_sites") >= 1.0);
    BOOST_TEST(r.domain_diagnostics.summary.find("moved onto") != std::string::npos);
    double off = 0;  // every vertex on the input, those moved onto cones too
    for(const auto& x : out.points) off = std::max(off, (femur.project(x).position - x).norm());
    BOOST_TEST(off <= 1e-9 * femur.bounding_box_diagonal());
    BOOST_TEST(r.quality.G_avg >= 0.90);      // measured 0.924 (1500), 0.939 (2000)
    BOOST_TEST(r.quality.theta_min >= 15.0);  // measured 23.3, 19.8
    BOOST_TEST(r.hausdorff_distance_relative < 0.03);
  }
}

// The femur with the curvature metric (stretch 5, 2000 vertices): the cone placement ended with 3
// triangles flat in the cone metric, each facing an edge whose flip would have doubled an edge around a
// thin handle (the angles facing it summed to pi + 2.5), and was refused; cheese (genus 133) the same
// with 14. cone_embedding() now solves it again with flips that may double an edge (a Delta-complex,
// Gillespie, Springborn and Crane 2021), and the metric it returns is flat, with the femur's total
// curvature at the cones.
BOOST_AUTO_TEST_CASE(cone_placement_that_ends_flat_is_solved_again_with_flips_that_double_edges)
{
  const AC::Input_surface femur = read_femur();
  const AC::Curvature_metric metric = stretch_5_curvature_metric(femur);
  const std::size_t n = 2000;
  AC::Intrinsic_triangulation itri(femur, AC::compute_metric_square_roots(femur, metric));
  AC::refine_background(itri, femur, metric, n);
  AC::adjust_edge_lengths(itri, femur);
  const AC::Cone_embedding emb = AC::Cone_domain::embed(itri, AC::parameters::number_of_vertices(n));
  BOOST_TEST_MESSAGE("femur, curvature metric: " << emb.cones.size() << " cones, range of u " << emb.u_range);
  BOOST_TEST(emb.double_edges);  // the first try ended flat
  BOOST_TEST(emb.u_range <= 4.0);
  // Gauss-Bonnet: the cones carry the curvature 2 pi chi = -4 pi of a genus-2 surface
  double curvature = 0;
  for(double a : emb.cone_angles) curvature += 2 * 3.14159265358979323846 - a;
  BOOST_TEST(std::abs(curvature + 4 * 3.14159265358979323846) < 1e-6);
  // no face flat in the atlas's layout
  std::size_t flat = 0;
  for(const auto& p : emb.corner_uv) {
    const Eigen::Vector2d a = p[1] - p[0], b = p[2] - p[0];
    flat += !(a.x() * b.y() - a.y() * b.x() > 0);
  }
  BOOST_TEST(flat == 0u);
}

// The femur with the curvature metric (stretch 5, 2000 vertices) through cones end to end: the dual was
// refused ("1 pairs of sites are joined twice"): a site of degree 6 whose star wraps a thin handle meets one
// neighbour twice, and no cone was merged into either site of the pair, so none was moved onto a cone. A
// cone merged into a neighbour of the pair now gets the nearest free site moved onto it. Since the cone
// domain's non-monotone line search (stop 63) this seed's sites end elsewhere and no site is moved (the
// move itself is tested on the isotropic femur above); the run stays as the femur's curvature regression.
BOOST_AUTO_TEST_CASE(femur_with_the_curvature_metric_remeshes_through_cones)
{
  const AC::Input_surface femur = read_femur();
  const AC::Curvature_metric metric = stretch_5_curvature_metric(femur);
  const std::size_t n = 2000;
  AC::Remeshing_result r;
  const AC::Remeshed_surface out =
    AC::remesh(femur, metric, r,
               AC::parameters::number_of_vertices(n).parametric_domain(AC::Parametric_domain::CONE).curvature_sizing(
                 AC::Curvature_sizing::OFF));  // the run this test is about: with the curvature sizing it fails and is run again without
  BOOST_TEST_MESSAGE("femur, curvature metric -> " << n << ": " << r.domain_diagnostics.summary << "; G_avg " << r.quality.G_avg
                                                   << " theta_min " << r.quality.theta_min << " Hausdorff " << r.hausdorff_distance_relative);
  BOOST_TEST(out.points.size() == n);
  BOOST_TEST(closed_manifold_genus(n, out.faces) == 2);
  BOOST_TEST(r.inverted_triangles == 0u);
  double off = 0;
  for(const auto& x : out.points) off = std::max(off, (femur.project(x).position - x).norm());
  BOOST_TEST(off <= 1e-9 * femur.bounding_box_diagonal());
  BOOST_TEST(r.quality.G_avg >= 0.86);      // measured 0.894 (the tool: 0.898)
  // measured 14.1 since stop 63 (22.9 before; the tool at seeds 0-3 gave 17.5 to 29.9 before and 18.9 to
  // 26.8 after: the femur's worst triangle moves with any change of the CVT's path)
  BOOST_TEST(r.quality.theta_min >= 12.0);
  BOOST_TEST(r.hausdorff_distance_relative < 0.03);
}

// With the cow's noisy creases kept (drop_ragged_creases(false): 276 corners as fixed sites) the runs
// with crease sites fail; the run that keeps only the corners as fixed sites stands (before stop 63 it
// failed too, with inverted triangles between fixed sites half an output edge apart, and the run without
// any feature site was kept: it was refused, exit 3, before that fallback existed); the report says why
// and still measures the input's features on the output. If a later change makes another run stand here,
// this test names it: update the expected run then. With the defaults the
// creases are ragged and left out before the runs: no run with feature sites is tried (only the sphere's
// attempt is thrown away).
BOOST_AUTO_TEST_CASE(the_cow_with_its_noisy_creases_remeshes_without_crease_sites_when_they_fail)
{
  const AC::Input_surface cow = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/cow.off");
  const std::size_t n = 2000;
  AC::Remeshing_result rd;
  const AC::Remeshed_surface plain = AC::remesh(cow, AC::Uniform_metric(), rd, AC::parameters::number_of_vertices(n));
  BOOST_TEST_MESSAGE("cow -> " << n << " with the defaults: " << rd.features.ragged_components_dropped << " ragged components left out; G_avg "
                               << rd.quality.G_avg << " theta_min " << rd.quality.theta_min << ", " << rd.total_seconds() << " s");
  BOOST_TEST(rd.features.rough_surface);
  BOOST_TEST(rd.features.corners == 0u);
  BOOST_TEST((rd.crease_run == AC::Crease_run::NONE));
  BOOST_TEST(plain.points.size() == n);
  BOOST_TEST(rd.inverted_triangles == 0u);
  BOOST_TEST(rd.quality.theta_min >= 25.0);  // measured 30.7
  // the feature sizing off: with it (the default since 2026-12-07) the cow's noisy creases close to each
  // other are refined and the first run with crease sites stands (measured: run "refined", G_avg 0.913,
  // theta_min 18.3), so the fallback this test is about is not reached; so with the curvature sizing
  // (stop 60: run "refined", theta_min 18.3 too)
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh(
    cow, AC::Uniform_metric(), r,
    AC::parameters::number_of_vertices(n).drop_ragged_creases(false).feature_sizing(false).curvature_sizing(AC::Curvature_sizing::OFF));
  BOOST_TEST_MESSAGE("cow -> " << n << " with the defaults: run " << AC::crease_run_name(r.crease_run) << "; corners not kept: "
                               << r.corners_not_kept << "; G_avg " << r.quality.G_avg << " theta_min " << r.quality.theta_min << ", "
                               << r.total_seconds() << " s of which " << r.discarded_seconds << " thrown away");
  // since the cone domain's non-monotone line search (stop 63) the run that keeps the corners but not the
  // creases stands (measured G_avg 0.922, theta_min 21.5), where every run with feature sites failed before
  BOOST_TEST((r.crease_run == AC::Crease_run::NOT_FOLLOWED));
  BOOST_TEST(!r.creases_not_followed.empty());
  // a failed run with crease sites had embedded this run's background, edge lengths and all: taken, not
  // solved again (internal/remesh/embedding_memo.h)
  BOOST_TEST(r.embedding_reused);
  BOOST_TEST(r.features.corners > 100u);  // the input's, measured on the output
  BOOST_TEST(r.discarded_seconds > 0);
  BOOST_TEST(out.points.size() == n);
  BOOST_TEST(closed_manifold_genus(n, out.faces) == 0);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.quality.G_avg >= 0.90);      // measured 0.922 (0.932 without feature sites, before stop 63)
  BOOST_TEST(r.quality.theta_min >= 15.0);  // measured 21.5 (31.9)
}

namespace {

// An open tube of radius 1 and length `length` along z: `around` vertices on each ring, `rings` + 1 rings,
// every other ring turned by half a step; genus 0 with two boundary loops (at z = 0 and z = length)
AC::Input_surface make_open_tube(double length, int around, int rings)
{
  std::vector<Eigen::Vector3d> points;
  for(int j = 0; j <= rings; ++j)
    for(int i = 0; i < around; ++i) {
      const double t = 2 * 3.14159265358979323846 * (i + 0.5 * (j % 2)) / around;
      points.emplace_back(std::cos(t), std::sin(t), length * j / rings);
    }
  std::vector<AC::Input_surface::Face> faces;
  for(int j = 0; j < rings; ++j)
    for(int i = 0; i < around; ++i) {
      const std::size_t a = std::size_t(j * around + i), b = std::size_t(j * around + (i + 1) % around);
      const std::size_t c = a + std::size_t(around), d = b + std::size_t(around);
      if(j % 2 == 0) {
        faces.push_back({{a, b, c}});
        faces.push_back({{b, d, c}});
      } else {
        faces.push_back({{a, b, d}});
        faces.push_back({{a, d, c}});
      }
    }
  return AC::Input_surface(std::move(points), std::move(faces));
}

using test::segment_distance;

// checks that the output keeps the tube's topology (genus 0, two loops) and that every output boundary
// vertex lies on an input loop; returns the number of output boundary vertices
std::size_t check_open_tube_output(const AC::Input_surface& tube, const AC::Remeshed_surface& out)
{
  std::vector<AC::Input_surface::Face> faces(out.faces.begin(), out.faces.end());
  const AC::Input_surface s(out.points, std::move(faces));
  BOOST_TEST(s.genus() == 0);
  BOOST_TEST(s.boundary_loops().size() == 2u);
  std::size_t on_loops = 0;
  for(const auto& loop : s.boundary_loops())
    for(std::size_t v : loop) {
      double best = 1e300;
      for(const auto& input_loop : tube.boundary_loops())
        for(std::size_t k = 0; k < input_loop.size(); ++k)
          best = std::min(best, segment_distance(s.points()[v], tube.points()[input_loop[k]],
                                                 tube.points()[input_loop[(k + 1) % input_loop.size()]]));
      BOOST_TEST(best <= 1e-9 * tube.bounding_box_diagonal());
      ++on_loops;
    }
  return on_loops;
}

} // namespace

BOOST_AUTO_TEST_CASE(a_long_open_tube_goes_to_cones_with_both_loops)
{
  // 40 times longer than its radius: through the sphere, with its two ends closed by patches, the middle
  // shrinks beyond double precision ("too small on the sphere"); the automatic choice then takes the
  // cone domain, with the same patches (no CVT density in them) and loop sites
  const AC::Input_surface tube = make_open_tube(40.0, 16, 160);
  BOOST_TEST_REQUIRE(tube.boundary_loops().size() == 2u);
  const std::size_t n = 400;
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = AC::remesh(tube, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n));
  BOOST_TEST_MESSAGE("open tube 40 -> " << n << ": " << r.domain_choice << "; " << r.domain_diagnostics.summary << "; G_avg "
                                        << r.quality.G_avg << " theta_min " << r.quality.theta_min << " Hausdorff "
                                        << r.hausdorff_distance_relative << ", " << r.total_seconds() << " s");
  BOOST_TEST((r.domain == AC::Parametric_domain::CONE));
  BOOST_TEST(r.domain_choice.rfind("cones, because the sphere failed: ", 0) == 0u);
  BOOST_TEST(out.points.size() == n);
  const std::size_t on_loops = check_open_tube_output(tube, out);
  BOOST_TEST(on_loops == r.boundary_sites);
  BOOST_TEST(on_loops >= 8u);  // measured 14 (7 a loop: the loop's length over the edge length)
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.patch_sites_moved == 0u);  // the patches hold no CVT density
  BOOST_TEST(r.quality.G_avg >= 0.90);      // measured 0.948
  BOOST_TEST(r.quality.theta_min >= 25.0);  // measured 36.1
  BOOST_TEST(r.hausdorff_distance_relative < 0.01);
}

// A free site that the CVT leaves on a loop's chain of sites blocks the chain's edge; the run is then made
// again from initial sites drawn with the next seed (Remeshing_result::reseeded says why). Measured on the
// tube above at 400 vertices: seeds 0 and 6 of 0..7 needed it when this was written, one of them at stop 64
// (the test counts them, it does not fix which). Every seed remeshes, and a reseeded output
// is the run of the next seed, bit for bit (its conformal embedding the first run's, since stop 64).
BOOST_AUTO_TEST_CASE(a_site_blocking_a_loop_chain_makes_the_run_start_again_with_the_next_seed)
{
  const AC::Input_surface tube = make_open_tube(40.0, 16, 160);
  const std::size_t n = 400;
  std::vector<AC::Remeshed_surface> outs;
  std::vector<std::string> reseeded;
  for(unsigned seed = 0; seed < 8; ++seed) {
    AC::Remeshing_result r;
    BOOST_TEST_CONTEXT("seed " << seed)
    {
      outs.push_back(AC::remesh(tube, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n).random_seed(seed)));
      BOOST_TEST(outs.back().points.size() == n);
      BOOST_TEST(check_open_tube_output(tube, outs.back()) == r.boundary_sites);
      BOOST_TEST(r.inverted_triangles == 0u);
      BOOST_TEST(r.quality.G_avg >= 0.90);
      reseeded.push_back(r.reseeded);
      if(!r.reseeded.empty()) {
        BOOST_TEST(r.reseeded.find("came too close to the loop") != std::string::npos);
        BOOST_TEST(r.discarded_seconds > 0.0);
      }
      // the second run's background is the first's: its embedding is taken, not solved again (embedding_memo.h)
      BOOST_TEST(r.embedding_reused == !r.reseeded.empty());
    }
  }
  std::size_t retries = 0;
  for(unsigned seed = 0; seed + 1 < 8; ++seed)
    if(!reseeded[seed].empty()) {
      ++retries;
      BOOST_TEST_CONTEXT("seed " << seed)
      {
        BOOST_TEST((outs[seed].points == outs[seed + 1].points));
        BOOST_TEST((outs[seed].faces == outs[seed + 1].faces));
      }
    }
  BOOST_TEST_MESSAGE("runs made again with the next seed: " << retries << " of 8");
}

BOOST_AUTO_TEST_CASE(cone_domain_takes_holes_through_patches)
{
  // on request, a short tube (which the sphere also takes) goes through cones with its holes patched
  const AC::Input_surface tube = make_open_tube(4.0, 16, 16);
  const std::size_t n = 200;
  AC::Remeshing_result r;
  const AC::Remeshed_surface out =
    AC::remesh(tube, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n).parametric_domain(AC::Parametric_domain::CONE));
  BOOST_TEST_MESSAGE("open tube 4 -> " << n << " through cones: " << r.domain_diagnostics.summary << "; G_avg " << r.quality.G_avg
                                       << " theta_min " << r.quality.theta_min);
  BOOST_TEST((r.domain == AC::Parametric_domain::CONE));
  BOOST_TEST(r.domain_choice.empty());
  BOOST_TEST(r.discarded_seconds == 0);  // no run thrown away
  BOOST_TEST(out.points.size() == n);
  BOOST_TEST(check_open_tube_output(tube, out) == r.boundary_sites);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.quality.G_avg >= 0.88);
  BOOST_TEST(r.quality.theta_min >= 25.0);
}

namespace {
// the area of the convex polygon `cell` (counterclockwise) intersected with the triangle `t` (counterclockwise):
// the cell clipped by the triangle's three half-planes (Sutherland and Hodgman)
double clipped_area(std::vector<Eigen::Vector2d> cell, const std::array<Eigen::Vector2d, 3>& t)
{
  for(int k = 0; k < 3 && !cell.empty(); ++k) {
    const Eigen::Vector2d a = t[std::size_t(k)], b = t[std::size_t((k + 1) % 3)];
    auto side = [&](const Eigen::Vector2d& p) { return (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x(); };
    std::vector<Eigen::Vector2d> kept;
    for(std::size_t i = 0; i < cell.size(); ++i) {
      const Eigen::Vector2d& p = cell[i];
      const Eigen::Vector2d& q = cell[(i + 1) % cell.size()];
      const double sp = side(p), sq = side(q);
      if(sp >= 0) kept.push_back(p);
      if((sp >= 0) != (sq >= 0)) kept.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    cell = kept;
  }
  double area = 0;
  for(std::size_t i = 0; i < cell.size(); ++i) {
    const Eigen::Vector2d& p = cell[i];
    const Eigen::Vector2d& q = cell[(i + 1) % cell.size()];
    area += 0.5 * (p.x() * q.y() - p.y() * q.x());
  }
  return area;
}
}  // namespace

// A chart's Delaunay triangulation kept from one integration to the next (internal::
// Cone_chart_kept_delaunay): after the points move a little and come in another order (sites that changed
// faces), the repaired triangulation has CGAL's neighbours; a site with one point more, or another band,
// is refused; a point thrown far away either folds the triangles (refused) or is repaired right.
BOOST_AUTO_TEST_CASE(a_chart_triangulation_repaired_by_flips_has_the_neighbours_of_cgals)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  AC::internal::Cone_chart_points cp;
  for(int i = 0; i < 300; ++i) {  // a jittered 20 x 15 grid: no sliver a small move folds
    cp.points.emplace_back((i % 20 + 0.2 + 0.6 * unit(rng)) / 20.0, (i / 20 + 0.2 + 0.6 * unit(rng)) / 15.0);
    cp.original.push_back(i < 250 ? i : i - 250);  // sites 0-49 have a second point (a copy)
  }
  for(int i = 0; i < 24; ++i) {  // sites 300-323 on a circle around them, which stay: the convex hull
    cp.points.push_back(Eigen::Vector2d(0.5, 0.5) + Eigen::Vector2d(std::cos(0.2618 * i), std::sin(0.2618 * i)));
    cp.original.push_back(300 + i);
  }
  cp.own = 250;
  cp.dt.build(cp.points);
  AC::internal::Cone_chart_kept_delaunay kept;
  kept.take(cp, 0.5);
  BOOST_TEST_REQUIRE(kept.flips.valid());
  // whether the kept triangulation's neighbours are those of CGAL's triangulation of the same points (as
  // sets of positions: the two may number the points differently)
  const auto same_as_cgal = [&kept](AC::internal::Cone_chart_points& q) {
    std::vector<int> start[2], nbr[2];
    kept.flips.neighbours(start[0], nbr[0]);
    q.dt.build(q.points);
    AC::internal::delaunay_neighbours(q.dt.dt, q.dt.handle, start[1], nbr[1]);
    std::vector<std::vector<Eigen::Vector2d>> sets[2];
    for(int k = 0; k < 2; ++k) {
      sets[k].assign(q.points.size(), {});
      for(std::size_t i = 0; i < q.points.size(); ++i) {
        for(int j = start[k][i]; j < start[k][i + 1]; ++j) sets[k][i].push_back(q.points[std::size_t(nbr[k][std::size_t(j)])]);
        std::sort(sets[k][i].begin(), sets[k][i].end(), [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
          return u.x() < v.x() || (u.x() == v.x() && u.y() < v.y());
        });
      }
    }
    return sets[0] == sets[1];
  };
  for(int round = 0; round < 5; ++round) {
    AC::internal::Cone_chart_points moved;
    std::vector<std::size_t> order(cp.points.size());
    for(std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin() + 250, order.begin() + 300, rng);  // the copies in another order
    std::swap(order[3], order[17]);  // two own sites too
    for(std::size_t i : order) {
      moved.points.push_back(cp.points[i] + (cp.original[i] < 300 ? 0.002 : 0.0) * Eigen::Vector2d(unit(rng) - 0.5, unit(rng) - 0.5));
      moved.original.push_back(cp.original[i]);
    }
    moved.own = 250;
    BOOST_TEST_REQUIRE(kept.repair(moved, 0.5));
    BOOST_TEST(same_as_cgal(moved));
    cp = moved;
  }
  BOOST_TEST(kept.repairs == 5u);
  BOOST_TEST(kept.builds == 1u);
  AC::internal::Cone_chart_points more = cp;
  more.points.emplace_back(0.5, 0.5);
  more.original.push_back(7);
  BOOST_TEST(!kept.repair(more, 0.5));  // site 7 has a point more: built anew
  BOOST_TEST(!kept.repair(cp, 0.8));    // another band
  AC::internal::Cone_chart_points far = cp;
  far.points[100] = Eigen::Vector2d(30.0, -20.0);
  if(kept.repair(far, 0.5)) {
    BOOST_TEST(same_as_cgal(far));
  } else {
    BOOST_TEST(!kept.flips.valid());
  }
}

// The distance to a chart on its grid (internal::Cone_chart_distance) bounds the exact distance from
// below and above, within the cell's diagonal where the grid knows it; far points get a lower bound only.
BOOST_AUTO_TEST_CASE(the_distance_to_a_chart_is_bounded_by_its_grid)
{
  // an L of six triangles
  const std::vector<Eigen::Vector2d> v = {{0, 0}, {3, 0}, {3, 1}, {0, 1}, {0, 3}, {1, 3}, {1, 1}};
  const std::vector<std::array<int, 3>> f = {{{0, 1, 2}}, {{0, 2, 6}}, {{0, 6, 3}}, {{3, 6, 5}}, {{3, 5, 4}}};
  std::vector<AC::internal::Background_triangle> tri;
  for(const auto& t : f)
    tri.push_back(AC::internal::make_background_triangle({{v[std::size_t(t[0])], v[std::size_t(t[1])], v[std::size_t(t[2])]}}, {{1.0, 1.0, 1.0}}, 0));
  const auto exact = [&](const Eigen::Vector2d& x) {
    // the L is [0,3]x[0,1] united with [0,1]x[0,3]
    const auto box = [&](double x0, double x1, double y0, double y1) {
      return Eigen::Vector2d(std::max({x0 - x.x(), 0.0, x.x() - x1}), std::max({y0 - x.y(), 0.0, x.y() - y1})).norm();
    };
    return std::min(box(0, 3, 0, 1), box(0, 1, 0, 3));
  };
  AC::internal::Cone_chart_distance dist;
  const double margin = 0.8;
  dist.build(tri, margin);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> coord(-3.0, 6.0);
  std::size_t known = 0;
  for(int i = 0; i < 20000; ++i) {
    const Eigen::Vector2d x(coord(rng), coord(rng));
    const double d = exact(x), lo = dist.lower(x), hi = dist.upper(x);
    BOOST_TEST_REQUIRE(lo <= d + 1e-12);
    BOOST_TEST_REQUIRE(hi >= d - 1e-12);
    if(d < 1.5 * margin) {
      BOOST_TEST_REQUIRE(std::isfinite(hi));  // within 1.5 margins the grid knows the distance
      BOOST_TEST_REQUIRE(hi - lo <= 2 * 0.7072 * margin / 8 + 1e-12);
      ++known;
    }
    if(d > 1.5 * margin + 0.2) BOOST_TEST_REQUIRE(lo >= 1.5 * margin);  // beyond, never taken for near
  }
  BOOST_TEST(known > 1000u);
}

// The cone domain's integrals do not depend on whether a chart's triangulation was repaired or built
// anew: sites moved after one integration give the same cells as the same sites in fresh traits.
BOOST_AUTO_TEST_CASE(cone_domain_integrals_are_the_same_from_repaired_triangulations)
{
  const AC::Input_surface surface = AC::make_ellipsoid(3);
  AC::Intrinsic_triangulation itri(surface, AC::compute_metric_square_roots(surface, AC::Uniform_metric()));
  AC::adjust_edge_lengths(itri, surface);
  const AC::Cone_embedding emb = AC::Cone_domain::embed(itri, AC::parameters::number_of_vertices(std::size_t(300)));
  AC::Cone_domain_traits kept(itri, emb, 1);
  std::vector<AC::Cone_domain_traits::Point> sites = kept.initial_sites(300, 5u);
  std::vector<AC::Cone_domain_traits::Cell> cells;
  kept.integrate(sites, cells);
  const double spacing = std::sqrt(kept.total_mass() / 300.0);
  for(int round = 0; round < 3; ++round) {
    for(std::size_t i = 0; i < sites.size(); ++i) sites[i] += 1e-3 * spacing * Eigen::Vector2d(std::cos(double(i + round)), std::sin(double(3 * i)));
    std::vector<AC::Cone_domain_traits::Cell> a, b;
    kept.integrate(sites, a);
    AC::Cone_domain_traits once(itri, emb, 1);
    once.initial_sites(300, 5u);
    once.integrate(sites, b);  // built anew in every chart
    BOOST_TEST(once.number_of_chart_triangulations().first == 0u);
    double mass = 0;
    for(std::size_t i = 0; i < sites.size(); ++i) {
      BOOST_TEST(a[i].mass == b[i].mass, boost::test_tools::tolerance(1e-9));
      BOOST_TEST((a[i].centroid - b[i].centroid).norm() <= 1e-9 * spacing);
      BOOST_TEST(a[i].energy == b[i].energy, boost::test_tools::tolerance(1e-7));
      mass += a[i].mass;
    }
    BOOST_TEST(mass == kept.total_mass(), boost::test_tools::tolerance(1e-9));
  }
  const auto n = kept.number_of_chart_triangulations();
  BOOST_TEST_MESSAGE("charts: " << kept.number_of_charts() << "; triangulations repaired " << n.first << ", built " << n.second);
  BOOST_TEST(n.first > n.second);  // small moves: most charts repaired
}

BOOST_AUTO_TEST_CASE(voronoi_cells_in_the_charts_tile_the_cone_surface_and_draw)
{
  // the pictures' cells (Cone_domain_traits::voronoi_cells(), IO::write_cone_cvt_svg()) on an ellipsoid
  // through cones: every site is an own point of exactly one chart and lies in its own cell, and the
  // cells clipped to the charts' triangles cover the flat surface once
  const AC::Input_surface surface = AC::make_ellipsoid(3);
  AC::Intrinsic_triangulation itri(surface, AC::compute_metric_square_roots(surface, AC::Uniform_metric()));
  AC::adjust_edge_lengths(itri, surface);
  const AC::Cone_embedding emb = AC::Cone_domain::embed(itri, AC::parameters::number_of_vertices(std::size_t(200)));
  BOOST_TEST_REQUIRE(emb.cones.size() >= 4u);
  AC::Cone_domain_traits traits(itri, emb, 1);
  std::vector<AC::Cone_domain_traits::Point> sites = traits.initial_sites(200, 3u);
  const std::vector<AC::Cone_domain_traits::Chart_cells> charts = traits.voronoi_cells(sites);
  BOOST_TEST(charts.size() == traits.number_of_charts());
  std::vector<int> owned(sites.size(), 0);
  double flat_area = 0, covered = 0;
  std::size_t cone_corners = 0;
  for(const auto& cc : charts) {
    BOOST_TEST(cc.points.size() == cc.sites.size());
    BOOST_TEST(cc.points.size() == cc.cells.size());
    BOOST_TEST(cc.cones.size() == cc.cone_angles.size());
    BOOST_TEST(!cc.outline.empty());  // no chart is the whole closed surface
    for(std::size_t e = 0; e < cc.own; ++e) {
      ++owned[cc.sites[e]];
      const std::vector<Eigen::Vector2d>& cell = cc.cells[e];
      BOOST_TEST_REQUIRE(cell.size() >= 3u);
      double inside = 1e300;  // the smallest signed distance of the point to the cell's edges (convex, counterclockwise)
      for(std::size_t k = 0; k < cell.size(); ++k) {
        const Eigen::Vector2d d = cell[(k + 1) % cell.size()] - cell[k], p = cc.points[e] - cell[k];
        inside = std::min(inside, (d.x() * p.y() - d.y() * p.x()) / d.norm());
      }
      BOOST_TEST(inside > 0);
    }
    for(const auto& t : cc.triangles) {
      flat_area += 0.5 * ((t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x());
      for(const auto& cell : cc.cells)
        if(cell.size() >= 3) covered += clipped_area(cell, t);
    }
    for(double a : cc.cone_angles)
      BOOST_TEST((std::find(emb.cone_angles.begin(), emb.cone_angles.end(), a) != emb.cone_angles.end()));
    cone_corners += cc.cones.size();
  }
  BOOST_TEST(std::count(owned.begin(), owned.end(), 1) == std::ptrdiff_t(sites.size()));
  BOOST_TEST(cone_corners >= emb.cones.size());  // each cone is a corner of some chart
  BOOST_TEST_MESSAGE("cone atlas: " << charts.size() << " charts, flat area " << flat_area << ", covered by the cells " << covered);
  BOOST_TEST(std::abs(covered - flat_area) <= 1e-9 * flat_area);

  // the picture, and its errors named
  const std::string dir = ANISO_CONFORMAL_TEST_OUTPUT_DIR;
  std::vector<double> values(sites.size());
  for(std::size_t i = 0; i < values.size(); ++i) values[i] = double(i % 7);
  AC::IO::write_cone_cvt_svg(dir + "/cone_cvt.svg", charts, values, "test");
  std::ifstream f(dir + "/cone_cvt.svg");
  const std::string svg((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  BOOST_TEST(svg.find("<svg") != std::string::npos);
  BOOST_TEST(svg.find("clip-path=\"url(#chart" + std::to_string(charts.size() - 1) + ")\"") != std::string::npos);
  BOOST_TEST(svg.find(std::to_string(sites.size()) + " sites in " + std::to_string(charts.size()) + " charts") != std::string::npos);
  BOOST_TEST(svg.find("</svg>") != std::string::npos);
  BOOST_CHECK_THROW(AC::IO::write_cone_cvt_svg(dir + "/bad.svg", charts, std::vector<double>(3, 0.0), ""), AC::Invalid_input);
  BOOST_CHECK_THROW(AC::IO::write_cone_cvt_svg(dir + "/bad.svg", std::vector<AC::Cone_domain_traits::Chart_cells>(), values, ""),
                    AC::Invalid_input);
  BOOST_CHECK_THROW(AC::IO::write_cone_cvt_svg("/nonexistent-dir/x.svg", charts, values, ""), AC::Invalid_input);
  auto broken = charts;
  broken.front().cells.pop_back();
  BOOST_CHECK_THROW(AC::IO::write_cone_cvt_svg(dir + "/bad.svg", broken, values, ""), AC::Invalid_input);
}

BOOST_AUTO_TEST_CASE(cone_domain_refuses_bad_input)
{
  // a disk: the plane takes it, the cone domain does not (it takes holes only through patches, and a disk
  // has no hole to patch)
  const AC::Input_surface square = AC::make_square_background(AC::Uniform_metric(), 300);
  AC::Remeshing_result r;
  BOOST_TEST(test::message_of([&] {
               AC::remesh(square, AC::Uniform_metric(), r,
                          AC::parameters::number_of_vertices(std::size_t(100)).parametric_domain(AC::Parametric_domain::CONE));
             }).find("does not fit the input") != std::string::npos);
  BOOST_CHECK_THROW(AC::remesh(square, AC::Uniform_metric(), r,
                               AC::parameters::number_of_vertices(std::size_t(100)).parametric_domain(AC::Parametric_domain::CONE)),
                    AC::Invalid_input);
  const AC::Input_surface sphere = AC::make_ellipsoid(3);
  BOOST_CHECK_THROW(AC::remesh(sphere, AC::Uniform_metric(), r,
                               AC::parameters::number_of_vertices(std::size_t(3)).parametric_domain(AC::Parametric_domain::CONE)),
                    AC::Invalid_input);
}

BOOST_AUTO_TEST_SUITE_END()
