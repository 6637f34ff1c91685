// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The command-line tool: argument parsing on its own (CLI11), then the built tool run end to end (exit
// status 0/1/2/3, the one-line printable messages, the files it writes and does not write, the JSON report
// read back with nlohmann-json).

#define BOOST_TEST_MODULE Aniso_conformal_cli
#include <boost/test/unit_test.hpp>

#include "../tools/command_line.h"

#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/make_dupin_cyclide.h>
#include <Aniso_conformal/make_ellipsoid.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

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
  // per process: CTest runs the cow's case (test_cli_cones) beside the others, two processes of this module
  const std::string pid = std::to_string(long(getpid()));
  const std::string o = out_dir + "/cli_stdout_" + pid + ".txt", e = out_dir + "/cli_stderr_" + pid + ".txt";
  const int rc = std::system((tool + " " + args + " > " + o + " 2> " + e).c_str());
  Run r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp(o);
  r.err = slurp(e);
  std::remove(o.c_str());
  std::remove(e.c_str());
  return r;
}

bool exists(const std::string& p) { return std::ifstream(p).good(); }

void write_file(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(slurp(path)); }

// one line of printable ASCII: what the tool may print about any input
bool printable_line(const std::string& s)
{
  if(s.empty() || s.back() != '\n') return false;
  return std::all_of(s.begin(), s.end() - 1, [](char c) { return c >= 0x20 && c < 0x7f; });
}

// `n` bytes of binary garbage (every byte value, NUL, newlines, an escape sequence), the same on every run
std::string garbage(std::size_t n, unsigned seed)
{
  std::mt19937 random(seed);
  std::string g(n, '\0');
  for(char& c : g) c = char(random() & 0xff);
  g[3] = '\x1b';  // an ANSI escape
  g[10] = '\n';
  return g;
}

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
  BOOST_TEST(d.stretch_max == 10.0);
  BOOST_TEST(d.threads == 0u);
  BOOST_TEST(d.anisotropy == -1.0);
  BOOST_TEST(d.surface_optimization == "repair");
  BOOST_TEST(parse({"--input", "a.off", "--vertices", "10", "--surface-optimization", "always"}).surface_optimization == "always");
  BOOST_TEST(parse({"--help"}).help);
  BOOST_TEST(parse({"-h"}).help);
  BOOST_TEST(parse({"--version"}).version);
  // --help needs no other option and wins over bad ones
  BOOST_TEST(parse({"--vertices", "2", "--help"}).help);
  // integers are decimal (CLI11 alone would read "010" as octal); a repeated option keeps its last value
  const auto z = parse({"--input", "a.off", "--vertices", "010", "--seed", "4294967295", "--vertices", "0012"});
  BOOST_TEST(z.vertices == 12);
  BOOST_TEST(z.seed == 4294967295u);
  // reals are read by strtod, correctly rounded (CLI11's strtold rounds this one twice, one ulp off)
  BOOST_TEST(parse({"--image", "a.png", "--vertices", "10", "--anisotropy", "0.002877"}).anisotropy == 0.002877);
  BOOST_TEST(parse({"--input", "a.off", "--vertices", "10", "--corner-angle", "0"}).corner_angle == 0.0);
  BOOST_TEST(d.curvature_sizing == "cones");
  BOOST_TEST(parse({"--input", "a.off", "--vertices", "10", "--curvature-sizing", "always"}).curvature_sizing == "always");
  BOOST_TEST(parse_error({"--input", "a.off", "--vertices", "10", "--curvature-sizing", "sometimes"}).find("--curvature-sizing") !=
             std::string::npos);
}

// the curvature metric is built from the command line: every option that concerns it reaches it (before
// this test, --feature-angle, --no-features and --threads did not: the metric's smoothing stopped at
// 60-degree edges whatever the remeshing took as a crease)
BOOST_AUTO_TEST_CASE(curvature_metric_options_follow_the_command_line)
{
  const Aniso_conformal::Curvature_metric_options library;
  const auto d = aniso_remesh::curvature_metric_options(parse({"--input", "a.off", "--vertices", "500", "--metric", "curvature"}));
  BOOST_TEST(d.stretch_max == 10.0);
  BOOST_TEST(d.smoothing_iterations == library.smoothing_iterations);
  BOOST_TEST(d.smoothing_rings == library.smoothing_rings);
  BOOST_TEST(d.scale_smoothing_iterations == library.scale_smoothing_iterations);
  BOOST_TEST(d.gradation == library.gradation);
  BOOST_TEST(d.gradation_vertices == 500u);  // the gradation's lengths are the output's
  BOOST_TEST(d.feature_angle == library.feature_angle);
  BOOST_TEST(d.number_of_threads == 0u);
  const auto o = aniso_remesh::curvature_metric_options(
    parse({"--input", "a.off", "--vertices", "700", "--metric", "curvature", "--stretch-max", "30", "--smoothing-iterations", "3",
           "--smoothing-rings", "1", "--scale-smoothing-iterations", "0", "--gradation", "0", "--feature-angle", "35", "--threads", "1"}));
  BOOST_TEST(o.stretch_max == 30.0);
  BOOST_TEST(o.smoothing_iterations == 3);
  BOOST_TEST(o.smoothing_rings == 1);
  BOOST_TEST(o.scale_smoothing_iterations == 0);
  BOOST_TEST(o.gradation == 0.0);
  BOOST_TEST(o.gradation_vertices == 700u);
  BOOST_TEST(o.feature_angle == 35.0);
  BOOST_TEST(o.number_of_threads == 1u);
  // --no-features: no edge is a crease, for the metric's smoothing either
  BOOST_TEST(aniso_remesh::curvature_metric_options(
               parse({"--input", "a.off", "--vertices", "10", "--metric", "curvature", "--no-features"})).feature_angle == 180.0);
  // and the remeshing's sharp features take the same angle (one function for both)
  BOOST_TEST(aniso_remesh::feature_angle(parse({"--input", "a.off", "--vertices", "10", "--no-features"})) == 180.0);
  BOOST_TEST(aniso_remesh::feature_angle(parse({"--input", "a.off", "--vertices", "10", "--feature-angle", "35"})) == 35.0);
  BOOST_TEST(aniso_remesh::feature_angle(parse({"--input", "a.off", "--vertices", "10"})) == 60.0);
}

