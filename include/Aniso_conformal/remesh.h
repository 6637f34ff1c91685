// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_REMESH_H
#define ANISO_CONFORMAL_REMESH_H

#include <Aniso_conformal/Euclidean_periodic_domain_traits.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Hyperbolic_klein_domain_traits.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Planar_domain_traits.h>
#include <Aniso_conformal/Remeshing_result.h>
#include <Aniso_conformal/Spherical_domain_traits.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/adjust_edge_lengths.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/conformal_embedding.h>
#include <Aniso_conformal/extract_dual_mesh.h>
#include <Aniso_conformal/flat_torus_embedding.h>
#include <Aniso_conformal/hyperbolic_embedding.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/mesh_quality.h>
#include <Aniso_conformal/parameters.h>
#include <Aniso_conformal/spherical_embedding.h>
#include <Aniso_conformal/weighted_centroidal_Voronoi_tessellation.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

/// \file remesh.h

namespace Aniso_conformal {

namespace internal {

// Marks as corners the input boundary vertices whose boundary turns by more than `angle_deg`.
inline std::size_t mark_corners(const Input_surface& s, Intrinsic_triangulation& itri, double angle_deg)
{
  const double limit = angle_deg * 3.14159265358979323846 / 180.0;
  std::size_t n = 0;
  for(const auto& loop : s.boundary_loops())
    for(std::size_t i = 0; i < loop.size(); ++i) {
      const Eigen::Vector3d& p = s.points()[loop[(i + loop.size() - 1) % loop.size()]];
      const Eigen::Vector3d& v = s.points()[loop[i]];
      const Eigen::Vector3d& q = s.points()[loop[(i + 1) % loop.size()]];
      const Eigen::Vector3d a = v - p, b = q - v;
      const double turn = std::atan2(a.cross(b).norm(), a.dot(b));
      if(turn > limit) {
        itri.set_corner(int(loop[i]), true);
        ++n;
      }
    }
  return n;
}

class Stage_timer {
public:
  template <typename Visitor>
  Stage_timer(Visitor& vis, Stage s) : m_stage(s), m_start(std::chrono::steady_clock::now()) { vis.on_stage_started(s); }
  template <typename Visitor>
  double stop(Visitor& vis)
  {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    vis.on_stage_finished(m_stage, t);
    return t;
  }

private:
  Stage m_stage;
  std::chrono::steady_clock::time_point m_start;
};

} // namespace internal

namespace internal {

// the domain for `surface`: `requested`, checked against the topology, or chosen from it
inline Parametric_domain choose_domain(const Input_surface& surface, Parametric_domain requested)
{
  const bool closed = surface.boundary_loops().empty();
  const Parametric_domain fits = surface.is_disk() ? Parametric_domain::PLANE
                                 : !closed         ? Parametric_domain::AUTOMATIC
                                 : surface.genus() == 0 ? Parametric_domain::SPHERE
                                 : surface.genus() == 1 ? Parametric_domain::FLAT_TORUS
                                                        : Parametric_domain::HYPERBOLIC;
  if(requested != Parametric_domain::AUTOMATIC && requested != fits)
    throw Invalid_input(std::string("remesh(): the ") + domain_name(requested) + " domain does not fit the input, which is " +
                        surface.topology_description() +
                        " (the plane takes topological disks, the sphere closed surfaces of genus 0, the flat torus closed "
                        "surfaces of genus 1, the hyperbolic disk closed surfaces of genus 2 or more)");
  if(fits == Parametric_domain::AUTOMATIC)
    throw Remeshing_failure("remesh(): the input is " + surface.topology_description() +
                        "; this version remeshes topological disks (the plane) and closed surfaces of genus 0 (the sphere), "
                        "1 (the flat torus) and 2 or more (the hyperbolic disk)");
  return fits;
}

// the fewest vertices of a triangulation of the closed surface of genus g >= 1 (Ringel and Jungerman:
// Heawood's bound ceil((7 + sqrt(1 + 48 g)) / 2), except 10 for genus 2)
inline std::size_t minimum_vertices_of_genus(int g)
{
  if(g == 2) return 10;
  return std::size_t(std::ceil((7 + std::sqrt(1.0 + 48.0 * g)) / 2 - 1e-9));
}

template <typename Embedding>
void record_embedding(const Embedding& emb, Remeshing_result& result)
{
  result.conformal_iterations = emb.iterations;
  result.conformal_residual = emb.residual;
  result.conformal_flips = emb.flips;
  result.conformal_factor_min = *std::min_element(emb.conformal_factor.begin(), emb.conformal_factor.end());
  result.conformal_factor_max = *std::max_element(emb.conformal_factor.begin(), emb.conformal_factor.end());
}

// stages 4 and 5, the same for every domain
template <typename DomainTraits, typename NamedParameters, typename Visitor>
Remeshed_surface cvt_and_dual_mesh(const Input_surface& surface, const Intrinsic_triangulation& itri, const DomainTraits& domain,
                                   std::vector<typename DomainTraits::Point>& sites, const NamedParameters& np, Visitor& vis,
                                   Remeshing_result& result)
{
  Stage_timer t4(vis, Stage::CVT);
  result.boundary_sites = domain.number_of_fixed_sites();
  result.cvt = weighted_centroidal_Voronoi_tessellation(domain, sites, domain.number_of_fixed_sites(), np);
  result.seconds[int(Stage::CVT)] = t4.stop(vis);
  Stage_timer t5(vis, Stage::DUAL_MESH);
  Remeshed_surface out = extract_dual_mesh(surface, itri, domain, sites);
  result.seconds[int(Stage::DUAL_MESH)] = t5.stop(vis);
  return out;
}

// The output as a validated surface: a 2-manifold, consistently oriented, connected, with the input's
// genus and number of boundary loops; also gives the closest-point queries of the Hausdorff distance.
inline Input_surface check_output_topology(const Remeshed_surface& out, const Input_surface& input)
{
  std::vector<Input_surface::Face> faces(out.faces.begin(), out.faces.end());
  try {
    Input_surface s(out.points, std::move(faces));
    if(s.genus() != input.genus() || s.boundary_loops().size() != input.boundary_loops().size())
      throw Convergence_failure("remesh(): the output is " + s.topology_description() + " but the input is " +
                                    input.topology_description(),
                                0);
    return s;
  } catch(const Invalid_input& e) {
    throw Convergence_failure(std::string("remesh(): the output is not a valid surface: ") + e.what(), 0);
  }
}

// symmetric Hausdorff distance, sampled (see Remeshing_result::hausdorff_distance)
inline double hausdorff_distance(const Input_surface& input, const Input_surface& output)
{
  double d = 0;
  for(const Eigen::Vector3d& p : input.points()) d = std::max(d, (output.project(p).position - p).norm());
  const auto& P = output.points();
  for(const auto& f : output.faces()) {
    const Eigen::Vector3d a = P[f[0]], b = P[f[1]], c = P[f[2]];
    for(const Eigen::Vector3d& q : {a, Eigen::Vector3d((a + b) / 2), Eigen::Vector3d((b + c) / 2), Eigen::Vector3d((c + a) / 2),
                                    Eigen::Vector3d((a + b + c) / 3)})
      d = std::max(d, (input.project(q).position - q).norm());
  }
  return d;
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalMain
 * remeshes `surface` into a triangle mesh with exactly `number_of_vertices` vertices whose triangles are
 * as close to equilateral as possible when measured in `metric`, by the method of Zhong et al.\ 2014:
 * metric edge lengths (with metric-Delaunay flips and longest-edge splits), conformal embedding into
 * the canonical domain of the surface's topology, weighted CVT with density `cf^2` there, Delaunay dual
 * mapped back onto the input.
 *
 * The domain follows the topology (or the `parametric_domain` named parameter, checked against it):
 * - a topological disk (a 2D domain, an image, an open curved patch) goes to the plane: the output
 *   keeps the boundary (boundary vertices on the input boundary, corners turning by more than
 *   `corner_angle` degrees kept as vertices) and is a single disk;
 * - a closed surface of genus 0 goes to the unit sphere (`spherical_embedding()`,
 *   `Spherical_domain_traits`): the output is a closed genus-0 surface;
 * - a closed surface of genus 1 goes to the flat torus (`flat_torus_embedding()`,
 *   `Euclidean_periodic_domain_traits`): the output is a closed genus-1 surface;
 * - a closed surface of genus `g >= 2` goes to the hyperbolic disk (`hyperbolic_embedding()`,
 *   `Hyperbolic_klein_domain_traits`): the output is a closed genus-`g` surface.
 *
 * The output is checked before it is returned: a consistently oriented, connected 2-manifold with the
 * input's genus and boundary count, no triangle inverted against the input's normals; every vertex lies
 * on the input (`Remeshing_result::hausdorff_distance` measures how close the output follows it).
 *
 * \tparam AnisotropicMetric a model of `AnisotropicMetric`
 * \param surface the input (never modified)
 * \param metric the metric
 * \param result receives the diagnostics
 * \param np named parameters:
 *   - `number_of_vertices` (required): the number of output vertices;
 *   - `number_of_iterations` (default 100): CVT iterations;
 *   - `cvt_method` (default `Cvt_method::LBFGS`);
 *   - `random_seed` (default 0): seed of the initial sites; the same seed gives the same output bit for bit;
 *   - `parametric_domain` (default `Parametric_domain::AUTOMATIC`): the domain, refused if it does not
 *     fit the topology;
 *   - `corner_angle` (default 30): boundary turning angle, in degrees, above which a vertex is a corner;
 *   - `max_adjustment_rounds` (default 50), `max_conformal_iterations` (default 100),
 *     `conformal_tolerance` (default 1e-9): bounds of stages 2 and 3;
 *   - `number_of_threads` (default 0 = all cores) for the CVT integration;
 *   - `visitor`: a model of `AnisoConformalVisitor` (default `Default_visitor`).
 * \returns the output mesh as arrays
 * \throws Invalid_input if the topology has no domain in this version (a surface with several boundary
 *         loops, or a boundary and a genus) or does not fit `parametric_domain`, the metric is
 *         unusable (non-finite, not symmetric, not positive definite on the tangent plane),
 *         `number_of_vertices` is missing, below the minimum (3 and the number of corners; 4 on the sphere, 7 on the flat torus,
 *         the smallest triangulation of the genus above that: 10 for genus 2, 12 for genus 3),
 *         or above the number of background vertices
 * \throws Convergence_failure if an iterative stage does not converge within its bound, or if the
 *         output would have an inverted or degenerate triangle or a wrong topology (it is never returned)
 * \throws Cancelled if the visitor asked to stop
 */
template <typename AnisotropicMetric, typename NamedParameters = parameters::Default_named_parameters>
Remeshed_surface remesh(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                        const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const std::size_t n = choose_parameter(get_parameter(np, internal_np::number_of_vertices), std::size_t(0));
  const unsigned seed = choose_parameter(get_parameter(np, CGAL::internal_np::random_seed), 0u);
  const double corner_angle = choose_parameter(get_parameter(np, internal_np::corner_angle), 30.0);
  const unsigned threads = choose_parameter(get_parameter(np, internal_np::number_of_threads), 0u);
  const Parametric_domain requested =
      choose_parameter(get_parameter(np, internal_np::parametric_domain), Parametric_domain::AUTOMATIC);
  typename internal::Visitor_reference<NamedParameters>::type vis = internal::get_visitor(np);

  if(n == 0) throw Invalid_input("remesh(): the number of output vertices must be given (number_of_vertices) and positive");
  if(n < 3) throw Invalid_input("remesh(): at least 3 output vertices are needed, " + std::to_string(n) + " were requested");
  const Parametric_domain domain = internal::choose_domain(surface, requested);
  if(domain == Parametric_domain::FLAT_TORUS && n < 7)
    throw Invalid_input("remesh(): a closed surface of genus 1 needs at least 7 output vertices (the smallest torus "
                        "triangulation), " + std::to_string(n) + " were requested");
  if(domain == Parametric_domain::HYPERBOLIC && n < internal::minimum_vertices_of_genus(surface.genus()))
    throw Invalid_input("remesh(): a closed surface of genus " + std::to_string(surface.genus()) + " needs at least " +
                        std::to_string(internal::minimum_vertices_of_genus(surface.genus())) +
                        " output vertices (the smallest triangulation of that genus), " + std::to_string(n) + " were requested");
  if(domain == Parametric_domain::SPHERE && n < 4)
    throw Invalid_input("remesh(): a closed surface of genus 0 needs at least 4 output vertices (the tetrahedron), " +
                        std::to_string(n) + " were requested");
  result = Remeshing_result();
  result.domain = domain;
  result.input_vertices = surface.number_of_vertices();
  result.input_faces = surface.number_of_faces();

  // 1. metric
  internal::Stage_timer t1(vis, Stage::METRIC);
  Intrinsic_triangulation itri(surface, compute_metric_square_roots(surface, metric));
  if(domain == Parametric_domain::PLANE) result.corners = internal::mark_corners(surface, itri, corner_angle);
  result.seconds[int(Stage::METRIC)] = t1.stop(vis);

  // 2. edge lengths
  internal::Stage_timer t2(vis, Stage::EDGE_LENGTHS);
  result.adjustment = adjust_edge_lengths(itri, surface, np);
  result.background_vertices = itri.number_of_vertices();
  result.background_faces = itri.number_of_faces();
  result.seconds[int(Stage::EDGE_LENGTHS)] = t2.stop(vis);
  if(n > itri.number_of_vertices())
    throw Remeshing_failure("remesh(): " + std::to_string(n) + " output vertices exceed what the background triangulation can carry (" +
                        std::to_string(itri.number_of_vertices()) + " vertices); refine the input");

  // 3. conformal embedding, 4. weighted CVT, 5. dual mesh, in the domain
  Remeshed_surface out;
  if(domain == Parametric_domain::PLANE) {
    internal::Stage_timer t3(vis, Stage::EMBEDDING);
    const Planar_embedding emb = conformal_embedding(itri, np);
    internal::record_embedding(emb, result);
    result.seconds[int(Stage::EMBEDDING)] = t3.stop(vis);
    Planar_domain_traits traits(itri, emb, threads);  // after the embedding's flips, whose lengths the boundary spacing matches
    std::vector<Planar_domain_traits::Point> sites = traits.initial_sites(n, seed);
    out = internal::cvt_and_dual_mesh(surface, itri, traits, sites, np, vis, result);
  } else if(domain == Parametric_domain::SPHERE) {
    internal::Stage_timer t3(vis, Stage::EMBEDDING);
    const Spherical_embedding emb = spherical_embedding(itri, np);
    internal::record_embedding(emb, result);
    char text[160];
    std::snprintf(text, sizeof(text), "angle distortion of the conformal map: mean %.3f deg, max %.3f deg",
                  emb.angle_distortion_mean, emb.angle_distortion_max);
    result.domain_diagnostics.summary = text;
    result.domain_diagnostics.add("angle_distortion_mean_degrees", emb.angle_distortion_mean,
                                  "mean over the corners of |chordal angle - adjusted angle|, degrees");
    result.domain_diagnostics.add("angle_distortion_max_degrees", emb.angle_distortion_max,
                                  "largest |chordal angle - adjusted angle| over the corners, degrees");
    result.seconds[int(Stage::EMBEDDING)] = t3.stop(vis);
    Spherical_domain_traits traits(itri, emb, threads);
    std::vector<Spherical_domain_traits::Point> sites = traits.initial_sites(n, seed);
    out = internal::cvt_and_dual_mesh(surface, itri, traits, sites, np, vis, result);
  } else if(domain == Parametric_domain::HYPERBOLIC) {
    internal::Stage_timer t3(vis, Stage::EMBEDDING);
    const Hyperbolic_embedding emb = hyperbolic_embedding(itri, np);
    internal::record_embedding(emb, result);
    result.domain_diagnostics.add("group_relation_error", emb.relation_error,
                                  "largest entry of (product of the side pairings around a vertex) - I");
    result.seconds[int(Stage::EMBEDDING)] = t3.stop(vis);
    Hyperbolic_klein_domain_traits traits(itri, emb, threads);
    std::vector<Hyperbolic_klein_domain_traits::Point> sites = traits.initial_sites(n, seed);
    out = internal::cvt_and_dual_mesh(surface, itri, traits, sites, np, vis, result);
    result.domain_diagnostics.add("group_elements", double(traits.number_of_group_elements()),
                                  "group elements whose tiles the CVT's band of images reached", true);
    char text[160];
    std::snprintf(text, sizeof(text), "group relations hold to %.1e; %zu group elements near the fundamental domain",
                  emb.relation_error, traits.number_of_group_elements());
    result.domain_diagnostics.summary = text;
  } else {
    internal::Stage_timer t3(vis, Stage::EMBEDDING);
    const Flat_torus_embedding emb = flat_torus_embedding(itri, np);
    internal::record_embedding(emb, result);
    result.domain_diagnostics.add("lattice", {emb.lattice[0].x(), emb.lattice[0].y(), emb.lattice[1].x(), emb.lattice[1].y()}, 2,
                                  "reduced lattice basis a, b by rows (units of the flat metric)");
    result.domain_diagnostics.add("lattice_error", emb.lattice_error,
                                  "largest distance of a cut edge's translation to the lattice, lattice coordinates");
    char text[160];
    std::snprintf(text, sizeof(text), "lattice a = (%.4f, %.4f), b = (%.4f, %.4f), layout error %.1e", emb.lattice[0].x(),
                  emb.lattice[0].y(), emb.lattice[1].x(), emb.lattice[1].y(), emb.lattice_error);
    result.domain_diagnostics.summary = text;
    result.seconds[int(Stage::EMBEDDING)] = t3.stop(vis);
    Euclidean_periodic_domain_traits traits(itri, emb, threads);
    std::vector<Euclidean_periodic_domain_traits::Point> sites = traits.initial_sites(n, seed);
    out = internal::cvt_and_dual_mesh(surface, itri, traits, sites, np, vis, result);
  }

  // 6. quality, in the metric, orientation against the input, topology and distance to the input
  internal::Stage_timer t6(vis, Stage::QUALITY);
  std::vector<Eigen::Matrix3d> Q(out.points.size());
  for(std::size_t i = 0; i < Q.size(); ++i) Q[i] = internal::symmetric_sqrt(metric.tensor(out.surface_points[i]));
  result.quality = compute_mesh_quality(out.points, out.faces, Q);
  for(const auto& f : out.faces) {
    const Eigen::Vector3d nf = (out.points[f[1]] - out.points[f[0]]).cross(out.points[f[2]] - out.points[f[0]]);
    Eigen::Vector3d ref = Eigen::Vector3d::Zero();
    for(int k = 0; k < 3; ++k) {
      const Surface_point& sp = out.surface_points[f[k]];
      for(int j = 0; j < 3; ++j) ref += sp.barycentric[j] * surface.vertex_normals()[sp.vertices[j]];
    }
    if(surface.is_planar()) ref = Eigen::Vector3d(0, 0, 1);
    if(!(nf.dot(ref) > 0)) ++result.inverted_triangles;
  }
  if(result.inverted_triangles > 0)
    throw Convergence_failure("remesh(): the output has " + std::to_string(result.inverted_triangles) +
                                  " inverted or degenerate triangles (G_min " + std::to_string(result.quality.G_min) +
                                  (domain == Parametric_domain::PLANE
                                       ? "): the metric is too strong for this background near its boundary"
                                       : "): the output is too coarse for thin or strongly curved parts of the surface, or the "
                                         "metric too strong for the background (more vertices or a finer input may help)"),
                              double(result.inverted_triangles));
  const Input_surface checked = internal::check_output_topology(out, surface);
  result.hausdorff_distance = internal::hausdorff_distance(surface, checked);
  result.hausdorff_distance_relative = result.hausdorff_distance / surface.bounding_box_diagonal();
  result.seconds[int(Stage::QUALITY)] = t6.stop(vis);
  return out;
}

/*!
 * \ingroup PkgAnisoConformalMain
 * remeshes the triangle mesh `tmesh` (any model of `FaceListGraph`: `CGAL::Surface_mesh`,
 * `CGAL::Polyhedron_3`, ...) into `out_mesh` (a model of `MutableFaceGraph`), as the overload on
 * `Input_surface` does; `out_mesh` is cleared and written only on success (strong guarantee), and
 * `tmesh` is never modified.
 *
 * \tparam TriangleMesh a model of `FaceListGraph` with a vertex point map
 * \tparam AnisotropicMetric a model of `AnisotropicMetric` indexed by the vertex index map of `np`
 * \tparam OutputMesh a model of `MutableFaceGraph` with an internal vertex point map
 * \param tmesh the input mesh (never modified)
 * \param metric the metric, evaluated through `Surface_point`s whose vertex indices are those of the
 *        vertex index map of `np`
 * \param out_mesh receives the output (cleared and written only on success)
 * \param np as for the other overload, plus `vertex_point_map` and `vertex_index_map` of `tmesh`
 * \returns the diagnostics (`Remeshing_result`)
 */
template <typename TriangleMesh, typename AnisotropicMetric, typename OutputMesh,
          typename NamedParameters = parameters::Default_named_parameters>
Remeshing_result remesh(const TriangleMesh& tmesh, const AnisotropicMetric& metric, OutputMesh& out_mesh,
                        const NamedParameters& np = parameters::default_values())
{
  const Input_surface surface = Input_surface::from_mesh(tmesh, np);
  Remeshing_result result;
  const Remeshed_surface out = remesh(surface, metric, result, np);
  typedef typename boost::graph_traits<OutputMesh>::vertex_descriptor vertex_descriptor;
  // build aside, then assign: out_mesh changes only on success
  OutputMesh built;
  auto vpm = get(CGAL::vertex_point, built);
  typedef typename boost::property_traits<decltype(vpm)>::value_type Point;
  std::vector<vertex_descriptor> vd(out.points.size());
  for(std::size_t i = 0; i < vd.size(); ++i) {
    vd[i] = add_vertex(built);
    put(vpm, vd[i], Point(out.points[i].x(), out.points[i].y(), out.points[i].z()));
  }
  for(const auto& f : out.faces) {
    std::array<vertex_descriptor, 3> t = {{vd[f[0]], vd[f[1]], vd[f[2]]}};
    if(CGAL::Euler::add_face(t, built) == boost::graph_traits<OutputMesh>::null_face())
      throw Convergence_failure("remesh(): the output is not a valid 2-manifold (add_face refused a triangle)", 0);
  }
  out_mesh = built;
  return result;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_REMESH_H
