// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Closed genus-1 surfaces through the flat torus: the homology basis, the flat conformal metric and its
// lattice (exact on a flat torus), the periodic CVT's integrals and dual, remesh() on the paper's Table 2
// cyclide against the quality bar, the BGL entry point, the pictures of the periodic CVT and of a curved
// mesh, and every error path.

#ifndef ANISO_CONFORMAL_TEST_UNITY  // else compiled with other modules in one translation unit (CMakeLists.txt)
#define BOOST_TEST_MODULE Aniso_conformal_flat_torus
#endif
#include <boost/test/unit_test.hpp>

#include <Aniso_conformal/Curvature_metric.h>
#include <Aniso_conformal/Euclidean_periodic_domain_traits.h>
#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/IO/write_report.h>
#include <Aniso_conformal/IO/write_svg.h>
#include <Aniso_conformal/Tensor_field_metric.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/flat_torus_embedding.h>
#include <Aniso_conformal/make_dupin_cyclide.h>
#include <Aniso_conformal/Flat_torus_domain.h>
#include <Aniso_conformal/remesh_in_domain.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include "domain_concept_checks.h"
#include "mesh_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <utility>

BOOST_AUTO_TEST_SUITE(flat_torus)  // also a namespace: keeps the helpers apart from other modules in one unit

namespace AC = Aniso_conformal;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;

namespace {

// the pipeline in the flat torus: what remesh() runs for a closed surface of genus 1
template <typename... Args>
auto remesh_torus(Args&&... args) -> decltype(AC::remesh_in_domain<AC::Flat_torus_domain>(std::forward<Args>(args)...))
{
  return AC::remesh_in_domain<AC::Flat_torus_domain>(std::forward<Args>(args)...);
}


const double pi = 3.14159265358979323846;

// a background with the metric's edge lengths, flipped and split until valid (stages 1 and 2)
template <typename Metric>
AC::Intrinsic_triangulation background(const AC::Input_surface& s, const Metric& metric)
{
  AC::Intrinsic_triangulation t(s, AC::compute_metric_square_roots(s, metric));
  AC::adjust_edge_lengths(t, s);
  return t;
}

// angle sum of every vertex for the scaled lengths
std::vector<double> angle_sums(const AC::Intrinsic_triangulation& t, const std::vector<double>& u)
{
  std::vector<double> sum(t.number_of_vertices(), 0.0);
  for(std::size_t f = 0; f < t.number_of_faces(); ++f) {
    bool deg = false;
    const auto a = AC::internal::corner_angles(AC::internal::scaled_face_lengths(t, int(f), u), deg);
    for(int k = 0; k < 3; ++k) sum[std::size_t(t.face_vertices(f)[k])] += a[k];
  }
  return sum;
}

// The output is a closed, connected, consistently oriented genus-1 2-manifold with n vertices
void check_torus_output(const AC::Remeshed_surface& out, std::size_t n)
{
  BOOST_TEST(out.points.size() == n);
  BOOST_TEST(out.faces.size() == 2 * n);
  const test::Mesh_counts m = test::count_mesh(out.points, out.faces);
  BOOST_TEST(m.boundary_edges == 0u);
  BOOST_TEST(m.euler == 0);
  // Input_surface checks manifoldness, orientation and connectivity
  std::vector<AC::Input_surface::Face> faces(out.faces.begin(), out.faces.end());
  BOOST_CHECK_NO_THROW(AC::Input_surface(out.points, faces));
}

} // namespace

BOOST_AUTO_TEST_CASE(flat_torus_domain_models_its_concepts)
{
  const AC::Input_surface octahedron = AC::Input_surface({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                                           {{{0, 2, 4}}, {{2, 1, 4}}, {{1, 3, 4}}, {{3, 0, 4}}, {{2, 0, 5}}, {{1, 2, 5}}, {{3, 1, 5}}, {{0, 3, 5}}});
  test::check_domain_concept<AC::Flat_torus_domain>(AC::make_dupin_cyclide(24, 16), octahedron, 200);
  // the fewest vertices of a torus: 7 (Moebius' torus)
  BOOST_CHECK_NO_THROW(AC::Flat_torus_domain::check_number_of_vertices(AC::make_dupin_cyclide(24, 16), 7));
  BOOST_CHECK_THROW(AC::Flat_torus_domain::check_number_of_vertices(AC::make_dupin_cyclide(24, 16), 6), AC::Invalid_input);
}

// the flat torus has none of the optional hooks of a curved domain: its CVT is the unconstrained one
static_assert(!AC::internal::Has_project_to_domain<AC::Euclidean_periodic_domain_traits>::value, "the torus has no hook");
static_assert(!AC::internal::Has_project_to_tangent_plane<AC::Euclidean_periodic_domain_traits>::value, "the torus has no hook");

BOOST_AUTO_TEST_CASE(tree_cotree_gives_two_generators_whose_loops_close)
{
  const AC::Input_surface s = AC::make_dupin_cyclide(12, 8);
  const AC::Intrinsic_triangulation t(s, std::vector<Eigen::Matrix3d>(s.number_of_vertices(), Eigen::Matrix3d::Identity()));
  const AC::internal::Tree_cotree tc = AC::internal::tree_cotree(t);
  BOOST_TEST(tc.generators.size() == 2u);
  std::size_t tree = 0, cotree = 0;
  for(int h = 0; h < int(t.number_of_halfedges()); ++h)
    if(t.is_edge_representative(h)) {
      tree += tc.in_tree[std::size_t(h)];
      cotree += tc.in_cotree[std::size_t(h)];
      BOOST_TEST(!(tc.in_tree[std::size_t(h)] && tc.in_cotree[std::size_t(h)]));
    }
  BOOST_TEST(tree == t.number_of_vertices() - 1);
  BOOST_TEST(cotree == t.number_of_faces() - 1);
  for(int g : tc.generators) {
    const std::vector<int> loop = AC::internal::generator_loop(t, tc, g);
    BOOST_TEST(loop.front() == t.head(g));
    BOOST_TEST(loop.back() == t.tail(g));
    for(std::size_t i = 0; i + 1 < loop.size(); ++i) BOOST_TEST(t.find_halfedge(loop[i], loop[i + 1]) >= 0);
  }
  // a disk has no homology basis to find
  const AC::Input_surface disk({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)}, {{{0, 1, 2}}});
  const AC::Intrinsic_triangulation td(disk, std::vector<Eigen::Matrix3d>(3, Eigen::Matrix3d::Identity()));
  BOOST_CHECK_THROW(AC::internal::tree_cotree(td), AC::Invalid_input);
}

