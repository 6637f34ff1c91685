// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The groups of the reference manual (read by Doxygen only; not a header to include).

/*!
 * \defgroup PkgAnisoConformalRef Reference
 * Everything a user of Aniso_conformal includes, grouped by role. The main page (the user manual)
 * explains the method; each entity below names the paper section or equation it implements.
 */

/*!
 * \defgroup PkgAnisoConformalMain Entry points
 * \ingroup PkgAnisoConformalRef
 * `remesh()` on an `Input_surface` or on any BGL triangle mesh (the domain chosen from the topology),
 * `remesh_in_domain()` (one domain chosen at compile time), the validated input copy, and the
 * diagnostics they return (with the domain's own figures, `Domain_diagnostics`).
 */

/*!
 * \defgroup PkgAnisoConformalStages Pipeline stages
 * \ingroup PkgAnisoConformalRef
 * Each stage callable on its own: metric square roots and edge lengths, edge-length adjustment,
 * conformal embedding, weighted CVT and dual mesh, with their reports; `remesh()` only composes them.
 */

/*!
 * \defgroup PkgAnisoConformalMetrics Metrics
 * \ingroup PkgAnisoConformalRef
 * Models of `AnisotropicMetric`: tensor fields, analytic 2D fields (with the fields of the paper's
 * Fig.\ 6 and 7), curvature (paper eq.\ 4), images (paper eq.\ 9) and the uniform metric, and the
 * `Surface_point` at which they are evaluated.
 */

/*!
 * \defgroup PkgAnisoConformalDomains Domains and backgrounds
 * \ingroup PkgAnisoConformalRef
 * The four canonical domains as models of `ParametricDomain` (`Planar_domain`, `Spherical_domain`,
 * `Flat_torus_domain`, `Hyperbolic_domain`), their domain traits, models of `ParametricDomainTraits`
 * (the plane, the unit sphere, the flat torus, the hyperbolic surface in the Klein disk), and the
 * builders of background triangulations for 2D domains and images.
 */

/*!
 * \defgroup PkgAnisoConformalQuality Quality
 * \ingroup PkgAnisoConformalRef
 * Quality measured in the metric (paper section 3.6, after Frey and Borouchaki): `G`, angles, angle
 * histogram and metric edge lengths.
 */

/*!
 * \defgroup PkgAnisoConformalVisitors Visitors
 * \ingroup PkgAnisoConformalRef
 * Progress reporting and cancellation: the stages, and the do-nothing model of `AnisoConformalVisitor`.
 */

/*!
 * \defgroup PkgAnisoConformalParameters Named parameters
 * \ingroup PkgAnisoConformalRef
 * The optional arguments of the functions, in CGAL's style:
 * `Aniso_conformal::parameters::number_of_vertices(1000).number_of_iterations(100).random_seed(0)`.
 *
 * A chain must start with one of the functions of `Aniso_conformal::parameters` (CGAL 5.5 has no
 * `combine()`, so a pack started with a `CGAL::parameters` function cannot be extended with ours).
 *
 * | parameter | default | used by |
 * |---|---|---|
 * | `number_of_vertices` | required | `remesh()`: the exact number of output vertices |
 * | `number_of_iterations` | 100 | CVT iterations |
 * | `cvt_method` | `Cvt_method::LBFGS` | the CVT optimiser |
 * | `random_seed` | 0 | initial sites; the same seed gives the same output bit for bit |
 * | `corner_angle` | 30 | boundary turning angle (degrees) above which an input vertex is kept as a corner |
 * | `max_adjustment_rounds` | 50 | bound on the flip-then-split rounds of `adjust_edge_lengths()` |
 * | `max_flips_per_edge` | 50 | bound on the flips of one intrinsic flip pass, per edge it starts with, plus 100: in `adjust_edge_lengths()` the pass stops and the splits go on; in the conformal solves it is a `Convergence_failure` |
 * | `max_conformal_iterations` | 100 | bound on the Newton steps of `conformal_embedding()`, `spherical_embedding()`, `flat_torus_embedding()`, `hyperbolic_embedding()` |
 * | `conformal_tolerance` | 1e-9 | angle-sum error (radians) Newton's method must reach |
 * | `number_of_threads` | 0 (all cores) | workers of the CVT integration |
 * | `parametric_domain` | `Parametric_domain::AUTOMATIC` | `remesh()`: the domain, refused (`Invalid_input`) if it does not fit the topology |
 * | `visitor` | `Default_visitor` | a model of `AnisoConformalVisitor`; pass `std::ref(v)` to keep its state |
 * | `vertex_point_map`, `vertex_index_map` | the mesh's internal maps | the input BGL mesh of `remesh()` |
 */

/*!
 * \defgroup PkgAnisoConformalErrors Errors
 * \ingroup PkgAnisoConformalRef
 * The exceptions the library throws, all derived from `Aniso_conformal::Error` (a
 * `std::runtime_error`); every message names the problem and where (file, line, vertex, face).
 * `Invalid_input`: the input is wrong (the tool exits 2); `Remeshing_failure` and its
 * `Convergence_failure`: a valid input this version cannot remesh (exit 3); `Internal_error`: a broken
 * invariant of the library, a bug (exit 1); `Cancelled`: a visitor stopped the run.
 */

/*!
 * \defgroup PkgAnisoConformalIO Input and output
 * \ingroup PkgAnisoConformalRef
 * Readers of meshes, metric files and images (each failure an `Invalid_input` naming the file), and
 * writers of meshes, JSON reports and SVG pictures.
 */

/*!
 * \defgroup PkgAnisoConformalConcepts Concepts
 * \ingroup PkgAnisoConformalRef
 * What a user type must provide to plug into the pipeline: a metric (`AnisotropicMetric`), a
 * parametric domain (`ParametricDomain`, with its `ParametricDomainTraits`), a visitor
 * (`AnisoConformalVisitor`).
 */

/*!
 * \namespace Aniso_conformal
 * The namespace of the library: `remesh()`, its stages, the metrics, domains, reports and exceptions.
 */

/*!
 * \namespace Aniso_conformal::IO
 * Readers and writers: triangle meshes, metric files, images, JSON reports and SVG pictures.
 */
