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
#include <Aniso_conformal/internal/features/boundary_distance.h>
#include <Aniso_conformal/internal/features/crease_sites.h>
#include <Aniso_conformal/internal/features/feature_size.h>
#include <Aniso_conformal/internal/features/fixed_corner_sites.h>
#include <Aniso_conformal/internal/features/ragged_creases.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/internal/remesh/canonical_parameters.h>
#include <Aniso_conformal/internal/remesh/embedding_memo.h>
#include <Aniso_conformal/internal/remesh/hole_patches.h>
#include <Aniso_conformal/internal/remesh/loop_sites.h>
#include <Aniso_conformal/internal/remesh/pipeline_start.h>
#include <Aniso_conformal/internal/remesh/pipeline_steps.h>
#include <Aniso_conformal/internal/stretch_limit.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/measure_features.h>
#include <Aniso_conformal/mesh_quality.h>
#include <Aniso_conformal/parameters.h>
#include <Aniso_conformal/weighted_centroidal_Voronoi_tessellation.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

/// \file remesh_in_domain.h
/// The pipeline of `remesh()` in one parametric domain, chosen at compile time: includes no domain, so a
/// program that knows its topology compiles only the domain it uses.

namespace Aniso_conformal {

namespace internal {

// The checks of the request, the feature graph, the patches, stage 1 and the refinement of stage 2 in
// `Domain` (the caller's parameters read into values and its visitor behind a handle,
// canonical_parameters.h: compiled once per domain and metric). `result` is cleared once the request is
// checked, and filled as the steps go (a failure leaves the figures so far); `start.result` is a copy.
template <typename Domain, typename AnisotropicMetric>
Pipeline_start start_pipeline(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                              const Remeshing_options& options, Visitor_handle& vis)
{
  const auto np = canonical_parameters(options, vis);
  const std::size_t n = options.number_of_vertices;
  if(n == 0) throw Invalid_input("remesh(): the number of output vertices must be given (number_of_vertices) and positive");
  if(n < 3) throw Invalid_input("remesh(): at least 3 output vertices are needed, " + std::to_string(n) + " were requested");
  constexpr bool closed = Domain::kind != Parametric_domain::PLANE;  // the closed domains keep the corners
  Pipeline_start start;
  // a surface with boundary loops in a closed domain: its holes closed by patches (issue 15, item 3); a
  // disk goes to the plane (the sphere and the cone domain refuse it: fits()). In the cone domain the
  // patches hold no CVT density, as in the others (without that, free sites strayed into them: the
  // annulus at 300 measured G_avg 0.69; with it 0.922, the sphere's 0.884)
  if(closed && !surface.boundary_loops().empty() &&
     !((Domain::kind == Parametric_domain::SPHERE || Domain::kind == Parametric_domain::CONE) && surface.is_disk()))
    start.patches.reset(new Hole_patches(close_holes(surface, options.split_pinched_loops, options.collar_thin_loops ? estimated_output_edge_length(surface, n) : 0.0)));
  const Input_surface& background = start.background(surface);
  if(!Domain::fits(background))
    throw Invalid_input(std::string("remesh(): the ") + domain_name(Domain::kind) + " domain does not fit the input, which is " +
                        surface.topology_description() + " (the " + domain_name(Domain::kind) + " domain takes " +
                        Domain::topology() + ")");
  Domain::check_number_of_vertices(background, n);
  result = Remeshing_result();
  result.domain = Domain::kind;
  result.input_vertices = surface.number_of_vertices();
  result.input_faces = surface.number_of_faces();
  if(start.patches) result.collared_loops = start.patches->collared_loops;
  // the input's sharp features (issue 15): measured on the output, their time counted as the metric's
  const auto features_start = std::chrono::steady_clock::now();
  start.features = detect_features(surface, options.feature_angle, options.corner_angle, options.feature_edges, options.feature_vertices);
  if(options.drop_ragged_creases)  // noise and staircases, not sharp creases (ragged_creases.h)
    start.features = without_ragged_crease_components(surface, start.features, n, options.feature_angle, options.corner_angle,
                                                      options.feature_edges, options.feature_vertices, start.ragged_creases);
  const double features_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - features_start).count();
  // 1. metric, 2. edge lengths (begun)
  if(start.patches)
    start.itri.emplace(metric_and_background(background, Patched_metric<AnisotropicMetric>(metric, *start.patches), n, np, vis, result,
                                             start.edge_lengths_seconds, start.patches.get(), &surface));
  else
    start.itri.emplace(metric_and_background(surface, metric, n, np, vis, result, start.edge_lengths_seconds));
  // the crease components shorter than an output edge dropped (fixed_corner_sites.h), then the corners
  // counted against the vertices asked for
  const auto short_start = std::chrono::steady_clock::now();
  start.features = without_short_crease_components(surface, start.features, *start.itri, result.refinement.output_edge_length,
                                                   options.corner_angle, options.feature_edges, options.feature_vertices,
                                                   start.short_creases_dropped, start.short_crease_length_dropped);
  if(closed)  // the corners that get a fixed site: those at least half an output edge apart
    check_vertices_for_corners(corners_to_fix(start.features, *start.itri, result.refinement.output_edge_length).size(), n,
                               options.feature_angle);
  result.seconds[int(Stage::METRIC)] += features_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - short_start).count();
  start.result = result;
  return start;
}