BOOST_AUTO_TEST_CASE(flat_torus_embedding_recovers_a_flat_lattice_exactly)
{
  // A grid on the torus with the edge lengths of the flat torus R^2 / (Z a0 + Z b0): the solve must
  // leave u = 0 and give back the same lattice (up to a rotation and the reduction of the basis).
  const std::size_t nu = 9, nv = 7;
  const AC::Input_surface s = AC::make_dupin_cyclide(nu, nv);
  AC::Intrinsic_triangulation t(s, std::vector<Eigen::Matrix3d>(s.number_of_vertices(), Eigen::Matrix3d::Identity()));
  const Eigen::Vector2d a0(1.0, 0.0), b0(0.35, 0.8);
  for(int h = 0; h < int(t.number_of_halfedges()); ++h) {
    const int p = t.tail(h), q = t.head(h);
    // grid steps between the two ends, taken modulo the grid (neighbours differ by at most one step)
    auto step = [](int d, int n) { return d > n / 2 ? d - n : (d < -n / 2 ? d + n : d); };
    const int di = step(q / int(nv) - p / int(nv), int(nu)), dj = step(q % int(nv) - p % int(nv), int(nv));
    t.set_length(h, (double(di) / nu * a0 + double(dj) / nv * b0).norm());
  }
  const AC::Flat_torus_embedding emb = AC::flat_torus_embedding(t);
  for(double u : emb.u) BOOST_TEST(std::abs(u) < 1e-9);
  const Eigen::Vector2d a = emb.lattice[0], b = emb.lattice[1];
  Eigen::Vector2d ra = a0, rb = b0;
  AC::internal::reduce_lattice_basis(ra, rb);
  BOOST_TEST(std::abs(a.norm() - ra.norm()) < 1e-9);
  BOOST_TEST(std::abs(b.norm() - rb.norm()) < 1e-9);
  BOOST_TEST(std::abs(a.dot(b) - ra.dot(rb)) < 1e-9);
  BOOST_TEST(a.x() * b.y() - a.y() * b.x() > 0);
  BOOST_TEST(emb.lattice_error < 1e-9);
  for(double cf : emb.conformal_factor) BOOST_TEST(std::abs(cf - 1) < 1e-9);
  // the lattice is reduced
  BOOST_TEST(a.norm() <= b.norm() + 1e-12);
  BOOST_TEST(std::abs(a.dot(b)) <= 0.5 * a.squaredNorm() + 1e-12);
}

BOOST_AUTO_TEST_CASE(flat_torus_embedding_of_a_curved_cyclide_is_flat_and_consistent)
{
  const AC::Input_surface s = AC::make_dupin_cyclide(36, 24);
  AC::Curvature_metric_options co;
  co.stretch_max = 10;
  AC::Intrinsic_triangulation t = background(s, AC::Curvature_metric(s, co));
  const AC::Flat_torus_embedding emb = AC::flat_torus_embedding(t, AC::parameters::conformal_tolerance(1e-10));
  BOOST_TEST(emb.residual <= 1e-10);
  BOOST_TEST(emb.u[0] == 0.0);
  for(double sum : angle_sums(t, emb.u)) BOOST_TEST(std::abs(sum - 2 * pi) < 1e-8);
  // the cell's area is the area of the flat metric, and every face is laid out counterclockwise
  double area = 0;
  for(const auto& c : emb.corner_uv) {
    const Eigen::Vector2d e1 = c[1] - c[0], e2 = c[2] - c[0];
    const double a = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    BOOST_TEST(a > 0);
    area += a;
  }
  const double det = emb.lattice[0].x() * emb.lattice[1].y() - emb.lattice[0].y() * emb.lattice[1].x();
  BOOST_TEST(std::abs(det - area) < 1e-8 * area);
  BOOST_TEST(emb.lattice_error < 1e-6);
  for(const auto& loop : emb.homology_basis) BOOST_TEST(loop.size() >= 3u);
  for(double cf : emb.conformal_factor) BOOST_TEST((cf > 0 && std::isfinite(cf)));
  // the Newton bound is reported with the residual reached
  AC::Intrinsic_triangulation t2 = background(s, AC::Curvature_metric(s, co));
  try {
    AC::flat_torus_embedding(t2, AC::parameters::max_conformal_iterations(1u).conformal_tolerance(1e-15));
    BOOST_FAIL("the bound was not enforced");
  } catch(const AC::Convergence_failure& e) {
    BOOST_TEST(std::string(e.what()).find("flat torus embedding") != std::string::npos);
    BOOST_TEST(e.residual() > 0);
  }
  // wrong topology
  const AC::Input_surface disk({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)}, {{{0, 1, 2}}});
  AC::Intrinsic_triangulation td = background(disk, AC::Uniform_metric());
  BOOST_CHECK_THROW(AC::flat_torus_embedding(td), AC::Invalid_input);
}

BOOST_AUTO_TEST_CASE(coarse_faceted_torus_is_not_flagged_as_inverted)
{
  // CGAL's pipe.off (160 vertices, 320 faces) to 2000: refused as "inverted" before (issue 14), when the
  // output triangles along its creases were judged against averaged vertex normals only
  const AC::Input_surface s = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_TEST_DATA_DIR) + "/cgal/pipe.off");
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = remesh_torus(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(2000)));
  BOOST_TEST(out.points.size() == 2000u);
  BOOST_TEST(out.faces.size() == 4000u);  // genus 1: F = 2V
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.quality.G_avg >= 0.9);
  BOOST_TEST(r.quality.theta_min >= 25.0);
}

