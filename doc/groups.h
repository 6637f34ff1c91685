// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
// The groups of the reference manual (Doxygen only; not a header to include).

/// \defgroup PkgAnisoConformalRef Reference
/// Everything a user of Aniso_conformal includes, grouped by pipeline stage.

/// \defgroup PkgAnisoConformalMain Entry points
/// \ingroup PkgAnisoConformalRef
/// `remesh()` on an `Input_surface` or on any BGL triangle mesh, and what it returns.

/// \defgroup PkgAnisoConformalStages Pipeline stages
/// \ingroup PkgAnisoConformalRef
/// Each stage callable on its own: metric square roots and edge lengths, edge-length adjustment,
/// conformal embedding, weighted CVT, dual mesh; `remesh()` only composes them.

/// \defgroup PkgAnisoConformalMetrics Metrics
/// \ingroup PkgAnisoConformalRef
/// Models of `AnisotropicMetric`: tensor fields, analytic 2D fields (the paper's Fig. 6 and 7),
/// curvature (paper eq. 4), images (paper eq. 9), uniform.

/// \defgroup PkgAnisoConformalDomains Domains and backgrounds
/// \ingroup PkgAnisoConformalRef
/// The input surface, the parametric domain traits (models of `ParametricDomainTraits`) and the
/// builders of background triangulations for 2D domains and images.

/// \defgroup PkgAnisoConformalQuality Quality
/// \ingroup PkgAnisoConformalRef
/// Quality measured in the metric (paper 3.6): G, angles, histogram, metric edge lengths.

/// \defgroup PkgAnisoConformalVisitors Visitors
/// \ingroup PkgAnisoConformalRef
/// Progress reporting and cancellation (models of `AnisoConformalVisitor`).

/// \defgroup PkgAnisoConformalParameters Named parameters
/// \ingroup PkgAnisoConformalRef
/// The optional arguments of every function, `Aniso_conformal::parameters::`.

/// \defgroup PkgAnisoConformalErrors Errors
/// \ingroup PkgAnisoConformalRef
/// The exceptions the library throws; every message names the problem (file, line, vertex, face).

/// \defgroup PkgAnisoConformalIO Input and output
/// \ingroup PkgAnisoConformalRef
/// Readers of meshes, metric files and images (each failure an `Invalid_input` naming the file), and
/// writers of meshes, JSON reports and SVG pictures.

/// \defgroup PkgAnisoConformalConcepts Concepts
/// \ingroup PkgAnisoConformalRef
/// What a user type must provide to plug into the pipeline.
