// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Integration tests of the pipeline in the plane, remesh_in_domain<Planar_domain>() (what remesh() runs
// for a disk): the paper's planar figures against the quality bar, the BGL entry point on Surface_mesh
// and Polyhedron_3, determinism, disk surfaces, every error path of the entry point, and the
// ParametricDomain / ParametricDomainTraits concept checks of the planar models, images end to end (a CT
// crop and the whole slice), the bundled face mask and the graded square background. This module
// compiles the plane only; test_properties covers remesh()'s choice of the domain.

#ifndef ANISO_CONFORMAL_TEST_UNITY  // else compiled with other modules in one translation unit (CMakeLists.txt)
#define BOOST_TEST_MODULE Aniso_conformal_remesh
#endif
#include <boost/test/unit_test.hpp>

#include <Aniso_conformal/Analytic_metric_2.h>
#include <Aniso_conformal/Curvature_metric.h>
#include <Aniso_conformal/Image_metric.h>
#include <Aniso_conformal/Paper_metrics.h>
#include <Aniso_conformal/Tensor_field_metric.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/adjust_edge_lengths.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/refine_background.h>
#include <Aniso_conformal/IO/read_metric_file.h>
#include <Aniso_conformal/IO/read_image.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/IO/write_report.h>
#include <Aniso_conformal/make_image_background.h>
#include <Aniso_conformal/make_square_background.h>
#include <Aniso_conformal/Planar_domain.h>
#include <Aniso_conformal/remesh_in_domain.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/boost/graph/helpers.h>

#include "domain_concept_checks.h"
#include "mesh_checks.h"
#include "message_checks.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <utility>

BOOST_AUTO_TEST_SUITE(remesh)  // also a namespace: keeps the helpers apart from other modules in one unit

namespace AC = Aniso_conformal;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;

namespace {

// the pipeline in the plane: what remesh() runs for a disk
template <typename... Args>
auto remesh_plane(Args&&... args) -> decltype(AC::remesh_in_domain<AC::Planar_domain>(std::forward<Args>(args)...))
{
  return AC::remesh_in_domain<AC::Planar_domain>(std::forward<Args>(args)...);
}

struct Planar_checks {
  double area = 0;
  std::size_t corners_found = 0;
  std::size_t boundary_edges = 0;
  int euler = 0;
};

// Area, corners, boundary and Euler characteristic of a planar output.
Planar_checks check_planar(const AC::Remeshed_surface& out)
{
  const test::Mesh_counts m = test::count_mesh(out.points, out.faces);
  Planar_checks c;
  c.area = m.planar_area;
  c.boundary_edges = m.boundary_edges;
  c.euler = m.euler;
  for(const auto& p : out.points)
    for(const Eigen::Vector3d& corner : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0),
                                        Eigen::Vector3d(0, 1, 0)})
      if((p - corner).norm() < 1e-12) ++c.corners_found;
  return c;
}

template <typename Metric>
AC::Remeshed_surface remesh_square(const Metric& metric, std::size_t n, AC::Remeshing_result& r, unsigned seed = 0)
{
  const AC::Input_surface bg = AC::make_square_background(metric, n);
  return remesh_plane(bg, metric, r, AC::parameters::number_of_vertices(n).random_seed(seed));
}

template <typename Mesh>
void fill_mesh(const AC::Input_surface& s, Mesh& m)
{
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vd;
  std::vector<vd> v;
  for(const auto& p : s.points()) {
    v.push_back(add_vertex(m));
    put(get(CGAL::vertex_point, m), v.back(), K::Point_3(p.x(), p.y(), p.z()));
  }
  for(const auto& f : s.faces()) {
    std::array<vd, 3> t = {{v[f[0]], v[f[1]], v[f[2]]}};
    BOOST_REQUIRE(CGAL::Euler::add_face(t, m) != boost::graph_traits<Mesh>::null_face());
  }
}

const std::string data_dir = ANISO_CONFORMAL_DATA_DIR;

using test::contains;

struct Cancel_after {
  std::size_t calls = 0, limit = 3;
  void on_stage_started(AC::Stage) {}
  void on_stage_finished(AC::Stage, double) {}
  bool on_iteration(AC::Stage, std::size_t, std::size_t, double) { return ++calls < limit; }
};

} // namespace