BOOST_AUTO_TEST_CASE(periodic_cvt_integrates_exactly_and_its_dual_is_a_torus)
{
  const AC::Input_surface s = AC::make_dupin_cyclide(36, 24);
  AC::Intrinsic_triangulation t = background(s, AC::Uniform_metric());
  const AC::Flat_torus_embedding emb = AC::flat_torus_embedding(t);
  AC::Euclidean_periodic_domain_traits domain(t, emb, 2);
  const std::size_t n = 150;
  std::vector<Eigen::Vector2d> sites = domain.initial_sites(n, 3);
  for(const auto& p : sites) {
    const Eigen::Vector2d st = domain.lattice_coordinates(p);
    BOOST_TEST((st.x() >= 0 && st.x() < 1 && st.y() >= 0 && st.y() < 1));
  }
  std::vector<AC::Euclidean_periodic_domain_traits::Cell> cells;
  domain.integrate(sites, cells);
  double mass = 0;
  for(const auto& c : cells) {
    BOOST_TEST(c.mass > 0);
    mass += c.mass;
  }
  BOOST_TEST(std::abs(mass - domain.total_mass()) < 1e-9 * domain.total_mass());
  // a site's class, not its translate, matters: translating a site by a lattice vector changes nothing
  // but moves its centroid along
  std::vector<Eigen::Vector2d> moved = sites;
  moved[7] += 2.0 * domain.lattice()[0] - domain.lattice()[1];
  std::vector<AC::Euclidean_periodic_domain_traits::Cell> cells2;
  domain.integrate(moved, cells2);
  BOOST_TEST(std::abs(cells2[7].mass - cells[7].mass) < 1e-12 * mass);
  BOOST_TEST(std::abs(cells2[7].energy - cells[7].energy) < 1e-12 * mass);
  BOOST_TEST(((cells2[7].centroid - moved[7]) - (cells[7].centroid - sites[7])).norm() < 1e-9);
  // the gradient 2 m (x - c) matches a central difference of the energy
  auto energy = [&](const std::vector<Eigen::Vector2d>& x) {
    std::vector<AC::Euclidean_periodic_domain_traits::Cell> c;
    domain.integrate(x, c);
    double e = 0;
    for(const auto& cell : c) e += cell.energy;
    return e;
  };
  const double h = 1e-6 * std::sqrt(domain.area());
  for(int d = 0; d < 2; ++d) {
    std::vector<Eigen::Vector2d> xp = sites, xm = sites;
    xp[11][d] += h;
    xm[11][d] -= h;
    const double fd = (energy(xp) - energy(xm)) / (2 * h);
    const double g = 2 * cells[11].mass * (sites[11][d] - cells[11].centroid[d]);
    BOOST_TEST(std::abs(fd - g) < 1e-4 * (std::abs(g) + cells[11].mass * std::sqrt(domain.area() / n)));
  }
  // Lloyd and L-BFGS decrease the energy
  std::vector<Eigen::Vector2d> x;
  for(AC::Cvt_method method : {AC::Cvt_method::LLOYD, AC::Cvt_method::LBFGS}) {
    x = sites;
    const AC::Cvt_report rep =
        AC::weighted_centroidal_Voronoi_tessellation(domain, x, 0, AC::parameters::number_of_iterations(20u).cvt_method(method));
    BOOST_TEST(rep.energy.back() < rep.energy.front());
    BOOST_TEST(rep.iterations == 20u);
  }
  // the dual of the optimised sites is the periodic Delaunay triangulation: 2 n triangles forming a torus
  sites = x;
  const auto tris = domain.dual_triangles(sites);
  BOOST_TEST(tris.size() == 2 * n);
  std::vector<Eigen::Vector3d> pts;
  for(const auto& p : sites) pts.emplace_back(p.x(), p.y(), 0.0);
  const test::Mesh_counts m = test::count_mesh(pts, tris);
  BOOST_TEST(m.boundary_edges == 0u);
  BOOST_TEST(m.euler == 0);
  // coincident sites are refused
  std::vector<Eigen::Vector2d> twins = sites;
  twins[1] = twins[0] + domain.lattice()[1];
  BOOST_CHECK_THROW(domain.dual_triangles(twins), AC::Convergence_failure);
  // every site maps back onto the background
  int face = -1;
  Eigen::Vector3d bary;
  for(const auto& p : sites) BOOST_TEST(domain.background_location(0, p + domain.lattice()[0], face, bary));
  BOOST_TEST(!domain.background_location(0, Eigen::Vector2d(std::numeric_limits<double>::quiet_NaN(), 0), face, bary));
}

BOOST_AUTO_TEST_CASE(delaunay_graph_repaired_by_flips_gives_the_integrals_of_a_new_one)
{
  // The periodic Delaunay triangulation is kept between integrations and repaired by flips: along a CVT's
  // path, with sites crossing the fundamental cell's sides and a jump that breaks the triangulation, the
  // integrals are bit for bit those of traits that triangulate afresh (one thread, and two: the split
  // triangulation), and most integrations were repairs
  const AC::Input_surface s = AC::make_dupin_cyclide(36, 24);
  AC::Intrinsic_triangulation t = background(s, AC::Uniform_metric());
  const AC::Flat_torus_embedding emb = AC::flat_torus_embedding(t);
  AC::Euclidean_periodic_domain_traits domain(t, emb, 1);
  const std::size_t n = 150;
  std::vector<Eigen::Vector2d> x = domain.initial_sites(n, 5);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> jitter(0.0, 0.05 * std::sqrt(domain.area() / double(n)));
  typedef AC::Euclidean_periodic_domain_traits::Cell Cell;
  std::size_t compared = 0;
  for(int step = 0; step < 24; ++step) {
    std::vector<Cell> kept, fresh1, fresh2;
    domain.integrate(x, kept);
    AC::Euclidean_periodic_domain_traits(t, emb, 1).integrate(x, fresh1);
    AC::Euclidean_periodic_domain_traits(t, emb, 2).integrate(x, fresh2);
    for(std::size_t i = 0; i < n; ++i) {
      BOOST_TEST(kept[i].mass == fresh1[i].mass);
      BOOST_TEST(kept[i].energy == fresh1[i].energy);
      BOOST_TEST((kept[i].centroid == fresh1[i].centroid));
      BOOST_TEST(kept[i].mass == fresh2[i].mass);
      BOOST_TEST(kept[i].energy == fresh2[i].energy);
    }
    ++compared;
    // Lloyd's step with a little noise; some sites pushed across the cell's sides by a lattice vector
    for(std::size_t i = 0; i < n; ++i) {
      x[i] = kept[i].centroid + Eigen::Vector2d(jitter(rng), jitter(rng));
      if(i % 37 == std::size_t(step) % 37) x[i] += domain.lattice()[0] - 2.0 * domain.lattice()[1];
    }
    if(step == 12) std::shuffle(x.begin(), x.end(), rng);  // every site elsewhere: no triangulation to repair
  }
  BOOST_TEST(compared == 24u);
  BOOST_TEST(domain.delaunay_repairs() >= 20u);
  BOOST_TEST(domain.delaunay_repairs() <= 22u);  // the first integration, and the one after the shuffle, built anew
}