BOOST_AUTO_TEST_CASE(parser_rejects_bad_command_lines)
{
  // each refusal is one line naming the option and the problem: CLI11's for one option or a pair, ours
  // for what CLI11 cannot say (inputs, --domain, options that apply to one kind of input)
  auto refused = [](std::vector<std::string> args, const std::string& part) {
    const std::string m = parse_error(args);
    BOOST_TEST_INFO("message: " << m);
    return m.find(part) != std::string::npos && m.find('\n') == std::string::npos;
  };
  BOOST_TEST(refused({"--vertices", "10"}, "give exactly one of --input, --domain square, --image"));
  BOOST_TEST(refused({"--input", "a.off", "--domain", "square", "--vertices", "10"}, "give exactly one of --input"));
  BOOST_TEST(refused({"--input", "a.off", "--image", "a.png", "--vertices", "10"}, "--input excludes --image"));
  BOOST_TEST(refused({"--domain", "square"}, "--vertices is required"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "2"}, "--vertices: Value 2 not in range 3 to 100000000"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "ten"}, "--vertices: 'ten' is not an integer"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "0x10"}, "'0x10' is not an integer"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "10", "--iterations", "1.5"}, "--iterations: '1.5' is not an integer"));
  BOOST_TEST(refused({"--domain", "disk", "--vertices", "10"}, "--domain: disk not in {square,"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "10", "--bogus"}, "not expected: --bogus"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "10", "stray"}, "not expected: stray"));
  BOOST_TEST(refused({"--domain", "square", "--vertices"}, "--vertices: 1 required"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "10", "--metric", "weird"}, "--metric: weird not in {curvature,fig6,fig7,isotropic}"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "10", "--surface-optimization", "sometimes"}, "--surface-optimization: sometimes not in"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--metric", "fig6", "--metric-file", "m.txt"},
                     "--metric excludes --metric-file"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "10", "--metric-file", "m.txt"}, "--metric-file requires --input"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "10", "--metric", "curvature"}, "--metric curvature needs a surface"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--stretch-max", "nan"}, "--stretch-max: 'nan' is not a finite number"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--stretch-max", "1e400"}, "'1e400' is not a finite number"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--stretch-max", "0.5"}, "--stretch-max: must be at least 1"));
  BOOST_TEST(refused({"--image", "a.png", "--vertices", "10", "--metric", "fig6"}, "--image excludes --metric"));
  BOOST_TEST(refused({"--image", "a.png", "--vertices", "10", "--metric-file", "m"}, "--image excludes --metric-file"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--anisotropy", "0.1"}, "--anisotropy requires --image"));
  BOOST_TEST(refused({"--image", "a.png", "--vertices", "10", "--anisotropy", "-1"}, "--anisotropy: must be positive"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--cvt", "newton"}, "--cvt: newton not in {lloyd,lbfgs}"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--corner-angle", "180"}, "--corner-angle: must be in [0, 180)"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--threads", "2000"}, "--threads: Value 2000 not in range 0 to 1024"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--seed", "-1"}, "--seed: Value -1 not in range 0 to 4294967295"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "10", "--background-vertices", "500"},
                     "--background-vertices applies to --domain square only"));
  BOOST_TEST(refused({"--input", "a.off", "--vertices", "99999999999999999999"}, "not in range 3 to 100000000"));
  BOOST_TEST(refused({"--domain", "square", "--vertices", "10", "--no-repair"}, "--no-repair requires --input"));
  BOOST_TEST(parse({"--input", "a.off", "--vertices", "10", "--no-repair"}).no_repair);
  BOOST_TEST(!parse({"--input", "a.off", "--vertices", "10"}).no_repair);
}