// In a closed domain, the sites (the input's corners first, fixed; the crease sites with `creases`; with
// `patches` the loops' sites and, on the sphere when the patches cover half of it or more, one more fixed
// site at a patch's apex (removed from the output), at each apex that sees every edge of its loop's chain
// of sites under 60 degrees at most: no large patch is left without a site, which the sphere's dual needs
// (its sites must not all lie in one hemisphere); elsewhere no site in a patch), then
// `cvt_and_dual(traits)` (which reads `apexes`, the number of apex sites, set here), the patches'
// triangles removed and the crease edges recovered (crease_sites.h).
// An apex site close to its loop's chords (a small hole, 3 or 4 loop sites around it: the apex sees a
// loop edge under about 120 or 90 degrees) made the edge between two consecutive loop sites a Delaunay
// edge only if the free site facing it saw it under at most 60 or 90 degrees, which the CVT's free sites
// next to the loop do not keep (torus_with_hole.off failed at 100 to 1000 vertices). With only loop sites
// on the patch side (or an apex seeing the edge under 60 degrees at most), a loop edge is in the dual
// whenever the free site facing it lies outside the circle through it and the loop site facing it across
// the patch (the loop's own circle for a round hole), as at a boundary of the plane.
template <typename Domain, typename CvtAndDual>
Remeshed_surface closed_domain_dual(const Input_surface& surface, const Pipeline_start& start, const Intrinsic_triangulation& itri,
                                    const typename Domain::Embedding& emb, double loop_edge_length, const Feature_graph* creases,
                                    const Remeshing_options& options, Remeshing_result& result, std::size_t& apexes,
                                    CvtAndDual& cvt_and_dual, const std::vector<Eigen::Vector3d>& sphere_sites)
{
  const std::size_t n = options.number_of_vertices;
  const Feature_graph& features = start.features;
  const Hole_patches* patches = start.patches.get();
  apexes = 0;
  std::vector<std::size_t> corners = corners_to_fix(features, itri, result.refinement.output_edge_length);
  if(patches)  // the loops' corners are placed with their sites
    corners.erase(std::remove_if(corners.begin(), corners.end(), [&](std::size_t v) { return itri.seam(int(v)) >= 0; }), corners.end());
  auto fixed = corner_sites<Domain>(emb, itri, corners);
  // the domain's own fixed sites (the cone domain's cones of negative curvature), after the corners; with
  // patches not those on a patch face (a loop vertex has its loop's site; a patch's vertex is no output
  // vertex): elephant-with-holes' cones on loops made two fixed sites coincide
  std::vector<std::size_t> domain_kept = Domain::vertices_kept(emb);
  if(patches) {
    std::vector<char> on_patch(itri.number_of_vertices(), 0);
    for(std::size_t f = 0; f < itri.number_of_faces(); ++f)
      if(itri.is_patch_face(f))
        for(int v : itri.face_vertices(f)) on_patch[std::size_t(v)] = 1;
    domain_kept.erase(std::remove_if(domain_kept.begin(), domain_kept.end(), [&](std::size_t v) { return on_patch[v] != 0; }), domain_kept.end());
  }
  const std::vector<std::size_t> kept = kept_vertices_apart(domain_kept, corners, itri, result.refinement.output_edge_length, n / 8);
  const std::size_t first_kept = fixed.size();  // their output vertices: [first_kept, first_kept + kept.size())
  for(std::size_t v : kept) fixed.push_back(seam_site<Domain>(emb, itri, int(v)));
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
    for(std::size_t v : kept) taken[v] = 1;
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
                             n - std::min(n, fixed.size() + std::max<std::size_t>(4, n / 4)), !options.split_pinched_loops);
    for(const auto& l : loops.vertices) {
      first.push_back(fixed.size());
      for(int v : l) fixed.push_back(seam_site<Domain>(emb, itri, v));
    }
    first.push_back(fixed.size());
    if constexpr(Domain::kind == Parametric_domain::SPHERE)
      if(patches_need_apex_sites<Domain>(itri, emb))
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
  // the domain's kept vertices: fixed for the CVT and the dual, free for the surface optimisation (the
  // patches' apexes removed below come after them: their indices stand)
  for(std::size_t j = 0; j < kept.size(); ++j) dual.released_vertices.push_back(first_kept + j);
  if(patches) {
    const auto mended = remove_patch_triangles(dual, loops, first, apexes, surface.number_of_vertices(), patches->closed, surface,
                                               sphere_sites.empty() ? nullptr : &sphere_sites);
    result.loop_edges_recovered = mended.first;
    result.patch_sites_moved = mended.second;
  }
  if(creases) {
    const auto joined = recover_crease_edges(surface, dual, crease_chain, crease_closed);
    result.crease_sites = crease_sites.size();
    result.crease_edges_recovered = joined.first;
    result.crease_edges_missing = joined.second;
  }
  result.boundary_sites = loops.size();  // the crease corners are not boundary
  return dual;
}