// The Delaunay graph built as two halves on two threads is the graph of one triangulation: every
// point with a triangle that matters has the same neighbours, and the same triangles matter; a margin
// too narrow for the points is detected, not trusted.
BOOST_AUTO_TEST_CASE(split_delaunay_graph_equals_one_triangulation)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector2d> pts;
  for(int i = 0; i < 6000; ++i) {  // dense on the left, sparse on the right (spacing 1 to 6 times)
    const double x = std::pow(u(rng), 2.0);
    pts.emplace_back(2 * x, u(rng));
  }
  const auto inner = [](const std::array<int, 3>&, const Eigen::Vector2d& c) {
    return c.x() > 0.2 && c.x() < 1.8 && c.y() > 0.1 && c.y() < 0.9;
  };
  AC::internal::Delaunay_fans whole, split;
  AC::internal::whole_delaunay_fans(pts, inner, whole);
  const double spacing = std::sqrt(2.0 / double(pts.size()));
  BOOST_REQUIRE(AC::internal::split_delaunay_fans(pts, 8 * spacing, 2, inner, split));
  BOOST_TEST(split.start.size() == pts.size() + 1);
  std::set<std::array<int, 3>> fw(whole.faces.begin(), whole.faces.end()), fs(split.faces.begin(), split.faces.end());
  BOOST_TEST(fw.size() == whole.faces.size());
  BOOST_TEST(fs.size() == split.faces.size());
  BOOST_TEST((fw == fs));
  std::set<int> relevant;
  for(const auto& f : whole.faces) relevant.insert(f.begin(), f.end());
  BOOST_TEST(relevant.size() > 2000u);
  std::size_t same = 0;
  for(int i : relevant) {
    const std::vector<int> a(whole.nbr.begin() + whole.start[std::size_t(i)], whole.nbr.begin() + whole.start[std::size_t(i) + 1]);
    const std::vector<int> b(split.nbr.begin() + split.start[std::size_t(i)], split.nbr.begin() + split.start[std::size_t(i) + 1]);
    BOOST_TEST(std::is_sorted(a.begin(), a.end()));
    same += a == b;
  }
  BOOST_TEST(same == relevant.size());
  // one thread builds the same halves in turn
  AC::internal::Delaunay_fans serial;
  BOOST_REQUIRE(AC::internal::split_delaunay_fans(pts, 8 * spacing, 1, inner, serial));
  BOOST_TEST((serial.nbr == split.nbr));
  BOOST_TEST((serial.start == split.start));
  // a margin of a hundredth of a spacing leaves wrong triangles along the split: refused
  AC::internal::Delaunay_fans narrow;
  BOOST_TEST(!AC::internal::split_delaunay_fans(pts, 0.01 * spacing, 2, inner, narrow));
}

// The periodic CVT integrates the same cells, bit for bit, on one thread (one triangulation) and on two
// (two halves), with a density that varies over the torus.
BOOST_AUTO_TEST_CASE(periodic_cvt_integrals_do_not_depend_on_the_threads)
{
  const AC::Input_surface s = AC::make_dupin_cyclide(72, 48);
  AC::Intrinsic_triangulation t = background(s, AC::Uniform_metric());
  const AC::Flat_torus_embedding emb = AC::flat_torus_embedding(t);
  AC::Euclidean_periodic_domain_traits one(t, emb, 1), two(t, emb, 2);
  std::vector<Eigen::Vector2d> sites = one.initial_sites(3000, 4);
  AC::weighted_centroidal_Voronoi_tessellation(two, sites, 0, AC::parameters::number_of_iterations(10u));
  std::vector<AC::Euclidean_periodic_domain_traits::Cell> c1, c2;
  one.integrate(sites, c1);
  two.integrate(sites, c2);
  BOOST_REQUIRE(c1.size() == c2.size());
  std::size_t differ = 0;
  double mass = 0;
  for(std::size_t i = 0; i < c1.size(); ++i) {
    differ += !(c1[i].mass == c2[i].mass && c1[i].energy == c2[i].energy && c1[i].centroid == c2[i].centroid);
    mass += c2[i].mass;
  }
  BOOST_TEST(differ == 0u);
  BOOST_TEST(std::abs(mass - two.total_mass()) < 1e-9 * two.total_mass());
}

BOOST_AUTO_TEST_CASE(table2_cyclide_meets_the_quality_bar)
{
  // the paper's Table 2 / Fig. 11 case: 25920 vertices, curvature metric with stretch up to 29, 8000 vertices
  const AC::Input_surface s = AC::make_dupin_cyclide(180, 144);
  const std::vector<Eigen::Vector3d> points_before = s.points();
  AC::Curvature_metric_options co;
  co.stretch_max = 29;
  const AC::Curvature_metric metric(s, co);
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = remesh_torus(s, metric, r, AC::parameters::number_of_vertices(std::size_t(8000)));
  check_torus_output(out, 8000);
  BOOST_TEST((r.domain == AC::Parametric_domain::FLAT_TORUS));
  const AC::Quality_report& q = r.quality;
  BOOST_TEST_MESSAGE("Table 2: G_min " << q.G_min << " G_avg " << q.G_avg << " theta_min " << q.theta_min << " %<30 "
                                       << q.percent_below_30 << " Hausdorff " << r.hausdorff_distance_relative);
  BOOST_TEST(q.G_avg >= 0.90);
  BOOST_TEST(q.theta_min >= 20.0);
  BOOST_TEST(q.percent_below_30 <= 0.5);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.hausdorff_distance_relative < 0.005);
  BOOST_TEST(r.hausdorff_distance_relative > 0.0);
  // every vertex on the input: its barycentric position is the vertex
  for(const auto& sp : out.surface_points) {
    const Eigen::Vector3d x = sp.barycentric[0] * s.points()[sp.vertices[0]] + sp.barycentric[1] * s.points()[sp.vertices[1]] +
                              sp.barycentric[2] * s.points()[sp.vertices[2]];
    BOOST_TEST((x - sp.position).norm() < 1e-9);
  }
  BOOST_TEST((s.points() == points_before));
}

