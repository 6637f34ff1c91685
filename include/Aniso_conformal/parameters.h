// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_PARAMETERS_H
#define ANISO_CONFORMAL_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

/// \file parameters.h
/// Named parameters in CGAL's style: `Aniso_conformal::parameters::number_of_vertices(1000).number_of_iterations(100)`.

namespace Aniso_conformal {

#ifndef DOXYGEN_RUNNING
// tags of the named parameters owned by this library
namespace internal_np {
#define ANISO_CONFORMAL_ADD_NAMED_PARAMETER(X, Y, Z) enum X { Y };
#include <Aniso_conformal/internal/parameters_interface.h>
#undef ANISO_CONFORMAL_ADD_NAMED_PARAMETER
} // namespace internal_np
#endif

/*!
 * \ingroup PkgAnisoConformalParameters
 * the CVT optimiser (stage 4)
 */
enum class Cvt_method {
  LLOYD,  ///< Lloyd's fixed-point iteration (the paper's method; the reference)
  LBFGS   ///< L-BFGS on the CVT energy (Liu et al. 2009; converges in far fewer iterations)
};

/*!
 * \ingroup PkgAnisoConformalParameters
 * the canonical domain of the conformal embedding (stage 3), chosen from the input's topology by default
 */
enum class Parametric_domain {
  AUTOMATIC,   ///< from the topology: a disk goes to the plane, a closed genus-1 surface to the flat torus
  PLANE,       ///< the plane, for topological disks (2D domains, images, open patches)
  FLAT_TORUS,  ///< the flat torus, for closed surfaces of genus 1
  SPHERE,      ///< the unit sphere, for closed surfaces of genus 0
  HYPERBOLIC,  ///< the hyperbolic disk, for closed surfaces of genus 2 or more
  CONE         ///< a flat metric with cone singularities, for closed surfaces of any genus (long limbs, any area distortion)
};

/*!
 * \ingroup PkgAnisoConformalParameters
 * what the conformal map of a disk into the plane keeps of the boundary (stage 3, `conformal_embedding()`)
 */
enum class Planar_boundary {
  /// the default: `KEEP_LENGTHS` when its layout is embedded (the paper's map, which measured better on
  /// the images and the paper's figures), `KEEP_SHAPE` when it is not (its Newton solve fails, or the
  /// boundary bent by the metric crosses itself: a swirling field at a re-entrant corner, a boundary that
  /// touches itself); `Planar_embedding::boundary` says which one was kept
  AUTOMATIC,
  /// the input's shape: the turning angle of the input's boundary is prescribed at every boundary vertex
  /// (its corners keep theirs), the lengths along the boundary are free, so the layout is the input's
  /// outline (an L stays an L, a square becomes a rectangle) and the conformal factor stays bounded; when
  /// that outline would touch or cross itself (a boundary that touches itself), a convex one
  KEEP_SHAPE,
  /// the boundary's metric lengths (`u = 0` on the boundary, the paper's choice): the layout bends the
  /// boundary as the metric demands, which can make conformal factors large near it (images at a strong
  /// anisotropy) or the layout overlap itself (then a `Remeshing_failure`)
  KEEP_LENGTHS
};

/*!
 * \ingroup PkgAnisoConformalParameters
 * when the final optimisation of the output on the input surface runs (`optimize_surface_mesh()`, stage
 * `Stage::SURFACE_OPTIMIZATION`)
 */
enum class Surface_optimization {
  OFF,     ///< never: the dual mesh of stage 5 is the output (refused if it has an inverted triangle)
  REPAIR,  ///< only when the dual mesh has inverted triangles, to repair them, or a triangle below 30 degrees in the metric (the default); as `ALWAYS` in the cone domain (`Cone_domain::optimizes_on_the_surface_by_default`), on a planar input (`Input_surface::is_planar()`: images, the square, plates) and on an output that follows creases (`Remeshed_surface::kept_edges` not empty)
  ALWAYS   ///< on every output, with the max-min angle pass everywhere (not only next to fixed vertices inside), a second phase of moves toward each vertex's ideal point in the metric, and boundary vertices sliding along straight pieces of the input's boundary (`optimize_surface_mesh()`): the choice for images and for the best quality
};

/*!
 * \ingroup PkgAnisoConformalParameters
 * where the metric is scaled up at thin parts and tips, where the surface bends more tightly than an
 * output edge (`internal/features/curvature_size.h`; manual, "Thin parts and tips")
 */
enum class Curvature_sizing {
  OFF,     ///< never
  CONES,   ///< in the cone domain (`Cone_domain::sizes_by_curvature_by_default`), where the limbs are and where it was measured to pay (the default); on CGAL's corpus through the sphere, torus and hyperbolic disk it was mixed (Hausdorff distance -5 % at the median, theta_min from -9.9 to +8.6 degrees)
  ALWAYS   ///< in every domain
};

/*!
 * \ingroup PkgAnisoConformalParameters
 * the name of a domain, as the command-line tool spells it ("plane", "flat-torus", ...)
 */
inline const char* domain_name(Parametric_domain d)
{
  switch(d) {
  case Parametric_domain::PLANE: return "plane";
  case Parametric_domain::FLAT_TORUS: return "flat-torus";
  case Parametric_domain::SPHERE: return "sphere";
  case Parametric_domain::HYPERBOLIC: return "hyperbolic";
  case Parametric_domain::CONE: return "cones";
  default: return "automatic";
  }
}

/*!
 * \ingroup PkgAnisoConformalParameters
 * a sequence of named parameters. It is a `CGAL::Named_function_parameters`, so it can be passed to
 * CGAL functions, and it adds chaining members for this library's own parameters and for the CGAL
 * parameters this library documents (CGAL 5.5 has no `combine()`, so a pack built from a CGAL
 * parameter first cannot be extended with ours: start the chain with one of ours).
 */
template <typename T, typename Tag, typename Base = CGAL::internal_np::No_property>
struct Named_parameters : CGAL::Named_function_parameters<T, Tag, Base> {
#ifndef DOXYGEN_RUNNING
  typedef CGAL::Named_function_parameters<T, Tag, Base> Cgal_pack;
  typedef Named_parameters<T, Tag, Base> self;
  explicit Named_parameters(const T& v) : Cgal_pack(v) {}
  Named_parameters(const T& v, const Base& b) : Cgal_pack(v, b) {}

#define ANISO_CONFORMAL_ADD_NAMED_PARAMETER(X, Y, Z)                          \
  template <typename K>                                                       \
  Named_parameters<K, ::Aniso_conformal::internal_np::X, self> Z(const K& k) const \
  {                                                                           \
    return Named_parameters<K, ::Aniso_conformal::internal_np::X, self>(k, *this); \
  }
#include <Aniso_conformal/internal/parameters_interface.h>
#undef ANISO_CONFORMAL_ADD_NAMED_PARAMETER

#define ANISO_CONFORMAL_ADD_CGAL_PARAMETER(X, Z)                              \
  template <typename K>                                                       \
  Named_parameters<K, CGAL::internal_np::X, self> Z(const K& k) const         \
  {                                                                           \
    return Named_parameters<K, CGAL::internal_np::X, self>(k, *this);         \
  }
  ANISO_CONFORMAL_ADD_CGAL_PARAMETER(number_of_iterations_t, number_of_iterations)
  ANISO_CONFORMAL_ADD_CGAL_PARAMETER(random_seed_t, random_seed)
  ANISO_CONFORMAL_ADD_CGAL_PARAMETER(visitor_t, visitor)
  ANISO_CONFORMAL_ADD_CGAL_PARAMETER(verbose_t, verbose)
  ANISO_CONFORMAL_ADD_CGAL_PARAMETER(vertex_point_t, vertex_point_map)
  ANISO_CONFORMAL_ADD_CGAL_PARAMETER(vertex_index_t, vertex_index_map)
#endif
};

/// named-parameter functions; see the manual page for the list with their defaults
namespace parameters {

using CGAL::parameters::Default_named_parameters;
using CGAL::parameters::default_values;

#ifndef DOXYGEN_RUNNING
#define ANISO_CONFORMAL_ADD_NAMED_PARAMETER(X, Y, Z)                          \
  template <typename K>                                                       \
  Named_parameters<K, ::Aniso_conformal::internal_np::X> Z(const K& k)        \
  {                                                                           \
    return Named_parameters<K, ::Aniso_conformal::internal_np::X>(k);         \
  }
#include <Aniso_conformal/internal/parameters_interface.h>
#undef ANISO_CONFORMAL_ADD_NAMED_PARAMETER

#define ANISO_CONFORMAL_ADD_CGAL_FREE_PARAMETER(X, Z)                         \
  template <typename K>                                                       \
  Named_parameters<K, CGAL::internal_np::X> Z(const K& k)                     \
  {                                                                           \
    return Named_parameters<K, CGAL::internal_np::X>(k);                      \
  }
ANISO_CONFORMAL_ADD_CGAL_FREE_PARAMETER(number_of_iterations_t, number_of_iterations)
ANISO_CONFORMAL_ADD_CGAL_FREE_PARAMETER(random_seed_t, random_seed)
ANISO_CONFORMAL_ADD_CGAL_FREE_PARAMETER(visitor_t, visitor)
ANISO_CONFORMAL_ADD_CGAL_FREE_PARAMETER(verbose_t, verbose)
ANISO_CONFORMAL_ADD_CGAL_FREE_PARAMETER(vertex_point_t, vertex_point_map)
ANISO_CONFORMAL_ADD_CGAL_FREE_PARAMETER(vertex_index_t, vertex_index_map)
#undef ANISO_CONFORMAL_ADD_CGAL_FREE_PARAMETER
#endif

} // namespace parameters
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_PARAMETERS_H
