// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_REMESH_IN_DOMAIN_H
#define ANISO_CONFORMAL_REMESH_IN_DOMAIN_H

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
#include <Aniso_conformal/internal/features/fixed_corner_sites.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/internal/remesh/canonical_parameters.h>
#include <Aniso_conformal/internal/remesh/hole_patches.h>
#include <Aniso_conformal/internal/remesh/pipeline_steps.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/measure_features.h>
#include <Aniso_conformal/mesh_quality.h>
#include <Aniso_conformal/parameters.h>
#include <Aniso_conformal/weighted_centroidal_Voronoi_tessellation.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

/// \file remesh_in_domain.h
/// The pipeline of `remesh()` in one parametric domain, chosen at compile time: includes no domain, so a
/// program that knows its topology compiles only the domain it uses.

namespace Aniso_conformal {

namespace internal {

// `true` if the holes' patches need a fixed site at each apex: on the sphere when the patches cover half of
// it or more (their chordal triangles' area against all of them), as the sites of the rest could then lie
// in one hemisphere, where their Delaunay triangulation does not cover the sphere; never in the other
// domains (see run_pipeline_once())
template <typename Domain>
bool patches_need_apex_sites(const Intrinsic_triangulation& itri, const typename Domain::Embedding& emb)
{
  if constexpr(Domain::kind == Parametric_domain::SPHERE) {
    double patch = 0, all = 0;
    for(std::size_t f = 0; f < itri.number_of_faces(); ++f) {
      const auto& c = itri.face_vertices(f);
      const Eigen::Vector3d &a = emb.position[std::size_t(c[0])], &b = emb.position[std::size_t(c[1])], &d = emb.position[std::size_t(c[2])];
      const double area = 0.5 * (b - a).cross(d - a).norm();
      all += area;
      if(itri.is_patch_face(f)) patch += area;
    }
    return !(patch < 0.5 * all);
  } else {
    (void)itri;
    (void)emb;
    return false;
  }
}

// The pipeline in `Domain`, with the caller's parameters read into values and its visitor behind a
// handle (canonical_parameters.h): compiled once per domain and metric. With `follow_creases` the
// creases of a closed domain are followed (crease_sites.h); `creases_tried` says whether they were.
template <typename Domain, typename AnisotropicMetric>
Remeshed_surface run_pipeline_once(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                                   const Remeshing_options& options, Visitor_handle& vis, bool follow_creases, bool& creases_tried)
{
  const auto np = canonical_parameters(options, vis);
  const std::size_t n = options.number_of_vertices;
  if(n == 0) throw Invalid_input("remesh(): the number of output vertices must be given (number_of_vertices) and positive");
  if(n < 3) throw Invalid_input("remesh(): at least 3 output vertices are needed, " + std::to_string(n) + " were requested");
  constexpr bool closed = Domain::kind != Parametric_domain::PLANE;  // the closed domains keep the corners
  // a surface with boundary loops in a closed domain: its holes closed by patches (issue 15, item 3)
  std::unique_ptr<const Hole_patches> patches;
  if(closed && !surface.boundary_loops().empty() && !(Domain::kind == Parametric_domain::SPHERE && surface.is_disk()))
    patches.reset(new Hole_patches(close_holes(surface)));
  const Input_surface& background = patches ? patches->closed : surface;
  if(!Domain::fits(background))
    throw Invalid_input(std::string("remesh(): the ") + domain_name(Domain::kind) + " domain does not fit the input, which is " +
                        surface.topology_description() + " (the " + domain_name(Domain::kind) + " domain takes " +
                        Domain::topology() + ")");
  Domain::check_number_of_vertices(background, n);
  result = Remeshing_result();
  result.domain = Domain::kind;
  result.input_vertices = surface.number_of_vertices();
  result.input_faces = surface.number_of_faces();
  // the input's sharp features (issue 15): measured on the output below, their time counted as the metric's
  const auto features_start = std::chrono::steady_clock::now();
  const Feature_graph features = detect_features(surface, options.feature_angle, options.corner_angle, options.feature_edges,
                                                   options.feature_vertices);
  const double features_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - features_start).count();
  if(closed) check_vertices_for_corners(features.corners.size(), n, options.feature_angle);