BOOST_AUTO_TEST_CASE(unsmoothed_table2_field_reaches_the_angle_bar_with_the_surface_optimization)
{
  // issue 17: the Table 2 cyclide's curvature field with its scales unsmoothed (stretch bound 29 reached
  // where a principal curvature vanishes), 2000 vertices, Surface_optimization::ALWAYS. The max-min angle
  // pass aims its targets at the apex equilateral in the metric, not only in space: measured theta_min
  // 18.2 after the dual -> 31.26, %<30 0.275 -> 0, G_avg 0.933 with the second phase (vertices toward their
  // ideal point in the metric; first phase only: 30.74 and 0; with the apex in space only: 29.61 and 0.025)
  const AC::Input_surface s = AC::make_dupin_cyclide(180, 144);
  AC::Curvature_metric_options co;
  co.stretch_max = 29;
  co.smoothing_iterations = 0;
  co.scale_smoothing_iterations = 0;
  const AC::Curvature_metric metric(s, co);
  AC::Remeshing_result r;
  const AC::Remeshed_surface out =
      remesh_torus(s, metric, r, AC::parameters::number_of_vertices(std::size_t(2000)).surface_optimization(AC::Surface_optimization::ALWAYS));
  check_torus_output(out, 2000);
  BOOST_TEST_MESSAGE("unsmoothed Table 2 field, 2000 vertices: G_min " << r.quality.G_min << " G_avg " << r.quality.G_avg
                                                                     << " theta_min " << r.quality.theta_min << " %<30 "
                                                                     << r.quality.percent_below_30);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.surface_optimization.ran);
  BOOST_TEST(r.surface_optimization.theta_min_before < 25.0);
  BOOST_TEST(r.quality.G_avg >= 0.90);
  BOOST_TEST(r.quality.theta_min > 30.0);
  BOOST_TEST(r.quality.percent_below_30 < 0.0125);
  BOOST_TEST(r.quality.stretch_max > 6.0);  // the anisotropy is realised (8.17 measured at the vertices)
}

BOOST_AUTO_TEST_CASE(paper_stretch_field_remeshes_with_the_stretch_bounded_where_edges_cannot_follow_it)
{
  // issue 17: a field on the Table 2 cyclide whose stretch spans the paper's [2, 29] exactly
  // (make_dupin_cyclide_stretch_field(): the long axis along the tube, stretch |kappa_v / kappa_u| clamped).
  // Along the tube the long axis turns within the tangent plane (geodesic curvature up to ~1), and at 2000
  // vertices the longest elements' straight edges leave it by more than the elements' width: the run in
  // the field as given folds 8 triangles (Convergence_failure before the stretch bound). remesh_in_domain()
  // then bounds the stretch where it cannot be followed (Stretch_limit_report) and remeshes. Measured:
  // 6670 input vertices bounded (bounds 4.83 to 29, median 6.3), G_avg 0.918, theta_min 30.1, %<30 0 in the
  // bounded metric; in the field as given G_avg 0.902, theta_min 13.6; stretch at the output [2, 9.99].
  const AC::Input_surface s = AC::make_dupin_cyclide(180, 144);
  const AC::Tensor_field_metric field = AC::make_dupin_cyclide_stretch_field(180, 144);
  BOOST_REQUIRE(field.size() == s.number_of_vertices());
  // the field's own stretch at the vertices spans [2, 29]
  double lo = 1e300, hi = 0;
  for(std::size_t v = 0; v < s.number_of_vertices(); ++v) {
    const AC::internal::Tangent_scales sc = AC::internal::tangent_scales(field.tensors()[v], s.vertex_normals()[v]);
    lo = std::min(lo, sc.big / sc.small);
    hi = std::max(hi, sc.big / sc.small);
  }
  BOOST_TEST(lo == 2.0, boost::test_tools::tolerance(0.02));
  BOOST_TEST(hi == 29.0, boost::test_tools::tolerance(0.02));
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = remesh_torus(s, field, r, AC::parameters::number_of_vertices(std::size_t(2000)));
  check_torus_output(out, 2000);
  const AC::Stretch_limit_report& l = r.stretch_limit;
  BOOST_TEST_MESSAGE("[2, 29] field, 2000 vertices: " << l.vertices_limited << " vertices bounded (from " << l.bound_min
                     << ", median " << l.bound_median << "); G_avg " << r.quality.G_avg << " theta_min " << r.quality.theta_min
                     << " %<30 " << r.quality.percent_below_30 << "; in the field as given G_avg " << l.given_G_avg
                     << " theta_min " << l.given_theta_min << "; stretch at the output [" << r.quality.stretch_min << ", "
                     << r.quality.stretch_max << "]; discarded " << r.discarded_seconds << " s");
  BOOST_TEST(l.applied);
  BOOST_TEST(l.reason.find("inverted") != std::string::npos);
  BOOST_TEST(l.vertices_limited > 1000u);
  BOOST_TEST(l.vertices_limited < s.number_of_vertices() / 2);
  BOOST_TEST(l.stretch_asked_max == 29.0, boost::test_tools::tolerance(0.02));
  BOOST_TEST(l.bound_min > 2.0);
  BOOST_TEST(l.bound_min < l.bound_median);
  BOOST_TEST(r.discarded_seconds > 0.0);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.quality.G_avg >= 0.90);
  BOOST_TEST(r.quality.theta_min >= 25.0);
  BOOST_TEST(r.quality.stretch_min >= 1.95);  // the lower end of the field is realised
  BOOST_TEST(r.quality.stretch_max > 7.0);    // and far more than the curvature metric's default smoothing keeps
  BOOST_TEST(l.given_G_avg > 0.85);
  BOOST_TEST(l.given_G_avg < r.quality.G_avg);  // the bounded elements are rounder than the field asks
  const nlohmann::json j = AC::IO::report_json(r);  // the JSON report says it too
  BOOST_TEST(j.at("stretch_limit").at("vertices_limited").get<std::size_t>() == l.vertices_limited);
  BOOST_TEST(j.at("stretch_limit").at("given_metric_quality").at("G_avg").get<double>() ==
             l.given_G_avg, boost::test_tools::tolerance(1e-9));
  // the bound does not touch a field the output can follow: an isotropic metric fails as it did
  BOOST_CHECK_THROW(remesh_torus(AC::make_dupin_cyclide(12, 8), AC::Uniform_metric(), r,
                                 AC::parameters::number_of_vertices(std::size_t(2000)).max_conformal_iterations(1)),
                    AC::Convergence_failure);
  BOOST_TEST(!r.stretch_limit.applied);
}

