// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_REMESH_PIPELINE_STEPS_H
#define ANISO_CONFORMAL_INTERNAL_REMESH_PIPELINE_STEPS_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Feature_graph.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Remeshing_result.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/adjust_edge_lengths.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/extract_dual_mesh.h>
#include <Aniso_conformal/internal/features/crease_sites.h>
#include <Aniso_conformal/internal/optimize/triangle_orientation.h>
#include <Aniso_conformal/internal/parallel_for.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/internal/remesh/hole_patches.h>
#include <Aniso_conformal/internal/tensor.h>
#include <Aniso_conformal/mesh_quality.h>
#include <Aniso_conformal/optimize_surface_mesh.h>
#include <Aniso_conformal/refine_background.h>
#include <Aniso_conformal/weighted_centroidal_Voronoi_tessellation.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

// The steps of remesh_in_domain() that do not depend on the domain: stages 1, 2, 4, 5 and 6 around the
// domain's stage 3.

namespace Aniso_conformal {
namespace internal {

// times one stage and tells the visitor when it starts and ends
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

// Stage 1 and the start of stage 2: the metric at the input vertices, the corners of the boundary, the
// background refined for `n` output vertices. With `patches` (`surface` is then `patches->closed`, the
// `input` with its holes closed, and `metric` extends the input's onto the patches) the patches and seams
// are tagged, the seams refined to a quarter of the output edge length (measured without the patches).
// Stage 2 is left open (its start told to the visitor, its seconds so far in `edge_lengths_seconds`):
// finish_edge_lengths() ends it. run_pipeline() keeps this background to retry without the creases.
template <typename AnisotropicMetric, typename NamedParameters, typename Visitor>
Intrinsic_triangulation metric_and_background(const Input_surface& surface, const AnisotropicMetric& metric, std::size_t n,
                                              const NamedParameters& np, Visitor& vis, Remeshing_result& result,
                                              double& edge_lengths_seconds, const Hole_patches* patches = nullptr,
                                              const Input_surface* input = nullptr)
{
  Stage_timer t1(vis, Stage::METRIC);
  Intrinsic_triangulation itri(surface, compute_metric_square_roots(surface, metric));
  if(patches) tag_hole_patches(itri, *patches);
  result.corners = mark_corners(surface, itri, corner_angle(np));
  result.seconds[int(Stage::METRIC)] = t1.stop(vis);
  vis.on_stage_started(Stage::EDGE_LENGTHS);
  const auto start = std::chrono::steady_clock::now();
  result.refinement = refine_background(itri, surface, metric, n);
  if(patches)
    refine_seams(itri, *input, 0.25 * edge_length_without_patches(itri, n), 64 * n + 4 * result.refinement.vertices_before);
  edge_lengths_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return itri;
}

// The rest of stage 2 on the background of metric_and_background() (`surface`, `patches` and `input` as
// there): with `creases` (the input's feature graph) and `crease_splits`, the background's pieces of the
// crease edges are refined to a third of the output edge length (refine_creases(); nothing happens without
// a crease curve) and the number of splits stored in `*crease_splits`, also when the refinement fails
// (without it the crease sites are placed on the background's own crease vertices); then the adjusted lengths; with `patches` the seams
// made closer to Delaunay and the output edge length without the patches returned in `*edge_length`. Ends
// stage 2 for the visitor, its seconds `seconds_before` (metric_and_background()'s share) plus this step's.
template <typename NamedParameters, typename Visitor>
void finish_edge_lengths(Intrinsic_triangulation& itri, const Input_surface& surface, std::size_t n, const NamedParameters& np,
                         Visitor& vis, Remeshing_result& result, double seconds_before, const Hole_patches* patches = nullptr,
                         const Input_surface* input = nullptr, double* edge_length = nullptr, const Feature_graph* creases = nullptr,
                         std::size_t* crease_splits = nullptr)
{
  const auto start = std::chrono::steady_clock::now();
  // to a third of the output edge length: a quarter (as the loops) split each crease edge of
  // cube_grid.off (test/data/cases) in 4 at 120 and 150 vertices, and the spherical embedding's intrinsic
  // Delaunay flips then never ended (a regular grid of ties); 0.3 to 0.5 kept 100 % of its creases at
  // every size tried from 60 to 600
  // a refinement that fails (Remeshing_failure: too many vertices) has split pieces before it gave up
  // (its bound lies above the background's size): their number, the vertices it added, is stored before
  // the failure goes on, so that run_pipeline() tries the creases on the unsplit background next
  if(creases && !creases->curves.empty() && crease_splits) {
    const std::size_t before = itri.number_of_vertices();
    try {
      *crease_splits = refine_creases(itri, input ? *input : surface, *creases, (1.0 / 3.0) * edge_length_without_patches(itri, n),
                                      64 * n + 4 * result.refinement.vertices_before + before);
    } catch(const Remeshing_failure&) {
      *crease_splits = itri.number_of_vertices() - before;
      throw;
    }
  }
  result.adjustment = adjust_edge_lengths(itri, surface, np);
  if(patches) {
    std::size_t seam_vertices = 0;
    for(int v = 0; v < int(itri.number_of_vertices()); ++v) seam_vertices += itri.seam(v) >= 0;
    make_seams_delaunay(itri, *input, 8, seam_vertices);
    *edge_length = edge_length_without_patches(itri, n);
  }
  result.background_vertices = itri.number_of_vertices();
  result.background_faces = itri.number_of_faces();
  result.seconds[int(Stage::EDGE_LENGTHS)] =
      seconds_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  vis.on_stage_finished(Stage::EDGE_LENGTHS, result.seconds[int(Stage::EDGE_LENGTHS)]);
}

// the figures every embedding has
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
  Remeshed_surface out = extract_dual_mesh(surface, itri, domain, sites, number_of_threads(np));
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

// Symmetric Hausdorff distance, sampled (see Remeshing_result::hausdorff_distance): every input vertex
// against the output, and each output triangle's corners, edge midpoints and centroid against the input,
// through the AABB trees of both surfaces (Input_surface::project()); n log m, on `threads` threads. The
// maximum does not depend on the order, so neither does the result.
inline double hausdorff_distance(const Input_surface& input, const Input_surface& output, unsigned threads = 0)
{
  // build both trees here: Input_surface builds its tree on the first projection, which must not race
  output.project(input.points().front());
  input.project(output.points().front());
  auto maximum = [threads](std::size_t n, const auto& distance) {
    std::vector<double> block_max(resolve_thread_count(threads), 0.0);
    parallel_blocks(n, threads, [&](std::size_t begin, std::size_t end, std::size_t t) {
      double d = 0;
      for(std::size_t i = begin; i < end; ++i) d = std::max(d, distance(i));
      block_max[t] = d;
    });
    return *std::max_element(block_max.begin(), block_max.end());
  };
  const auto& P = output.points();
  const double to_output = maximum(input.number_of_vertices(), [&](std::size_t i) {
    const Eigen::Vector3d& p = input.points()[i];
    return (output.project(p).position - p).norm();
  });
  const double to_input = maximum(output.number_of_faces(), [&](std::size_t i) {
    const auto& f = output.faces()[i];
    const Eigen::Vector3d a = P[f[0]], b = P[f[1]], c = P[f[2]];
    double d = 0;
    for(const Eigen::Vector3d& q : {a, Eigen::Vector3d((a + b) / 2), Eigen::Vector3d((b + c) / 2), Eigen::Vector3d((c + a) / 2),
                                    Eigen::Vector3d((a + b + c) / 3)})
      d = std::max(d, (input.project(q).position - q).norm());
    return d;
  });
  return std::max(to_output, to_input);
}

// the output triangles whose normal disagrees with the input's normals at their corners (for a planar
// input, the side of z = 0 its faces face: +z when counter-clockwise seen from +z, -z when clockwise):
// triangle_is_inverted()
inline std::size_t count_inverted_triangles(const Input_surface& surface, const Remeshed_surface& out, unsigned threads = 0)
{
  const double side = planar_side(surface);
  std::vector<char> inverted(out.faces.size(), 0);
  parallel_for(out.faces.size(), threads, [&](std::size_t i) {
    const auto& f = out.faces[i];
    inverted[i] = triangle_is_inverted(surface, out.points[f[0]], out.points[f[1]], out.points[f[2]], out.surface_points[f[0]],
                                       out.surface_points[f[1]], out.surface_points[f[2]], side);
  });
  return std::size_t(std::count(inverted.begin(), inverted.end(), 1));
}

// the square root of `metric` at each vertex of `out`, as compute_mesh_quality() takes them; serial: a
// user's metric model need not be safe for concurrent calls (and this loop is short)
template <typename AnisotropicMetric>
std::vector<Eigen::Matrix3d> metric_square_roots_at(const AnisotropicMetric& metric, const Remeshed_surface& out)
{
  std::vector<Eigen::Matrix3d> Q(out.points.size());
  for(std::size_t i = 0; i < Q.size(); ++i) Q[i] = symmetric_sqrt(metric.tensor(out.surface_points[i]));
  return Q;
}

// `true` if a triangle of `out` has an angle below 30 degrees in `metric` (as the quality report measures)
template <typename AnisotropicMetric>
bool has_angle_below_30_degrees(const AnisotropicMetric& metric, const Remeshed_surface& out, unsigned threads)
{
  return compute_mesh_quality(out.points, out.faces, metric_square_roots_at(metric, out), threads).theta_min < 30;
}

// Stage 6 of 7, before the quality: the surface optimisation (optimize_surface_mesh()) when `mode` asks for
// it, on every output or only on one with inverted triangles, to repair them, or with a triangle below
// 30 degrees in the metric (CGAL's bear at 2000 vertices: theta_min 17.1 -> 30.4, G_avg 0.878 -> 0.895;
// its max-min angle pass, surface_optimizer.h). An output that follows creases gets ALWAYS from
// remesh_in_domain(): a free site of the CVT can settle on a crease between two crease sites, and its
// vertex then makes a flat triangle with their edge (CGAL's fandisk at 2000: theta_min 5.8 degrees, 19.3
// after the optimisation, which moves it off).
template <typename AnisotropicMetric, typename Visitor>
void optimize_output(const Input_surface& surface, const AnisotropicMetric& metric, Remeshed_surface& out,
                     Surface_optimization mode, Visitor& vis, Remeshing_result& result, unsigned threads = 0)
{
  Stage_timer t(vis, Stage::SURFACE_OPTIMIZATION);
  if(mode == Surface_optimization::ALWAYS ||
     (mode == Surface_optimization::REPAIR && (count_inverted_triangles(surface, out, threads) > 0 || has_angle_below_30_degrees(metric, out, threads))))
    result.surface_optimization = optimize_surface_mesh(surface, metric, out, defaults::surface_optimization_rounds, vis,
                                                        mode == Surface_optimization::ALWAYS);
  result.seconds[int(Stage::SURFACE_OPTIMIZATION)] = t.stop(vis);
}

// Stage 6: quality in the metric, then the checks (no inverted triangle, whose message ends with the
// domain's `hint`; the input's topology) and the Hausdorff distance to the input, on `threads` threads.
template <typename AnisotropicMetric, typename Visitor>
void measure_and_check_output(const Input_surface& surface, const AnisotropicMetric& metric, const Remeshed_surface& out,
                              const char* hint, Visitor& vis, Remeshing_result& result, unsigned threads = 0)
{
  Stage_timer t6(vis, Stage::QUALITY);
  result.quality = compute_mesh_quality(out.points, out.faces, metric_square_roots_at(metric, out), threads);
  result.inverted_triangles = count_inverted_triangles(surface, out, threads);
  if(result.inverted_triangles > 0)
    throw Convergence_failure("remesh(): the output has " + std::to_string(result.inverted_triangles) +
                                  " inverted or degenerate triangles" +
                                  (result.surface_optimization.ran ? " left after the surface optimisation" : "") + " (G_min " +
                                  std::to_string(result.quality.G_min) + "): " + hint,
                              double(result.inverted_triangles));
  const Input_surface checked = check_output_topology(out, surface);
  result.hausdorff_distance = hausdorff_distance(surface, checked, threads);
  result.hausdorff_distance_relative = result.hausdorff_distance / surface.bounding_box_diagonal();
  result.seconds[int(Stage::QUALITY)] = t6.stop(vis);
}

// Writes `out` into the face graph `out_mesh`, which changes only on success (built aside, then assigned).
template <typename OutputMesh>
void copy_to_face_graph(const Remeshed_surface& out, OutputMesh& out_mesh)
{
  typedef typename boost::graph_traits<OutputMesh>::vertex_descriptor vertex_descriptor;
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
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_REMESH_PIPELINE_STEPS_H
