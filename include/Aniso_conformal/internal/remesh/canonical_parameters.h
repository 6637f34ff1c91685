// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_REMESH_CANONICAL_PARAMETERS_H
#define ANISO_CONFORMAL_INTERNAL_REMESH_CANONICAL_PARAMETERS_H

#include <Aniso_conformal/Stage.h>
#include <Aniso_conformal/internal/parameter_defaults.h>
#include <Aniso_conformal/internal/visitor_helper.h>
#include <Aniso_conformal/parameters.h>

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

// The pipeline's stages are templates over the named-parameter pack, whose type differs with every
// combination of parameters a caller passes: each combination instantiated the whole pipeline again
// (a test module calling remesh() with five combinations compiled it five times). remesh_in_domain()
// therefore reads the caller's pack once into plain values, wraps the caller's visitor behind one
// concrete type, and runs the stages with a pack of one fixed type: the pipeline is compiled once per
// domain and metric, whatever the caller passes. Every named parameter a stage reads must be carried
// here (Remeshing_options, from() and canonical_parameters()): one left out is silently replaced by its
// default (test_remesh's planar_boundary_reaches_the_embedding guards the last one added).

namespace Aniso_conformal {
namespace internal {

// a model of AnisoConformalVisitor that forwards to the caller's visitor, whatever its type
class Visitor_handle {
public:
  template <typename Visitor>
  explicit Visitor_handle(Visitor& v)
    : m_visitor(&v),
      m_started([](void* p, Stage s) { static_cast<Visitor*>(p)->on_stage_started(s); }),
      m_finished([](void* p, Stage s, double t) { static_cast<Visitor*>(p)->on_stage_finished(s, t); }),
      m_iteration([](void* p, Stage s, std::size_t it, std::size_t bound, double value) {
        return bool(static_cast<Visitor*>(p)->on_iteration(s, it, bound, value));
      })
  {}
  void on_stage_started(Stage s) { m_started(m_visitor, s); }
  void on_stage_finished(Stage s, double seconds) { m_finished(m_visitor, s, seconds); }
  bool on_iteration(Stage s, std::size_t it, std::size_t bound, double value) { return m_iteration(m_visitor, s, it, bound, value); }

private:
  void* m_visitor;
  void (*m_started)(void*, Stage);
  void (*m_finished)(void*, Stage, double);
  bool (*m_iteration)(void*, Stage, std::size_t, std::size_t, double);
};

// the caller's parameters as values (defaults from parameter_defaults.h)
struct Remeshing_options {
  std::size_t number_of_vertices = 0;
  std::size_t number_of_iterations = defaults::number_of_iterations;
  Cvt_method cvt_method = defaults::cvt_method;
  unsigned random_seed = defaults::random_seed;
  double corner_angle = defaults::corner_angle;
  double feature_angle = defaults::feature_angle;
  bool drop_ragged_creases = defaults::drop_ragged_creases;
  bool feature_sizing = defaults::feature_sizing;
  Curvature_sizing curvature_sizing = defaults::curvature_sizing;
  std::vector<std::array<std::size_t, 2>> feature_edges;  // the user's creases (none by default)
  std::vector<std::size_t> feature_vertices;              // the user's corners (none by default)
  unsigned number_of_threads = defaults::number_of_threads;
  std::size_t max_adjustment_rounds = defaults::max_adjustment_rounds;
  std::size_t max_flips_per_edge = defaults::max_flips_per_edge;
  std::size_t max_conformal_iterations = defaults::max_conformal_iterations;
  double conformal_tolerance = defaults::conformal_tolerance;
  Planar_boundary planar_boundary = defaults::planar_boundary;
  Surface_optimization surface_optimization = defaults::surface_optimization;
  // not a named parameter: true in the second run of run_again_if_a_loop_is_blocked() on an input whose
  // loops pass twice through a point: its holes closed lobe by lobe (close_holes()), its loops' sites
  // not keeping those points as corners (place_loop_sites())
  bool split_pinched_loops = false;
  // not a named parameter: true in the second run of run_again_with_collars_if_a_loop_is_blocked(): the
  // loops along both faces of a part thinner than an output edge closed by a collar first (patch_collars.h)
  bool collar_thin_loops = false;

  template <typename NamedParameters>
  static Remeshing_options from(const NamedParameters& np)
  {
    Remeshing_options o;
    o.number_of_vertices = internal::number_of_vertices(np);
    o.number_of_iterations = internal::number_of_iterations(np);
    o.cvt_method = internal::cvt_method(np);
    o.random_seed = internal::random_seed(np);
    o.corner_angle = internal::corner_angle(np);
    o.feature_angle = internal::feature_angle(np);
    o.drop_ragged_creases = internal::drop_ragged_creases(np);
    o.feature_sizing = internal::feature_sizing(np);
    o.curvature_sizing = internal::curvature_sizing(np);
    o.feature_edges = internal::feature_edges(np);
    o.feature_vertices = internal::feature_vertices(np);
    o.number_of_threads = internal::number_of_threads(np);
    o.max_adjustment_rounds = internal::max_adjustment_rounds(np);
    o.max_flips_per_edge = internal::max_flips_per_edge(np);
    o.max_conformal_iterations = internal::max_conformal_iterations(np);
    o.conformal_tolerance = internal::conformal_tolerance(np);
    o.planar_boundary = internal::planar_boundary(np);
    o.surface_optimization = internal::surface_optimization(np);
    return o;
  }
};

// the pack of one fixed type that the pipeline's stages receive
inline auto canonical_parameters(const Remeshing_options& o, Visitor_handle& vis)
{
  return parameters::number_of_vertices(o.number_of_vertices)
      .number_of_iterations(o.number_of_iterations)
      .cvt_method(o.cvt_method)
      .random_seed(o.random_seed)
      .corner_angle(o.corner_angle)
      .feature_angle(o.feature_angle)
      .drop_ragged_creases(o.drop_ragged_creases)
      .number_of_threads(o.number_of_threads)
      .max_adjustment_rounds(o.max_adjustment_rounds)
      .max_flips_per_edge(o.max_flips_per_edge)
      .max_conformal_iterations(o.max_conformal_iterations)
      .conformal_tolerance(o.conformal_tolerance)
      .planar_boundary(o.planar_boundary)
      .surface_optimization(o.surface_optimization)
      .visitor(std::ref(vis));
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_REMESH_CANONICAL_PARAMETERS_H
