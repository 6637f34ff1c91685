// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Property tests of remesh() (issue 6): random valid meshes of the supported topologies (perturbed
// planar grids, curved height-field disks, Dupin ring cyclides and ring tori of random grid sizes) with
// random smooth SPD tensor fields (stretch ratios up to 100, scale varying by 1000x across the mesh),
// fixed seeds and bounded sizes. Every trial either returns a valid output (exact vertex count, the
// input's genus and boundary count, no inverted triangle, every vertex on the input) or throws one of
// the documented exceptions; the input is bit-for-bit unchanged either way. Also the BGL entry point's
// strong guarantee, and the bad inputs of the manual's catalogue that no other module covers.

#ifndef ANISO_CONFORMAL_TEST_UNITY  // else compiled with other modules in one translation unit (CMakeLists.txt)
#define BOOST_TEST_MODULE Aniso_conformal_properties
#endif
#include <boost/test/unit_test.hpp>

#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/Tensor_field_metric.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/make_dupin_cyclide.h>
#include <Aniso_conformal/make_ellipsoid.h>
#include <Aniso_conformal/make_square_background.h>
#include <Aniso_conformal/make_subdivided_surface.h>
#include <Aniso_conformal/remesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

BOOST_AUTO_TEST_SUITE(properties)  // also a namespace: keeps the helpers apart from other modules in one unit

namespace AC = Aniso_conformal;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;

namespace {

const double pi = 3.14159265358979323846;
const std::string out_dir = ANISO_CONFORMAL_TEST_OUTPUT_DIR;

typedef std::vector<Eigen::Vector3d> Points;
typedef std::vector<AC::Input_surface::Face> Faces;

double uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
int uniform_int(std::mt19937& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

// an nx x ny grid over [0, 1]^2 (or [-1, 1]^2 for the height field), each square split along a random
// diagonal, interior vertices moved by up to 0.2 of a cell (which keeps every triangle positively oriented)
AC::Input_surface random_grid_disk(std::mt19937& rng, int nx, int ny, bool curved)
{
  Points p;
  const double hx = 1.0 / (nx - 1), hy = 1.0 / (ny - 1);
  const double amp = uniform(rng, 0.1, 0.5), fx = uniform(rng, 1, 4), fy = uniform(rng, 1, 4);
  const double px = uniform(rng, 0, 2 * pi), py = uniform(rng, 0, 2 * pi);
  for(int j = 0; j < ny; ++j)
    for(int i = 0; i < nx; ++i) {
      double x = i * hx, y = j * hy;
      if(i > 0 && i < nx - 1 && j > 0 && j < ny - 1) {
        x += uniform(rng, -0.2, 0.2) * hx;
        y += uniform(rng, -0.2, 0.2) * hy;
      }
      if(!curved) {
        p.emplace_back(x, y, 0.0);
      } else {
        const double u = 2 * x - 1, v = 2 * y - 1;  // z = f(x, y) over [-1, 1]^2
        p.emplace_back(u, v, amp * std::sin(fx * u + px) * std::cos(fy * v + py));
      }
    }
  Faces f;
  for(int j = 0; j + 1 < ny; ++j)
    for(int i = 0; i + 1 < nx; ++i) {
      const std::size_t a = std::size_t(j * nx + i), b = a + 1, c = a + std::size_t(nx) + 1, d = a + std::size_t(nx);
      if(rng() % 2) {
        f.push_back({{a, b, c}});
        f.push_back({{a, c, d}});
      } else {
        f.push_back({{a, b, d}});
        f.push_back({{b, c, d}});
      }
    }
  return AC::Input_surface(std::move(p), std::move(f));
}

// A random smooth SPD 3x3 tensor per vertex: R(x) diag(1, r(x), r(x)^2) R(x)^T times s(x), with R a
// smooth rotation field (axis-angle vector made of sines), r(x) in [1, stretch_max] (a stretch ratio of
// lengths, the square root of the eigenvalue ratio) and, for `scale_range` > 1, s(x) going from 1 to
// `scale_range` linearly along a random direction across the mesh.
std::vector<Eigen::Matrix3d> random_tensor_field(std::mt19937& rng, const AC::Input_surface& s, double stretch_max, double scale_range)
{
  Eigen::Vector3d freq[3], phase, dir, fr;
  for(auto& f : freq) f = Eigen::Vector3d(uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3));
  phase = Eigen::Vector3d(uniform(rng, 0, 2 * pi), uniform(rng, 0, 2 * pi), uniform(rng, 0, 2 * pi));
  fr = Eigen::Vector3d(uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3));
  const double fphase = uniform(rng, 0, 2 * pi);
  dir = Eigen::Vector3d(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)).normalized();
  double lo = 1e300, hi = -1e300;
  for(const auto& p : s.points()) {
    lo = std::min(lo, dir.dot(p));
    hi = std::max(hi, dir.dot(p));
  }
  std::vector<Eigen::Matrix3d> t;
  t.reserve(s.number_of_vertices());
  for(const auto& p : s.points()) {
    Eigen::Vector3d w;
    for(int k = 0; k < 3; ++k) w[k] = pi * std::sin(freq[k].dot(p) + phase[k]);
    const Eigen::Matrix3d R =
        w.norm() > 0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() : Eigen::Matrix3d::Identity();
    const double r = std::pow(stretch_max, 0.5 + 0.5 * std::sin(fr.dot(p) + fphase));
    const double scale = hi > lo ? std::pow(scale_range, (dir.dot(p) - lo) / (hi - lo)) : 1.0;
    Eigen::Matrix3d M = scale * R * Eigen::Vector3d(1, r, r * r).asDiagonal() * R.transpose();
    M = 0.5 * (M + M.transpose());  // exactly symmetric
    t.push_back(M);
  }
  return t;
}

