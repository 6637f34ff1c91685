// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tests of the input/output module: mesh, metric-file, feature-file and image readers with their error
// messages and the fuzzers' regressions, the image metric and the image background, the Input_surface
// validation, and the JSON report and SVG writers. It compiles no remesher (the pipeline runs on images,
// the bundled face mask and square backgrounds are in test_remesh): CI builds and runs it under ASan and
// UBSan (./test.sh --sanitize-subset), where it must stay quick.

#define BOOST_TEST_MODULE Aniso_conformal_io
#include <boost/test/unit_test.hpp>

#include <Aniso_conformal/IO/read_feature_file.h>
#include <Aniso_conformal/IO/read_image.h>
#include <Aniso_conformal/IO/read_metric_file.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/IO/write_report.h>
#include <Aniso_conformal/IO/write_svg.h>
#include <Aniso_conformal/mesh_quality.h>
#include <Aniso_conformal/Image_metric.h>
#include <Aniso_conformal/make_image_background.h>

#include "mesh_checks.h"
#include "message_checks.h"

#include <nlohmann/json.hpp>
#include <png.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <utility>

namespace AC = Aniso_conformal;

namespace {

const std::string out_dir = ANISO_CONFORMAL_TEST_OUTPUT_DIR;
const std::string data_dir = ANISO_CONFORMAL_DATA_DIR;

std::string write_file(const std::string& name, const std::string& content)
{
  const std::string path = out_dir + "/" + name;
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

using test::message_of;

// the message of reading a mesh file `name` holding `content`
std::string mesh_file_error(const std::string& name, const std::string& content)
{
  return message_of([&] { AC::IO::read_triangle_mesh(write_file(name, content)); });
}

using test::contains;

const std::string tetra_off = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";

} // namespace

// ------------------------------------------------------------------------------- meshes

BOOST_AUTO_TEST_CASE(mesh_files_round_trip_in_every_format)
{
  const AC::Input_surface sq = AC::make_rectangle_background(1.0, 0.5, 5, 3);
  BOOST_TEST(sq.number_of_vertices() == 15u);
  BOOST_TEST(sq.number_of_faces() == 16u);
  BOOST_TEST(sq.is_disk());
  BOOST_TEST(sq.is_planar());
  for(const std::string ext : {"off", "obj", "ply"}) {
    const std::string path = out_dir + "/roundtrip." + ext;
    std::vector<std::array<std::size_t, 3>> faces(sq.faces().begin(), sq.faces().end());
    AC::IO::write_polygon_soup(path, sq.points(), faces);
    const AC::Input_surface back = AC::IO::read_triangle_mesh(path);
    BOOST_TEST(back.number_of_vertices() == sq.number_of_vertices());
    BOOST_TEST(back.number_of_faces() == sq.number_of_faces());
    for(std::size_t v = 0; v < sq.number_of_vertices(); ++v) BOOST_TEST((back.points()[v] - sq.points()[v]).norm() == 0.0);
  }
  const AC::Input_surface tet = AC::IO::read_triangle_mesh(write_file("tetra.off", tetra_off));
  BOOST_TEST(!tet.is_disk());
  BOOST_TEST(contains(tet.topology_description(), "closed surface of genus 0"));
}

BOOST_AUTO_TEST_CASE(bad_mesh_files_name_the_problem)
{
  BOOST_TEST(contains(message_of([] { AC::IO::read_triangle_mesh(out_dir + "/missing.off"); }), "missing.off: cannot be opened"));
  BOOST_TEST(contains(mesh_file_error("mesh.stl", "solid x\n"), "unsupported extension"));
  BOOST_TEST(contains(mesh_file_error("garbage.off", "this is not a mesh\n"), "garbage.off"));
  BOOST_TEST(contains(mesh_file_error("empty.off", ""), "empty.off"));
  BOOST_TEST(contains(mesh_file_error("quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"), "face 0 has 4 vertices"));
  BOOST_TEST(contains(mesh_file_error("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), "nan.off"));
  // non-manifold edge: three triangles on the edge 0-1
  BOOST_TEST(contains(mesh_file_error("fin.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n"), "edge"));
  // zero-area face
  BOOST_TEST(contains(mesh_file_error("flat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n"), "face 0 is degenerate"));
  // two triangles touching at one vertex: a non-manifold vertex
  BOOST_TEST(contains(mesh_file_error("bowtie.off", "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 0 3 4\n"), "vertex 0 is non-manifold"));
  // two separate triangles
  BOOST_TEST(contains(mesh_file_error("two.off", "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n5 0 0\n6 0 0\n5 1 0\n3 0 1 2\n3 3 4 5\n"), "2 connected components"));
  // an index out of range
  BOOST_TEST(contains(message_of([] { AC::Input_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{{0, 1, 7}}}); }),
                      "face 0 refers to vertex 7"));
  // write errors
  BOOST_TEST(contains(message_of([] {
                        AC::IO::write_polygon_soup(out_dir + "/no/such/dir/x.off", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{{0, 1, 2}}});
                      }),
                      "cannot write"));
}

BOOST_AUTO_TEST_CASE(mesh_files_are_repaired_in_every_format)
{
  // a 2 x 2 grid of quads, clockwise seen from +z, with a vertex of no face, in each format: read as it is
  // it is refused; with repairs, 4 quads triangulated, 1 vertex dropped, the plane turned counter-clockwise
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                          {2, 1, 0}, {0, 2, 0}, {1, 2, 0}, {2, 2, 0}, {5, 5, 0}};
  const std::vector<std::vector<std::size_t>> quads = {{0, 3, 4, 1}, {1, 4, 5, 2}, {3, 6, 7, 4}, {4, 7, 8, 5}};
  std::ostringstream off, obj, ply;
  off << "OFF\n" << p.size() << " " << quads.size() << " 0\n";
  obj << "# quads\n";
  ply << "ply\nformat ascii 1.0\nelement vertex " << p.size() << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "element face " << quads.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for(const auto& x : p) {
    off << x.x() << " " << x.y() << " " << x.z() << "\n";
    obj << "v " << x.x() << " " << x.y() << " " << x.z() << "\n";
    ply << x.x() << " " << x.y() << " " << x.z() << "\n";
  }
  for(const auto& q : quads) {
    off << "4";
    obj << "f";
    ply << "4";
    for(std::size_t v : q) {
      off << " " << v;
      obj << " " << v + 1;
      ply << " " << v;
    }
    off << "\n";
    obj << "\n";
    ply << "\n";
  }
  for(const auto& [ext, text] : {std::make_pair("off", off.str()), std::make_pair("obj", obj.str()), std::make_pair("ply", ply.str())}) {
    BOOST_TEST_CONTEXT(ext)
    {
      const std::string path = write_file(std::string("quads.") + ext, text);
      BOOST_TEST(contains(message_of([&] { AC::IO::read_triangle_mesh(path); }), "face 0 has 4 vertices"));
      AC::Repair_report r;
      const AC::Input_surface s = AC::IO::read_triangle_mesh(path, r);
      BOOST_TEST(s.is_disk());
      BOOST_TEST(s.number_of_vertices() == 9u);
      BOOST_TEST(s.number_of_faces() == 8u);
      BOOST_TEST(r.polygons_triangulated == 4u);
      BOOST_TEST(r.triangles_from_polygons == 8u);
      BOOST_TEST(r.isolated_points_dropped == 1u);
      BOOST_TEST(r.planar_clockwise);
      BOOST_TEST(test::count_mesh(s.points(), s.faces()).planar_area == 4.0);
      // the soup as read, unrepaired
      std::vector<Eigen::Vector3d> pts;
      std::vector<std::vector<std::size_t>> polys;
      AC::IO::read_polygon_soup(path, pts, polys);
      BOOST_TEST((pts == p));
      BOOST_TEST((polys == quads));
    }
  }
}