// The quality bar on the unit square: exactly n vertices, no inverted triangle, the square
// covered exactly with its four corners, one disk, G_avg >= 0.85, theta_min >= 10, %<30 <= 5.
template <typename Metric>
void check_quality_bar(const char* name, const Metric& metric, std::size_t n)
{
  AC::Remeshing_result r;
  const auto out = remesh_square(metric, n, r);
  const Planar_checks c = check_planar(out);
  BOOST_TEST(out.points.size() == n);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(std::abs(c.area - 1.0) <= 1e-9);
  BOOST_TEST(c.corners_found == 4u);
  BOOST_TEST(c.euler == 1);
  BOOST_TEST(c.boundary_edges == r.boundary_sites);
  BOOST_TEST(r.quality.G_avg >= 0.85);
  BOOST_TEST(r.quality.theta_min >= 10.0);
  BOOST_TEST(r.quality.percent_below_30 <= 5.0);
  BOOST_TEST_MESSAGE(name << ": G_min " << r.quality.G_min << " G_avg " << r.quality.G_avg << " theta_min "
                          << r.quality.theta_min << " %<30 " << r.quality.percent_below_30);
}

BOOST_AUTO_TEST_CASE(fig6_meets_the_quality_bar)
{
  check_quality_bar("Fig. 6", AC::make_analytic_metric_2(AC::Fig6_metric()), 1000);
}

BOOST_AUTO_TEST_CASE(fig7_meets_the_quality_bar)
{
  check_quality_bar("Fig. 7", AC::make_analytic_metric_2(AC::Circular_metric()), 4000);
}

BOOST_AUTO_TEST_CASE(circular_field_beats_table2_with_the_surface_optimization)
{
  // issue 17's bar for the circular field: the paper's Table 2 figures (G_min 0.3771, G_avg 0.9068,
  // theta_min 22.57, theta_avg 52.48, %<30 0.0187). With Surface_optimization::ALWAYS, whose second phase
  // moves each vertex toward its ideal point in the metric and may lower a one-ring's G_min and smallest
  // angle down to 0.6 and 35 degrees (or the mesh's, if higher) to raise its G: measured at 4000 vertices G_min 0.535, G_avg 0.923,
  // theta_min 33.3, theta_avg 53.5, %<30 0 (first phase only: 0.481, 0.900, 30.2, 52.2, 0); at 2000
  // G_avg 0.884 after the dual -> 0.908 (first phase only: 0.887), theta_min 31.5
  const auto metric = AC::make_analytic_metric_2(AC::Circular_metric());
  for(const std::size_t n : {std::size_t(2000), std::size_t(4000)}) {
    AC::Remeshing_result r;
    const auto out = remesh_plane(AC::make_square_background(metric, n), metric, r,
                                  AC::parameters::number_of_vertices(n).surface_optimization(AC::Surface_optimization::ALWAYS));
    BOOST_TEST_MESSAGE("circular field, " << n << " vertices: G_min " << r.quality.G_min << " G_avg " << r.quality.G_avg
                                          << " theta_min " << r.quality.theta_min << " theta_avg " << r.quality.theta_avg
                                          << " %<30 " << r.quality.percent_below_30);
    BOOST_TEST(out.points.size() == n);
    BOOST_TEST(r.inverted_triangles == 0u);
    BOOST_TEST(check_planar(out).corners_found == 4u);
    // neither phase lowers G_min or theta_min nor adds a thin triangle to an output without inverted ones
    BOOST_TEST(r.surface_optimization.inverted_before == 0u);
    BOOST_TEST(r.quality.G_min >= r.surface_optimization.G_min_before);
    BOOST_TEST(r.quality.theta_min >= r.surface_optimization.theta_min_before);
    BOOST_TEST(r.quality.percent_below_30 <= r.surface_optimization.percent_below_30_before);
    BOOST_TEST(r.quality.G_avg >= r.surface_optimization.G_avg_before + 0.015);
    BOOST_TEST(r.quality.G_avg >= 0.90);
    BOOST_TEST(r.quality.theta_min >= 30.0);
    if(n == 4000) {
      BOOST_TEST(r.quality.G_min >= 0.3771);
      BOOST_TEST(r.quality.G_avg >= 0.9068 + 0.008);
      BOOST_TEST(r.quality.theta_avg >= 52.48 + 0.5);
      BOOST_TEST(r.quality.percent_below_30 <= 0.0187);
    }
  }
}