struct Outcomes {
  int ok = 0, invalid_input = 0, remeshing_failure = 0, other = 0;
  std::vector<std::string> undocumented;  // failure messages that name no stage of the pipeline
};

// A Remeshing_failure must say which stage gave up: its message starts with one of the stages' names.
bool names_a_stage(const std::string& m)
{
  for(const char* stage : {"edge-length adjustment", "conformal embedding", "spherical embedding", "flat torus embedding",
                           "hyperbolic embedding", "flat torus:", "hyperbolic domain", "dual mesh", "remesh(): the output"})
    if(m.rfind(stage, 0) == 0) return true;
  return false;
}

// bitwise equality of two arrays of trivially copyable values
template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// The output is a valid remeshing of `s`: n vertices, a manifold with s's genus and boundary count, no
// inverted triangle, each vertex reproduced by its Surface_point's barycentric combination of s's vertices.
void check_valid_output(const AC::Input_surface& s, const AC::Remeshed_surface& out, const AC::Remeshing_result& r, std::size_t n,
                        const std::string& what)
{
  BOOST_TEST(out.points.size() == n, what);
  BOOST_TEST(out.surface_points.size() == out.points.size(), what);
  BOOST_TEST(r.inverted_triangles == 0u, what);
  Faces faces(out.faces.begin(), out.faces.end());
  try {
    const AC::Input_surface o(out.points, faces);
    BOOST_TEST(o.genus() == s.genus(), what);
    BOOST_TEST(o.boundary_loops().size() == s.boundary_loops().size(), what);
  } catch(const AC::Invalid_input& e) {
    BOOST_ERROR(what << ": the output is not a valid surface: " << e.what());
  }
  const double tol = 1e-9 * s.bounding_box_diagonal();
  std::size_t off = 0;
  double worst = 0;
  for(std::size_t i = 0; i < out.points.size() && i < out.surface_points.size(); ++i) {
    const AC::Surface_point& sp = out.surface_points[i];
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    bool in_range = true;
    for(int k = 0; k < 3; ++k) {
      if(sp.vertices[k] >= s.number_of_vertices()) { in_range = false; break; }
      p += sp.barycentric[k] * s.points()[sp.vertices[k]];
    }
    const double d = in_range ? (p - out.points[i]).norm() : std::numeric_limits<double>::infinity();
    const bool bary_ok = sp.barycentric.minCoeff() >= 0 && std::abs(sp.barycentric.sum() - 1) < 1e-12;
    if(!(d <= tol) || !bary_ok) ++off;
    worst = std::max(worst, d);
  }
  BOOST_TEST(off == 0u, what << ": " << off << " vertices off the input (worst distance " << worst << ")");
}

// One remesh() trial: counts the outcome, fails on anything undocumented (another exception type, a
// Remeshing_failure that names no stage, Invalid_input on a valid surface and metric).
void run_trial(const AC::Input_surface& s, const std::vector<Eigen::Matrix3d>& tensors, std::size_t n, unsigned seed,
               const std::string& what, Outcomes& count)
{
  const AC::Tensor_field_metric metric(tensors);
  AC::Remeshing_result r;
  const auto t0 = std::chrono::steady_clock::now();
  std::string outcome;
  try {
    const AC::Remeshed_surface out =
        AC::remesh(s, metric, r, AC::parameters::number_of_vertices(n).random_seed(seed).number_of_iterations(30u));
    check_valid_output(s, out, r, n, what);
    ++count.ok;
    outcome = "ok, G_avg " + std::to_string(r.quality.G_avg);
  } catch(const AC::Invalid_input& e) {
    ++count.invalid_input;
    outcome = std::string("Invalid_input: ") + e.what();
  } catch(const AC::Remeshing_failure& e) {
    ++count.remeshing_failure;
    outcome = std::string("Remeshing_failure: ") + e.what();
    if(!names_a_stage(e.what())) count.undocumented.push_back(e.what());
  } catch(const std::exception& e) {
    ++count.other;
    BOOST_ERROR(what << ": undocumented exception: " << e.what());
  } catch(...) {
    ++count.other;
    BOOST_ERROR(what << ": undocumented exception of unknown type");
  }
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  BOOST_TEST_MESSAGE(what << " (" << sec << " s): " << outcome);
}

std::string describe(const std::string& mesh, std::size_t nv, double stretch, double scale, std::size_t n, unsigned seed)
{
  return mesh + " (" + std::to_string(nv) + " vertices), stretch " + std::to_string(stretch) + ", scale range " +
         std::to_string(scale) + ", n " + std::to_string(n) + ", seed " + std::to_string(seed);
}

// the metric parameters of a trial: stretch ratio log-uniform in [1, 100], every other trial scale 1000x
void random_metric_parameters(std::mt19937& rng, int trial, double& stretch, double& scale)
{
  stretch = std::pow(100.0, uniform(rng, 0, 1));
  if(trial % 4 == 0) stretch = 100;  // the extreme case, always represented
  scale = trial % 2 ? 1000.0 : 1.0;
}