// In the plane with the creases followed (issue 15, item 2), the same steps as closed_domain_dual() around
// the boundary's own sites: the `corners` (plane_corners_to_fix()) on the boundary are corners of the boundary
// (marked before the embedding, so its 1D CVT has a site exactly there and a crease ending there ends at
// that site; a crease is never a boundary edge, detect_features()), the others are fixed sites inside,
// followed by the crease sites (place_crease_sites()), after the boundary's sites
// (Traits_with_interior_fixed_sites); then `cvt_and_dual(traits)` and the crease edges recovered. No crease
// site is placed within half an output edge (in the metric at the site) of the boundary: the polygon of the
// boundary sites bounds the dual, and a fixed site near it would make a sliver or fall outside.
template <typename Domain, typename CvtAndDual>
Remeshed_surface planar_dual_with_creases(const Input_surface& surface, const Feature_graph& features, const Intrinsic_triangulation& itri,
                                          const typename Domain::Embedding& emb, const std::vector<std::size_t>& corners,
                                          const Remeshing_options& options, Remeshing_result& result, CvtAndDual& cvt_and_dual)
{
  const std::size_t n = options.number_of_vertices, nv = itri.number_of_vertices();
  const double h = result.refinement.output_edge_length;
  std::vector<std::size_t> inner;  // the corners inside, as fixed sites
  std::vector<std::size_t> site_of(nv, std::size_t(-1));  // background vertex -> index among the fixed sites inside
  for(std::size_t v : corners)
    if(!itri.is_boundary_vertex(int(v))) {
      site_of[v] = inner.size();
      inner.push_back(v);
    }
  auto fixed = corner_sites<Domain>(emb, itri, inner);
  std::vector<char> taken(nv, 0);
  for(std::size_t v : corners) taken[v] = 1;
  // the boundary's metric length, and the chain vertices too near it
  double perimeter = 0;
  for(int e = 0; e < int(itri.number_of_halfedges()); ++e)
    if(itri.is_boundary_edge(e)) perimeter += itri.length(e);
  const auto chains = crease_chains(itri, surface, features);
  const Boundary_distance to_boundary(itri);  // in the metric (boundary_distance.h)
  for(const auto& ch : chains)
    for(const auto& tv : ch) {
      const int v = tv.second;
      if(!taken[std::size_t(v)] && (itri.is_boundary_vertex(v) || to_boundary(v) < 0.5 * h))
        taken[std::size_t(v)] = 1;
    }
  const std::size_t boundary_sites = std::size_t(std::ceil(perimeter / h));  // about as many as the boundary gets
  const Crease_sites crease_sites =
      place_crease_sites(itri, features, chains, h, std::move(taken),
                         n - std::min(n, fixed.size() + boundary_sites + std::max<std::size_t>(4, n / 4)), corners);
  for(std::size_t c = 0; c < features.curves.size(); ++c)
    for(int v : crease_sites.vertices[c]) {
      site_of[std::size_t(v)] = fixed.size();
      fixed.push_back(seam_site<Domain>(emb, itri, v));
    }
  Traits_with_interior_fixed_sites<typename Domain::Traits> traits(Domain::make_traits(itri, emb, options.number_of_threads), std::move(fixed));
  Remeshed_surface dual = cvt_and_dual(traits);
  // per curve its sites as output vertices (site i is output vertex i), its corners at the ends
  const std::size_t nb = traits.number_of_boundary_sites();
  std::vector<std::size_t> boundary_site(nv, std::size_t(-1));
  for(std::size_t i = 0; i < nb; ++i) {
    const int w = traits.boundary_site_vertex(i);
    if(w >= 0 && std::size_t(w) < nv) boundary_site[std::size_t(w)] = i;
  }
  auto output_vertex = [&](std::size_t v) { return site_of[v] != std::size_t(-1) ? nb + site_of[v] : boundary_site[v]; };
  std::vector<std::vector<std::size_t>> crease_chain;
  std::vector<char> crease_closed;
  for(std::size_t c = 0; c < features.curves.size(); ++c) {
    const Feature_curve& curve = features.curves[c];
    std::vector<std::size_t> chain;
    const std::size_t front = output_vertex(curve.vertices.front()), back = output_vertex(curve.vertices.back());
    if(!curve.closed && front != std::size_t(-1)) chain.push_back(front);
    for(int v : crease_sites.vertices[c]) chain.push_back(output_vertex(std::size_t(v)));
    if(!curve.closed && back != std::size_t(-1)) chain.push_back(back);
    crease_chain.push_back(std::move(chain));
    crease_closed.push_back(curve.closed ? 1 : 0);
  }
  const auto joined = recover_crease_edges(surface, dual, crease_chain, crease_closed);
  result.crease_sites = crease_sites.size();
  result.crease_edges_recovered = joined.first;
  result.crease_edges_missing = joined.second;
  result.boundary_sites = nb;  // the interior fixed sites are not boundary
  return dual;
}