BOOST_AUTO_TEST_CASE(same_seed_same_output_bit_for_bit)
{
  const auto metric = AC::make_analytic_metric_2(AC::Fig6_metric());
  AC::Remeshing_result r1, r2, r3;
  const auto a = remesh_square(metric, 300, r1, 7), b = remesh_square(metric, 300, r2, 7), c = remesh_square(metric, 300, r3, 8);
  BOOST_REQUIRE(a.points.size() == b.points.size());
  bool same = a.faces == b.faces, differs = false;
  for(std::size_t i = 0; i < a.points.size(); ++i) {
    same = same && a.points[i] == b.points[i];
    differs = differs || a.points[i] != c.points[i];
  }
  BOOST_TEST(same);
  BOOST_TEST(differs);
}

typedef boost::mpl::list<CGAL::Surface_mesh<K::Point_3>, CGAL::Polyhedron_3<K>> Mesh_types;

BOOST_AUTO_TEST_CASE_TEMPLATE(bgl_entry_point_on_mesh_types, Mesh, Mesh_types)
{
  const auto metric = AC::make_analytic_metric_2(AC::Fig6_metric());
  const AC::Input_surface bg = AC::make_square_background(metric, 300);
  Mesh in, out;
  fill_mesh(bg, in);
  std::vector<K::Point_3> before;
  for(auto v : vertices(in)) before.push_back(get(CGAL::vertex_point, in, v));
  const AC::Remeshing_result r = remesh_plane(in, metric, out, AC::parameters::number_of_vertices(std::size_t(300)));
  BOOST_TEST(num_vertices(out) == 300u);
  BOOST_TEST(CGAL::is_valid_polygon_mesh(out));
  BOOST_TEST(CGAL::is_triangle_mesh(out));
  BOOST_TEST(int(num_vertices(out)) - int(num_edges(out)) + int(num_faces(out)) == 1);
  BOOST_TEST(r.quality.G_avg >= 0.85);
  std::size_t i = 0;  // the input is untouched
  bool unchanged = num_vertices(in) == before.size();
  for(auto v : vertices(in)) unchanged = unchanged && get(CGAL::vertex_point, in, v) == before[i++];
  BOOST_TEST(unchanged);
}

// A planar input clockwise seen from +z is remeshed as it is (the BGL entry point does not repair): the
// plane's layout keeps the input's orientation, so the output is clockwise too, with no triangle judged
// inverted (each is judged against the side the input faces), and the square is covered exactly.
BOOST_AUTO_TEST_CASE(clockwise_planar_input_is_remeshed_as_it_is)
{
  const AC::Input_surface bg = AC::make_square_background(AC::Uniform_metric(), 200);
  CGAL::Surface_mesh<K::Point_3> in, out;
  fill_mesh(bg, in);
  CGAL::Polygon_mesh_processing::reverse_face_orientations(in);
  const AC::Remeshing_result r = remesh_plane(in, AC::Uniform_metric(), out, AC::parameters::number_of_vertices(std::size_t(200)));
  BOOST_TEST(num_vertices(out) == 200u);
  BOOST_TEST(r.inverted_triangles == 0u);
  double area2 = 0;  // twice the signed area seen from +z
  for(auto f : faces(out)) {
    std::vector<K::Point_3> p;
    for(auto v : vertices_around_face(halfedge(f, out), out)) p.push_back(out.point(v));
    area2 += (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[1].y() - p[0].y()) * (p[2].x() - p[0].x());
  }
  BOOST_TEST(std::abs(area2 / 2 + 1.0) <= 1e-9);  // clockwise: the unit square's area, negative
  BOOST_TEST(r.quality.G_avg >= 0.85);
}

BOOST_AUTO_TEST_CASE_TEMPLATE(cancelling_visitor_leaves_output_unchanged, Mesh, Mesh_types)
{
  const AC::Input_surface bg = AC::make_square_background(AC::Uniform_metric(), 100);
  Mesh in, out;
  fill_mesh(bg, in);
  fill_mesh(bg, out);
  const std::size_t nv = num_vertices(out);
  Cancel_after cancel;
  BOOST_CHECK_THROW(remesh_plane(in, AC::Uniform_metric(), out,
                               AC::parameters::number_of_vertices(std::size_t(100)).visitor(std::ref(cancel))),
                    AC::Cancelled);
  BOOST_TEST(num_vertices(out) == nv);
  BOOST_TEST(cancel.calls == cancel.limit);
}