// Every trial's input is valid (a manifold disk or closed surface, an SPD metric, a vertex count the
// topology allows), so none may be refused as bad input, and every failure must name its stage.
void report(const std::string& name, const Outcomes& c, int trials)
{
  BOOST_TEST_MESSAGE(name << ": " << trials << " trials, " << c.ok << " valid outputs, " << c.invalid_input << " Invalid_input, "
                          << c.remeshing_failure << " Remeshing_failure, " << c.other << " other");
  BOOST_TEST(c.other == 0);
  BOOST_TEST(c.invalid_input == 0, name << ": a valid input was refused as bad input");
  for(const std::string& m : c.undocumented) BOOST_ERROR(name << ": a failure that names no stage: " << m);
}

Mesh to_surface_mesh(const AC::Input_surface& s)
{
  Mesh m;
  std::vector<Mesh::Vertex_index> v;
  for(const auto& p : s.points()) v.push_back(m.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
  for(const auto& f : s.faces()) m.add_face(v[f[0]], v[f[1]], v[f[2]]);
  return m;
}

// points and face corner indices of a Surface_mesh, to compare before and after
std::pair<std::vector<double>, std::vector<std::size_t>> snapshot(const Mesh& m)
{
  std::pair<std::vector<double>, std::vector<std::size_t>> s;
  for(auto v : m.vertices())
    for(int k = 0; k < 3; ++k) s.first.push_back(m.point(v)[k]);
  for(auto f : m.faces())
    for(auto v : CGAL::vertices_around_face(m.halfedge(f), m)) s.second.push_back(std::size_t(v));
  return s;
}

std::string write_file(const std::string& name, const std::string& content)
{
  const std::string path = out_dir + "/" + name;
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

// the message of an Invalid_input thrown by f, or a marker
std::string invalid_input_message(const std::function<void()>& f)
{
  try {
    f();
  } catch(const AC::Invalid_input& e) {
    return e.what();
  } catch(const std::exception& e) {
    return std::string("(another exception: ") + e.what() + ")";
  }
  return "(no exception)";
}

// the message of a Remeshing_failure thrown by f, or a marker
std::string remeshing_failure_message(const std::function<void()>& f)
{
  try {
    f();
  } catch(const AC::Remeshing_failure& e) {
    return e.what();
  } catch(const std::exception& e) {
    return std::string("(another exception: ") + e.what() + ")";
  }
  return "(no exception)";
}

bool contains(const std::string& s, const std::string& part)
{
  BOOST_TEST_MESSAGE("  message: " << s);
  if(s.find(part) != std::string::npos) return true;
  BOOST_TEST_MESSAGE("'" << s << "' does not contain '" << part << "'");
  return false;
}

// The boundary of a union of unit voxels (x, y, 0) (one layer), outward oriented, as triangles
AC::Input_surface voxel_surface(const std::vector<std::array<int, 2>>& cells)
{
  std::map<std::array<int, 2>, bool> filled;
  for(const auto& c : cells) filled[c] = true;
  std::map<std::array<int, 3>, std::size_t> index;
  Points points;
  Faces faces;
  auto vid = [&](int x, int y, int z) {
    const std::array<int, 3> key = {{x, y, z}};
    auto it = index.find(key);
    if(it != index.end()) return it->second;
    points.emplace_back(x, y, z);
    return index[key] = points.size() - 1;
  };
  // a quad (a, b, c, d) counterclockwise seen from outside
  auto quad = [&](std::size_t a, std::size_t b, std::size_t c, std::size_t d) {
    faces.push_back({{a, b, c}});
    faces.push_back({{a, c, d}});
  };
  for(const auto& c : cells) {
    const int x = c[0], y = c[1];
    quad(vid(x, y, 1), vid(x + 1, y, 1), vid(x + 1, y + 1, 1), vid(x, y + 1, 1));  // top (+z)
    quad(vid(x, y, 0), vid(x, y + 1, 0), vid(x + 1, y + 1, 0), vid(x + 1, y, 0));  // bottom (-z)
    if(!filled.count({{x + 1, y}})) quad(vid(x + 1, y, 0), vid(x + 1, y + 1, 0), vid(x + 1, y + 1, 1), vid(x + 1, y, 1));
    if(!filled.count({{x - 1, y}})) quad(vid(x, y, 0), vid(x, y, 1), vid(x, y + 1, 1), vid(x, y + 1, 0));
    if(!filled.count({{x, y + 1}})) quad(vid(x, y + 1, 0), vid(x, y + 1, 1), vid(x + 1, y + 1, 1), vid(x + 1, y + 1, 0));
    if(!filled.count({{x, y - 1}})) quad(vid(x, y, 0), vid(x + 1, y, 0), vid(x + 1, y, 1), vid(x, y, 1));
  }
  return AC::Input_surface(std::move(points), std::move(faces));
}

} // namespace

// ------------------------------------------------------------------------------------ disks

BOOST_AUTO_TEST_CASE(random_planar_and_curved_disks_remesh_or_throw_a_documented_exception)
{
  std::mt19937 rng(20260601u);
  Outcomes planar, curved;
  const int trials = 20;
  for(int trial = 0; trial < 2 * trials; ++trial) {
    const bool is_curved = trial % 2 == 1;
    const int nx = uniform_int(rng, 20, 40), ny = uniform_int(rng, 20, 40);
    const AC::Input_surface s = random_grid_disk(rng, nx, ny, is_curved);
    BOOST_REQUIRE(s.is_disk());
    double stretch, scale;
    random_metric_parameters(rng, trial / 2, stretch, scale);
    const std::vector<Eigen::Matrix3d> t = random_tensor_field(rng, s, stretch, scale);
    const std::size_t n = std::size_t(uniform_int(rng, 100, 600));
    const unsigned seed = unsigned(rng() % 1000);
    run_trial(s, t, n, seed,
              describe(is_curved ? "height-field disk " + std::to_string(nx) + "x" + std::to_string(ny)
                                 : "perturbed planar grid " + std::to_string(nx) + "x" + std::to_string(ny),
                       s.number_of_vertices(), stretch, scale, n, seed),
              is_curved ? curved : planar);
  }
  report("planar disks", planar, trials);
  report("curved disks", curved, trials);
  // measured with these seeds: 15 of 20 valid outputs each; the other 10 are Convergence_failure, all
  // at a stretch of 20 or more; the bar leaves a margin for other thread counts and compilers
  BOOST_TEST(planar.ok >= 12);
  BOOST_TEST(curved.ok >= 12);
}

// ---------------------------------------------------------------------------- closed genus 1

BOOST_AUTO_TEST_CASE(random_cyclides_and_ring_tori_remesh_or_throw_a_documented_exception)
{
  // three kinds of metric in turn: mild (stretch up to 4, constant scale, n >= 300), the strong
  // stretch (up to 100) and the 1000x scale range (with stretch up to 10); the flat torus with a few
  // hundred sites often cannot carry the strong ones (Convergence_failure), which is allowed
  std::mt19937 rng(20260602u);
  Outcomes mild, strong;
  const int trials = 30;
  for(int trial = 0; trial < trials; ++trial) {
    const int kind = trial % 3;
    const std::size_t nu = std::size_t(uniform_int(rng, 24, 72));
    const std::size_t nv = std::size_t(std::clamp(int(std::lround(double(nu) * 2 / 3)) + uniform_int(rng, -4, 4), 16, 48));
    AC::Dupin_cyclide_parameters p;
    p.a = 1;
    p.b = trial % 4 == 0 ? 1.0 : uniform(rng, 0.9, 0.99);  // b = a: a ring torus (c = 0)
    const double c = std::sqrt(p.a * p.a - p.b * p.b);
    p.mu = uniform(rng, c + 0.15, 0.65);  // the thinnest part of the tube at least 0.15
    const AC::Input_surface s = AC::make_dupin_cyclide(nu, nv, p);
    BOOST_REQUIRE(s.genus() == 1);
    const double stretch = kind == 0 ? std::pow(4.0, uniform(rng, 0, 1)) : kind == 1 ? std::pow(100.0, uniform(rng, 0.5, 1))
                                                                                     : std::pow(10.0, uniform(rng, 0, 1));
    const double scale = kind == 2 ? 1000.0 : 1.0;
    const std::vector<Eigen::Matrix3d> t = random_tensor_field(rng, s, stretch, scale);
    const std::size_t n = std::size_t(uniform_int(rng, kind == 0 ? 300 : 100, 600));
    const unsigned seed = unsigned(rng() % 1000);
    const std::string name = (c == 0 ? "ring torus " : "cyclide ") + std::to_string(nu) + "x" + std::to_string(nv) +
                             " b " + std::to_string(p.b) + " mu " + std::to_string(p.mu);
    run_trial(s, t, n, seed, describe(name, s.number_of_vertices(), stretch, scale, n, seed), kind == 0 ? mild : strong);
  }
  report("closed genus 1, mild metrics", mild, trials / 3);
  report("closed genus 1, stretch up to 100 or scale 1000x", strong, 2 * trials / 3);
  // measured with these seeds: 10 of 10 mild, 2 of 20 strong (the flat torus with a few hundred sites
  // rarely carries a 1000x scale range or a stretch of 100: 'too few for the flat torus' or inverted triangles)
  BOOST_TEST(mild.ok >= 8);
  BOOST_TEST(strong.ok >= 1);
}

BOOST_AUTO_TEST_CASE(random_metrics_on_genus_two_and_three_remesh_or_throw_a_documented_exception)
{
  // the 1k Eight (genus 2) and CGAL's 3torus refined by 3 Loop subdivisions (genus 3), with the three
  // kinds of metric of the genus-1 test in turn; the hyperbolic disk with 100 to 400 sites
  const AC::Input_surface eight = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/eight_1k.off");
  const AC::Input_surface genus3 = AC::make_subdivided_surface(std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/3torus.off", 3);
  std::mt19937 rng(20261123u);
  Outcomes mild, strong;
  const int trials = 12;
  for(int trial = 0; trial < trials; ++trial) {
    const int kind = trial % 3;
    const AC::Input_surface& s = trial % 2 ? genus3 : eight;
    const double stretch = kind == 0 ? std::pow(4.0, uniform(rng, 0, 1)) : kind == 1 ? std::pow(100.0, uniform(rng, 0.5, 1))
                                                                                     : std::pow(10.0, uniform(rng, 0, 1));
    const double scale = kind == 2 ? 1000.0 : 1.0;
    const std::vector<Eigen::Matrix3d> t = random_tensor_field(rng, s, stretch, scale);
    const std::size_t n = std::size_t(uniform_int(rng, kind == 0 ? 200 : 100, 400));
    const unsigned seed = unsigned(rng() % 1000);
    run_trial(s, t, n, seed, describe(trial % 2 ? "genus-3 3torus" : "genus-2 eight", s.number_of_vertices(), stretch, scale, n, seed),
              kind == 0 ? mild : strong);
  }
  report("closed genus 2 and 3, mild metrics", mild, trials / 3);
  report("closed genus 2 and 3, stretch up to 100 or scale 1000x", strong, 2 * trials / 3);
  // measured with these seeds: 4 of 4 mild trials remesh; the 8 strong ones (100 to 400 sites for a
  // stretch up to 100 or a 1000x scale range) end in a Remeshing_failure naming its stage, none remeshes
  BOOST_TEST(mild.ok >= 3);
  BOOST_TEST(strong.ok + strong.remeshing_failure == 2 * trials / 3);
}

// ------------------------------------------------------------- remesh(): the choice of the domain

BOOST_AUTO_TEST_CASE(remesh_chooses_the_domain_from_the_topology_and_checks_a_requested_one)
{
  const AC::Input_surface square = AC::make_square_background(AC::Uniform_metric(), 150);
  const AC::Input_surface ellipsoid = AC::make_ellipsoid(2);
  const AC::Input_surface cyclide = AC::make_dupin_cyclide(24, 16);
  const AC::Input_surface eight = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/eight_1k.off");
  typedef AC::Parametric_domain D;
  const std::vector<std::pair<const AC::Input_surface*, D>> cases = {
      {&square, D::PLANE}, {&ellipsoid, D::SPHERE}, {&cyclide, D::FLAT_TORUS}, {&eight, D::HYPERBOLIC}};
  for(const auto& c : cases) {
    AC::Remeshing_result r;
    const AC::Remeshed_surface out = AC::remesh(*c.first, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(120)));
    BOOST_TEST((r.domain == c.second), AC::domain_name(c.second) << " expected, " << AC::domain_name(r.domain) << " chosen");
    BOOST_TEST(out.points.size() == 120u);
    // the same domain requested: the same output; any other requested: refused as bad input, naming both
    AC::Remeshing_result r2;
    const AC::Remeshed_surface again =
        AC::remesh(*c.first, AC::Uniform_metric(), r2, AC::parameters::number_of_vertices(std::size_t(120)).parametric_domain(c.second));
    BOOST_TEST(same_bits(again.points, out.points));
    for(const auto& other : cases) {
      if(other.second == c.second) continue;
      const std::string m = invalid_input_message([&] {
        AC::remesh(*c.first, AC::Uniform_metric(), r2,
                   AC::parameters::number_of_vertices(std::size_t(120)).parametric_domain(other.second));
      });
      BOOST_TEST(contains(m, std::string("the ") + AC::domain_name(other.second) + " domain does not fit the input, which is " +
                                 c.first->topology_description()),
                 m);
    }
  }
}

// ------------------------------------------------------------------ BGL entry point guarantee

BOOST_AUTO_TEST_CASE(bgl_entry_point_leaves_the_input_alone_and_the_output_empty_on_failure)
{
  std::mt19937 rng(20260603u);
  const AC::Input_surface cyclide = AC::make_dupin_cyclide(36, 24);
  const AC::Input_surface patch = random_grid_disk(rng, 25, 25, true);
  for(const AC::Input_surface* s : {&cyclide, &patch}) {
    const Mesh in = to_surface_mesh(*s);
    const auto before = snapshot(in);
    const std::vector<Eigen::Matrix3d> t = random_tensor_field(rng, *s, 2, 10);
    const AC::Tensor_field_metric field(t);
    // a valid run
    Mesh out;
    const std::size_t n = 300;
    try {
      const AC::Remeshing_result r =
          AC::remesh(in, field, out, AC::parameters::number_of_vertices(n).random_seed(3u).number_of_iterations(30u));
      BOOST_TEST(num_vertices(out) == n);
      BOOST_TEST(CGAL::is_valid_polygon_mesh(out));
      BOOST_TEST(CGAL::is_triangle_mesh(out));
      BOOST_TEST(CGAL::is_closed(out) == s->boundary_loops().empty());
      BOOST_TEST(int(num_vertices(out)) - int(num_edges(out)) + int(num_faces(out)) == s->euler_characteristic());
      BOOST_TEST(r.inverted_triangles == 0u);
    } catch(const AC::Error& e) {
      BOOST_ERROR("the BGL run failed: " << e.what());
    }
    BOOST_TEST((snapshot(in) == before));
    // Invalid_input (a metric with a NaN): the output stays empty
    Mesh empty;
    std::vector<Eigen::Matrix3d> nan_field = t;
    nan_field[1](0, 0) = std::numeric_limits<double>::quiet_NaN();
    BOOST_CHECK_THROW(AC::remesh(in, AC::Tensor_field_metric(nan_field), empty, AC::parameters::number_of_vertices(n)),
                      AC::Invalid_input);
    BOOST_TEST(num_vertices(empty) == 0u);
    BOOST_TEST(num_faces(empty) == 0u);
    // Convergence_failure deep in the pipeline (a 1e8 jump between neighbours, 2 Newton iterations)
    std::vector<Eigen::Matrix3d> wild(s->number_of_vertices(), Eigen::Matrix3d::Identity());
    for(std::size_t i = 0; i < wild.size(); i += 2) wild[i] *= 1e8;
    BOOST_CHECK_THROW(AC::remesh(in, AC::Tensor_field_metric(wild), empty,
                                 AC::parameters::number_of_vertices(n).max_conformal_iterations(2u)),
                      AC::Convergence_failure);
    BOOST_TEST(num_vertices(empty) == 0u);
    BOOST_TEST(num_faces(empty) == 0u);
    // a previous output is kept as it was
    const auto out_before = snapshot(out);
    BOOST_CHECK_THROW(AC::remesh(in, field, out, AC::parameters::number_of_vertices(std::size_t(2))), AC::Invalid_input);
    BOOST_TEST((snapshot(out) == out_before));
    BOOST_TEST((snapshot(in) == before));
  }
}

// ------------------------------------------------------- bad inputs of the manual's catalogue

BOOST_AUTO_TEST_CASE(wrong_magic_and_infinite_coordinates)
{
  BOOST_TEST(contains(invalid_input_message([] { AC::IO::read_triangle_mesh(write_file("magic.off", "OFX\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")); }),
                      "magic.off"));
  BOOST_TEST(contains(invalid_input_message([] {
                        AC::IO::read_triangle_mesh(write_file("magic.ply", "plx\nformat ascii 1.0\nelement vertex 0\nend_header\n"));
                      }),
                      "not a PLY file"));
  BOOST_TEST(contains(invalid_input_message([] { AC::IO::read_triangle_mesh(write_file("inf.off", "OFF\n3 1 0\n0 0 0\ninf 0 0\n0 1 0\n3 0 1 2\n")); }),
                      "inf.off"));
  const double inf = std::numeric_limits<double>::infinity();
  BOOST_TEST(contains(invalid_input_message([&] { AC::Input_surface({{0, 0, 0}, {1, 0, 0}, {0, -inf, 0}}, {{{0, 1, 2}}}); }),
                      "vertex 2 has a non-finite coordinate"));
}

BOOST_AUTO_TEST_CASE(empty_mesh_in_memory)
{
  BOOST_TEST(contains(invalid_input_message([] { AC::Input_surface({}, {}); }), "the input mesh is empty"));
  BOOST_TEST(contains(invalid_input_message([] { AC::Input_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}); }), "the input mesh is empty"));
  Mesh empty, out;
  BOOST_TEST(contains(invalid_input_message([&] {
                        AC::remesh(empty, AC::Uniform_metric(), out, AC::parameters::number_of_vertices(std::size_t(10)));
                      }),
                      "the input mesh is empty"));
}