// The torus (R = 2, r = 1) as a 240 x 80 grid, and its exact curvature metric at stretch 30 (what
// benchmark/make_torus_metric.py writes as a metric file): at (u, v) the principal curvatures are 1 / r
// along the tube (t_v) and cos v / (R + r cos v) around the axis (t_u); scales their square roots, the
// smaller raised to the larger over 30. `exact_sqrt(p)` is the square root of that metric at the torus
// point p (tangent only), to judge a mesh in the exact metric whatever metric remeshed it.
namespace {
struct Stretch_30_torus {
  static constexpr double R = 2, r = 1, stretch = 30, pi = 3.14159265358979323846;
  static void scales(double u, double v, Eigen::Vector3d& tu, Eigen::Vector3d& tv, double& s_u, double& s_v)
  {
    const double rho = R + r * std::cos(v);
    tu = Eigen::Vector3d(-std::sin(u), std::cos(u), 0);
    tv = Eigen::Vector3d(-std::sin(v) * std::cos(u), -std::sin(v) * std::sin(u), std::cos(v));
    s_v = std::sqrt(1.0 / r);
    s_u = std::sqrt(std::abs(std::cos(v) / rho));
    const double big = std::max(s_v, s_u);
    s_v = std::max(s_v, big / stretch);
    s_u = std::max(s_u, big / stretch);
  }
  static Eigen::Matrix3d exact_sqrt(const Eigen::Vector3d& p)
  {
    const double u = std::atan2(p.y(), p.x()), v = std::atan2(p.z(), std::hypot(p.x(), p.y()) - R);
    Eigen::Vector3d tu, tv;
    double s_u, s_v;
    scales(u, v, tu, tv, s_u, s_v);
    return s_v * tv * tv.transpose() + s_u * tu * tu.transpose();
  }
  std::vector<Eigen::Matrix3d> tensors;  // the exact metric at the grid's vertices
  AC::Input_surface surface;
  Stretch_30_torus() : surface(make(tensors)) {}
  static AC::Input_surface make(std::vector<Eigen::Matrix3d>& tensors)
  {
    const std::size_t nu = 240, nv = 80;
    std::vector<Eigen::Vector3d> points;
    std::vector<AC::Input_surface::Face> faces;
    for(std::size_t j = 0; j < nv; ++j) {
      const double v = 2 * pi * double(j) / double(nv);
      for(std::size_t i = 0; i < nu; ++i) {
        const double u = 2 * pi * double(i) / double(nu), rho = R + r * std::cos(v);
        points.emplace_back(rho * std::cos(u), rho * std::sin(u), r * std::sin(v));
        Eigen::Vector3d tu, tv;
        double s_u, s_v;
        scales(u, v, tu, tv, s_u, s_v);
        tensors.push_back(s_v * s_v * tv * tv.transpose() + s_u * s_u * tu * tu.transpose());
      }
    }
    for(std::size_t j = 0; j < nv; ++j)
      for(std::size_t i = 0; i < nu; ++i) {
        const std::size_t p = j * nu + i, q = j * nu + (i + 1) % nu, a = ((j + 1) % nv) * nu + (i + 1) % nu, b = ((j + 1) % nv) * nu + i;
        faces.push_back({{p, q, a}});
        faces.push_back({{p, a, b}});
      }
    return AC::Input_surface(points, faces);
  }
};
} // namespace

BOOST_AUTO_TEST_CASE(exact_stretch_30_torus_metric_meets_the_quality_bar)
{
  // issue 17's bar: the stretch-30 torus with its exact curvature metric (a metric file's tensors),
  // 4000 vertices, Surface_optimization::ALWAYS: G_avg >= 0.90, theta_min >= 22.6, %<30 <= 0.02. Measured:
  // G_avg 0.937, theta_min 30.3, %<30 0 (the tool on make_torus_metric.py's files: 0.939, 32.2; before the
  // second phase of ALWAYS, which moves vertices toward their ideal point in the metric: 0.922, 30.3); with the max-min angle pass aimed at the apex
  // equilateral in space only and 3 steps: theta_min 20.1, %<30 0.175; in the metric too, 3 steps: 20.1
  // and 0.037; the default REPAIR: 9.4 and 0.31
  const Stretch_30_torus t;
  BOOST_REQUIRE(t.surface.genus() == 1);
  AC::Remeshing_result r_;
  const AC::Remeshed_surface out = remesh_torus(t.surface, AC::Tensor_field_metric(t.tensors), r_,
                                                AC::parameters::number_of_vertices(std::size_t(4000))
                                                  .surface_optimization(AC::Surface_optimization::ALWAYS));
  check_torus_output(out, 4000);
  BOOST_TEST_MESSAGE("stretch-30 torus: G_min " << r_.quality.G_min << " G_avg " << r_.quality.G_avg << " theta_min "
                                                << r_.quality.theta_min << " %<30 " << r_.quality.percent_below_30);
  BOOST_TEST(r_.inverted_triangles == 0u);
  BOOST_TEST(r_.quality.G_avg >= 0.90);
  BOOST_TEST(r_.quality.theta_min >= 22.6);
  BOOST_TEST(r_.quality.percent_below_30 <= 0.02);
  BOOST_TEST(r_.quality.stretch_max > 10.0);  // the stretch is realised, not smoothed away
}

BOOST_AUTO_TEST_CASE(own_curvature_metric_at_bound_30_meets_the_bar_in_the_exact_metric)
{
  // issue 17's bar, second half: the same torus remeshed with the library's own Curvature_metric at
  // stretch_max 30, judged in the exact metric. With its scales unsmoothed (scale_smoothing_iterations =
  // 0, the stretch-keeping setting; directions smoothed as by default) and Surface_optimization::ALWAYS:
  // measured in the exact metric G_avg 0.938, theta_min 30.5, %<30 0 (the tool, same settings: 0.938, 30.2). With the
  // default 10 rounds of scale smoothing the field's stretch at the output is at most 3.7 and the mesh,
  // judged in the exact metric, has theta_min 21.0 and 0.44 % below 30 degrees (bar not met)
  const Stretch_30_torus t;
  AC::Curvature_metric_options co;
  co.stretch_max = 30;
  co.scale_smoothing_iterations = 0;
  const AC::Curvature_metric metric(t.surface, co);
  AC::Remeshing_result r_;
  const AC::Remeshed_surface out = remesh_torus(t.surface, metric, r_,
                                                AC::parameters::number_of_vertices(std::size_t(4000))
                                                  .surface_optimization(AC::Surface_optimization::ALWAYS));
  check_torus_output(out, 4000);
  std::vector<Eigen::Matrix3d> exact(out.points.size());
  for(std::size_t i = 0; i < out.points.size(); ++i) exact[i] = Stretch_30_torus::exact_sqrt(out.points[i]);
  const AC::Quality_report q = AC::compute_mesh_quality(out.points, out.faces, exact);
  BOOST_TEST_MESSAGE("stretch-30 torus, own curvature metric, judged in the exact metric: G_min "
                     << q.G_min << " G_avg " << q.G_avg << " theta_min " << q.theta_min << " %<30 " << q.percent_below_30);
  BOOST_TEST(r_.inverted_triangles == 0u);
  BOOST_TEST(q.G_avg >= 0.90);
  BOOST_TEST(q.theta_min >= 22.6);
  BOOST_TEST(q.percent_below_30 <= 0.02);
}

