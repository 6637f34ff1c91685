// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_REMESH_PIPELINE_START_H
#define ANISO_CONFORMAL_INTERNAL_REMESH_PIPELINE_START_H

#include <Aniso_conformal/Feature_graph.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/Remeshing_result.h>
#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/extract_dual_mesh.h>
#include <Aniso_conformal/internal/features/ragged_creases.h>
#include <Aniso_conformal/internal/remesh/hole_patches.h>
#include <Aniso_conformal/measure_features.h>

#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>

// What the pipeline of remesh_in_domain.h computes once per domain, before its runs, and the features'
// measure on a run's output.

namespace Aniso_conformal {
namespace internal {

// What run_pipeline() computes once, whether the creases are then followed or not: the request checked,
// the input's feature graph, the holes' patches (a surface with boundary loops in a closed domain), and
// the background after stage 1 and the refinement of stage 2, before its creases are refined.
struct Pipeline_start {
  std::unique_ptr<const Hole_patches> patches;  // none in the plane or for a disk on the sphere
  Feature_graph features;
  std::optional<Intrinsic_triangulation> itri;  // metric_and_background()
  Remeshing_result result;                      // the figures so far
  double edge_lengths_seconds = 0;              // stage 2's seconds so far
  std::size_t short_creases_dropped = 0;        // crease components shorter than an output edge, dropped
  double short_crease_length_dropped = 0;       // their length (input units)
  internal::Ragged_creases ragged_creases;      // the ragged crease components left out (ragged_creases.h)
  const Input_surface& background(const Input_surface& surface) const { return patches ? patches->closed : surface; }
};

// The input's features (start.features) measured on the output `out` (Remeshing_result::features), the
// time counted as the quality stage's
inline void record_features(const Input_surface& surface, const Pipeline_start& start, const Remeshed_surface& out, Remeshing_result& result)
{
  const auto measure_start = std::chrono::steady_clock::now();
  result.features = measure_features(surface, start.features, out.points, out.faces);
  result.features.short_components_dropped = start.short_creases_dropped;
  result.features.short_length_dropped = start.short_crease_length_dropped;
  result.features.ragged_components_dropped = start.ragged_creases.components;
  result.features.ragged_length_dropped = start.ragged_creases.length;
  result.features.rough_surface = start.ragged_creases.rough;
  result.seconds[int(Stage::QUALITY)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - measure_start).count();
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_REMESH_PIPELINE_START_H
