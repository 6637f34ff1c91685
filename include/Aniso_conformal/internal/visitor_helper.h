// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_VISITOR_HELPER_H
#define ANISO_CONFORMAL_INTERNAL_VISITOR_HELPER_H

#include <Aniso_conformal/Default_visitor.h>

#include <CGAL/Named_function_parameters.h>

namespace Aniso_conformal {
namespace internal {

// CGAL's idiom for an optional visitor: a reference to the user's (possibly std::ref-wrapped) visitor,
// or to a static no-op one.
template <typename NamedParameters>
struct Visitor_reference {
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::visitor_t, NamedParameters,
                                                             Default_visitor>::reference type;
};

template <typename NamedParameters>
typename Visitor_reference<NamedParameters>::type get_visitor(const NamedParameters& np)
{
  static thread_local Default_visitor default_visitor;
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter_reference(np, CGAL::internal_np::visitor),
                                            default_visitor);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_VISITOR_HELPER_H