  // 1. metric, 2. edge lengths
  double loop_edge_length = 0;  // with patches: the output edge length over the surface without them
  // in a closed domain the creases are kept as chains of output edges (issue 15, item 2): their background
  // pieces refined here, fixed sites along them below
  const Feature_graph* creases = follow_creases && closed && !features.curves.empty() ? &features : nullptr;
  creases_tried = creases != nullptr;
  Intrinsic_triangulation itri = patches ? metric_and_edge_lengths(background, Patched_metric<AnisotropicMetric>(metric, *patches), n, np,
                                                                   vis, result, patches.get(), &surface, &loop_edge_length, creases)
                                         : metric_and_edge_lengths(surface, metric, n, np, vis, result, nullptr, nullptr, nullptr, creases);
  result.seconds[int(Stage::METRIC)] += features_seconds;

  // 3. conformal embedding, 4. weighted CVT, 5. dual mesh, in the domain
  Stage_timer t3(vis, Stage::EMBEDDING);
  const typename Domain::Embedding emb = Domain::embed(itri, np);
  record_embedding(emb, result);
  result.seconds[int(Stage::EMBEDDING)] = t3.stop(vis);
  const auto setup_start = std::chrono::steady_clock::now();  // the CVT's set-up counts as CVT time
  // the sites (in a closed domain the input's corners first, fixed), the CVT and the dual, with any traits
  // with patches on the sphere, when they cover half of it or more, one more fixed site at a patch's
  // apex (removed from the output), at each apex that sees every edge of its loop's chain of sites under
  // 60 degrees at most: no large patch is left without a site, which the sphere's dual needs (its sites
  // must not all lie in one hemisphere). Elsewhere no site in a patch. An apex site close to its loop's
  // chords (a small hole, 3 or 4 loop sites around it: the apex sees a loop edge under about 120 or 90
  // degrees) made the edge between two consecutive loop sites a Delaunay edge only if the free site
  // facing it saw it under at most 60 or 90 degrees, which the CVT's free sites next to the loop do not
  // keep (torus_with_hole.off failed at 100 to 1000 vertices). With only loop sites on the patch side
  // (or an apex seeing the edge under 60 degrees at most), a loop edge is in the dual whenever the free
  // site facing it lies outside the circle through it and the loop site facing it across the patch (the
  // loop's own circle for a round hole), as at a boundary of the plane. `apexes` is set with the loops'
  // sites below.
  const bool apex_sites_needed = patches && patches_need_apex_sites<Domain>(itri, emb);
  std::size_t apexes = 0;
  auto cvt_and_dual = [&](auto& traits) {
    auto sites = traits.initial_sites(n + apexes, options.random_seed);
    const double setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
    Remeshed_surface dual = cvt_and_dual_mesh(surface, itri, traits, sites, np, vis, result);
    result.seconds[int(Stage::CVT)] += setup_seconds;
    result.domain_diagnostics = Domain::diagnostics(emb, traits);
    return dual;
  };
  Remeshed_surface out = [&] {
    if constexpr(Domain::kind != Parametric_domain::PLANE) {
      std::vector<std::size_t> corners = corners_to_fix(features, itri, result.refinement.output_edge_length);
      if(patches)  // the loops' corners are placed with their sites
        corners.erase(std::remove_if(corners.begin(), corners.end(), [&](std::size_t v) { return itri.seam(int(v)) >= 0; }), corners.end());
      auto fixed = corner_sites<Domain>(emb, itri, corners);
      // the crease sites after the corners, at equal metric arc length along each curve (crease_sites.h)
      Crease_sites crease_sites;
      std::vector<std::vector<std::size_t>> crease_chain;  // per curve, its sites as output vertices, with its fixed corners
      std::vector<char> crease_closed;
      if(creases) {
        const double h = patches ? loop_edge_length : result.refinement.output_edge_length;
        std::vector<char> taken(itri.number_of_vertices(), 0);
        std::vector<std::size_t> corner_index(itri.number_of_vertices(), std::size_t(-1));
        for(std::size_t j = 0; j < corners.size(); ++j) {
          taken[corners[j]] = 1;
          corner_index[corners[j]] = j;
        }
        crease_sites = place_crease_sites(itri, features, crease_chains(itri, surface, features), h, std::move(taken),
                                          n - std::min(n, fixed.size() + std::max<std::size_t>(4, n / 4)), corners);
        for(std::size_t c = 0; c < features.curves.size(); ++c) {
          const Feature_curve& curve = features.curves[c];
          std::vector<std::size_t> chain;
          if(!curve.closed && corner_index[curve.vertices.front()] != std::size_t(-1)) chain.push_back(corner_index[curve.vertices.front()]);
          for(int v : crease_sites.vertices[c]) {
            chain.push_back(fixed.size());
            fixed.push_back(seam_site<Domain>(emb, itri, v));
          }
          if(!curve.closed && corner_index[curve.vertices.back()] != std::size_t(-1)) chain.push_back(corner_index[curve.vertices.back()]);
          crease_chain.push_back(std::move(chain));
          crease_closed.push_back(curve.closed ? 1 : 0);
        }
      }
      Loop_sites loops;
      std::vector<std::size_t> first;
      if(patches) {
        loops = place_loop_sites(itri, *patches, loop_edge_length, options.corner_angle,
                                 n - std::min(n, fixed.size() + std::max<std::size_t>(4, n / 4)));
        for(const auto& l : loops.vertices) {
          first.push_back(fixed.size());
          for(int v : l) fixed.push_back(seam_site<Domain>(emb, itri, v));
        }
        first.push_back(fixed.size());
        if constexpr(Domain::kind == Parametric_domain::SPHERE)
          if(apex_sites_needed)
            for(std::size_t l = 0; l < patches->loops.size(); ++l) {
              auto apex = seam_site<Domain>(emb, itri, int(patches->apex[l]));
              const std::size_t k = loops.vertices[l].size();
              bool narrow = true;
              for(std::size_t j = 0; j < k && narrow; ++j) {
                const Eigen::Vector3d u = fixed[first[l] + j].site - apex.site, v = fixed[first[l] + (j + 1) % k].site - apex.site;
                narrow = std::atan2(u.cross(v).norm(), u.dot(v)) <= 3.14159265358979323846 / 3;
              }
              if(narrow) fixed.push_back(apex);
            }
        apexes = fixed.size() - first.back();
      }
      Traits_with_fixed_corners<typename Domain::Traits> traits(Domain::make_traits(itri, emb, options.number_of_threads), std::move(fixed));
      Remeshed_surface dual = cvt_and_dual(traits);
      if(patches) remove_patch_triangles(dual, loops, first, apexes, surface.number_of_vertices());
      if(creases) {
        const auto joined = recover_crease_edges(surface, dual, crease_chain, crease_closed);
        result.crease_sites = crease_sites.size();
        result.crease_edges_recovered = joined.first;
        result.crease_edges_missing = joined.second;
      }
      result.boundary_sites = loops.size();  // the crease corners are not boundary
      return dual;
    } else {
      typename Domain::Traits traits = Domain::make_traits(itri, emb, options.number_of_threads);
      return cvt_and_dual(traits);
    }
  }();