// The pipeline from `start` (start_pipeline()) on its background `itri`: the rest of stage 2 (with
// `follow_creases` the creases kept, crease_sites.h: with `crease_splits` their background pieces refined
// first, the splits counted there; without it the crease sites on the background's own crease vertices),
// the conformal embedding, the weighted CVT and the dual in `Domain`, the surface optimisation, the
// quality and the checks. `result` starts as `start.result`.
template <typename Domain, typename AnisotropicMetric>
Remeshed_surface finish_pipeline(const Input_surface& surface, const AnisotropicMetric& metric, const Pipeline_start& start,
                                 Intrinsic_triangulation itri, Remeshing_result& result, const Remeshing_options& options,
                                 Visitor_handle& vis, bool follow_creases, std::size_t* crease_splits,
                                 Embedding_memo<Domain>* memo = nullptr)
{
  const auto np = canonical_parameters(options, vis);
  const std::size_t n = options.number_of_vertices;
  constexpr bool closed = Domain::kind != Parametric_domain::PLANE;
  result = start.result;
  const Hole_patches* patches = start.patches.get();
  // the creases are kept as chains of output edges (issue 15, item 2): their background pieces refined
  // here, fixed sites along them in closed_domain_dual() or planar_dual_with_creases()
  const Feature_graph* creases = follow_creases && !start.features.curves.empty() ? &start.features : nullptr;
  double loop_edge_length = 0;  // with patches: the output edge length over the surface without them
  finish_edge_lengths(itri, start.background(surface), n, np, vis, result, start.edge_lengths_seconds, patches,
                      patches ? &surface : nullptr, patches ? &loop_edge_length : nullptr, creases, crease_splits);
  // in the plane, the corners kept with the creases; those on the boundary become the boundary's corners
  std::vector<std::size_t> plane_corners;
  if(!closed && creases) plane_corners = plane_corners_to_fix(start.features, itri, result.refinement.output_edge_length);

  // 3. conformal embedding, 4. weighted CVT, 5. dual mesh, in the domain
  Stage_timer t3(vis, Stage::EMBEDDING);
  bool reused = false;  // the embedding of an earlier run on this background (embedding_memo.h)
  const typename Domain::Embedding emb = memo ? memo->embed(itri, np, reused) : Domain::embed(itri, np);
  record_embedding(emb, result);
  result.embedding_reused = reused;
  result.seconds[int(Stage::EMBEDDING)] = t3.stop(vis);
  const auto setup_start = std::chrono::steady_clock::now();  // the CVT's set-up counts as CVT time
  std::size_t apexes = 0;  // the patches' apex sites on the sphere, set by closed_domain_dual()
  std::vector<Eigen::Vector3d> sphere_sites;  // on the sphere with patches: the sites after the CVT (the loop edges' recovery)
  auto cvt_and_dual = [&](auto& traits) {
    auto sites = traits.initial_sites(n + apexes, options.random_seed);
    const double setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
    Remeshed_surface dual = cvt_and_dual_mesh(surface, itri, traits, sites, np, vis, result);
    if constexpr(Domain::kind == Parametric_domain::SPHERE)
      if(patches) sphere_sites.assign(sites.begin(), sites.end());
    result.seconds[int(Stage::CVT)] += setup_seconds;
    result.domain_diagnostics = Domain::diagnostics(emb, traits);
    return dual;
  };
  Remeshed_surface out = [&] {
    if constexpr(closed) {
      return closed_domain_dual<Domain>(surface, start, itri, emb, loop_edge_length, creases, options, result, apexes, cvt_and_dual,
                                        sphere_sites);
    } else {
      if(creases) return planar_dual_with_creases<Domain>(surface, start.features, itri, emb, plane_corners, options, result, cvt_and_dual);
      typename Domain::Traits traits = Domain::make_traits(itri, emb, options.number_of_threads);
      return cvt_and_dual(traits);
    }
  }();

  // the optimisation on the surface, in the metric; REPAIR as ALWAYS in the cone domain and on a planar
  // input, where flips cannot move the output off the input, and on an output that follows creases, whose
  // fixed crease sites leave the CVT's cells beside them irregular (doc/manual.md, the pipeline's stage 5)
  const bool always = Domain::optimizes_on_the_surface_by_default || surface.is_planar() || !out.kept_edges.empty();
  const Surface_optimization optimization =
      always && options.surface_optimization == Surface_optimization::REPAIR ? Surface_optimization::ALWAYS : options.surface_optimization;
  optimize_output(surface, metric, out, optimization, vis, result, options.number_of_threads);

  // 6. quality in the metric, orientation against the input, topology and distance to the input
  measure_and_check_output(surface, metric, out, Domain::inverted_triangles_hint(), vis, result, options.number_of_threads);
  record_features(surface, start, out, result);
  return out;
}