BOOST_AUTO_TEST_CASE(duplicated_vertices)
{
  std::mt19937 rng(7u);
  const AC::Input_surface grid = random_grid_disk(rng, 6, 6, false);
  const std::size_t nv = grid.number_of_vertices();
  // an unused copy of a vertex
  {
    Points p = grid.points();
    p.push_back(p[0]);
    BOOST_TEST(contains(invalid_input_message([&] { AC::Input_surface(p, grid.faces()); }),
                        "vertex " + std::to_string(nv) + " belongs to no face"));
  }
  // a face whose two corners are distinct indices at the same position: zero area
  {
    Points p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}};
    BOOST_TEST(contains(invalid_input_message([&] { AC::Input_surface(p, {{{0, 1, 2}}, {{1, 3, 2}}}); }), "face 1 is degenerate (zero area)"));
  }
  // a triangle soup (every face with its own three vertices, as in STL): one component per face
  {
    Points p;
    Faces f;
    for(const auto& t : grid.faces()) {
      for(int k = 0; k < 3; ++k) p.push_back(grid.points()[t[k]]);
      f.push_back({{p.size() - 3, p.size() - 2, p.size() - 1}});
    }
    BOOST_TEST(contains(invalid_input_message([&] { AC::Input_surface(p, f); }),
                        std::to_string(grid.number_of_faces()) + " connected components"));
  }
  // an interior vertex whose fan is split between it and a copy at the same position: a zero-width
  // slit through the vertex makes a second boundary loop of zero area, which no patch closes: remesh()
  // refuses it as a valid input it cannot remesh
  {
    const std::size_t v = 2 * 6 + 2;  // interior
    Points p = grid.points();
    p.push_back(p[v]);
    Faces f = grid.faces();
    // the faces of the fan of v that lie on the side y < y_v of it use the copy
    for(auto& t : f) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for(int k = 0; k < 3; ++k) c += grid.points()[t[k]] / 3;
      for(int k = 0; k < 3; ++k)
        if(t[k] == v && c.y() < grid.points()[v].y()) t[k] = nv;
    }
    std::string m;
    try {
      const AC::Input_surface s(p, f);
      AC::Remeshing_result r;
      AC::remesh(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(20)));
      m = "(accepted)";
    } catch(const AC::Remeshing_failure& e) {  // a valid input this version cannot remesh
      m = e.what();
    }
    BOOST_TEST(contains(m, "spans no area"), m);
  }
}

