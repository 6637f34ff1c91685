// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_REMESH_H
#define ANISO_CONFORMAL_REMESH_H

#include <Aniso_conformal/Cone_domain.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Flat_torus_domain.h>
#include <Aniso_conformal/Hyperbolic_domain.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Planar_domain.h>
#include <Aniso_conformal/Remeshing_result.h>
#include <Aniso_conformal/Spherical_domain.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/parameters.h>
#include <Aniso_conformal/remesh_in_domain.h>

#include <chrono>
#include <string>

/// \file remesh.h
/// The entry point: `remesh()` chooses the parametric domain from the topology and runs
/// `remesh_in_domain()` there. It includes the four domains; a program that remeshes one topology only
/// can include `remesh_in_domain.h` and that domain's header instead, and compiles faster.

namespace Aniso_conformal {

namespace internal {

// the domain for `surface`: `requested` (each domain checks that it fits), or the one its topology takes
inline Parametric_domain choose_domain(const Input_surface& surface, Parametric_domain requested)
{
  if(requested != Parametric_domain::AUTOMATIC) return requested;
  if(surface.is_disk()) return Parametric_domain::PLANE;
  // a closed surface, or one with several boundary loops or a boundary and a genus: the closed domain of
  // its genus (its holes closed by patches there, remesh_in_domain())
  return surface.genus() == 0 ? Parametric_domain::SPHERE
         : surface.genus() == 1 ? Parametric_domain::FLAT_TORUS
                                : Parametric_domain::HYPERBOLIC;
}

// how much of the input's features a run kept: its creases (2), its corners only (1), neither (0)
inline int features_kept_rank(Crease_run run)
{
  return run == Crease_run::FEATURES_DROPPED ? 0 : run == Crease_run::NOT_FOLLOWED ? 1 : 2;
}

// The automatic choice on a closed surface, or one whose holes are closed by patches (issue 16, item 5):
// the uniformization domain `Domain` (the sphere, the hyperbolic disk); if it fails to converge (a conformal factor that double
// precision cannot represent, sites too close to tell apart, an output that does not close), the cone
// domain, whose area distortion is bounded by construction. The reason is in
// Remeshing_result::domain_choice. If the cone run fails too, Convergence_failure with the first failure's
// message (and residual) followed by the cone run's. If `Domain` remeshes but only without the creases
// (its runs with crease sites failed: CGAL's cactus at 4000 vertices through the sphere, whose crease
// sites on the arms make triangles too small on the sphere for double precision), the cone domain is run
// too, and its output stands if it keeps more of the features (the creases, or at least the corners);
// otherwise the first output stands and the cone run's time is counted as discarded.
template <typename Domain, typename AnisotropicMetric, typename NamedParameters>
Remeshed_surface remesh_with_cones_if_it_fails(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                                               const NamedParameters& np)
{
  std::string reason;
  double residual = 0;
  Feature_sizing_once sizing;  // both domains' runs share it; each counts the time of what it computed
  const auto start = std::chrono::steady_clock::now();
  try {
    Remeshed_surface out = remesh_in_domain_with_sizing<Domain>(surface, metric, result, np, sizing);
    if(features_kept_rank(result.crease_run) == 2) return out;
    const auto cone_start = std::chrono::steady_clock::now();
    const double first_seconds = std::chrono::duration<double>(cone_start - start).count();
    try {
      Remeshing_result cone_result;
      Remeshed_surface cone_out = remesh_in_domain_with_sizing<Cone_domain>(surface, metric, cone_result, np, sizing);
      if(features_kept_rank(cone_result.crease_run) > features_kept_rank(result.crease_run)) {
        cone_result.discarded_seconds += first_seconds;
        cone_result.domain_choice = std::string("cones, because the ") + domain_name(Domain::kind) + " kept " +
                                    (result.crease_run == Crease_run::NOT_FOLLOWED ? "the corners but not the creases: " + result.creases_not_followed
                                                                                  : "no feature: " + result.corners_not_kept);
        result = std::move(cone_result);
        return cone_out;
      }
    } catch(const Remeshing_failure&) {
      // the cone domain does no better: the first output stands
    }
    result.discarded_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - cone_start).count();
    return out;
  } catch(const Convergence_failure& e) {
    reason = e.what();
    residual = e.residual();
  }
  const double failed_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result = Remeshing_result();
  try {
    Remeshed_surface out = remesh_in_domain_with_sizing<Cone_domain>(surface, metric, result, np, sizing);
    result.discarded_seconds += failed_seconds;  // after the cone run, which starts from a fresh result
    result.domain_choice = std::string("cones, because the ") + domain_name(Domain::kind) + " failed: " + reason;
    return out;
  } catch(const Remeshing_failure& e) {
    // both failed: the topology's own domain's failure first (it names its stage and, for too few sites,
    // the fix), then the cone domain's
    throw Convergence_failure(reason + "; the cone domain failed too: " + e.what(), residual);
  }
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalMain
 * remeshes `surface` into a triangle mesh with exactly `number_of_vertices` vertices whose triangles are
 * as close to equilateral as possible when measured in `metric`, by the method of Zhong et al.\ 2014:
 * metric edge lengths (with metric-Delaunay flips and longest-edge splits), conformal embedding into
 * the canonical domain of the surface's topology, weighted CVT with density `cf^2` there, Delaunay dual
 * mapped back onto the input, then (by default only when that mesh has inverted triangles) a final
 * optimisation on the input surface in the metric (`optimize_surface_mesh()`: metric-Delaunay flips and
 * vertex moves along the surface).
 *
 * The domain follows the topology (or the `parametric_domain` named parameter, checked against it); each
 * is a model of `ParametricDomain` and `remesh()` calls `remesh_in_domain()` with it:
 * - a topological disk (a 2D domain, an image, an open curved patch) goes to the plane: the output
 *   keeps the boundary (boundary vertices on the input boundary, corners turning by more than
 *   `corner_angle` degrees kept as vertices) and is a single disk;
 * - a closed surface of genus 0 goes to the unit sphere (`spherical_embedding()`,
 *   `Spherical_domain_traits`): the output is a closed genus-0 surface;
 * - a closed surface of genus 1 goes to the flat torus (`flat_torus_embedding()`,
 *   `Euclidean_periodic_domain_traits`): the output is a closed genus-1 surface;
 * - a closed surface of genus `g >= 2` goes to the hyperbolic disk (`hyperbolic_embedding()`,
 *   `Hyperbolic_klein_domain_traits`): the output is a closed genus-`g` surface;
 * - a surface with several boundary loops, or a boundary and a genus, goes to the closed domain of its
 *   genus with each hole closed by a virtual patch (no CVT density; its loop a chain of fixed sites at
 *   about equal metric arc length, each an output vertex on the input loop; the patch's dual triangles
 *   removed): the output has the input's genus and loops (manual, "Several boundary loops");
 * - with `parametric_domain(Parametric_domain::CONE)`, or automatically when the sphere or the hyperbolic
 *   disk fails with `Convergence_failure` on a closed surface or one with holes (long limbs, a long open
 *   tube: a conformal factor double precision cannot represent), the cone domain (`cone_embedding()`,
 *   `Cone_domain_traits`; issue 16): a flat metric with cone singularities whose area distortion is at
 *   most `e^4`, holes closed by patches as above (a disk is refused there); the output has the input's
 *   genus and loops, and `Remeshing_result::domain_choice` says why cones were chosen. If the cone run
 *   fails too, `Convergence_failure` gives both reasons, the first domain's first. Likewise, when the
 *   sphere or the hyperbolic disk remeshes only without following the creases (`Crease_run::NOT_FOLLOWED`
 *   or `FEATURES_DROPPED`: its runs with crease sites failed), the cone domain runs too and its output
 *   stands if it keeps more of the features (`domain_choice` says so); else the first output stands.
 *
 * The output is checked before it is returned: a consistently oriented, connected 2-manifold with the
 * input's genus and boundary count, no triangle inverted against the input's normals; every vertex lies
 * on the input (`Remeshing_result::hausdorff_distance` measures how close the output follows it). If
 * it has folded (inverted) triangles while the metric asks somewhere for more stretch than straight edges
 * can follow where its long axis turns, the run is made again with the stretch bounded there
 * (`remesh_in_domain()`, `Stretch_limit_report` in `Remeshing_result::stretch_limit`; issue 17).
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
 *   - `corner_angle` (default 30): boundary turning angle, in degrees, above which a vertex is a corner
 *     (also the turn that makes a vertex of a crease a corner);
 *   - `feature_angle` (default 60): angle in degrees between the normals of two triangles above which their
 *     edge is a crease (`detect_features()`; 180: no crease). On a closed surface every corner of the
 *     creases (where 1 or 3 and more meet, or where one turns by more than `corner_angle`) is a fixed site
 *     of the CVT and an output vertex exactly, except a corner closer than half the output's edge length
 *     (in the metric) to another one; a crease component (creases connected through their vertices)
 *     shorter than one output edge in the metric is left out with its corners unless the user marked part
 *     of it (`Feature_report::short_components_dropped`); `Remeshing_result::features` measures what is kept;
 *   - `drop_ragged_creases` (default `true`): crease components that are noise rather than sharp creases
 *     are left out before the rest: a crease edge is ragged when another edge of one of its triangles,
 *     shorter than an output edge of an isotropic mesh, bends by half `feature_angle` or more; a component
 *     of which ragged edges make 20 % of the length is left out with its corners, and when such
 *     components make a quarter of the detected crease length, every detected crease is (a rough surface:
 *     a noisy scan, a crease across the triangles); the user's marked features stay
 *     (`Feature_report::ragged_components_dropped`, `rough_surface`; manual, "Sharp features");
 *   - `feature_sizing` (default `true`): where two crease curves run closer
 *     than an output triangle's height, the metric's lengths are scaled up so that the output's edges there
 *     are about 1.3 times the gap, graded by a factor 1.2 per edge, at most 6 times, all gaps or none
 *     within an area factor of 6; the vertex count stays the one asked for (`Feature_sizing_report` in
 *     `Remeshing_result::feature_sizing`; `internal/features/feature_size.h`; manual, "Sharp features");
 *   - `curvature_sizing` (`Curvature_sizing`, default `CONES`: in the cone domain; `ALWAYS`, `OFF`): where the surface bends more tightly than an output edge can
 *     follow (a thin limb, a tip, a rounded rim: the largest principal curvature's radius, averaged over
 *     half an output edge, shorter than the edge), the metric's lengths are scaled up so that the
 *     output's edges there are about 1.25 times the radius, graded by a factor 1.8 per edge, at most 3
 *     times, in the same field and area budget as `feature_sizing`; a run with it that fails is run again
 *     without it (`Feature_sizing_report::curved_points`, `curvature_applied`;
 *     `internal/features/curvature_size.h`; manual, "Thin parts and tips");
 *   - `feature_edges` (`std::vector<std::array<std::size_t, 2>>`, default none) and `feature_vertices`
 *     (`std::vector<std::size_t>`, default none): the user's own creases (pairs of input vertex indices)
 *     and corners, kept whatever their angle, on top of those `feature_angle` finds (`detect_features()`;
 *     with `feature_angle(180)`, only these);
 *   - `max_adjustment_rounds` (default 50), `max_conformal_iterations` (default 100),
 *     `conformal_tolerance` (default 1e-9): bounds of stages 2 and 3;
 *   - `surface_optimization` (default `Surface_optimization::REPAIR`): when the final optimisation on the
 *     surface runs (`OFF`; `REPAIR`: only when the dual mesh has inverted triangles or a triangle with an
 *     angle below 30 degrees in the metric; as `ALWAYS` in the cone domain and on a planar input, where
 *     flips cannot move the output off the input, and on an output that follows creases, whose fixed
 *     crease sites leave the cells beside them irregular; `ALWAYS`);
 *   - `number_of_threads` (default 0 = all cores) for the CVT integration, the dual mesh's projections and
 *     the quality (the output does not depend on it);
 *   - `visitor`: a model of `AnisoConformalVisitor` (default `Default_visitor`).
 * \returns the output mesh as arrays
 * \throws Remeshing_failure if a hole's loop spans no area (no patch closes it), or more vertices are asked
 *         for than the background can carry
 * \throws Invalid_input if the topology does not fit `parametric_domain`, the metric is
 *         unusable (non-finite, not symmetric, not positive definite on the tangent plane),
 *         `number_of_vertices` is missing, below the minimum (3 and the number of corners; 4 on the sphere, 7 on the flat torus,
 *         the smallest triangulation of the genus above that: 10 for genus 2, 12 for genus 3; on a closed
 *         surface the number of corners of its creases), `feature_angle` is not in [0, 180], or a
 *         `feature_edges` pair is not an edge of the input or a `feature_vertices` index not a vertex
 * \throws Convergence_failure if an iterative stage does not converge within its bound, or if the
 *         output would have an inverted or degenerate triangle (left after the surface optimisation, and
 *         after the stretch bound where the metric asks for more than edges can follow) or a
 *         wrong topology (it is never returned)
 * \throws Cancelled if the visitor asked to stop
 */
template <typename AnisotropicMetric, typename NamedParameters = parameters::Default_named_parameters>
Remeshed_surface remesh(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                        const NamedParameters& np = parameters::default_values())
{
  if(internal::number_of_vertices(np) == 0)
    throw Invalid_input("remesh(): the number of output vertices must be given (number_of_vertices) and positive");
  if(internal::number_of_vertices(np) < 3)
    throw Invalid_input("remesh(): at least 3 output vertices are needed, " + std::to_string(internal::number_of_vertices(np)) +
                        " were requested");
  const bool automatic = internal::parametric_domain(np) == Parametric_domain::AUTOMATIC;
  switch(internal::choose_domain(surface, internal::parametric_domain(np))) {
  case Parametric_domain::PLANE: return remesh_in_domain<Planar_domain>(surface, metric, result, np);
  case Parametric_domain::SPHERE:
    if(!automatic) return remesh_in_domain<Spherical_domain>(surface, metric, result, np);
    return internal::remesh_with_cones_if_it_fails<Spherical_domain>(surface, metric, result, np);
  case Parametric_domain::FLAT_TORUS: return remesh_in_domain<Flat_torus_domain>(surface, metric, result, np);
  case Parametric_domain::HYPERBOLIC:
    if(!automatic) return remesh_in_domain<Hyperbolic_domain>(surface, metric, result, np);
    return internal::remesh_with_cones_if_it_fails<Hyperbolic_domain>(surface, metric, result, np);
  case Parametric_domain::CONE: return remesh_in_domain<Cone_domain>(surface, metric, result, np);
  case Parametric_domain::AUTOMATIC: break;
  }
  throw Internal_error("remesh(): no domain was chosen");
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
  internal::copy_to_face_graph(remesh(surface, metric, result, np), out_mesh);
  return result;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_REMESH_H