  // the optimisation on the surface, in the metric (always, or to repair inverted triangles)
  optimize_output(surface, metric, out, options.surface_optimization, vis, result, options.number_of_threads);

  // 6. quality in the metric, orientation against the input, topology and distance to the input
  measure_and_check_output(surface, metric, out, Domain::inverted_triangles_hint(), vis, result, options.number_of_threads);
  const auto measure_start = std::chrono::steady_clock::now();
  result.features = measure_features(surface, features, out.points, out.faces);
  result.seconds[int(Stage::QUALITY)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - measure_start).count();
  return out;
}

// The pipeline, following the creases in a closed domain; if that run fails (Remeshing_failure: the
// crease pieces split in the background can make a thin or sharply folded input's embedding fail, as on
// test/data/cases/pillow_005.off at 150 vertices), the run without them, as before issue 15 item 2, whose
// result (or failure) stands, with the first run's reason in Remeshing_result::creases_not_followed.
template <typename Domain, typename AnisotropicMetric>
Remeshed_surface run_pipeline(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                              const Remeshing_options& options, Visitor_handle& vis)
{
  bool tried = false;
  std::string reason;
  try {
    return run_pipeline_once<Domain>(surface, metric, result, options, vis, true, tried);
  } catch(const Remeshing_failure& e) {
    if(!tried) throw;
    reason = e.what();
  }
  Remeshed_surface out = run_pipeline_once<Domain>(surface, metric, result, options, vis, false, tried);
  result.creases_not_followed = reason;
  return out;
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalMain
 * remeshes `surface` as `remesh()` does, through the parametric domain `Domain` (a model of
 * `ParametricDomain`: `Planar_domain`, `Spherical_domain`, `Flat_torus_domain`, `Hyperbolic_domain`)
 * instead of the one the topology selects: the six stages of Zhong et al.\ 2014 (metric, edge lengths,
 * conformal embedding, weighted CVT with density `cf^2`, Delaunay dual mapped back, quality in the
 * metric), with `Domain` supplying stage 3, the domain traits of stages 4 and 5 and its diagnostics.
 * `remesh()` is this function behind one switch on the topology; call it directly to compile only the
 * domain you need (each domain brings its own CGAL triangulations, which dominate the build time).
 *
 * \tparam Domain a model of `ParametricDomain`
 * \tparam AnisotropicMetric a model of `AnisotropicMetric`
 * \param surface the input (never modified)
 * \param metric the metric
 * \param result receives the diagnostics (`Remeshing_result::domain_diagnostics` from `Domain`)
 * \param np the named parameters of `remesh()` (`parametric_domain` is ignored: `Domain` is the domain)
 * \returns the output mesh as arrays
 * \throws Invalid_input if `number_of_vertices` is missing or below the minimum of the domain and topology,
 *         if `Domain` does not fit the topology (`Domain::fits()`), or if the metric is unusable
 * \throws Remeshing_failure (or its `Convergence_failure`) if a stage cannot handle this valid input; the
 *         output is never returned with an inverted triangle or a wrong topology
 * \throws Cancelled if the visitor asked to stop
 */
template <typename Domain, typename AnisotropicMetric, typename NamedParameters = parameters::Default_named_parameters>
Remeshed_surface remesh_in_domain(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                                  const NamedParameters& np = parameters::default_values())
{
  typename internal::Visitor_reference<NamedParameters>::type visitor = internal::get_visitor(np);
  internal::Visitor_handle handle(visitor);
  return internal::run_pipeline<Domain>(surface, metric, result, internal::Remeshing_options::from(np), handle);
}

/*!
 * \ingroup PkgAnisoConformalMain
 * remeshes the triangle mesh `tmesh` (any model of `FaceListGraph`) into `out_mesh` (a model of
 * `MutableFaceGraph`) through the parametric domain `Domain`, as the overload on `Input_surface` does;
 * `out_mesh` is cleared and written only on success (strong guarantee), and `tmesh` is never modified.
 * \returns the diagnostics (`Remeshing_result`)
 */
template <typename Domain, typename TriangleMesh, typename AnisotropicMetric, typename OutputMesh,
          typename NamedParameters = parameters::Default_named_parameters>
Remeshing_result remesh_in_domain(const TriangleMesh& tmesh, const AnisotropicMetric& metric, OutputMesh& out_mesh,
                                  const NamedParameters& np = parameters::default_values())
{
  const Input_surface surface = Input_surface::from_mesh(tmesh, np);
  Remeshing_result result;
  internal::copy_to_face_graph(remesh_in_domain<Domain>(surface, metric, result, np), out_mesh);
  return result;
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_REMESH_IN_DOMAIN_H