BOOST_AUTO_TEST_CASE(disk_surface_keeps_boundary_and_corners)
{
  // a curved square patch z = 0.3 (x^2 - y^2) over [-1,1]^2: four corners, one boundary loop
  const int g = 31;
  std::vector<Eigen::Vector3d> pts;
  std::vector<AC::Input_surface::Face> faces;
  for(int j = 0; j < g; ++j)
    for(int i = 0; i < g; ++i) {
      const double x = -1 + 2.0 * i / (g - 1), y = -1 + 2.0 * j / (g - 1);
      pts.emplace_back(x, y, 0.3 * (x * x - y * y));
    }
  for(int j = 0; j + 1 < g; ++j)
    for(int i = 0; i + 1 < g; ++i) {
      const std::size_t a = j * g + i, b = a + 1, c = a + g + 1, d = a + g;
      faces.push_back({{a, b, c}});
      faces.push_back({{a, c, d}});
    }
  const AC::Input_surface s(pts, faces);
  AC::Remeshing_result r;
  const auto out = remesh_plane(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(200)));
  BOOST_TEST(out.points.size() == 200u);
  BOOST_TEST(r.corners == 4u);
  BOOST_TEST(r.inverted_triangles == 0u);
  std::size_t corners = 0;
  for(const auto& p : out.points)
    for(std::size_t v : {std::size_t(0), std::size_t(g - 1), std::size_t(g * g - 1), std::size_t(g * (g - 1))})
      if((p - pts[v]).norm() < 1e-12) ++corners;
  BOOST_TEST(corners == 4u);
  // boundary vertices of the output lie on the input boundary (|x| = 1 or |y| = 1)
  const std::set<std::size_t> boundary = test::count_mesh(out.points, out.faces).boundary_vertices;
  BOOST_TEST(boundary.size() == r.boundary_sites);
  for(std::size_t v : boundary) {
    const Eigen::Vector3d& p = out.points[v];
    BOOST_TEST((std::abs(std::abs(p.x()) - 1) < 1e-12 || std::abs(std::abs(p.y()) - 1) < 1e-12));
  }
  // every vertex is on the surface
  for(const auto& p : out.points) BOOST_TEST(std::abs(p.z() - 0.3 * (p.x() * p.x() - p.y() * p.y())) < 2e-3);
  BOOST_TEST(r.quality.G_avg >= 0.85);
}

