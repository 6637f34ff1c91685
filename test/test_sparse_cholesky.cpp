// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The Newton solves' sparse factorisation as the build configured it: CHOLMOD when CMake found it
// (ANISO_CONFORMAL_WITH_CHOLMOD), with its fallbacks to Eigen's LDLT; Eigen's LDLT alone otherwise.

#define BOOST_TEST_MODULE Aniso_conformal_sparse_cholesky
#include <boost/test/unit_test.hpp>

#include "sparse_cholesky_checks.h"

BOOST_AUTO_TEST_CASE(the_build_uses_cholmod_when_cmake_found_it)
{
#if defined(ANISO_CONFORMAL_USE_CHOLMOD)
  BOOST_TEST(expected_backend == "CHOLMOD");
#else
  BOOST_TEST(expected_backend == "Eigen SimplicialLDLT");
#endif
}
