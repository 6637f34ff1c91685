// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The command-line tool: argument parsing on its own, then the built tool run end to end (exit status,
// the one-line messages, the files it writes and does not write).

#define BOOST_TEST_MODULE Aniso_conformal_cli
#include <boost/test/unit_test.hpp>

#include "../tools/command_line.h"

#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/make_dupin_cyclide.h>
#include <Aniso_conformal/make_ellipsoid.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace {

const std::string tool = ANISO_CONFORMAL_TOOL;
const std::string out_dir = ANISO_CONFORMAL_TEST_OUTPUT_DIR;
const std::string data_dir = ANISO_CONFORMAL_DATA_DIR;

struct Run {
  int status = -1;
  std::string out, err;
};

std::string slurp(const std::string& path)
{
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

Run run(const std::string& args)
{
  const std::string o = out_dir + "/cli_stdout.txt", e = out_dir + "/cli_stderr.txt";
  const int rc = std::system((tool + " " + args + " > " + o + " 2> " + e).c_str());
  Run r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp(o);
  r.err = slurp(e);
  return r;
}

bool exists(const std::string& p) { return std::ifstream(p).good(); }

void write_file(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

aniso_remesh::Options parse(std::vector<std::string> a) { return aniso_remesh::parse_command_line(a); }

std::string parse_error(std::vector<std::string> a)
{
  try { aniso_remesh::parse_command_line(a); } catch(const Aniso_conformal::Invalid_input& e) { return e.what(); }
  return "(accepted)";
}

} // namespace

BOOST_AUTO_TEST_CASE(parser_reads_options_and_defaults)
{
  const auto o = parse({"--domain", "square", "--metric", "fig6", "--vertices", "1000", "--seed", "3", "--cvt", "lloyd"});
  BOOST_TEST(o.domain == "square");
  BOOST_TEST(o.metric == "fig6");
  BOOST_TEST(o.vertices == 1000);
  BOOST_TEST(o.seed == 3u);
  BOOST_TEST(o.cvt == "lloyd");
  BOOST_TEST(o.iterations == 100);
  const auto d = parse({"--input", "a.off", "--vertices", "10"});
  BOOST_TEST(d.metric == "isotropic");
  BOOST_TEST(parse({"--help"}).help);
}

BOOST_AUTO_TEST_CASE(parser_rejects_bad_command_lines)
{
  BOOST_TEST(parse_error({"--vertices", "10"}).find("exactly one of --input") != std::string::npos);
  BOOST_TEST(parse_error({"--domain", "square"}).find("--vertices N is required") != std::string::npos);
  BOOST_TEST(parse_error({"--domain", "square", "--vertices", "2"}).find("at least 3") != std::string::npos);
  BOOST_TEST(parse_error({"--domain", "square", "--vertices", "ten"}).find("not an integer") != std::string::npos);
  BOOST_TEST(parse_error({"--domain", "disk", "--vertices", "10"}).find("unknown domain") != std::string::npos);
  BOOST_TEST(parse_error({"--domain", "square", "--vertices", "10", "--bogus"}).find("unknown option '--bogus'") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--domain", "square", "--vertices"}).find("needs a value") != std::string::npos);
  BOOST_TEST(parse_error({"--domain", "square", "--vertices", "10", "--metric", "weird"}).find("unknown metric") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--domain", "square", "--vertices", "10", "--metric-file", "m.txt"}).find("needs --input") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--domain", "square", "--vertices", "10", "--metric", "curvature"}).find("needs a surface") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--input", "a.off", "--vertices", "10", "--stretch-max", "nan"}).find("not a finite number") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--input", "a.off", "--vertices", "10", "--stretch-max", "0.5"}).find("at least 1") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--image", "a.png", "--vertices", "10", "--metric", "fig6"}).find("its own metric") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--input", "a.off", "--vertices", "10", "--anisotropy", "0.1"}).find("--image only") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--input", "a.off", "--vertices", "10", "--cvt", "newton"}).find("lloyd or lbfgs") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--input", "a.off", "--vertices", "99999999999999999999"}).find("not an integer") !=
             std::string::npos);
}