BOOST_AUTO_TEST_CASE(disks_whose_paper_layout_overlaps_remesh)
{
  // Before: "dual mesh: the boundary polygon of the sites intersects itself". With u = 0 on the boundary
  // the swirl bends the L's boundary across itself, and the slit's two sides touch; the default
  // (Planar_boundary::AUTOMATIC) then lays out the input's outline (made convex for the slit).
  const std::string cases = std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cases/";
  struct Case {
    std::string mesh, metric;
    std::size_t n;
    bool convex;
  };
  for(const Case& c : {Case{"lshape8.off", "lshape8_swirl3.metric", 300, false}, Case{"annulus_slit_ccw.off", "", 150, true}}) {
    BOOST_TEST_CONTEXT(c.mesh)
    {
      const AC::Input_surface s = AC::IO::read_triangle_mesh(cases + c.mesh);
      AC::Remeshing_result r;
      AC::Remeshed_surface out;
      if(c.metric.empty())
        out = remesh_plane(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(c.n));
      else
        out = remesh_plane(s, AC::IO::read_metric_file(cases + c.metric, s.number_of_vertices()), r,
                           AC::parameters::number_of_vertices(c.n));
      BOOST_TEST(out.points.size() == c.n);
      BOOST_TEST(r.inverted_triangles == 0u);
      BOOST_TEST(r.quality.G_avg > 0.85);
      BOOST_TEST(r.quality.theta_min > 15.0);
      const test::Mesh_counts m = test::count_mesh(out.points, out.faces);
      BOOST_TEST(m.euler == 1);  // still a disk
      BOOST_TEST(r.domain_diagnostics.value("boundary_keeps_shape") == 1.0);
      BOOST_TEST(r.domain_diagnostics.value("convex_boundary") == (c.convex ? 1.0 : 0.0));
      // every boundary vertex of the output lies on the input's boundary (its edges' segments)
      std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
      for(const auto& loop : s.boundary_loops())
        for(std::size_t i = 0; i < loop.size(); ++i)
          segments.emplace_back(s.points()[loop[i]], s.points()[loop[(i + 1) % loop.size()]]);
      for(std::size_t v : m.boundary_vertices) {
        double d = std::numeric_limits<double>::infinity();
        for(const auto& e : segments) {
          const Eigen::Vector3d ab = e.second - e.first;
          const double t = std::clamp((out.points[v] - e.first).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
          d = std::min(d, (out.points[v] - (e.first + t * ab)).norm());
        }
        BOOST_TEST(d < 1e-9);
      }
      // asking for the paper's map alone is refused, with a typed exception naming the alternative
      if(c.convex) {
        bool refused = false;
        try {
          remesh_plane(s, AC::Uniform_metric(), r,
                       AC::parameters::number_of_vertices(c.n).planar_boundary(AC::Planar_boundary::KEEP_LENGTHS));
        } catch(const AC::Remeshing_failure& e) {
          refused = std::string(e.what()).find("KEEP_SHAPE") != std::string::npos;
        }
        BOOST_TEST(refused);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(planar_boundary_reaches_the_embedding)
{
  // the named parameter must survive remesh_in_domain()'s canonical parameters: the same square with
  // the outline kept, then with the lengths kept
  AC::Remeshing_result r;
  const auto metric = AC::make_analytic_metric_2(AC::Fig6_metric());
  const auto sq = AC::make_square_background(metric, 400);
  remesh_plane(sq, metric, r, AC::parameters::number_of_vertices(std::size_t(150)).planar_boundary(AC::Planar_boundary::KEEP_SHAPE));
  BOOST_TEST(r.domain_diagnostics.value("boundary_keeps_shape") == 1.0);
  remesh_plane(sq, metric, r, AC::parameters::number_of_vertices(std::size_t(150)));
  BOOST_TEST(r.domain_diagnostics.value("boundary_keeps_shape") == 0.0);  // AUTOMATIC: u = 0 is embedded here
}

BOOST_AUTO_TEST_CASE(errors_name_the_problem)
{
  const AC::Input_surface square = AC::make_square_background(AC::Uniform_metric(), 50);
  AC::Remeshing_result r;
  auto message_of = [&](auto&& f) -> std::string {
    try { f(); } catch(const AC::Error& e) { return e.what(); }
    return "(no exception)";
  };
  // vertex counts
  BOOST_TEST(message_of([&] { remesh_plane(square, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(2))); })
               .find("at least 3") != std::string::npos);
  BOOST_TEST(message_of([&] { remesh_plane(square, AC::Uniform_metric(), r, AC::parameters::random_seed(1u)); })
               .find("number of output vertices") != std::string::npos);
  // a closed surface (octahedron) does not fit the plane
  const AC::Input_surface octa({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                               {{{0, 2, 4}}, {{2, 1, 4}}, {{1, 3, 4}}, {{3, 0, 4}}, {{2, 0, 5}}, {{1, 2, 5}}, {{3, 1, 5}}, {{0, 3, 5}}});
  BOOST_TEST(message_of([&] {
               remesh_plane(octa, AC::Uniform_metric(), r,
                          AC::parameters::number_of_vertices(std::size_t(4)).parametric_domain(AC::Parametric_domain::PLANE));
             }).find("closed surface of genus 0") != std::string::npos);
  // metric problems name the vertex
  std::vector<Eigen::Matrix3d> tensors(square.number_of_vertices(), Eigen::Matrix3d::Identity());
  tensors[5](0, 0) = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(message_of([&] {
               remesh_plane(square, AC::Tensor_field_metric(tensors), r, AC::parameters::number_of_vertices(std::size_t(20)));
             }).find("vertex 5") != std::string::npos);
  tensors[5] = Eigen::Matrix3d::Identity();
  tensors[7] = Eigen::Vector3d(1, -1, 0).asDiagonal();
  BOOST_TEST(message_of([&] {
               remesh_plane(square, AC::Tensor_field_metric(tensors), r, AC::parameters::number_of_vertices(std::size_t(20)));
             }).find("vertex 7: the tensor is not positive definite") != std::string::npos);
  tensors.pop_back();
  tensors[7] = Eigen::Matrix3d::Identity();
  BOOST_TEST(message_of([&] {
               remesh_plane(square, AC::Tensor_field_metric(tensors), r, AC::parameters::number_of_vertices(std::size_t(20)));
             }).find("tensor field has") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(planar_domain_models_its_concepts)
{
  const AC::Input_surface square = AC::make_square_background(AC::Uniform_metric(), 300);
  const AC::Input_surface octa({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                               {{{0, 2, 4}}, {{2, 1, 4}}, {{1, 3, 4}}, {{3, 0, 4}}, {{2, 0, 5}}, {{1, 2, 5}}, {{3, 1, 5}}, {{0, 3, 5}}});
  test::check_domain_concept<AC::Planar_domain>(square, octa, 200);
}

BOOST_AUTO_TEST_CASE(lloyd_also_works)
{
  const auto metric = AC::make_analytic_metric_2(AC::Fig6_metric());
  const AC::Input_surface bg = AC::make_square_background(metric, 300);
  AC::Remeshing_result r;
  const auto out = remesh_plane(bg, metric, r,
                              AC::parameters::number_of_vertices(std::size_t(300)).cvt_method(AC::Cvt_method::LLOYD));
  BOOST_TEST(out.points.size() == 300u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.quality.G_avg >= 0.85);
  for(std::size_t i = 1; i < r.cvt.energy.size(); ++i) BOOST_TEST(r.cvt.energy[i] <= r.cvt.energy[i - 1] * (1 + 1e-12));
}

// ------------------------------------------------ images, the bundled face mask, square backgrounds

BOOST_AUTO_TEST_CASE(bundled_face_mask_remeshes_as_a_disk)
{
  // nefertiti.off: a 299-vertex face scan of disk topology, with a curvature metric
  const AC::Input_surface s = AC::IO::read_triangle_mesh(data_dir + "/meshes/nefertiti.off");
  BOOST_REQUIRE(s.is_disk());
  AC::Curvature_metric_options o;
  o.stretch_max = 4;
  const AC::Curvature_metric metric(s, o);
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = remesh_plane(s, metric, r, AC::parameters::number_of_vertices(std::size_t(250)));
  BOOST_TEST(out.points.size() == 250u);
  BOOST_TEST(r.inverted_triangles == 0u);
  // one disk: Euler characteristic 1, one boundary loop made of the boundary sites
  const test::Mesh_counts m = test::count_mesh(out.points, out.faces);
  BOOST_TEST(m.euler == 1);
  BOOST_TEST(m.boundary_edges == r.boundary_sites);
  // every output vertex lies on the input: its surface point reproduces it
  for(std::size_t i = 0; i < out.points.size(); ++i) {
    const AC::Surface_point& sp = out.surface_points[i];
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for(int k = 0; k < 3; ++k) p += sp.barycentric[k] * s.points()[sp.vertices[k]];
    BOOST_TEST((p - out.points[i]).norm() < 1e-9);
  }
  BOOST_TEST(r.quality.G_avg > 0.75);
}


BOOST_AUTO_TEST_CASE(image_pipeline_end_to_end)
{
  // a small crop of the CT image remeshes with its rectangle kept
  const AC::IO::Image ct = AC::IO::read_image(data_dir + "/images/ct_head_211.png");
  AC::IO::Image crop;
  crop.width = 60;
  crop.height = 50;
  crop.channels = 1;
  for(int y = 0; y < crop.height; ++y)
    for(int x = 0; x < crop.width; ++x) crop.data.push_back(ct.at(x + 80, y + 80, 0));
  const AC::Image_metric metric(crop, 0.5);
  const AC::Input_surface bg = AC::make_image_background(crop);
  AC::Remeshing_result r;
  const auto out = remesh_plane(bg, metric, r, AC::parameters::number_of_vertices(std::size_t(400)));
  BOOST_TEST(out.points.size() == 400u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.corners == 4u);
  BOOST_TEST(std::abs(test::count_mesh(out.points, out.faces).planar_area - 49.0 / 59.0) < 1e-9);
  BOOST_TEST(r.quality.G_avg > 0.75);

  // the report of this run: its counts (the writer's own checks, on a result filled by hand, are in test_io)
  const nlohmann::json j = AC::IO::report_json(r);
  BOOST_TEST(j.at("domain") == "plane");
  BOOST_TEST(j.at("input").at("vertices") == 3000);
  BOOST_TEST(j.at("output").at("vertices") == 400);
  BOOST_TEST(j.at("output").at("corners") == 4);
  BOOST_TEST(j.at("output").at("boundary_vertices") == r.boundary_sites);
  BOOST_TEST(j.at("cvt").at("iterations") == r.cvt.iterations);
}

BOOST_AUTO_TEST_CASE(high_contrast_image_needs_repairs_and_intrinsic_flips)
{
  // the whole CT slice: splits stall at the skull's edges (local length repair), the embedding needs
  // intrinsic Delaunay flips, and the layout's bulging border must not leave flat boundary ears
  const AC::IO::Image ct = AC::IO::read_image(data_dir + "/images/ct_head_211.png");
  const AC::Image_metric metric(ct, 0.2);
  AC::Remeshing_result r;
  const auto out = remesh_plane(AC::make_image_background(ct), metric, r, AC::parameters::number_of_vertices(std::size_t(1500)));
  BOOST_TEST(out.points.size() == 1500u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.conformal_flips > 0u);
  BOOST_TEST(r.quality.theta_min > 5.0);
  BOOST_TEST(r.quality.G_avg > 0.8);

  // at the paper's s = 0.5: the dual mesh has inverted triangles (30 at 3000 vertices), which the surface optimisation
  // repairs (before it, a refusal); the output is valid, though its smallest angle is still far below the
  // issue's bar of 20 degrees (4.4 measured)
  const auto strong = remesh_plane(AC::make_image_background(ct), AC::Image_metric(ct, 0.5), r,
                                   AC::parameters::number_of_vertices(std::size_t(3000)));
  BOOST_TEST(strong.points.size() == 3000u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.surface_optimization.ran);
  BOOST_TEST(r.surface_optimization.inverted_before > 0u);
  BOOST_TEST(r.surface_optimization.inverted_after == 0u);
  BOOST_TEST(r.quality.theta_min > 0.0);
  BOOST_TEST(r.quality.G_avg > 0.7);
}


BOOST_AUTO_TEST_CASE(default_surface_optimization_lifts_thin_triangles)
{
  // The dual of the L-shaped plate under its swirling field, 150 vertices, of a CVT stopped after 5
  // iterations has triangles below 30 degrees (24.2 measured) and none inverted: the default REPAIR runs
  // the surface optimisation on it (on a planar input as ALWAYS, since 2026-12-06), whose max-min angle
  // pass lifts them (30.9 measured with REPAIR's first phase alone) without lowering G_min or G_avg. (After 100 iterations the dual alone reaches 37.4 degrees since the initial sites
  // follow the optimal density of sites; with sites drawn by rho it had 23.3.)
  const std::string cases = std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cases/";
  const AC::Input_surface s = AC::IO::read_triangle_mesh(cases + "lshape8.off");
  const auto metric = AC::IO::read_metric_file(cases + "lshape8_swirl3.metric", s.number_of_vertices());
  AC::Remeshing_result off, r;
  const auto dual = remesh_plane(s, metric, off, AC::parameters::number_of_vertices(std::size_t(150)).number_of_iterations(5u)
                                                   .surface_optimization(AC::Surface_optimization::OFF));
  const auto out = remesh_plane(s, metric, r, AC::parameters::number_of_vertices(std::size_t(150)).number_of_iterations(5u));
  BOOST_TEST(dual.points.size() == 150u);
  BOOST_TEST(out.points.size() == 150u);
  BOOST_TEST(!off.surface_optimization.ran);
  BOOST_TEST(off.quality.theta_min < 30.0);  // what makes REPAIR run
  BOOST_TEST(off.inverted_triangles == 0u);
  BOOST_TEST(r.surface_optimization.ran);
  BOOST_TEST(r.surface_optimization.inverted_before == 0u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.quality.theta_min >= off.quality.theta_min + 5.0);
  BOOST_TEST(r.quality.G_min >= off.quality.G_min);
  BOOST_TEST(r.quality.G_avg >= off.quality.G_avg - 1e-9);
  BOOST_TEST(r.quality.percent_below_30 <= off.quality.percent_below_30);
  BOOST_TEST(test::count_mesh(out.points, out.faces).euler == 1);
  // the stage's figures after it, as reported, are those of the output's quality
  BOOST_TEST(std::abs(r.surface_optimization.theta_min_after - r.quality.theta_min) < 1e-9);
}

BOOST_AUTO_TEST_CASE(metric_delaunay_flip_cycles_stop_where_they_happen)
{
  // stage 2 on the whole CT slice at s = 0.2, refined for 3000 vertices: the metric-Delaunay test (paper Fig. 3) cycles on a few
  // quads across the skull's edges, where the metric changes by orders of magnitude between neighbours.
  // Before the per-vertex-pair bound, one cycle spent the budget of the whole first pass (50 flips per
  // edge: 6.8 million flips, 4.6 s, `flip_budget_hits` 1) and left the other edges unflipped; now an
  // edge whose ends were joined and flipped apart twice is kept (measured: 26163 flips, 1 refused)
  const AC::IO::Image ct = AC::IO::read_image(data_dir + "/images/ct_head_211.png");
  const AC::Input_surface bg = AC::make_image_background(ct);
  const AC::Image_metric metric(ct, 0.2);
  AC::Intrinsic_triangulation itri(bg, AC::compute_metric_square_roots(bg, metric));
  AC::refine_background(itri, bg, metric, 3000);  // as remesh() does for 3000 vertices
  const AC::Edge_adjustment_report r = AC::adjust_edge_lengths(itri, bg);
  BOOST_TEST(r.flip_budget_hits == 0u);
  BOOST_TEST(r.cycling_flips_refused >= 1u);
  BOOST_TEST(r.flips < 200000u);
  BOOST_TEST(AC::internal::count_invalid_triangles(itri) == 0u);
  itri.validate(true);
}


BOOST_AUTO_TEST_CASE(colour_image_reaches_the_angle_bar_with_the_surface_optimization)
{
  // Fig. 8 (issue 17 item 4, bar theta_min >= 20 degrees, %<30 <= 0.5): the dual mesh's thin triangles
  // sit across colour edges (theta_min 1.7 degrees); Surface_optimization::ALWAYS, whose max-min angle
  // pass then runs on every output, lifts them, and its second phase (vertices toward their ideal point in
  // the metric) raises G: measured theta_min 30.9, %<30 0, G_avg 0.909 (first phase only: 30.2, 0, 0.879;
  // without the angle pass everywhere: 24.1, 0.19). Since the initial sites follow the optimal density of
  // sites, the dual's smallest angle is 9.5 degrees (1.7 before).
  const AC::IO::Image photo = AC::IO::read_image(data_dir + "/images/photo_chelsea_323.png");
  AC::Remeshing_result r;
  const auto out = remesh_plane(AC::make_image_background(photo), AC::Image_metric(photo, 0.1), r,
                                AC::parameters::number_of_vertices(std::size_t(3000))
                                  .surface_optimization(AC::Surface_optimization::ALWAYS));
  BOOST_TEST(out.points.size() == 3000u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.surface_optimization.ran);
  BOOST_TEST(r.surface_optimization.theta_min_before < 20.0);
  BOOST_TEST(r.quality.theta_min > 26.0);
  BOOST_TEST(r.quality.percent_below_30 < 0.1);
  BOOST_TEST(r.quality.G_avg > 0.895);
}


BOOST_AUTO_TEST_CASE(square_background_resolves_the_metric)
{
  const auto metric = AC::make_analytic_metric_2(AC::Fig6_metric());
  const AC::Input_surface bg = AC::make_square_background(metric, 1000);
  BOOST_TEST(bg.is_disk());
  BOOST_TEST(bg.number_of_vertices() > 3000u);  // paper: 5112
  BOOST_TEST(bg.number_of_vertices() < 8000u);
  BOOST_TEST(std::abs(test::count_mesh(bg.points(), bg.faces()).planar_area - 1) < 1e-12);
  // graded like the metric: denser near the origin corner, where the metric is largest
  std::size_t near = 0, far = 0;
  for(const auto& p : bg.points()) {
    if(p.x() < 0.25 && p.y() < 0.25) ++near;
    if(p.x() > 0.75 && p.y() > 0.75) ++far;
  }
  BOOST_TEST(near > 10 * far);
  BOOST_TEST(AC::make_square_background(AC::Uniform_metric(), 100, 2000).number_of_vertices() >= 2000u);
  BOOST_TEST(contains(test::message_of([] { AC::make_square_background(AC::Uniform_metric(), 3); }), "at least 4 output vertices"));
  BOOST_TEST(contains(test::message_of([] {
                        AC::make_square_background(AC::make_analytic_metric_2([](double, double) {
                                                     return Eigen::Matrix2d(Eigen::Matrix2d::Identity() * std::nan(""));
                                                   }),
                                                   100);
                      }),
                      "not finite and positive definite"));
}

BOOST_AUTO_TEST_SUITE_END()  // remesh
