// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The Newton solves' sparse factorisation without CHOLMOD, as a build without SuiteSparse has it: the
// fallback path, Eigen's SimplicialLDLT, forced in this translation unit.

#define ANISO_CONFORMAL_DISABLE_CHOLMOD
#define BOOST_TEST_MODULE Aniso_conformal_sparse_cholesky_ldlt
#include <boost/test/unit_test.hpp>

#include "sparse_cholesky_checks.h"

BOOST_AUTO_TEST_CASE(cholmod_is_disabled_here)
{
#ifdef ANISO_CONFORMAL_HAS_CHOLMOD
  BOOST_TEST(false, "ANISO_CONFORMAL_DISABLE_CHOLMOD did not disable CHOLMOD");
#else
  BOOST_TEST(expected_backend == "Eigen SimplicialLDLT");
#endif
}