// The pipeline, following the creases, in up to four runs from the background kept after the refinement
// of stage 2 (start_pipeline(), not recomputed; a failure before it is not retried):
// 1. the crease pieces refined to a third of the output edge length (the crease sites then sit at about the
//    spacing asked for);
// 2. if run 1 fails (Remeshing_failure) after splitting crease pieces, the refinement's own failure
//    included (too many vertices: it splits before it gives up, finish_edge_lengths()): the crease sites on
//    the background's own crease vertices, nothing split. The splits can make a thin or sharply folded
//    input's embedding fail (test/data/cases/pillow_005.off at 150 vertices: the rim's midpoints, each
//    joined to a fan of the rim's thin latitude strips, turned 89 triangles over on the sphere), while the
//    background unsplit is the one the run without creases embeds;
// 3. if that fails too: the run without creases, as before issue 15 item 2 (the corners still fixed
//    sites), with the first run's reason in Remeshing_result::creases_not_followed; its result stands,
//    or, in the plane or without corners, its failure;
// 4. in a closed domain, if run 3 fails: the run without any feature site (Remeshing_result::
//    corners_not_kept says why run 3 failed), whose result stands, or run 3's failure.
// Remeshing_result::crease_run says which run stood. A run whose stage 2 gives the background an earlier
// run embedded (runs 2 to 4 mostly, and a boundary loop's second run) takes that embedding, or its failure
// (embedding_memo.h).
template <typename Domain, typename AnisotropicMetric>
Remeshed_surface run_pipeline(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                              const Remeshing_options& options, Visitor_handle& vis)
{
  Pipeline_start start = start_pipeline<Domain>(surface, metric, result, options, vis);
  const bool creases = !start.features.curves.empty();
  Embedding_memo<Domain> memo;  // the runs on one background share its embedding
  if(!creases) {  // with loops, a run that fails at a loop goes again (run_again_if_a_loop_is_blocked())
    std::string why;
    double discarded = 0;
    // a first run with loops keeps the background; with a loop through a point twice, any failure of it
    // leads to a second run whose holes are closed lobe by lobe, from the start
    const bool loops = !surface.boundary_loops().empty(), pinched = loops && has_pinched_loop(surface);
    Remeshed_surface out = run_again_if_a_loop_is_blocked(loops, [&](bool again) {
      Remeshing_options o = options;
      o.random_seed += again ? 1u : 0u;
      if(loops && !again) return finish_pipeline<Domain>(surface, metric, start, *start.itri, result, o, vis, false, nullptr, &memo);
      if(again && pinched) {
        o.split_pinched_loops = true;
        Pipeline_start split = start_pipeline<Domain>(surface, metric, result, o, vis);
        return finish_pipeline<Domain>(surface, metric, split, std::move(*split.itri), result, o, vis, false, nullptr);
      }
      if(again) vis.on_stage_started(Stage::EDGE_LENGTHS);
      memo.keep = false;
      return finish_pipeline<Domain>(surface, metric, start, std::move(*start.itri), result, o, vis, false, nullptr, again ? &memo : nullptr);
    }, why, discarded, pinched);
    result.crease_run = Crease_run::NONE;
    result.discarded_seconds += discarded;  // finish_pipeline() starts the result afresh: set after it
    result.reseeded = why;
    return out;
  }
  std::string reason;
  std::size_t splits = 0;
  // the wall time of a failed run is kept (Remeshing_result::discarded_seconds): each run starts from
  // start.result and overwrites the stages' seconds
  double discarded = 0;
  // one run: its output, or none when it fails (Remeshing_failure: its message into `why`, the exception
  // into `failure`, when given; its wall time into `discarded`)
  auto attempt = [&](const auto& run, std::string* why, std::exception_ptr* failure) -> std::optional<Remeshed_surface> {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      return run();
    } catch(const Remeshing_failure& e) {
      if(why) *why = e.what();
      if(failure) *failure = std::current_exception();
    }
    discarded += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return std::nullopt;
  };
  // the output of the run that stood, as `run`, with the time thrown away before it and, past the runs
  // that follow the creases, why they did not stand (set here: each run starts from start.result)
  auto stood = [&](Remeshed_surface&& out, Crease_run run) {
    result.crease_run = run;
    result.discarded_seconds += discarded;
    if(run == Crease_run::NOT_FOLLOWED || run == Crease_run::FEATURES_DROPPED) result.creases_not_followed = reason;
    if(run == Crease_run::INPUT_VERTICES) result.crease_refinement_failed = reason;
    return std::move(out);
  };
  if(auto out = attempt([&] { return finish_pipeline<Domain>(surface, metric, start, *start.itri, result, options, vis, true, &splits, &memo); }, &reason, nullptr))
    return stood(std::move(*out), Crease_run::REFINED);
  if(splits > 0) {
    vis.on_stage_started(Stage::EDGE_LENGTHS);  // the retry begins in stage 2, after the refinement
    if(auto out = attempt([&] { return finish_pipeline<Domain>(surface, metric, start, *start.itri, result, options, vis, true, nullptr, &memo); }, nullptr, nullptr))
      return stood(std::move(*out), Crease_run::INPUT_VERTICES);
  }
  vis.on_stage_started(Stage::EDGE_LENGTHS);
  constexpr bool closed = Domain::kind != Parametric_domain::PLANE;
  if(!closed || start.features.corners.empty()) {
    memo.keep = false;
    return stood(finish_pipeline<Domain>(surface, metric, start, std::move(*start.itri), result, options, vis, false, nullptr, &memo), Crease_run::NOT_FOLLOWED);
  }
  std::string corners_reason;
  std::exception_ptr corners_failure;  // rethrown, type and all, if the run without feature sites fails too
  if(auto out = attempt([&] { return finish_pipeline<Domain>(surface, metric, start, *start.itri, result, options, vis, false, nullptr, &memo); }, &corners_reason, &corners_failure))
    return stood(std::move(*out), Crease_run::NOT_FOLLOWED);
  // 4. in a closed domain, the run without any feature site: three corners half an output edge apart can
  // make a triangle that the surface optimisation, which moves no fixed vertex, cannot turn back (CGAL's
  // man at 2000 and 3000 with the defaults: 1 inverted triangle left); the features are still measured
  vis.on_stage_started(Stage::EDGE_LENGTHS);
  Feature_graph features;
  std::swap(features, start.features);
  memo.keep = false;
  auto out = attempt([&] { return finish_pipeline<Domain>(surface, metric, start, std::move(*start.itri), result, options, vis, false, nullptr, &memo); },
                     nullptr, nullptr);
  std::swap(features, start.features);
  if(!out) std::rethrow_exception(corners_failure);
  record_features(surface, start, *out, result);
  result.corners_not_kept = corners_reason;
  return stood(std::move(*out), Crease_run::FEATURES_DROPPED);
}