BOOST_AUTO_TEST_CASE(help_and_usage_document_the_options_and_exit_codes)
{
  const std::string u = aniso_remesh::usage();
  for(const char* part : {"usage: aniso_remesh (--input FILE | --domain square | --image FILE) --vertices N",
                          "--metric-file", "--stretch-max", "--corner-angle", "--histogram", "--no-repair", "exit status",
                          "  0  success", "  1  internal failure", "  2  bad input", "  3  valid input that this version cannot remesh"}) {
    BOOST_TEST_INFO("help has '" << part << "'");
    BOOST_TEST(u.find(part) != std::string::npos);
  }
  // the tool prints it on stdout and exits 0; --version likewise
  Run r = run("--help");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out == u);
  BOOST_TEST(r.err.empty());
  r = run("--version");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out == std::string(aniso_remesh::version_line()) + "\n");
  // a bad command line: exit 2, the message on stderr, nothing on stdout
  r = run("--domain square --vertices 10 --bogus");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.out.empty());
  BOOST_TEST(r.err.find("aniso_remesh: error: ") == 0u);
  BOOST_TEST(r.err.find("(see --help)") != std::string::npos);
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
  const nlohmann::json j = read_json(report);
  // the tool's own fields
  BOOST_TEST(j.at("input_name") == "square");
  BOOST_TEST(j.at("requested_vertices") == 300);
  BOOST_TEST(j.at("seed") == 0);
  BOOST_TEST(j.at("background_seconds").get<double>() >= 0);
  // the result's
  BOOST_TEST(j.at("domain") == "plane");
  BOOST_TEST(j.at("output").at("vertices") == 300);
  const std::size_t triangles = j.at("output").at("triangles");
  BOOST_TEST(j.at("output").at("corners") == 4);
  BOOST_TEST(j.at("output").at("inverted_triangles") == 0);
  BOOST_TEST(j.at("background").at("vertices").get<std::size_t>() >= j.at("input").at("vertices").get<std::size_t>());
  const nlohmann::json& q = j.at("quality");
  BOOST_TEST((q.at("G_min").get<double>() > 0 && q.at("G_min") <= q.at("G_avg") && q.at("G_avg").get<double>() <= 1));
  BOOST_TEST((q.at("theta_min").get<double>() > 0 && q.at("theta_min") <= q.at("theta_avg") && q.at("theta_avg") <= q.at("theta_max")));
  BOOST_TEST(q.at("angle_histogram").at("bin_width_degrees") == 5.0);
  double angles = 0;
  for(double c : q.at("angle_histogram").at("counts")) angles += c;
  BOOST_TEST(angles == 3.0 * double(triangles));
  BOOST_TEST(q.at("metric_edge_length").at("normalized_min") <= q.at("metric_edge_length").at("normalized_max"));
  // the realised anisotropy: Fig. 6's metric has stretch up to 33 (s1 = 1, s2 = 1 / (0.031 + y)), 1 nowhere inside
  const nlohmann::json& st = q.at("metric_stretch");
  BOOST_TEST((st.at("min").get<double>() >= 1 && st.at("min") <= st.at("median") && st.at("median") <= st.at("p95") &&
              st.at("p95") <= st.at("max")));
  BOOST_TEST(st.at("max").get<double>() > 10);
  BOOST_TEST(st.at("max").get<double>() <= 1.031 / 0.031 + 1e-6);
  BOOST_TEST(q.at("metric_edge_length").at("mean").get<double>() > 0);
  BOOST_TEST(r.out.find("metric stretch at the vertices") != std::string::npos);
  BOOST_TEST(j.at("edge_adjustment").at("flips").is_number_unsigned());
  BOOST_TEST(j.at("edge_adjustment").at("splits").is_number_unsigned());
  BOOST_TEST(j.at("conformal_embedding").at("newton_iterations").get<int>() > 0);
  BOOST_TEST(j.at("conformal_embedding").at("residual").get<double>() < 1e-6);
  BOOST_TEST(j.at("cvt").at("method") == "lbfgs");
  BOOST_TEST(j.at("cvt").at("iterations").get<int>() <= 50);
  BOOST_TEST(j.at("cvt").at("energy").size() == j.at("cvt").at("energy_evaluations").get<std::size_t>());
  BOOST_TEST(j.at("cvt").at("energy").front() >= j.at("cvt").at("energy").back());
  double stages = 0;
  for(const char* stage : {"metric", "edge_lengths", "embedding", "cvt", "dual_mesh", "surface_optimization", "quality", "discarded"})
    stages += j.at("seconds").at(stage).get<double>();
  BOOST_TEST(std::abs(stages - j.at("seconds").at("total").get<double>()) < 1e-6);

  BOOST_TEST(slurp(svg).find("<svg") != std::string::npos);
  BOOST_TEST(slurp(hist).find("<svg") != std::string::npos);
  // nothing was repaired: no summary line, no report object
  BOOST_TEST(r.out.find("repairs") == std::string::npos);
  BOOST_TEST(!j.contains("repairs"));
  // a planar input: the default surface optimisation runs as `always` (since 2026-12-06; before, on this
  // output without an inverted triangle or one below 30 degrees, it did not run), sides sliding
  BOOST_TEST(r.out.find("optimised    on the surface (both phases): ") != std::string::npos);
  BOOST_TEST(j.at("surface_optimization").at("ran") == true);
  BOOST_TEST(j.at("surface_optimization").at("second_phase") == true);
  BOOST_TEST(j.at("surface_optimization").at("sliding_vertices").get<std::size_t>() > 0u);
  BOOST_TEST(j.at("surface_optimization").at("G_avg_after").get<double>() >= j.at("surface_optimization").at("G_avg_before").get<double>());
}

