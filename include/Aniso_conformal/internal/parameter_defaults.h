// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_PARAMETER_DEFAULTS_H
#define ANISO_CONFORMAL_INTERNAL_PARAMETER_DEFAULTS_H

#include <Aniso_conformal/parameters.h>

#include <CGAL/Named_function_parameters.h>

#include <array>
#include <cstddef>
#include <vector>

// The one place where each named parameter's default lives, and the one function that reads it: every
// stage that takes a parameter reads it through these, so that a stage called alone and the same stage
// inside remesh() always agree (they did not: max_flips_per_edge defaulted to 20 in one stage and 50 in
// another). The manual's parameter table and the Doxygen of each stage quote these values.

namespace Aniso_conformal {
namespace internal {
namespace defaults {
constexpr unsigned number_of_iterations = 100;      // CVT iterations (stage 4)
constexpr Cvt_method cvt_method = Cvt_method::LBFGS;
constexpr unsigned random_seed = 0;
constexpr double corner_angle = 30.0;                // degrees
constexpr double feature_angle = 60.0;               // degrees between face normals; 180: no crease
constexpr bool drop_ragged_creases = true;          // ragged crease components left out (ragged_creases.h)
constexpr bool feature_sizing = true;               // the metric scaled up where crease curves run close (features/feature_size.h)
constexpr Curvature_sizing curvature_sizing = Curvature_sizing::CONES;  // the metric scaled up where the surface bends tighter than an edge (features/curvature_size.h)
constexpr unsigned number_of_threads = 0;           // 0: all cores
constexpr unsigned max_adjustment_rounds = 50;      // stage 2
constexpr unsigned max_flips_per_edge = 50;         // every intrinsic flip pass (stages 2 and 3)
// stage 2: times one vertex pair's edge may be flipped away within one pass before it is kept (the
// metric-Delaunay test is not a Delaunay criterion and can cycle on a quad; internal/intrinsic/flip_to_delaunay.h)
constexpr std::size_t metric_flips_per_vertex_pair = 2;
constexpr unsigned max_conformal_iterations = 100;  // Newton iterations (stage 3)
constexpr double conformal_tolerance = 1e-9;        // radians, on the angle sums
constexpr Parametric_domain parametric_domain = Parametric_domain::AUTOMATIC;
constexpr Planar_boundary planar_boundary = Planar_boundary::AUTOMATIC;  // stage 3 on a disk
constexpr Surface_optimization surface_optimization = Surface_optimization::REPAIR;
constexpr std::size_t surface_optimization_rounds = 5;  // bound on the rounds of the surface optimisation
// Surface_optimization::ALWAYS, its second phase (Surface_optimizer::relocation_pass(true)): a move may lower
// the smallest G and the smallest angle of a one-ring down to these floors, or to the mesh's G_min and
// theta_min when these are higher, if it raises the ring's sum of G
constexpr double relaxed_G_floor = 0.6;
constexpr double relaxed_angle_floor = 35;  // degrees
} // namespace defaults

#define ANISO_CONFORMAL_PARAMETER_GETTER(NAME, TAG, TYPE)                                                          \
  template <typename NamedParameters>                                                                              \
  TYPE NAME(const NamedParameters& np)                                                                             \
  {                                                                                                                \
    return TYPE(CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, TAG), TYPE(defaults::NAME))); \
  }
ANISO_CONFORMAL_PARAMETER_GETTER(number_of_iterations, CGAL::internal_np::number_of_iterations, std::size_t)
ANISO_CONFORMAL_PARAMETER_GETTER(cvt_method, internal_np::cvt_method, Cvt_method)
ANISO_CONFORMAL_PARAMETER_GETTER(random_seed, CGAL::internal_np::random_seed, unsigned)
ANISO_CONFORMAL_PARAMETER_GETTER(corner_angle, internal_np::corner_angle, double)
ANISO_CONFORMAL_PARAMETER_GETTER(feature_angle, internal_np::feature_angle, double)
ANISO_CONFORMAL_PARAMETER_GETTER(drop_ragged_creases, internal_np::drop_ragged_creases, bool)
ANISO_CONFORMAL_PARAMETER_GETTER(feature_sizing, internal_np::feature_sizing, bool)
ANISO_CONFORMAL_PARAMETER_GETTER(curvature_sizing, internal_np::curvature_sizing, Curvature_sizing)
ANISO_CONFORMAL_PARAMETER_GETTER(number_of_threads, internal_np::number_of_threads, unsigned)
ANISO_CONFORMAL_PARAMETER_GETTER(max_adjustment_rounds, internal_np::max_adjustment_rounds, std::size_t)
ANISO_CONFORMAL_PARAMETER_GETTER(max_flips_per_edge, internal_np::max_flips_per_edge, std::size_t)
ANISO_CONFORMAL_PARAMETER_GETTER(max_conformal_iterations, internal_np::max_conformal_iterations, std::size_t)
ANISO_CONFORMAL_PARAMETER_GETTER(conformal_tolerance, internal_np::conformal_tolerance, double)
ANISO_CONFORMAL_PARAMETER_GETTER(parametric_domain, internal_np::parametric_domain, Parametric_domain)
ANISO_CONFORMAL_PARAMETER_GETTER(planar_boundary, internal_np::planar_boundary, Planar_boundary)
ANISO_CONFORMAL_PARAMETER_GETTER(surface_optimization, internal_np::surface_optimization, Surface_optimization)
#undef ANISO_CONFORMAL_PARAMETER_GETTER

// the user's feature edges (pairs of input vertex indices) and feature vertices: none when not given
template <typename NamedParameters>
std::vector<std::array<std::size_t, 2>> feature_edges(const NamedParameters& np)
{
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, internal_np::feature_edges),
                                            std::vector<std::array<std::size_t, 2>>());
}
template <typename NamedParameters>
std::vector<std::size_t> feature_vertices(const NamedParameters& np)
{
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, internal_np::feature_vertices),
                                            std::vector<std::size_t>());
}

// the number of output vertices: required, 0 when not given
template <typename NamedParameters>
std::size_t number_of_vertices(const NamedParameters& np)
{
  return std::size_t(CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, internal_np::number_of_vertices),
                                                        std::size_t(0)));
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_PARAMETER_DEFAULTS_H