// ------------------------------------------------------------------------------ metric files

BOOST_AUTO_TEST_CASE(metric_files_round_trip_and_errors)
{
  std::vector<Eigen::Matrix3d> t(4, Eigen::Matrix3d::Identity());
  t[2] << 2, 0.5, 0, 0.5, 3, 0, 0, 0, 0;
  const std::string path = out_dir + "/metric.txt";
  AC::IO::write_metric_file(path, t);
  const AC::Tensor_field_metric m = AC::IO::read_metric_file(path, 4);
  BOOST_REQUIRE(m.tensors().size() == 4u);
  for(std::size_t i = 0; i < 4; ++i) BOOST_TEST((m.tensors()[i] - t[i]).norm() == 0.0);

  const std::string row = "1 0 0 1 0 1\n";
  BOOST_TEST(contains(message_of([] { AC::IO::read_metric_file(out_dir + "/missing_metric.txt", 4); }), "cannot be opened"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_metric_file(write_file("m_count.txt", "3\n" + row + row + row), 4); }),
                      "declares 3 tensors but the mesh has 4"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_metric_file(write_file("m_short.txt", "2\n" + row), 2); }), "1 rows"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_metric_file(write_file("m_long.txt", "1\n" + row + row), 1); }),
                      "line 3: more rows than the 1 declared"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_metric_file(write_file("m_nan.txt", "2\n" + row + "1 0 nan 1 0 1\n"), 2); }),
                      "line 3"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_metric_file(write_file("m_nan2.txt", "1\n1 0 nan 1 0 1\n"), 1); }),
                      "non-finite"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_metric_file(write_file("m_five.txt", "1\n1 0 0 1 0\n"), 1); }),
                      "5 numbers, expected 6"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_metric_file(write_file("m_word.txt", "1\n1 0 0 one 0 1\n"), 1); }),
                      "'one' is not a number"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_metric_file(write_file("m_head.txt", "four\n"), 1); }),
                      "the first line must be the number of vertices"));
}