BOOST_AUTO_TEST_CASE(tool_remeshes_the_square_and_writes_its_outputs)
{
  const std::string mesh = out_dir + "/cli_fig6.off", report = out_dir + "/cli_fig6.json", svg = out_dir + "/cli_fig6.svg",
                    hist = out_dir + "/cli_fig6_hist.svg";
  for(const auto& f : {mesh, report, svg, hist}) std::remove(f.c_str());
  const Run r = run("--domain square --metric fig6 --vertices 300 --iterations 50 --output " + mesh + " --report " +
                    report + " --svg " + svg + " --histogram " + hist);
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.find("G_avg") != std::string::npos);
  std::ifstream f(mesh);
  std::string magic;
  std::size_t nv = 0, nf = 0, ne = 0;
  f >> magic >> nv >> nf >> ne;
  BOOST_TEST(magic == "OFF");
  BOOST_TEST(nv == 300u);
  const std::string json = slurp(report);
  for(const char* key : {"\"G_avg\"", "\"theta_min\"", "\"angle_histogram\"", "\"flips\"", "\"splits\"",
                         "\"newton_iterations\"", "\"residual\"", "\"energy\"", "\"seconds\"", "\"metric_edge_length\""})
    BOOST_TEST(json.find(key) != std::string::npos, "report has " << key);
  BOOST_TEST(slurp(svg).find("<svg") != std::string::npos);
  BOOST_TEST(slurp(hist).find("<svg") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(tool_bad_input_exits_2_with_a_message)
{
  Run r = run("--domain square --vertices 2");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("at least 3") != std::string::npos);

  r = run("--input " + out_dir + "/does_not_exist.off --vertices 10");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("does_not_exist.off") != std::string::npos);

  // a metric file with the wrong number of rows
  const std::string square = out_dir + "/cli_square.off", metric = out_dir + "/cli_bad.metric";
  write_file(square, "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  write_file(metric, "3\n1 0 0 1 0 0\n1 0 0 1 0 0\n1 0 0 1 0 0\n");
  r = run("--input " + square + " --metric-file " + metric + " --vertices 4");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("4") != std::string::npos);

  // a NaN tensor names the line or vertex
  write_file(metric, "4\n1 0 0 1 0 0\n1 0 0 1 0 0\nnan 0 0 1 0 0\n1 0 0 1 0 0\n");
  r = run("--input " + square + " --metric-file " + metric + " --vertices 4");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("non-finite") != std::string::npos);

  // an indefinite tensor
  write_file(metric, "4\n1 0 0 1 0 0\n1 0 0 -1 0 0\n1 0 0 1 0 0\n1 0 0 1 0 0\n");
  r = run("--input " + square + " --metric-file " + metric + " --vertices 4");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("vertex 1") != std::string::npos);

  // more vertices than the background can carry
  r = run("--input " + square + " --vertices 50");
  BOOST_TEST(r.status == 3);  // a valid input this version cannot remesh
  BOOST_TEST(r.err.find("exceed") != std::string::npos);

  // a closed surface does not fit the plane
  const std::string tetra = out_dir + "/cli_tetra.off";
  write_file(tetra, "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
  r = run("--input " + tetra + " --vertices 4 --domain plane");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("closed surface of genus 0") != std::string::npos);

  // an unreadable image
  write_file(out_dir + "/cli_bad.png", "this is not a png");
  r = run("--image " + out_dir + "/cli_bad.png --vertices 100");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("cli_bad.png") != std::string::npos);

  // every message is one line
  BOOST_TEST(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

BOOST_AUTO_TEST_CASE(unwritable_output_exits_2_and_leaves_no_file)
{
  const std::string dir = out_dir + "/no_such_dir/";
  const Run r = run("--domain square --vertices 50 --iterations 5 --output " + dir + "out.off");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("out.off") != std::string::npos);
  BOOST_TEST(!exists(dir + "out.off"));
}

BOOST_AUTO_TEST_CASE(same_seed_same_file)
{
  const std::string a = out_dir + "/cli_seed_a.off", b = out_dir + "/cli_seed_b.off";
  BOOST_TEST(run("--domain square --metric fig7 --vertices 200 --iterations 30 --seed 5 --output " + a).status == 0);
  BOOST_TEST(run("--domain square --metric fig7 --vertices 200 --iterations 30 --seed 5 --output " + b).status == 0);
  BOOST_TEST(slurp(a) == slurp(b));
  BOOST_TEST(!slurp(a).empty());
}

BOOST_AUTO_TEST_CASE(tool_remeshes_a_genus_one_surface_on_the_flat_torus)
{
  // the domain is chosen from the topology; --domain is checked against it
  const aniso_remesh::Options o = parse({"--input", "t.off", "--domain", "flat-torus", "--vertices", "10"});
  BOOST_TEST(o.input == "t.off");
  BOOST_TEST(o.domain.empty());
  BOOST_TEST((o.parametric_domain == Aniso_conformal::Parametric_domain::FLAT_TORUS));
  BOOST_TEST(parse_error({"--domain", "flat-torus", "--vertices", "10"}).find("give --input") != std::string::npos);
  BOOST_TEST(parse_error({"--input", "t.off", "--domain", "donut", "--vertices", "10"}).find("unknown domain") != std::string::npos);

  const std::string in = out_dir + "/cli_cyclide.off", mesh = out_dir + "/cli_cyclide_out.off", report = out_dir + "/cli_cyclide.json";
  const Aniso_conformal::Input_surface cyclide = Aniso_conformal::make_dupin_cyclide(48, 32);
  Aniso_conformal::IO::write_polygon_soup(in, cyclide.points(), cyclide.faces());
  std::remove(mesh.c_str());
  const Run r = run("--input " + in + " --metric curvature --stretch-max 29 --vertices 500 --output " + mesh + " --report " + report);
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.find("domain flat-torus") != std::string::npos);
  BOOST_TEST(r.out.find("Hausdorff distance") != std::string::npos);
  const Aniso_conformal::Input_surface out = Aniso_conformal::IO::read_triangle_mesh(mesh);
  BOOST_TEST(out.number_of_vertices() == 500u);
  BOOST_TEST(out.genus() == 1);
  BOOST_TEST(out.boundary_loops().empty());
  const std::string json = slurp(report);
  BOOST_TEST(json.find("\"domain\": \"flat-torus\"") != std::string::npos);
  BOOST_TEST(json.find("\"lattice\"") != std::string::npos);
  BOOST_TEST(json.find("\"hausdorff_distance\"") != std::string::npos);

  // a domain that does not fit: exit 2, the message names both
  std::remove(mesh.c_str());
  const Run bad = run("--input " + in + " --domain plane --vertices 500 --output " + mesh);
  BOOST_TEST(bad.status == 2);
  BOOST_TEST(bad.err.find("plane domain does not fit") != std::string::npos);
  BOOST_TEST(bad.err.find("genus 1") != std::string::npos);
  BOOST_TEST(!exists(mesh));
}