BOOST_AUTO_TEST_CASE(inconsistent_orientation)
{
  // two triangles sharing the edge 1-2 in the same direction
  BOOST_TEST(contains(invalid_input_message([] {
                        AC::Input_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{{0, 1, 2}}, {{1, 2, 3}}});
                      }),
                      "faces 0 and 1 have inconsistent orientation along edge (1, 2)"));
  // the same from an OFF file
  BOOST_TEST(contains(invalid_input_message([] {
                        AC::IO::read_triangle_mesh(write_file("flipped.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 2 3\n"));
                      }),
                      "inconsistent orientation"));
}

// the faults of the faces and their edges as a scan of the faces one by one meets them (a face's own
// faults, then its edges' in corner order): the specification `Input_surface` reports the first fault by
std::string first_fault_by_scan(const Points& p, const Faces& f)
{
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> directed;
  for(std::size_t i = 0; i < f.size(); ++i) {
    const auto& t = f[i];
    for(int k = 0; k < 3; ++k)
      if(t[k] >= p.size()) return "face " + std::to_string(i) + " refers to vertex";
    if(t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return "face " + std::to_string(i) + " is degenerate (a repeated vertex)";
    for(int k = 0; k < 3; ++k) {
      const auto key = std::make_pair(t[k], t[(k + 1) % 3]);
      const auto it = directed.find(key);
      const std::string edge = "(" + std::to_string(key.first) + ", " + std::to_string(key.second) + ")";
      if(it != directed.end())
        return directed.count({key.second, key.first}) ? "edge " + edge + " is non-manifold"
                                                         : "faces " + std::to_string(it->second) + " and " + std::to_string(i) +
                                                             " have inconsistent orientation along edge " + edge;
      directed.emplace(key, i);
    }
  }
  return "";
}

// random faults in a grid (a flipped face, a third face on an edge, a repeated vertex, an index out of
// range, a duplicated face, the faces shuffled): the first fault in face order is the one reported
BOOST_AUTO_TEST_CASE(validation_reports_the_first_fault_in_face_order)
{
  std::mt19937 rng(21u);
  int faulty = 0;
  for(int trial = 0; trial < 300; ++trial) {
    const AC::Input_surface grid = random_grid_disk(rng, 5 + int(rng() % 4), 5 + int(rng() % 4), trial % 2 == 1);
    Points p = grid.points();
    Faces f = grid.faces();
    const int faults = 1 + int(rng() % 3);
    for(int k = 0; k < faults; ++k) {
      const std::size_t i = rng() % grid.number_of_faces();  // an input face: its indices are in range
      switch(rng() % 5) {
        case 0: std::swap(f[i][0], f[i][1]); break;  // flipped
        case 1:                                        // a third face on the edge f[i][0] - f[i][1]
          p.push_back(p[f[i][2]] + Eigen::Vector3d(0, 0, 1));
          f.push_back({{f[i][1], f[i][0], p.size() - 1}});
          break;
        case 2: f.push_back({{f[i][0], f[i][1], f[i][0]}}); break;
        case 3: f.push_back({{f[i][0], f[i][1], p.size() + 3}}); break;
        default: f.push_back(f[i]); break;
      }
    }
    std::shuffle(f.begin(), f.end(), rng);
    const std::string expected = first_fault_by_scan(p, f);
    if(expected.empty()) continue;
    ++faulty;
    const std::string m = invalid_input_message([&] { AC::Input_surface(p, f); });
    BOOST_TEST(contains(m, expected), "trial " << trial << ": " << m << " / expected: " << expected);
  }
  BOOST_TEST(faulty > 250);
}

// the Euler characteristic and the boundary loops of valid inputs, against counts made independently
BOOST_AUTO_TEST_CASE(topology_of_valid_inputs)
{
  std::mt19937 rng(22u);
  for(int trial = 0; trial < 20; ++trial) {
    const int nx = 3 + int(rng() % 6), ny = 3 + int(rng() % 6);
    const AC::Input_surface s = random_grid_disk(rng, nx, ny, trial % 2 == 1);
    std::set<std::pair<std::size_t, std::size_t>> edges;
    for(const auto& t : s.faces())
      for(int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    BOOST_TEST(s.euler_characteristic() == int(s.number_of_vertices()) - int(edges.size()) + int(s.number_of_faces()));
    BOOST_TEST(s.euler_characteristic() == 1);
    BOOST_REQUIRE(s.boundary_loops().size() == 1u);
    BOOST_TEST(s.boundary_loops()[0].size() == std::size_t(2 * (nx - 1) + 2 * (ny - 1)));
    BOOST_TEST(s.boundary_loops()[0].front() == 0u);  // started at the smallest boundary vertex
  }
}

BOOST_AUTO_TEST_CASE(non_symmetric_tensor_in_remesh)
{
  std::mt19937 rng(8u);
  const AC::Input_surface grid = random_grid_disk(rng, 8, 8, false);
  std::vector<Eigen::Matrix3d> t(grid.number_of_vertices(), Eigen::Matrix3d::Identity());
  t[4](0, 1) = 0.5;
  AC::Remeshing_result r;
  BOOST_TEST(contains(invalid_input_message([&] {
                        AC::remesh(grid, AC::Tensor_field_metric(t), r, AC::parameters::number_of_vertices(std::size_t(20)));
                      }),
                      "vertex 4: the tensor is not symmetric"));
}

BOOST_AUTO_TEST_CASE(tensor_field_with_missing_or_extra_tensors)
{
  std::mt19937 rng(9u);
  const AC::Input_surface grid = random_grid_disk(rng, 8, 8, false);
  AC::Remeshing_result r;
  // one tensor missing: refused, naming the vertex without one
  std::vector<Eigen::Matrix3d> t(grid.number_of_vertices() - 1, Eigen::Matrix3d::Identity());
  BOOST_TEST(contains(invalid_input_message([&] {
                        AC::remesh(grid, AC::Tensor_field_metric(t), r, AC::parameters::number_of_vertices(std::size_t(20)));
                      }),
                      "the tensor field has 63 tensors but the mesh refers to vertex 63"));
  // extra tensors (an API field longer than the mesh): ignored, the run is the one with the exact field
  t.assign(grid.number_of_vertices() + 5, Eigen::Matrix3d::Identity());
  AC::Remeshing_result r2;
  const AC::Remeshed_surface a = AC::remesh(grid, AC::Tensor_field_metric(t), r2, AC::parameters::number_of_vertices(std::size_t(20)));
  t.resize(grid.number_of_vertices());
  const AC::Remeshed_surface b = AC::remesh(grid, AC::Tensor_field_metric(t), r2, AC::parameters::number_of_vertices(std::size_t(20)));
  BOOST_TEST(a.points.size() == 20u);
  BOOST_TEST(same_bits(a.points, b.points));
}

BOOST_AUTO_TEST_CASE(closed_genus_two_goes_to_the_hyperbolic_disk)
{
  // a 5 x 3 slab of voxels with two holes through it: coarse (flat faces, sharp edges) but valid
  std::vector<std::array<int, 2>> cells;
  for(int x = 0; x < 5; ++x)
    for(int y = 0; y < 3; ++y)
      if(!(y == 1 && (x == 1 || x == 3))) cells.push_back({{x, y}});
  const AC::Input_surface s = voxel_surface(cells);
  BOOST_REQUIRE(s.boundary_loops().empty());
  BOOST_REQUIRE(s.genus() == 2);
  AC::Remeshing_result r;
  // below the smallest genus-2 triangulation: refused with the reason
  BOOST_TEST(contains(invalid_input_message([&] { AC::remesh(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(8))); }),
                      "genus 2 needs at least 10"));
  // its 24 corners (issue 15: where 3 edges of the voxels meet, each kept as an output vertex) need 24
  BOOST_TEST(contains(invalid_input_message([&] { AC::remesh(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(20))); }),
                      "the input has 24 corners"));
  // without features, 20 sites are too few for a Delaunay triangulation of this surface in the hyperbolic
  // disk that is a simplicial complex: a Remeshing_failure that says so (the smallest genus-2
  // triangulation has 10 vertices, but the sites of a CVT are not placed to realise it)
  BOOST_TEST(contains(remeshing_failure_message([&] {
                        AC::remesh(s, AC::Uniform_metric(), r,
                                   AC::parameters::number_of_vertices(std::size_t(20)).feature_angle(180.0).parametric_domain(
                                     AC::Parametric_domain::HYPERBOLIC));
                      }),
                      "too few for the hyperbolic surface"));
  // the automatic choice then tries the cone domain (issue 16): a closed genus-2 mesh of 20 vertices that
  // says why it left the hyperbolic disk, or, if the cones fail too, both reasons, the hyperbolic one first
  AC::Remeshed_surface through_cones;
  const std::string m = remeshing_failure_message([&] {
    through_cones = AC::remesh(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(20)).feature_angle(180.0));
  });
  BOOST_TEST_MESSAGE("genus-2 voxels at 20, automatic: " << (m == "(no exception)" ? r.domain_choice : m));
  if(m == "(no exception)") {
    BOOST_TEST((r.domain == AC::Parametric_domain::CONE));
    BOOST_TEST(contains(r.domain_choice, "too few for the hyperbolic surface"));
    BOOST_TEST(through_cones.points.size() == 20u);
    BOOST_TEST(through_cones.faces.size() == 2 * 20u + 4);  // 2 n + 4 g - 4, g = 2
  } else {
    BOOST_TEST(contains(m, "too few for the hyperbolic surface"));
    BOOST_TEST(contains(m, "; the cone domain failed too: "));
  }
  // 60 and 400 sites, more than this coarse input's 48 vertices: the background is refined on its faces
  // (issue 14), and the output is a valid genus-2 surface (2 n + 4 (g - 1) triangles) on the input
  for(std::size_t n : {60u, 400u}) {
    const AC::Remeshed_surface out = AC::remesh(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n));
    BOOST_TEST(out.points.size() == n);
    BOOST_TEST(out.faces.size() == 2 * n + 4);
    BOOST_TEST((r.domain == AC::Parametric_domain::HYPERBOLIC));
    BOOST_TEST(r.inverted_triangles == 0u);
    BOOST_TEST(r.refinement.vertices_after >= 2 * n);
    // the slab's sharp edges are rounded off (features: issue 15), less so with more vertices
    BOOST_TEST(r.hausdorff_distance_relative < (n < 100 ? 0.1 : 0.05), n << " sites: Hausdorff distance " << r.hausdorff_distance_relative);
  }
}

BOOST_AUTO_TEST_SUITE_END()  // properties