BOOST_AUTO_TEST_CASE(tool_optimises_on_the_surface_when_asked)
{
  const std::string report = out_dir + "/cli_fig6_optimised.json";
  std::remove(report.c_str());
  const Run r = run("--domain square --metric fig6 --vertices 300 --iterations 50 --surface-optimization always --report " + report);
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.find("optimised    on the surface (both phases): ") != std::string::npos);
  const nlohmann::json j = read_json(report);
  const nlohmann::json& so = j.at("surface_optimization");
  BOOST_TEST(so.at("ran") == true);
  BOOST_TEST(so.at("second_phase") == true);
  // the square's boundary vertices: its 4 corners fixed, the others slide along its sides
  BOOST_TEST(so.at("fixed_vertices").get<std::size_t>() + so.at("sliding_vertices").get<std::size_t>() ==
             j.at("output").at("boundary_vertices").get<std::size_t>());
  BOOST_TEST(so.at("fixed_vertices") == 4);
  BOOST_TEST(r.out.find("boundary vertices free to slide") != std::string::npos);
  BOOST_TEST(so.at("inverted_after") == 0);
  BOOST_TEST(so.at("G_avg_after") == j.at("quality").at("G_avg"));
  BOOST_TEST(so.at("G_avg_after").get<double>() >= so.at("G_avg_before").get<double>());
  BOOST_TEST(so.at("theta_min_after").get<double>() >= so.at("theta_min_before").get<double>());
  BOOST_TEST(j.at("output").at("vertices") == 300);
}

BOOST_AUTO_TEST_CASE(tool_bad_input_exits_2_with_a_message)
{
  Run r = run("--domain square --vertices 2");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("not in range 3 to") != std::string::npos);

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

  // more output vertices than the input has: the background is refined (issue 14)
  r = run("--input " + square + " --vertices 50 --output " + out_dir + "/cli_square_50.off");
  BOOST_TEST(r.status == 0, r.err);

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
  BOOST_TEST(parse_error({"--input", "t.off", "--domain", "donut", "--vertices", "10"}).find("--domain: donut not in {square,") !=
             std::string::npos);

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
  const nlohmann::json j = read_json(report);
  BOOST_TEST(j.at("domain") == "flat-torus");
  // the lattice basis, a 2 x 2 matrix by rows, of positive area
  const nlohmann::json& lattice = j.at("conformal_embedding").at("lattice");
  BOOST_REQUIRE((lattice.size() == 2u && lattice[0].size() == 2u && lattice[1].size() == 2u));
  const double area = lattice[0][0].get<double>() * lattice[1][1].get<double>() - lattice[0][1].get<double>() * lattice[1][0].get<double>();
  BOOST_TEST(std::abs(area) > 0);
  BOOST_TEST(j.at("output").at("vertices") == 500);
  BOOST_TEST(j.at("output").at("hausdorff_distance").get<double>() >= 0);
  BOOST_TEST(j.at("output").at("hausdorff_distance_relative").get<double>() < 0.1);

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
  const nlohmann::json j = read_json(report);
  BOOST_TEST(j.at("domain") == "hyperbolic");
  BOOST_TEST(j.at("conformal_embedding").at("group_relation_error").get<double>() < 1e-6);
  BOOST_TEST(j.at("conformal_embedding").at("group_elements").is_number_integer());
  BOOST_TEST(j.at("conformal_embedding").at("group_elements").get<int>() > 1);

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
  const nlohmann::json j = read_json(report);
  BOOST_TEST(j.at("domain") == "sphere");
  const double mean = j.at("conformal_embedding").at("angle_distortion_mean_degrees"),
               max = j.at("conformal_embedding").at("angle_distortion_max_degrees");
  BOOST_TEST((mean >= 0 && mean <= max && max < 90));

  // the flat torus does not fit a genus-0 surface: exit 2, nothing written
  std::remove(mesh.c_str());
  const Run bad = run("--input " + in + " --domain flat-torus --vertices 300 --output " + mesh);
  BOOST_TEST(bad.status == 2);
  BOOST_TEST(bad.err.find("flat-torus domain does not fit") != std::string::npos);
  BOOST_TEST(bad.err.find("genus 0") != std::string::npos);
  BOOST_TEST(!exists(mesh));
}