BOOST_AUTO_TEST_CASE(tool_remeshes_a_genus_two_surface_in_the_hyperbolic_disk)
{
  BOOST_TEST((parse({"--input", "e.off", "--domain", "hyperbolic", "--vertices", "10"}).parametric_domain ==
              Aniso_conformal::Parametric_domain::HYPERBOLIC));
  const std::string in = std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/eight_1k.off", mesh = out_dir + "/cli_eight_out.off",
                    report = out_dir + "/cli_eight.json";
  std::remove(mesh.c_str());
  const Run r = run("--input " + in + " --metric curvature --stretch-max 5 --vertices 300 --output " + mesh + " --report " + report);
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.find("domain hyperbolic") != std::string::npos);
  BOOST_TEST(r.out.find("group relations hold") != std::string::npos);
  const Aniso_conformal::Input_surface out = Aniso_conformal::IO::read_triangle_mesh(mesh);
  BOOST_TEST(out.number_of_vertices() == 300u);
  BOOST_TEST(out.genus() == 2);
  BOOST_TEST(out.boundary_loops().empty());
  const std::string json = slurp(report);
  BOOST_TEST(json.find("\"domain\": \"hyperbolic\"") != std::string::npos);
  BOOST_TEST(json.find("\"group_relation_error\"") != std::string::npos);

  // the sphere does not fit a genus-2 surface: exit 2, nothing written
  std::remove(mesh.c_str());
  const Run bad = run("--input " + in + " --domain sphere --vertices 300 --output " + mesh);
  BOOST_TEST(bad.status == 2);
  BOOST_TEST(bad.err.find("sphere domain does not fit") != std::string::npos);
  BOOST_TEST(bad.err.find("genus 2") != std::string::npos);
  BOOST_TEST(!exists(mesh));
}

BOOST_AUTO_TEST_CASE(tool_remeshes_a_genus_zero_surface_on_the_sphere)
{
  BOOST_TEST((parse({"--input", "e.off", "--domain", "sphere", "--vertices", "10"}).parametric_domain ==
              Aniso_conformal::Parametric_domain::SPHERE));

  const std::string in = out_dir + "/cli_ellipsoid.off", mesh = out_dir + "/cli_ellipsoid_out.off",
                    report = out_dir + "/cli_ellipsoid.json";
  const Aniso_conformal::Input_surface ellipsoid = Aniso_conformal::make_ellipsoid(3);
  Aniso_conformal::IO::write_polygon_soup(in, ellipsoid.points(), ellipsoid.faces());
  std::remove(mesh.c_str());
  const Run r = run("--input " + in + " --metric curvature --stretch-max 10 --vertices 300 --output " + mesh + " --report " + report);
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.find("domain sphere") != std::string::npos);
  BOOST_TEST(r.out.find("angle distortion") != std::string::npos);
  const Aniso_conformal::Input_surface out = Aniso_conformal::IO::read_triangle_mesh(mesh);
  BOOST_TEST(out.number_of_vertices() == 300u);
  BOOST_TEST(out.genus() == 0);
  BOOST_TEST(out.boundary_loops().empty());
  const std::string json = slurp(report);
  BOOST_TEST(json.find("\"domain\": \"sphere\"") != std::string::npos);
  BOOST_TEST(json.find("\"angle_distortion_mean_degrees\"") != std::string::npos);

  // the flat torus does not fit a genus-0 surface: exit 2, nothing written
  std::remove(mesh.c_str());
  const Run bad = run("--input " + in + " --domain flat-torus --vertices 300 --output " + mesh);
  BOOST_TEST(bad.status == 2);
  BOOST_TEST(bad.err.find("flat-torus domain does not fit") != std::string::npos);
  BOOST_TEST(bad.err.find("genus 0") != std::string::npos);
  BOOST_TEST(!exists(mesh));
}