BOOST_AUTO_TEST_CASE(feature_files_are_read_and_errors_name_the_line)
{
  // one index: a corner; two: a crease edge; '#' comments and blank lines skipped (issue 15, item 1)
  const AC::IO::Marked_features m =
    AC::IO::read_feature_file(write_file("f.txt", "# creases of a part\n0 1\n\n 2\t3  # an edge\n4\r\n"), 5);
  BOOST_REQUIRE(m.edges.size() == 2u);
  BOOST_TEST((m.edges[0] == std::array<std::size_t, 2>{{0, 1}}));
  BOOST_TEST((m.edges[1] == std::array<std::size_t, 2>{{2, 3}}));
  BOOST_REQUIRE(m.vertices.size() == 1u);
  BOOST_TEST(m.vertices[0] == 4u);
  BOOST_TEST(AC::IO::read_feature_file(write_file("f_empty.txt", "# nothing\n"), 5).edges.empty());

  BOOST_TEST(contains(message_of([] { AC::IO::read_feature_file(out_dir + "/missing_features.txt", 4); }), "cannot be opened"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_feature_file(write_file("f_three.txt", "0 1\n0 1 2\n"), 4); }),
                      "line 2: expected one vertex index (a corner) or two"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_feature_file(write_file("f_sign.txt", "-1 2\n"), 4); }), "line 1"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_feature_file(write_file("f_word.txt", "1 two\n"), 4); }), "line 1"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_feature_file(write_file("f_huge.txt", "99999999999999999999999\n"), 4); }),
                      "line 1"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_feature_file(write_file("f_range.txt", "\n1 4\n"), 4); }),
                      "line 2: vertex 4 does not exist (the mesh has 4"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_feature_file(write_file("f_loop.txt", "3 3\n"), 4); }), "to itself"));
  // a message never quotes the file's bytes
  const std::string binary = message_of([&] { AC::IO::read_feature_file(write_file("f_bin.txt", std::string("1 \x01\xff\0", 5)), 4); });
  BOOST_TEST(contains(binary, "line 1"));
  BOOST_TEST(binary.find('\xff') == std::string::npos);

  // through the repairs of a mesh file: its indices map to the repaired surface, a dropped point is refused
  const std::string square = "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n7 7 7\n3 0 1 2\n3 0 2 3\n";
  AC::Repair_report repairs;
  const AC::Input_surface s = AC::IO::read_triangle_mesh(write_file("f_square.off", square), repairs);
  BOOST_REQUIRE(s.number_of_vertices() == 4u);
  BOOST_TEST(AC::IO::read_feature_file(write_file("f_ok.txt", "0 2\n3\n"), repairs).edges.size() == 1u);
  BOOST_TEST(contains(message_of([&] { AC::IO::read_feature_file(write_file("f_dropped.txt", "4\n"), repairs); }),
                      "vertex 4 belongs to no face"));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_feature_file(write_file("f_norep.txt", "0\n"), AC::Repair_report()); }),
                      "no vertex map"));
}

// ------------------------------------------------------------------------------------ images

BOOST_AUTO_TEST_CASE(images_read_in_every_format)
{
  const AC::IO::Image chelsea = AC::IO::read_image(data_dir + "/images/photo_chelsea_323.png");
  BOOST_TEST(chelsea.width == 323);
  BOOST_TEST(chelsea.height == 323);
  BOOST_TEST(chelsea.channels == 3);
  const AC::IO::Image ct = AC::IO::read_image(data_dir + "/images/ct_head_211.png");
  BOOST_TEST(ct.width == 211);
  BOOST_TEST(ct.channels == 1);
  float lo = 1, hi = 0;
  for(float x : ct.data) { lo = std::min(lo, x); hi = std::max(hi, x); }
  BOOST_TEST((lo >= 0 && hi <= 1 && hi - lo > 0.5));

  // PNM round trip (binary) and an ASCII PGM with a comment
  AC::IO::write_pnm(chelsea, out_dir + "/chelsea.ppm");
  const AC::IO::Image back = AC::IO::read_image(out_dir + "/chelsea.ppm");
  BOOST_TEST(back.width == 323);
  BOOST_TEST(back.channels == 3);
  double diff = 0;
  for(std::size_t i = 0; i < back.data.size(); ++i) diff = std::max(diff, double(std::abs(back.data[i] - chelsea.data[i])));
  BOOST_TEST(diff < 1.0 / 255 + 1e-6);
  const AC::IO::Image a = AC::IO::read_image(write_file("ascii.pgm", "P2\n# a comment\n3 2\n255\n0 128 255\n255 0 64\n"));
  BOOST_TEST(a.width == 3);
  BOOST_TEST(a.height == 2);
  BOOST_TEST(a.at(2, 0, 0) == 1.0f);
  BOOST_TEST(a.at(0, 1, 0) == 1.0f);
  BOOST_TEST(std::abs(a.at(1, 0, 0) - 128.0f / 255) < 1e-6);
}