BOOST_AUTO_TEST_CASE(tool_remeshes_the_cow_through_cones)
{
  BOOST_TEST((parse({"--input", "e.off", "--domain", "cones", "--vertices", "10"}).parametric_domain ==
              Aniso_conformal::Parametric_domain::CONE));
  // the cow's legs and tail are too long for the sphere: the automatic choice goes to cones and says why
  const std::string in = data_dir + "/meshes/cow.off", mesh = out_dir + "/cli_cow_out.off", report = out_dir + "/cli_cow.json";
  std::remove(mesh.c_str());
  const Run r = run("--input " + in + " --no-features --vertices 1500 --output " + mesh + " --report " + report);
  BOOST_TEST(r.status == 0, r.err);
  BOOST_TEST(r.out.find("domain       cones, because the sphere failed") != std::string::npos);
  BOOST_TEST(r.out.find("(domain cones)") != std::string::npos);
  BOOST_TEST(r.out.find("area distortion") != std::string::npos);
  // the cone domain's default curvature sizing refines the tips (summary and report)
  BOOST_TEST(r.out.find("metric       curvature sizing: the surface bends with a radius down to") != std::string::npos, r.out);
  const Aniso_conformal::Input_surface out = Aniso_conformal::IO::read_triangle_mesh(mesh);
  BOOST_TEST(out.number_of_vertices() == 1500u);
  BOOST_TEST(out.genus() == 0);
  BOOST_TEST(out.boundary_loops().empty());
  const nlohmann::json j = read_json(report);
  BOOST_TEST(j.at("domain") == "cones");
  BOOST_TEST(std::string(j.at("domain_choice")).find("the sphere failed") != std::string::npos);
  BOOST_TEST(double(j.at("conformal_embedding").at("cones")) >= 4);
  BOOST_TEST(j.at("feature_sizing").at("curved_points").get<std::size_t>() > 0u);

  // a surface with holes goes through cones with its holes patched: both loops kept
  const std::string annulus = std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cases/annulus.off";
  std::remove(mesh.c_str());
  const Run holes = run("--input " + annulus + " --domain cones --vertices 300 --output " + mesh);
  BOOST_TEST(holes.status == 0);
  BOOST_TEST(holes.out.find("(domain cones)") != std::string::npos);
  const Aniso_conformal::Input_surface ring = Aniso_conformal::IO::read_triangle_mesh(mesh);
  BOOST_TEST(ring.number_of_vertices() == 300u);
  BOOST_TEST(ring.boundary_loops().size() == 2u);
  // a disk is not for cones (the plane takes it): exit 2, nothing written
  const std::string disk = std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cases/hip_roof.off";
  std::remove(mesh.c_str());
  const Run bad = run("--input " + disk + " --domain cones --vertices 300 --output " + mesh);
  BOOST_TEST(bad.status == 2);
  BOOST_TEST(bad.err.find("cones domain does not fit") != std::string::npos);
  BOOST_TEST(!exists(mesh));
}

