// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_STAGE_H
#define ANISO_CONFORMAL_STAGE_H

/// \file Stage.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalVisitors
 * the stages of the pipeline, in order, as reported to visitors and in `Remeshing_result`
 */
enum class Stage {
  METRIC = 0,    ///< metric evaluated at the input vertices
  EDGE_LENGTHS,  ///< metric edge lengths, flips and splits
  EMBEDDING,     ///< conformal embedding into the domain
  CVT,           ///< weighted CVT in the domain
  DUAL_MESH,     ///< dual Delaunay mesh mapped back onto the input
  SURFACE_OPTIMIZATION,  ///< flips and vertex moves on the input, in the metric (`optimize_surface_mesh()`)
  QUALITY        ///< quality measured in the metric
};

/// number of enumerators of `Stage`
constexpr int number_of_stages = 7;

/// \ingroup PkgAnisoConformalVisitors
/// the name of a stage ("metric", "edge_lengths", "embedding", "cvt", "dual_mesh", "surface_optimization", "quality")
inline const char* stage_name(Stage s)
{
  switch(s) {
  case Stage::METRIC: return "metric";
  case Stage::EDGE_LENGTHS: return "edge_lengths";
  case Stage::EMBEDDING: return "embedding";
  case Stage::CVT: return "cvt";
  case Stage::DUAL_MESH: return "dual_mesh";
  case Stage::SURFACE_OPTIMIZATION: return "surface_optimization";
  case Stage::QUALITY: return "quality";
  }
  return "unknown";
}

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_STAGE_H