// remesh_in_domain(), with the feature sizing taken from `once` (computed there by the first call that
// needs it); a call counts in the metric's stage the time of the sizings it computed, not of those it
// reused (the first call's time, thrown away or not, holds them). With the curvature's sizes (Curvature_sizing:
// ALWAYS, or CONES in a domain that sizes by curvature by default), a run that fails is run again with
// the crease gaps' sizes alone: the curvature sizing refines, it must not cost an output (CGAL's femur
// with the curvature metric at 2000 vertices: its cone run failed with them)
template <typename Domain, typename AnisotropicMetric, typename NamedParameters>
Remeshed_surface remesh_in_domain_with_sizing(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                                              const NamedParameters& np, Feature_sizing_once& once)
{
  typename Visitor_reference<NamedParameters>::type visitor = get_visitor(np);
  Visitor_handle handle(visitor);
  const Remeshing_options options = Remeshing_options::from(np);
  const auto run = [&](const auto& m) {
    return run_again_with_collars_if_a_loop_is_blocked(surface, options.number_of_vertices, result, [&](bool collars) {
      Remeshing_options o = options;
      o.collar_thin_loops = collars;
      return run_pipeline<Domain>(surface, m, result, o, handle);
    });
  };
  const bool curvature = options.curvature_sizing == Curvature_sizing::ALWAYS ||
                         (options.curvature_sizing == Curvature_sizing::CONES && Domain::sizes_by_curvature_by_default);
  if(!options.feature_sizing && !curvature) return run_with_stretch_bound(surface, metric, result, options, run);
  // feature curves close together, thin parts and tips: the metric scaled up there (features/feature_size.h)
  double spent = 0;  // the sizings computed by this call
  const auto run_with = [&](bool with_curvature) {
    const Feature_sizing& sizing =
        once.get(with_curvature, [&] { return feature_sizing(surface, metric, options, with_curvature, &once.measure); }, spent);
    Remeshed_surface out;
    if(const auto field = sizing.field) {
      const Adjusted_metric scaled(
          surface, [&metric](const Surface_point& p) { return Eigen::Matrix3d(metric.tensor(p)); }, {},
          [field](const Surface_point& x) { return field->scale(x); });
      out = run_with_stretch_bound(surface, scaled, result, options, run);
    } else
      out = run_with_stretch_bound(surface, metric, result, options, run);
    result.feature_sizing = sizing.report;
    return out;
  };
  Remeshed_surface out;
  try {
    out = run_with(curvature);
  } catch(const Remeshing_failure&) {
    if(!curvature || !once.sizing[true] || !once.sizing[true]->report.curvature_applied) throw;
    out = run_with(false);
    const Feature_sizing_report& tried = once.sizing[true]->report;
    result.feature_sizing.curved_points = tried.curved_points;  // measured, not applied: that run failed
    result.feature_sizing.radius_min = tried.radius_min;
  }
  result.seconds[int(Stage::METRIC)] += spent;  // the gaps and curvatures measured: counted as the metric's
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
 * A run whose output has folded triangles, in a metric asking for more stretch than straight edges can
 * follow where its long axis turns, is made again with the stretch bounded there (`Stretch_limit_report`
 * in `Remeshing_result::stretch_limit`, which says what was bounded; `quality` is then in that metric).
 * Where two crease curves run closer than an output triangle's height, the metric is first scaled up
 * there (`feature_sizing`, default on; `Feature_sizing_report` in `Remeshing_result::feature_sizing`).
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
 *         output is never returned with an inverted triangle or a wrong topology (after the stretch bound,
 *         the message gives the first run's reason and the bounded run's)
 * \throws Cancelled if the visitor asked to stop
 */
template <typename Domain, typename AnisotropicMetric, typename NamedParameters = parameters::Default_named_parameters>
Remeshed_surface remesh_in_domain(const Input_surface& surface, const AnisotropicMetric& metric, Remeshing_result& result,
                                  const NamedParameters& np = parameters::default_values())
{
  internal::Feature_sizing_once sizing;
  return internal::remesh_in_domain_with_sizing<Domain>(surface, metric, result, np, sizing);
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
