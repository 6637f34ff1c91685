// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// X-macro list of the named parameters owned by Aniso_conformal (no include guard on purpose:
// parameters.h includes it several times with different definitions of the macro).

ANISO_CONFORMAL_ADD_NAMED_PARAMETER(number_of_vertices_t, number_of_vertices, number_of_vertices)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(cvt_method_t, cvt_method, cvt_method)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(corner_angle_t, corner_angle, corner_angle)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(feature_angle_t, feature_angle, feature_angle)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(feature_edges_t, feature_edges, feature_edges)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(feature_vertices_t, feature_vertices, feature_vertices)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(conformal_tolerance_t, conformal_tolerance, conformal_tolerance)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(max_conformal_iterations_t, max_conformal_iterations, max_conformal_iterations)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(max_adjustment_rounds_t, max_adjustment_rounds, max_adjustment_rounds)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(max_flips_per_edge_t, max_flips_per_edge, max_flips_per_edge)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(number_of_threads_t, number_of_threads, number_of_threads)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(parametric_domain_t, parametric_domain, parametric_domain)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(planar_boundary_t, planar_boundary, planar_boundary)
ANISO_CONFORMAL_ADD_NAMED_PARAMETER(surface_optimization_t, surface_optimization, surface_optimization)