BOOST_AUTO_TEST_CASE(high_stretch_embeds_with_intrinsic_flips)
{
  // Stretch ratios really up to 50 (no smoothing: the bound is reached where a principal curvature
  // vanishes), beyond the paper's 29: the intrinsic flips keep the conformal solve valid.
  const AC::Input_surface fine = AC::make_dupin_cyclide(180, 144);
  AC::Curvature_metric_options co;
  co.stretch_max = 50;
  co.smoothing_iterations = 0;
  co.scale_smoothing_iterations = 0;
  co.gradation = 0;  // the raw field: the size gradation (default 1.8) would bound its stretch near 13
  const AC::Curvature_metric metric(fine, co);
  BOOST_TEST(*std::max_element(metric.stretch_ratios().begin(), metric.stretch_ratios().end()) > 49.0);
  AC::Intrinsic_triangulation t = background(fine, metric);
  const AC::Flat_torus_embedding emb = AC::flat_torus_embedding(t);
  BOOST_TEST(emb.flips > 0u);
  BOOST_TEST(emb.residual <= 1e-9);
  BOOST_TEST(emb.degenerate_triangles == 0u);
  BOOST_TEST(emb.lattice_error < 1e-6);
  // and the whole pipeline with the bound 50 and the default smoothing
  const AC::Input_surface s = AC::make_dupin_cyclide(90, 72);
  co.smoothing_iterations = 10;
  co.scale_smoothing_iterations = 10;
  AC::Remeshing_result r;
  const AC::Remeshed_surface out =
      remesh_torus(s, AC::Curvature_metric(s, co), r, AC::parameters::number_of_vertices(std::size_t(1500)).random_seed(4u));
  check_torus_output(out, 1500);
  BOOST_TEST(r.quality.G_avg >= 0.85);
  BOOST_TEST(r.quality.theta_min >= 15.0);
}

BOOST_AUTO_TEST_CASE(surface_mesh_entry_point_and_determinism)
{
  const AC::Input_surface s = AC::make_dupin_cyclide(48, 32);
  CGAL::Surface_mesh<K::Point_3> in, out, out2;
  std::vector<CGAL::Surface_mesh<K::Point_3>::Vertex_index> v;
  for(const auto& p : s.points()) v.push_back(in.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
  for(const auto& f : s.faces()) in.add_face(v[f[0]], v[f[1]], v[f[2]]);
  const AC::Remeshing_result r = remesh_torus(in, AC::Uniform_metric(), out, AC::parameters::number_of_vertices(std::size_t(400)));
  BOOST_TEST(num_vertices(out) == 400u);
  BOOST_TEST(CGAL::is_closed(out));
  BOOST_TEST(CGAL::is_triangle_mesh(out));
  BOOST_TEST(int(num_vertices(out)) - int(num_edges(out)) + int(num_faces(out)) == 0);
  BOOST_TEST(r.quality.G_avg > 0.9);
  remesh_torus(in, AC::Uniform_metric(), out2, AC::parameters::number_of_vertices(std::size_t(400)));
  bool same = true;
  for(auto vd : vertices(out)) same = same && out.point(vd) == out2.point(vd);
  BOOST_TEST(same);
}

BOOST_AUTO_TEST_CASE(bad_genus_one_inputs_name_the_problem)
{
  const AC::Input_surface s = AC::make_dupin_cyclide(24, 16);
  auto message_of = [](auto&& f) -> std::string {
    try {
      f();
    } catch(const AC::Error& e) {
      return e.what();
    }
    return "";
  };
  auto remesh_with = [&](const AC::Input_surface& in, std::size_t n) {
    AC::Remeshing_result r;
    remesh_torus(in, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(n));
  };
  // the flat torus does not take a disk (the other domains' refusals: test_properties); a genus-1 surface
  // with a boundary it takes, its hole closed by a patch (test_boundaries)
  const AC::Input_surface disk({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 1, 0)},
                               {{{0, 1, 2}}, {{1, 3, 2}}});
  std::string m = message_of([&] { remesh_with(disk, 3); });
  BOOST_TEST(m.find("flat-torus domain does not fit") != std::string::npos);
  std::vector<AC::Input_surface::Face> holed(s.faces().begin() + 1, s.faces().end());
  m = message_of([&] { remesh_with(AC::Input_surface(s.points(), holed), 100); });
  BOOST_TEST(m.empty(), m);
  // too few vertices for a torus
  m = message_of([&] { remesh_with(s, 6); });
  BOOST_TEST(m.find("at least 7") != std::string::npos);
  // two disjoint tori, a non-manifold vertex (two tori glued at one vertex)
  std::vector<Eigen::Vector3d> two = s.points();
  std::vector<AC::Input_surface::Face> two_faces = s.faces();
  const std::size_t nv = s.number_of_vertices();
  for(const auto& p : s.points()) two.push_back(p + Eigen::Vector3d(5, 0, 0));
  for(const auto& f : s.faces()) two_faces.push_back({{f[0] + nv, f[1] + nv, f[2] + nv}});
  m = message_of([&] { AC::Input_surface(two, two_faces); });
  BOOST_TEST(m.find("2 connected components") != std::string::npos);
  // the point reflection of the torus through its vertex 0 touches it there only
  std::vector<Eigen::Vector3d> glued_points = s.points();
  std::vector<AC::Input_surface::Face> glued = s.faces();
  for(std::size_t i = 1; i < nv; ++i) glued_points.push_back(2 * s.points()[0] - s.points()[i]);
  for(const auto& f : s.faces()) {
    AC::Input_surface::Face g;
    for(int k = 0; k < 3; ++k) g[std::size_t(k)] = f[std::size_t(k)] == 0 ? 0 : f[std::size_t(k)] + nv - 1;
    glued.push_back({{g[0], g[2], g[1]}});  // the reflection reverses the orientation
  }
  m = message_of([&] { AC::Input_surface(glued_points, glued); });
  BOOST_TEST(m.find("non-manifold") != std::string::npos);
  // a NaN metric
  std::vector<Eigen::Matrix3d> nan_field(nv, Eigen::Matrix3d::Identity());
  nan_field[5](0, 0) = std::numeric_limits<double>::quiet_NaN();
  m = message_of([&] {
    AC::Remeshing_result r;
    remesh_torus(s, AC::Tensor_field_metric(nan_field), r, AC::parameters::number_of_vertices(std::size_t(100)));
  });
  BOOST_TEST(m.find("vertex 5") != std::string::npos);
  // a metric too wild for the background: a 1e8 jump between neighbouring vertices, a tight Newton bound
  std::vector<Eigen::Matrix3d> wild(nv, Eigen::Matrix3d::Identity());
  for(std::size_t i = 0; i < nv; i += 2) wild[i] *= 1e8;
  try {
    AC::Remeshing_result r;
    remesh_torus(s, AC::Tensor_field_metric(wild), r, AC::parameters::number_of_vertices(std::size_t(100)).max_conformal_iterations(2u));
    BOOST_FAIL("a wild metric with 2 Newton iterations was accepted");
  } catch(const AC::Convergence_failure& e) {
    BOOST_TEST_MESSAGE("wild metric: " << e.what());
    BOOST_TEST(e.residual() > 0);
  }
}