BOOST_AUTO_TEST_CASE(garbage_files_exit_2_with_a_printable_one_line_message)
{
  // binary garbage as every kind of input file: exit 2, one line of printable ASCII on stderr (no raw
  // byte of the file reaches the terminal), nothing on stdout
  const std::string square = out_dir + "/cli_garbage_square.off";
  write_file(square, "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  const std::string off = out_dir + "/cli_garbage.off", obj = out_dir + "/cli_garbage.obj", ply = out_dir + "/cli_garbage.ply",
                    off_token = out_dir + "/cli_garbage_token.off", metric = out_dir + "/cli_garbage.metric",
                    metric_row = out_dir + "/cli_garbage_row.metric", image = out_dir + "/cli_garbage.img",
                    png = out_dir + "/cli_garbage.png", pgm = out_dir + "/cli_garbage.pgm";
  write_file(off, garbage(3000, 1));
  write_file(obj, garbage(3000, 2));
  write_file(ply, "ply\nformat ascii 1.0\n" + garbage(3000, 3));
  std::string token = garbage(60, 9).substr(12);
  std::replace_if(token.begin(), token.end(), [](char c) { return c == '\0' || std::isspace(static_cast<unsigned char>(c)) || c == '#'; }, '\x7f');
  write_file(off_token, "OFF\n3 1 0\n0 0 0\n1 " + token + " 0\n0 1 0\n3 0 1 2\n");
  write_file(metric, garbage(3000, 4));
  write_file(metric_row, "4\n1 0 0 1 0 0\n" + garbage(3000, 5));
  write_file(image, garbage(3000, 6));
  write_file(png, "\x89PNG\r\n\x1a\n" + garbage(3000, 7));
  write_file(pgm, "P5\n" + garbage(3000, 8));
  const std::vector<std::pair<std::string, std::string>> cases = {
    {"--input " + off, "cli_garbage.off"},
    {"--input " + off_token, "is not a number"},
    {"--input " + obj, "cli_garbage.obj"},
    {"--input " + ply, "cli_garbage.ply"},
    {"--input " + square + " --metric-file " + metric, "cli_garbage.metric"},
    {"--input " + square + " --metric-file " + metric_row, "is not a number"},
    {"--image " + image, "not a PNG, PGM or PPM file"},
    {"--image " + png, "invalid PNG"},
    {"--image " + pgm, "cli_garbage.pgm"}};
  for(const auto& [args, part] : cases) {
    const Run r = run(args + " --vertices 10");
    BOOST_TEST_INFO(args << " -> " << r.err);
    BOOST_TEST(r.status == 2);
    BOOST_TEST(printable_line(r.err));
    BOOST_TEST(r.err.find(part) != std::string::npos);
    BOOST_TEST(r.out.empty());
  }
  // a quoted token is escaped and cut: \xNN for its bytes, at most 40 of them, then "..."
  const Run r = run("--input " + off_token + " --vertices 10");
  BOOST_TEST(r.err.find("\\x7f") != std::string::npos);
  BOOST_TEST(r.err.find("...' is not a number") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(tool_remeshes_an_annulus_with_both_loops)
{
  // a planar annulus (two boundary loops) goes to the sphere with its hole and outline closed by patches
  const std::string annulus = std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cases/annulus.off";
  const std::string mesh = out_dir + "/cli_annulus_out.off";
  std::remove(mesh.c_str());
  const Run r = run("--input " + annulus + " --vertices 400 --output " + mesh + " --quiet");
  BOOST_TEST(r.status == 0, r.err);
  BOOST_TEST_REQUIRE(exists(mesh));
  const Aniso_conformal::Input_surface out = Aniso_conformal::IO::read_triangle_mesh(mesh);
  BOOST_TEST(out.number_of_vertices() == 400u);
  BOOST_TEST(out.genus() == 0);
  BOOST_TEST(out.boundary_loops().size() == 2u);
}

BOOST_AUTO_TEST_CASE(valid_input_this_version_cannot_remesh_exits_3)
{
  // the L-shaped plate under a field swirling around its re-entrant corner is valid, but with its
  // boundary's metric lengths kept (--planar-boundary lengths) its layout crosses itself
  const std::string cases = std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cases/";
  const std::string mesh = out_dir + "/cli_lshape_lengths_out.off";
  std::remove(mesh.c_str());
  const Run r = run("--input " + cases + "lshape8.off --metric-file " + cases + "lshape8_swirl3.metric --planar-boundary lengths --vertices 300 --output " + mesh);
  BOOST_TEST(r.status == 3);
  BOOST_TEST(r.err.find("aniso_remesh: cannot remesh: ") == 0u);
  BOOST_TEST(r.err.find("crosses itself") != std::string::npos);
  BOOST_TEST(printable_line(r.err));
  BOOST_TEST(r.out.empty());
  BOOST_TEST(!exists(mesh));
}

// ------------------------------------------------------------------------ repairs on reading (issue 14)

namespace {
const std::string repair_cases = std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/repairs";

// the signed area, seen from +z, of the triangles of an OFF file the tool wrote
double planar_area_of_off(const std::string& path)
{
  std::ifstream f(path);
  std::string magic;
  std::size_t nv = 0, nf = 0, ne = 0;
  f >> magic >> nv >> nf >> ne;
  std::vector<std::array<double, 2>> p(nv);
  double z = 0;
  for(auto& x : p) f >> x[0] >> x[1] >> z;
  double area = 0;
  for(std::size_t t = 0; t < nf; ++t) {
    std::size_t k = 0, a = 0, b = 0, c = 0;
    f >> k >> a >> b >> c;
    area += 0.5 * ((p[b][0] - p[a][0]) * (p[c][1] - p[a][1]) - (p[b][1] - p[a][1]) * (p[c][0] - p[a][0]));
  }
  return f ? area : 0.0;
}
} // namespace

BOOST_AUTO_TEST_CASE(tool_repairs_what_a_user_expects_and_counts_it)
{
  struct Case {
    std::string file, summary, key;
    nlohmann::json count;
    std::string refusal;  // with --no-repair
    int refusal_status;
  };
  const std::vector<Case> cases = {
    {"patch_quads.obj", "repairs      400 polygons triangulated into 800 triangles\n", "polygons_triangulated", 400,
     "face 0 has 4 vertices", 2},
    {"patch_soup.off", "repairs      1959 duplicated points welded\n", "points_welded", 1959,
     "800 connected components; remesh them one at a time", 2},
    {"disk_unref.off", "repairs      4 vertices of no face dropped\n", "isolated_vertices_dropped", 4,
     "vertex 169 belongs to no face", 2},
    {"square4_cw.off", "repairs      clockwise planar input remeshed counter-clockwise, output turned back clockwise\n",
     "planar_clockwise", true, "", 0}};  // --no-repair: remeshed as it is, clockwise
  for(const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.file)
    {
      const std::string in = repair_cases + "/" + c.file, mesh = out_dir + "/cli_repaired.off", report = out_dir + "/cli_repaired.json";
      const std::string before = slurp(in);
      std::remove(mesh.c_str());
      Run r = run("--input " + in + " --vertices 120 --iterations 30 --output " + mesh + " --report " + report);
      BOOST_TEST(r.status == 0, r.err);
      BOOST_TEST(r.out.find(c.summary) != std::string::npos, r.out);
      const nlohmann::json j = read_json(report);
      BOOST_TEST(j.at("output").at("vertices") == 120);
      BOOST_TEST(j.at("domain") == "plane");
      BOOST_TEST(j.at("repairs").at(c.key) == c.count);
      BOOST_TEST(j.at("repairs").at("input_vertices").get<std::size_t>() >= j.at("input").at("vertices").get<std::size_t>());
      // the output's orientation follows the input (the saddle patches and the disk: counter-clockwise;
      // the square: clockwise)
      const double area = planar_area_of_off(mesh);
      BOOST_TEST_INFO("signed area of the output seen from +z: " << area);
      BOOST_TEST((c.file == "square4_cw.off" ? area < 0 : area > 0));
      // --no-repair: the refusal of before, saying the repairs were off (the clockwise square: remeshed)
      std::remove(mesh.c_str());
      r = run("--input " + in + " --vertices 120 --iterations 30 --no-repair --output " + mesh);
      BOOST_TEST(r.status == c.refusal_status, r.err);
      if(c.refusal_status == 0) {  // taken as it is: no repair line, the output keeps the input's orientation
        BOOST_TEST(r.out.find("\nrepairs ") == std::string::npos, r.out);
        BOOST_TEST(planar_area_of_off(mesh) < 0);
        BOOST_TEST(slurp(in) == before);
        continue;
      }
      BOOST_TEST(r.err.find(c.refusal) != std::string::npos, r.err);
      if(c.refusal_status == 2) BOOST_TEST(r.err.find("read without repairs") != std::string::npos);
      BOOST_TEST(printable_line(r.err));
      BOOST_TEST(!exists(mesh));
      BOOST_TEST(slurp(in) == before);  // the input file is never changed
    }
  }
}

BOOST_AUTO_TEST_CASE(tool_metric_file_lines_up_with_the_kept_vertices)
{
  // disk_unref.off has 173 vertices, 4 of them in no face: the metric file has 173 rows, the last 4
  // (indefinite here) are ignored; a file of 169 rows is refused, naming the count expected
  const std::string in = repair_cases + "/disk_unref.off", metric = out_dir + "/cli_unref.metric";
  std::ostringstream m;
  m << "173\n";
  for(int i = 0; i < 173; ++i) m << (i < 169 ? "2 0.5 0 1 0 1\n" : "-1 0 0 -1 0 -1\n");
  write_file(metric, m.str());
  Run r = run("--input " + in + " --metric-file " + metric + " --vertices 150 --iterations 20");
  BOOST_TEST(r.status == 0, r.err);
  BOOST_TEST(r.out.find("4 vertices of no face dropped") != std::string::npos);
  std::ostringstream k;
  k << "169\n";
  for(int i = 0; i < 169; ++i) k << "1 0 0 1 0 1\n";
  write_file(metric, k.str());
  r = run("--input " + in + " --metric-file " + metric + " --vertices 150");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("declares 169 tensors but the mesh has 173 vertices") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(tool_refuses_non_manifold_input_saying_what_to_do)
{
  // a fin (three triangles on one edge), a bowtie, and a bowtie made by welding a soup: exit 2, one
  // printable line naming the edge or vertex and the fix
  const std::string fin = out_dir + "/cli_fin.off", bowtie = out_dir + "/cli_bowtie.off", soup = out_dir + "/cli_bowtie_soup.off";
  write_file(fin, "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  write_file(bowtie, "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 0 3 4\n");
  write_file(soup, "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 3 4 5\n");
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
    {fin, {"the edge from vertex 0 to vertex 1 is non-manifold: 3 faces share it", "split the mesh along it"}},
    {bowtie, {"vertex 0 is non-manifold", "give each fan its own copy of the vertex"}},
    {soup, {"input vertices 0 and 3, welded as duplicates", "after welding"}}};
  for(const auto& [file, parts] : cases) {
    const Run r = run("--input " + file + " --vertices 10");
    BOOST_TEST_INFO(file << " -> " << r.err);
    BOOST_TEST(r.status == 2);
    BOOST_TEST(printable_line(r.err));
    for(const std::string& part : parts) BOOST_TEST(r.err.find(part) != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(tool_reports_and_keeps_the_corners_of_a_cube)
{
  // issue 15: --feature-angle, --no-features, the summary's features line and the report's features object
  BOOST_TEST(parse({"--input", "a.off", "--vertices", "10"}).feature_angle == 60.0);
  BOOST_TEST(!parse({"--input", "a.off", "--vertices", "10"}).no_features);
  BOOST_TEST(parse({"--input", "a.off", "--vertices", "10", "--feature-angle", "180"}).feature_angle == 180.0);
  BOOST_TEST(parse({"--input", "a.off", "--vertices", "10", "--no-features"}).no_features);
  BOOST_TEST(parse_error({"--input", "a.off", "--vertices", "10", "--feature-angle", "181"}).find("--feature-angle: must be in [0, 180]") !=
             std::string::npos);
  BOOST_TEST(parse_error({"--input", "a.off", "--vertices", "10", "--feature-angle", "30", "--no-features"})
                 .find("--feature-angle excludes --no-features") != std::string::npos);
  // --keep-ragged-creases: remesh()'s drop_ragged_creases(false); meaningless without features
  BOOST_TEST(!parse({"--input", "a.off", "--vertices", "10"}).keep_ragged_creases);
  BOOST_TEST(parse({"--input", "a.off", "--vertices", "10", "--keep-ragged-creases"}).keep_ragged_creases);
  BOOST_TEST(parse_error({"--input", "a.off", "--vertices", "10", "--keep-ragged-creases", "--no-features"})
                 .find("--no-features excludes --keep-ragged-creases") != std::string::npos);

  const std::string in = out_dir + "/cli_cube.off", report = out_dir + "/cli_cube.json";
  Aniso_conformal::IO::write_polygon_soup(
    in, std::vector<Eigen::Vector3d>{{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
    std::vector<std::array<std::size_t, 3>>{{{0, 2, 1}}, {{0, 3, 2}}, {{4, 5, 6}}, {{4, 6, 7}}, {{0, 1, 5}}, {{0, 5, 4}}, {{1, 2, 6}},
                                            {{1, 6, 5}}, {{2, 3, 7}}, {{2, 7, 6}}, {{3, 0, 4}}, {{3, 4, 7}}});
  const Run r = run("--input " + in + " --vertices 300 --report " + report);
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.find("features     input 12 curves (crease length 24), 8 corners; output keeps 8 of the corners") != std::string::npos);
  const nlohmann::json j = read_json(report);
  BOOST_TEST(j.at("features").at("curves") == 12);
  BOOST_TEST(j.at("features").at("corners") == 8);
  BOOST_TEST(j.at("features").at("corners_kept") == 8);
  BOOST_TEST(j.at("features").at("crease_length") == 24.0);
  // --no-features: no line, no object
  const Run none = run("--input " + in + " --vertices 300 --no-features --report " + report);
  BOOST_TEST(none.status == 0);
  BOOST_TEST(none.out.find("features") == std::string::npos);
  BOOST_TEST(!read_json(report).contains("features"));
  // fewer vertices than corners: exit 2, saying how many and what to change
  const Run few = run("--input " + in + " --vertices 7");
  BOOST_TEST(few.status == 2);
  BOOST_TEST(few.err.find("8 corners") != std::string::npos);
  BOOST_TEST(few.err.find("--no-features") != std::string::npos);

  // --features FILE: the user's crease edges and corners; with --no-features only these
  BOOST_TEST(parse({"--input", "a.off", "--vertices", "10", "--features", "f.txt"}).features_file == "f.txt");
  const std::string marks = out_dir + "/cli_cube_features.txt", bad = out_dir + "/cli_cube_bad_features.txt";
  std::ofstream(marks) << "# one cube edge and the opposite corner\n0 1\n6\n";
  const Run marked = run("--input " + in + " --vertices 300 --no-features --features " + marks + " --report " + report);
  BOOST_TEST(marked.status == 0);
  const nlohmann::json jm = read_json(report);
  BOOST_TEST(jm.at("features").at("crease_edges") == 1);
  BOOST_TEST(jm.at("features").at("curves") == 1);
  BOOST_TEST(jm.at("features").at("corners") == 3);
  BOOST_TEST(jm.at("features").at("corners_kept") == 3);
  // a pair that is not an edge (a diagonal of the cube), a missing file, a mesh-less run: exit 2, named
  std::ofstream(bad) << "0 1\n0 6\n";
  const Run diagonal = run("--input " + in + " --vertices 300 --features " + bad);
  BOOST_TEST(diagonal.status == 2);
  BOOST_TEST(diagonal.err.find("(0, 6) is not an edge of the input") != std::string::npos);
  const Run missing = run("--input " + in + " --vertices 300 --features " + out_dir + "/no_such_features.txt");
  BOOST_TEST(missing.status == 2);
  BOOST_TEST(missing.err.find("cannot be opened") != std::string::npos);
  const Run square = run("--domain square --vertices 300 --features " + marks);
  BOOST_TEST(square.status == 2);
  BOOST_TEST(square.err.find("does not apply to --image or --domain") != std::string::npos);
  // the feature file is read with the mesh, before any metric: a malformed one is named before a missing metric file
  const std::string garbled = out_dir + "/cli_cube_garbled_features.txt";
  std::ofstream(garbled) << "0 1\n0 x\n";
  const Run first = run("--input " + in + " --vertices 300 --features " + garbled + " --metric-file " + out_dir + "/no_such_metric.txt");
  BOOST_TEST(first.status == 2);
  BOOST_TEST(first.err.find("line 2: expected one vertex index") != std::string::npos, first.err);
  // a repaired mesh (a leading point of no face, dropped: CGAL moves the last point into its place, so file
  // point 8 becomes vertex 0): the refused edge is named by the file's indices too
  const std::string shifted = out_dir + "/cli_cube_shifted.off", shifted_bad = out_dir + "/cli_cube_shifted_bad_features.txt";
  Aniso_conformal::IO::write_polygon_soup(
    shifted,
    std::vector<Eigen::Vector3d>{{5, 5, 5}, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
    std::vector<std::array<std::size_t, 3>>{{{1, 3, 2}}, {{1, 4, 3}}, {{5, 6, 7}}, {{5, 7, 8}}, {{1, 2, 6}}, {{1, 6, 5}}, {{2, 3, 7}},
                                            {{2, 7, 6}}, {{3, 4, 8}}, {{3, 8, 7}}, {{4, 1, 5}}, {{4, 5, 8}}});
  std::ofstream(shifted_bad) << "1 2\n2 8\n";  // an edge, then a diagonal: (1, -1, -1) to (-1, 1, 1)
  const Run repaired = run("--input " + shifted + " --vertices 300 --features " + shifted_bad);
  BOOST_TEST(repaired.status == 2);
  BOOST_TEST(repaired.err.find("(2, 0) (vertices 2 and 8 of the input file) is not an edge of the input") != std::string::npos,
             repaired.err);
}