BOOST_AUTO_TEST_CASE(bad_images_name_the_problem)
{
  BOOST_TEST(contains(message_of([] { AC::IO::read_image(out_dir + "/missing.png"); }), "missing.png: cannot be opened"));
  BOOST_TEST(contains(message_of([] { AC::IO::read_image(write_file("text.png", "hello")); }), "not a PNG, PGM or PPM"));
  BOOST_TEST(contains(message_of([] { AC::IO::read_image(write_file("short.pgm", "P5\n4 4\n255\nab")); }), "truncated"));
  BOOST_TEST(contains(message_of([] { AC::IO::read_image(write_file("zero.pgm", "P2\n0 4\n255\n")); }), "zero size"));
  BOOST_TEST(contains(message_of([] { AC::IO::read_image(write_file("max.pgm", "P2\n1 1\n70000\n1\n")); }), "maxval"));
  // a PNG cut in the middle of its data
  std::ifstream in(data_dir + "/images/ct_head_211.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  BOOST_REQUIRE(bytes.size() > 2000);
  const std::string cut = write_file("cut.png", bytes.substr(0, bytes.size() / 2));
  BOOST_TEST(contains(message_of([&] { AC::IO::read_image(cut); }), "cut.png"));
  // corrupt compressed data
  std::string corrupt = bytes;
  for(std::size_t i = 200; i < 600; ++i) corrupt[i] = char(i * 7);
  const std::string bad = write_file("corrupt.png", corrupt);
  BOOST_TEST(contains(message_of([&] { AC::IO::read_image(bad); }), "corrupt.png"));
}

BOOST_AUTO_TEST_CASE(image_metric_stretches_across_edges)
{
  // a vertical step edge in the middle of a grey image: short edges across it (x), isotropic far away
  AC::IO::Image img;
  img.width = 41;
  img.height = 21;
  img.channels = 1;
  for(int y = 0; y < img.height; ++y)
    for(int x = 0; x < img.width; ++x) img.data.push_back(x < 20 ? 0.f : 1.f);
  const AC::Image_metric m(img, 0.5);
  AC::Surface_point at_edge, far;
  at_edge.position = Eigen::Vector3d(19.5 / 40, 0.25, 0);
  far.position = Eigen::Vector3d(0.02, 0.25, 0);
  const Eigen::Matrix3d M = m.tensor(at_edge), F = m.tensor(far);
  BOOST_TEST(M(0, 0) > 10 * M(1, 1));
  BOOST_TEST(std::abs(M(1, 1) - 1) < 1e-6);
  BOOST_TEST((F - Eigen::Vector3d(1, 1, 0).asDiagonal().toDenseMatrix()).norm() < 1e-3);
  BOOST_TEST(M(2, 2) == 0.0);
  // the background matches the metric's coordinates: one vertex per pixel, unit width
  const AC::Input_surface bg = AC::make_image_background(img);
  BOOST_TEST(bg.number_of_vertices() == 41u * 21u);
  BOOST_TEST(std::abs(bg.points().back().x() - 1) < 1e-15);
  BOOST_TEST(std::abs(bg.points().back().y() - 0.5) < 1e-15);

  BOOST_TEST(contains(message_of([&] { AC::Image_metric(img, 0.0); }), "anisotropy s must be positive"));
  BOOST_TEST(contains(message_of([&] { AC::Image_metric(img, std::nan("")); }), "anisotropy"));
  AC::IO::Image tiny = img;
  tiny.width = 1;
  BOOST_TEST(contains(message_of([&] { AC::make_image_background(tiny); }), "at least 2 x 2"));
}

// a real figure as the report writes it (10 significant digits)
double report_figure(double x)
{
  char g[32];
  std::snprintf(g, sizeof(g), "%.10g", x);
  return std::strtod(g, nullptr);
}

// the JSON report and the SVG writers on a result filled by hand: the figures of a 6 x 6 grid's quality
// in the metric diag(4, 1, 1) (compute_mesh_quality), the counts of a planar image run
BOOST_AUTO_TEST_CASE(report_and_svg_writers)
{
  std::vector<Eigen::Vector3d> pts;
  std::vector<std::array<std::size_t, 3>> faces;
  const std::size_t g = 6;
  for(std::size_t y = 0; y < g; ++y)
    for(std::size_t x = 0; x < g; ++x) pts.emplace_back(double(x) + 0.1 * double((x * y) % 3), double(y), 0.0);
  for(std::size_t y = 0; y + 1 < g; ++y)
    for(std::size_t x = 0; x + 1 < g; ++x) {
      const std::size_t a = y * g + x;
      faces.push_back({a, a + 1, a + g + 1});
      faces.push_back({a, a + g + 1, a + g});
    }
  Eigen::Matrix3d q = Eigen::Matrix3d::Identity();
  q(0, 0) = 2;  // M = Q^2 = diag(4, 1, 1): stretch 2
  AC::Remeshing_result r;
  r.quality = AC::compute_mesh_quality(pts, faces, std::vector<Eigen::Matrix3d>(pts.size(), q), 1);
  r.domain = AC::Parametric_domain::PLANE;
  r.input_vertices = 3000;
  r.input_faces = 5800;
  r.boundary_sites = 20;
  r.corners = 4;
  r.adjustment.splits = 7;
  r.adjustment.flips = 3;
  r.conformal_flips = 5;
  r.cvt.energy = {3.0, 2.0, 1.5};
  r.cvt.iterations = 3;
  BOOST_REQUIRE(r.quality.G_avg > 0 && r.quality.G_avg < 1);

  // the JSON report parses back with the result's figures and the extra fields
  std::ostringstream json;
  AC::IO::write_report_json(json, r, {{"input_name", "crop \"60 x 50\" \xff\x01"}, {"s", 0.5}});
  const nlohmann::json j = nlohmann::json::parse(json.str());
  BOOST_TEST(j.at("input_name") == "crop \"60 x 50\" \xef\xbf\xbd\x01");  // invalid UTF-8 replaced by U+FFFD
  BOOST_TEST(j.at("s") == 0.5);
  BOOST_TEST(j.at("domain") == "plane");
  BOOST_TEST(j.at("input").at("vertices") == 3000);
  BOOST_TEST(j.at("input").at("faces") == 5800);
  BOOST_TEST(j.at("output").at("vertices") == g * g);
  BOOST_TEST(j.at("output").at("triangles") == faces.size());
  BOOST_TEST(j.at("output").at("corners") == 4);
  BOOST_TEST(j.at("output").at("boundary_vertices") == 20);
  // reals with 10 significant digits, as the report always had
  BOOST_TEST(j.at("quality").at("G_avg").get<double>() == report_figure(r.quality.G_avg));
  BOOST_TEST(std::abs(j.at("quality").at("G_avg").get<double>() - r.quality.G_avg) < 1e-9);
  BOOST_TEST(j.at("quality").at("angle_histogram").at("counts").size() == r.quality.angle_histogram.size());
  BOOST_TEST(j.at("edge_adjustment").at("splits") == 7);
  BOOST_TEST(j.at("edge_adjustment").at("flips") == 3);
  BOOST_TEST(j.at("conformal_embedding").at("intrinsic_flips") == 5);
  BOOST_TEST(!j.at("conformal_embedding").contains("reused"));  // written only when an earlier run's embedding was taken
  {
    AC::Remeshing_result reused = r;
    reused.embedding_reused = true;
    std::ostringstream o;
    AC::IO::write_report_json(o, reused);
    BOOST_TEST(nlohmann::json::parse(o.str()).at("conformal_embedding").at("reused") == true);
  }
  BOOST_TEST(j.at("cvt").at("energy").size() == 3u);
  BOOST_TEST(j.at("cvt").at("iterations") == 3);
  BOOST_TEST(j.at("seconds").size() == std::size_t(AC::number_of_stages) + 2);  // the stages, discarded and total
  // the realised anisotropy: the metric's stretch at the vertices (2 everywhere) and the edges' metric conformity
  const nlohmann::json& st = j.at("quality").at("metric_stretch");
  BOOST_TEST(st.at("min").get<double>() == report_figure(r.quality.stretch_min));
  BOOST_TEST(st.at("median").get<double>() == report_figure(r.quality.stretch_median));
  BOOST_TEST(st.at("p95").get<double>() == report_figure(r.quality.stretch_p95));
  BOOST_TEST(st.at("max").get<double>() == report_figure(r.quality.stretch_max));
  BOOST_TEST(std::abs(st.at("min").get<double>() - 2) < 1e-9);
  BOOST_TEST(std::abs(st.at("max").get<double>() - 2) < 1e-9);
  const nlohmann::json& el = j.at("quality").at("metric_edge_length");
  BOOST_TEST(el.at("mean").get<double>() == report_figure(r.quality.edge_length_mean));
  BOOST_TEST(el.at("normalized_stddev").get<double>() == report_figure(r.quality.edge_length_stddev));
  BOOST_TEST((el.at("normalized_min").get<double>() < 1 && el.at("normalized_max").get<double>() > 1));
  // nothing repaired: no `repairs` object; a repaired input's report has one, with its counts
  BOOST_TEST(!j.contains("repairs"));
  AC::Remeshing_result repaired = r;
  repaired.repairs.input_points = 8;
  repaired.repairs.input_polygons = 2;
  repaired.repairs.polygons_triangulated = 2;
  repaired.repairs.triangles_from_polygons = 4;
  repaired.repairs.points_welded = 2;
  repaired.repairs.planar_clockwise = true;
  std::ostringstream rj;
  AC::IO::write_report_json(rj, repaired);
  const nlohmann::json k = nlohmann::json::parse(rj.str()).at("repairs");
  BOOST_TEST(k.at("input_vertices") == 8);
  BOOST_TEST(k.at("input_faces") == 2);
  BOOST_TEST(k.at("polygons_triangulated") == 2);
  BOOST_TEST(k.at("triangles_from_polygons") == 4);
  BOOST_TEST(k.at("points_welded") == 2);
  BOOST_TEST(k.at("points_left_unwelded") == 0);
  BOOST_TEST(k.at("duplicate_faces_removed") == 0);
  BOOST_TEST(k.at("isolated_vertices_dropped") == 0);
  BOOST_TEST(k.at("faces_reoriented") == 0);
  BOOST_TEST(k.at("reversed_to_outward") == false);
  BOOST_TEST(k.at("planar_clockwise") == true);
  // the report's own keys cannot be overwritten, and extra fields must be an object
  BOOST_TEST(contains(message_of([&] { AC::IO::write_report_json(json, r, {{"quality", 1}}); }), "'quality' is a field of the report"));
  BOOST_TEST(contains(message_of([&] { AC::IO::write_report_json(json, r, nlohmann::json::array({1, 2})); }), "must be a JSON object"));

  // the SVG of the mesh coloured by G, with its title escaped, and the angle histogram
  AC::IO::write_svg(out_dir + "/grid.svg", pts, faces, r.quality.triangle_G, 0.5, 1.0, "grid & <test>");
  AC::IO::write_histogram_svg(out_dir + "/grid_hist.svg", r.quality.angle_histogram, r.quality.bin_width, "angles");
  std::ifstream svg(out_dir + "/grid.svg");
  const std::string s((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  BOOST_TEST(std::count(s.begin(), s.end(), '\n') > std::ptrdiff_t(faces.size()));
  BOOST_TEST(contains(s, "grid &amp; &lt;test&gt;"));
  BOOST_TEST(contains(s, "</svg>"));
  std::ifstream hist(out_dir + "/grid_hist.svg");
  const std::string h((std::istreambuf_iterator<char>(hist)), std::istreambuf_iterator<char>());
  BOOST_TEST(contains(h, "</svg>"));
  BOOST_TEST(contains(message_of([&] {
                        AC::IO::write_svg(out_dir + "/no/such/dir/x.svg", pts, faces, r.quality.triangle_G, 0, 1, "");
                      }),
                      "cannot write"));
}

// --------------------------------------------------- fuzzing regressions (doc/fuzzing.md, fuzz/)

namespace {

// an input the fuzzers (or reading the code behind a finding) showed to crash, hang or allocate gigabytes
std::string fuzz_input(const std::string& name)
{
  return std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/fuzz_regressions/" + name;
}

std::string mesh_error(const std::string& name)
{
  return message_of([&] { AC::IO::read_triangle_mesh(fuzz_input(name)); });
}

} // namespace

BOOST_AUTO_TEST_CASE(fuzz_regressions_off)
{
  // CGAL's OFF scanner read past the vertex line of an STOFF (texture) file: ASan SEGV in scan_texture()
  BOOST_TEST(contains(mesh_error("off_texture_vertex_read_past_line.off"), "'STOFF' is not a supported OFF header"));
  // a header count above INT_MAX: UBSan float-to-int overflow in CGAL, then arrays sized from it
  BOOST_TEST(contains(mesh_error("off_vertex_count_overflows_int.off"), "more than the 25-byte file can hold"));
  // a face size of 1e30: UBSan float-to-size_t overflow in CGAL, then a vector resized to it
  BOOST_TEST(contains(mesh_error("off_face_size_not_an_integer.off"), "line 6: '1e30' is not a valid face size"));
  // the same checks on inline inputs
  BOOST_TEST(contains(mesh_file_error("binary.off", "OFF BINARY\n"), "binary OFF is not supported"));
  BOOST_TEST(contains(mesh_file_error("few.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"), "declares 3 vertices but lists 2"));
  BOOST_TEST(contains(mesh_file_error("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                      "face 0 refers to vertex 3, but the file has 3 vertices"));
  BOOST_TEST(contains(mesh_file_error("neg.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), "'-1' is not a valid vertex index"));
  BOOST_TEST(contains(mesh_file_error("cut.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"), "truncated after 0 of 1 faces"));
  BOOST_TEST(contains(mesh_file_error("word.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"), "vertex 1: 'zero' is not a number"));
  // what CGAL read stays readable: comments, counts on the header line, colours and normals
  const AC::Input_surface c = AC::IO::read_triangle_mesh(
    write_file("colours.off", "# c\nCOFF 3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255 # v1\n\n0 1 0 0 0 255 255\n3 0 1 2 1 0.5 0\n"));
  BOOST_TEST(c.number_of_faces() == 1u);
  BOOST_TEST(AC::IO::read_triangle_mesh(write_file("normals.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n"))
               .number_of_vertices() == 3u);
}

BOOST_AUTO_TEST_CASE(fuzz_regressions_ply)
{
  // the fuzzer's input: a property before any element read the back of an empty vector in CGAL (UBSan)
  BOOST_TEST(contains(mesh_error("ply_property_before_element_fuzzer.ply"), "PLY header line 4: unknown keyword"));
  BOOST_TEST(contains(mesh_error("ply_property_before_element.ply"), "line 3: a property before any element"));
  // a 32-bit list length of 2e9: an 8 GB vector in CGAL before any index is read
  BOOST_TEST(contains(mesh_error("ply_32_bit_list_length.ply"), "list length type 'int' not supported"));
  // 10^15 items without properties: CGAL loops over them without reading anything (a hang)
  BOOST_TEST(contains(mesh_error("ply_element_without_properties.ply"), "declares 1000000000000000 items"));
  // the fuzzer's input: x double, y uchar; CGAL cast y to a float property unchecked (UBSan: null member call)
  BOOST_TEST(contains(mesh_error("ply_vertex_coordinate_not_float.ply"), "PLY property 'y' of element 'vertex' cannot have type uchar"));
  BOOST_TEST(contains(mesh_file_error("noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n"),
                      "needs the properties x, y and z once each"));
  BOOST_TEST(contains(mesh_file_error("floatlist.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty list float int v\nend_header\n"),
                      "list length type 'float' not supported"));
  BOOST_TEST(contains(mesh_file_error("noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"), "without end_header"));
}

BOOST_AUTO_TEST_CASE(fuzz_regressions_images)
{
  auto image_error = [](const std::string& name) { return message_of([&] { AC::IO::read_image(fuzz_input(name)); }); };
  // the fuzzer's input: a P6 header of 77777677 x 3 pixels in 39 bytes made the reader allocate 2.8 GB
  // before noticing the missing data
  BOOST_TEST(contains(image_error("ppm_pixels_allocated_before_size_check.ppm"), "truncated pixel data"));
  // width * height overflowed a long long (UBSan) for header values near 2^40 (PNM) and 2^32 (PNG)
  BOOST_TEST(contains(image_error("pgm_size_product_overflows.pgm"), "too large (1099511627775 x 1099511627775)"));
  // (libpng refuses those PNG sizes itself, as larger than 2^31 - 1)
  BOOST_TEST(contains(image_error("png_size_product_overflows.png"), "invalid PNG: PNG unsigned integer out of range"));
  // 16384 x 16384 RGBA 16 bits with 100 bytes of data: a 2 GB buffer before inflating them
  BOOST_TEST(contains(image_error("png_2_gb_buffer_for_100_bytes.png"), "corrupt or truncated PNG image data"));
  // the fuzzer's input, a 68-byte file whose tEXt chunk declares 1.1 GB: libpng only warns that the chunk
  // is above its 8 MB limit, then allocates it (libFuzzer out-of-memory); chunk lengths are checked first
  BOOST_TEST(contains(image_error("png_text_chunk_of_1_gb.png"), "invalid PNG: chunk 'tEXt' of 1140850691 bytes runs past the end"));
  // the same with the file ending right after the chunk's length and type (169 MB asked for)
  BOOST_TEST(contains(image_error("png_text_chunk_header_at_the_end.png"), "chunk 'tEXt' of 169478656 bytes runs past the end"));
  BOOST_TEST(contains(message_of([] { AC::IO::read_image(write_file("big_ascii.pgm", "P2\n1000 1000\n255\n0 0 0\n")); }),
                      "truncated pixel data"));
  // exact sizes still read: binary data right after the single whitespace, ASCII without a final newline
  BOOST_TEST(AC::IO::read_image(write_file("exact.pgm", std::string("P5\n2 1\n255\n\x01\x02", 13))).width == 2);
  BOOST_TEST(AC::IO::read_image(write_file("exact_ascii.pgm", "P2\n2 1\n255\n1 2")).width == 2);
}

// ------------------------------------------------------------------------------------- PNG by libpng

namespace {

// the test's sample of channel c at (x, y) for a bit depth: every value of the depth appears
unsigned test_sample(std::size_t x, std::size_t y, std::size_t c, int depth)
{
  return unsigned(x * 7 + y * 13 + c * 5 + x * y) % (1u << depth);
}

// writes a w x h PNG of the given colour type and bit depth with test_sample() values (palette images: the
// index), Adam7-interlaced or not, with a gAMA and (where the colour type has none) a tRNS chunk that the
// reader must ignore, and a tEXt chunk
void write_test_png(const std::string& path, int w, int h, int color, int depth, bool interlaced, int palette_size = 0)
{
  std::FILE* f = std::fopen(path.c_str(), "wb");
  BOOST_REQUIRE(f != nullptr);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  BOOST_REQUIRE((png != nullptr && info != nullptr));
  png_init_io(png, f);
  png_set_IHDR(png, info, png_uint_32(w), png_uint_32(h), depth, color, interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  std::vector<png_color> palette;
  for(int i = 0; i < palette_size; ++i)
    palette.push_back(png_color{png_byte(37 * i % 256), png_byte(255 - i), png_byte(i * i % 256)});
  if(color == PNG_COLOR_TYPE_PALETTE) {
    png_set_PLTE(png, info, palette.data(), palette_size);
    png_set_check_for_invalid_index(png, 0);  // out-of-range indices are written on purpose
  }
  png_set_gAMA(png, info, 0.7);
  if(color == PNG_COLOR_TYPE_RGB || color == PNG_COLOR_TYPE_GRAY) {
    png_color_16 transparent{};
    png_set_tRNS(png, info, nullptr, 0, &transparent);
  }
  png_text text{};
  text.compression = PNG_TEXT_COMPRESSION_NONE;
  text.key = const_cast<char*>("Comment");
  text.text = const_cast<char*>("a test image");
  png_set_text(png, info, &text, 1);
  png_write_info(png, info);
  if(depth < 8) png_set_packing(png);
  png_set_interlace_handling(png);
  const std::size_t samples = std::size_t(png_get_channels(png, info)), bytes = depth == 16 ? 2 : 1;
  std::vector<unsigned char> pixels(std::size_t(w) * std::size_t(h) * samples * bytes);
  std::vector<png_bytep> rows;
  for(std::size_t y = 0; y < std::size_t(h); ++y) {
    rows.push_back(pixels.data() + y * std::size_t(w) * samples * bytes);
    for(std::size_t x = 0; x < std::size_t(w); ++x)
      for(std::size_t c = 0; c < samples; ++c) {
        const unsigned v = test_sample(x, y, c, depth);
        unsigned char* p = rows.back() + (x * samples + c) * bytes;
        if(bytes == 2) { p[0] = static_cast<unsigned char>(v >> 8); p[1] = static_cast<unsigned char>(v & 0xff); }
        else p[0] = static_cast<unsigned char>(v);
      }
  }
  png_write_image(png, rows.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
}

// the CRC-32 of PNG chunks (ISO 3309, as in the PNG specification's annex D)
std::uint32_t crc32(const std::string& bytes)
{
  std::uint32_t c = 0xffffffffu;
  for(const unsigned char b : bytes) {
    c ^= b;
    for(int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

} // namespace

BOOST_AUTO_TEST_CASE(png_every_colour_type_bit_depth_and_interlacing)
{
  struct Kind { int color, depth; };
  const Kind kinds[] = {{PNG_COLOR_TYPE_GRAY, 1}, {PNG_COLOR_TYPE_GRAY, 2}, {PNG_COLOR_TYPE_GRAY, 4}, {PNG_COLOR_TYPE_GRAY, 8},
                        {PNG_COLOR_TYPE_GRAY, 16}, {PNG_COLOR_TYPE_GRAY_ALPHA, 8}, {PNG_COLOR_TYPE_GRAY_ALPHA, 16},
                        {PNG_COLOR_TYPE_RGB, 8}, {PNG_COLOR_TYPE_RGB, 16}, {PNG_COLOR_TYPE_RGB_ALPHA, 8},
                        {PNG_COLOR_TYPE_RGB_ALPHA, 16}, {PNG_COLOR_TYPE_PALETTE, 1}, {PNG_COLOR_TYPE_PALETTE, 2},
                        {PNG_COLOR_TYPE_PALETTE, 4}, {PNG_COLOR_TYPE_PALETTE, 8}};
  const int w = 13, h = 11;
  for(const Kind& k : kinds)
    for(const bool interlaced : {false, true}) {
      const std::string path = out_dir + "/png_c" + std::to_string(k.color) + "_d" + std::to_string(k.depth) + (interlaced ? "_i" : "") + ".png";
      const bool palette = k.color == PNG_COLOR_TYPE_PALETTE;
      write_test_png(path, w, h, k.color, k.depth, interlaced, palette ? 1 << k.depth : 0);
      const AC::IO::Image img = AC::IO::read_image(path);
      BOOST_TEST_INFO(path);
      BOOST_TEST(img.width == w);
      BOOST_TEST(img.height == h);
      BOOST_TEST(img.channels == ((k.color == PNG_COLOR_TYPE_GRAY || k.color == PNG_COLOR_TYPE_GRAY_ALPHA) ? 1 : 3));
      BOOST_REQUIRE(img.data.size() == std::size_t(w * h * img.channels));
      // each sample over the largest value of its depth, exactly as float(double / double); palette
      // entries over 255; no gamma, no transparency, alpha dropped
      bool exact = true;
      const double maxv = double((1u << k.depth) - 1);
      for(int y = 0; y < h; ++y)
        for(int x = 0; x < w; ++x)
          for(int c = 0; c < img.channels; ++c) {
            float expected;
            if(palette) {
              const unsigned i = test_sample(std::size_t(x), std::size_t(y), 0, k.depth);
              const int rgb[3] = {int(37 * i % 256), int(255 - i), int(i * i % 256)};
              expected = float(rgb[c] / 255.0);
            } else {
              expected = float(test_sample(std::size_t(x), std::size_t(y), std::size_t(c), k.depth) / maxv);
            }
            exact = exact && img.at(x, y, c) == expected;
          }
      BOOST_TEST(exact);
    }

  // a palette index past the palette: refused, as by the hand-written decoder before libpng
  write_test_png(out_dir + "/png_short_palette.png", w, h, PNG_COLOR_TYPE_PALETTE, 8, false, 20);
  BOOST_TEST(contains(message_of([] { AC::IO::read_image(out_dir + "/png_short_palette.png"); }), "palette index out of range"));
}

BOOST_AUTO_TEST_CASE(png_errors_name_the_file_and_libpngs_reason_and_print_nothing)
{
  write_test_png(out_dir + "/png_good.png", 9, 7, PNG_COLOR_TYPE_RGB, 8, false);
  std::ifstream in(out_dir + "/png_good.png", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t ihdr = bytes.find("IHDR"), text = bytes.find("tEXt"), idat = bytes.find("IDAT");
  BOOST_REQUIRE((ihdr != std::string::npos && text != std::string::npos && idat != std::string::npos));

  // libpng's warnings and errors go into the exception, never to stderr: stderr is a file meanwhile
  const std::string err_path = out_dir + "/png_stderr.txt";
  std::fflush(stderr);
  const int saved = ::dup(2);
  BOOST_REQUIRE(std::freopen(err_path.c_str(), "w", stderr) != nullptr);

  // a bad CRC on an ancillary chunk: a warning, the chunk is skipped and the image read
  std::string bad_text = bytes;
  bad_text[text + 4 + 8 + 4] ^= 0x55;  // past "tEXt" and the keyword "Comment\0": in the text
  bool read = false;
  try {
    const AC::IO::Image img = AC::IO::read_image(write_file("png_bad_text_crc.png", bad_text));
    read = img.width == 9 && img.height == 7;
  } catch(const AC::Error&) {
  }
  // a bad CRC on IHDR, a zero width, data cut short, no IEND: errors naming the file and the reason
  std::string bad_ihdr = bytes;
  bad_ihdr[ihdr + 4 + 12] ^= 0x01;  // the last byte of IHDR's data
  const std::string crc = message_of([&] { AC::IO::read_image(write_file("png_bad_ihdr_crc.png", bad_ihdr)); });
  std::string zero = bytes;
  zero[ihdr + 4] = zero[ihdr + 5] = zero[ihdr + 6] = zero[ihdr + 7] = 0;
  const std::uint32_t c = crc32(zero.substr(ihdr, 4 + 13));  // a valid CRC: the width is what is wrong
  for(int i = 0; i < 4; ++i) zero[ihdr + 17 + std::size_t(i)] = char((c >> (24 - 8 * i)) & 0xff);
  const std::string zero_width = message_of([&] { AC::IO::read_image(write_file("png_zero_width.png", zero)); });
  const std::string no_end = message_of([&] { AC::IO::read_image(write_file("png_no_iend.png", bytes.substr(0, bytes.size() - 12))); });
  const std::string cut = message_of([&] { AC::IO::read_image(write_file("png_cut.png", bytes.substr(0, idat + 10))); });

  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  std::ifstream err(err_path);
  const std::string printed((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  BOOST_TEST(printed.empty(), "printed: " << printed);

  BOOST_TEST(read);
  BOOST_TEST(contains(crc, "image " + out_dir + "/png_bad_ihdr_crc.png: invalid PNG: IHDR: CRC error"));
  BOOST_TEST(contains(zero_width, "png_zero_width.png: invalid PNG: "));
  BOOST_TEST(contains(zero_width, "width is zero"));
  BOOST_TEST(contains(no_end, "png_no_iend.png: invalid PNG: the file ends before its IEND chunk"));
  BOOST_TEST(contains(cut, "png_cut.png: invalid PNG: "));
}