BOOST_AUTO_TEST_CASE(a_coarse_torus_remeshes_to_ten_times_its_vertices)
{
  // 96 input vertices, 1000 output vertices: the background is refined on the input's faces (issue 14)
  const AC::Input_surface s = AC::make_dupin_cyclide(12, 8);
  AC::Remeshing_result r;
  const AC::Remeshed_surface out = remesh_torus(s, AC::Uniform_metric(), r, AC::parameters::number_of_vertices(std::size_t(1000)));
  BOOST_TEST(out.points.size() == 1000u);
  BOOST_TEST(out.faces.size() == 2000u);
  BOOST_TEST(r.inverted_triangles == 0u);
  BOOST_TEST(r.refinement.vertices_after >= 2000u);
  BOOST_TEST(r.quality.G_avg >= 0.9);
  BOOST_TEST(r.quality.theta_min >= 25.0);
  BOOST_TEST_MESSAGE("coarse cyclide to 1000: G_avg " << r.quality.G_avg << ", theta_min " << r.quality.theta_min);
}

BOOST_AUTO_TEST_CASE(a_real_genus_one_model_knot1)
{
  // CGAL's trefoil-knot tube (the shipped stand-in for the paper's Kitten), curvature metric [1, 5]
  const AC::Input_surface s = AC::IO::read_triangle_mesh(std::string(ANISO_CONFORMAL_DATA_DIR) + "/meshes/knot1.off");
  BOOST_TEST(s.genus() == 1);
  AC::Curvature_metric_options co;
  co.stretch_max = 5;
  AC::Remeshing_result r;
  const AC::Remeshed_surface out =
      remesh_torus(s, AC::Curvature_metric(s, co), r, AC::parameters::number_of_vertices(std::size_t(1000)));
  check_torus_output(out, 1000);
  BOOST_TEST(r.quality.G_avg >= 0.90);
  BOOST_TEST(r.quality.theta_min >= 25.0);
  BOOST_TEST(r.hausdorff_distance_relative < 0.01);
}

BOOST_AUTO_TEST_CASE(pictures_of_the_periodic_cvt_and_of_a_curved_mesh)
{
  const AC::Input_surface s = AC::make_dupin_cyclide(36, 24);
  AC::Intrinsic_triangulation t = background(s, AC::Uniform_metric());
  const AC::Flat_torus_embedding emb = AC::flat_torus_embedding(t);
  AC::Euclidean_periodic_domain_traits domain(t, emb, 1);
  const std::vector<Eigen::Vector2d> sites = domain.initial_sites(200, 0);
  const auto cells = domain.voronoi_cells(sites);
  BOOST_TEST(cells.size() == sites.size());
  for(const auto& c : cells) BOOST_TEST(c.size() >= 3u);
  const std::string dir = ANISO_CONFORMAL_TEST_OUTPUT_DIR;
  auto slurp = [](const std::string& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  };
  AC::IO::write_periodic_cvt_svg(dir + "/torus_cvt.svg", domain.lattice(), sites, cells, {}, "test");
  const std::string cvt = slurp(dir + "/torus_cvt.svg");
  BOOST_TEST(cvt.find("<svg") != std::string::npos);
  BOOST_TEST(cvt.find("clipPath") != std::string::npos);
  AC::IO::write_surface_svg(dir + "/torus_mesh.svg", s.points(), s.faces(), std::vector<double>(s.number_of_faces(), 0.9), 0.5, 1.0,
                            "test", Eigen::Vector3d(0.3, -0.5, 1.0));
  const std::string mesh = slurp(dir + "/torus_mesh.svg");
  BOOST_TEST(mesh.find("<svg") != std::string::npos);
  BOOST_TEST(mesh.find("<path") != std::string::npos);
  // errors are named
  BOOST_CHECK_THROW(AC::IO::write_periodic_cvt_svg(dir + "/bad.svg", {{Eigen::Vector2d(1, 0), Eigen::Vector2d(2, 0)}}, sites, cells, {}, ""),
                    AC::Invalid_input);
  BOOST_CHECK_THROW(AC::IO::write_surface_svg(dir + "/bad.svg", s.points(), s.faces(), {}, 0.5, 1.0, "", Eigen::Vector3d::Zero()),
                    AC::Invalid_input);
  BOOST_CHECK_THROW(AC::IO::write_surface_svg("/nonexistent-dir/x.svg", s.points(), s.faces(),
                                              std::vector<double>(s.number_of_faces(), 0.9), 0.5, 1.0, ""),
                    AC::Invalid_input);
}

BOOST_AUTO_TEST_SUITE_END()  // flat_torus
