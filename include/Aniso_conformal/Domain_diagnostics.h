// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_DOMAIN_DIAGNOSTICS_H
#define ANISO_CONFORMAL_DOMAIN_DIAGNOSTICS_H

#include <Aniso_conformal/Exceptions.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

/// \file Domain_diagnostics.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMain
 * one figure of what a parametric domain measured about its embedding and CVT (the flat torus's
 * lattice, the sphere's angle distortion, the hyperbolic group's relation error, ...).
 */
struct Domain_figure {
  std::string key;             ///< name in the JSON report, lower case with underscores ("lattice")
  std::vector<double> values;  ///< one value (a scalar) or several (a vector, or a matrix stored by rows)
  /// 0 for a scalar or a vector; otherwise `values` is a matrix with this many columns
  std::size_t columns = 0;
  bool integral = false;       ///< `true` for counts (written without a fractional part)
  std::string description;     ///< what it is, with its unit
};

/*!
 * \ingroup PkgAnisoConformalMain
 * the figures a parametric domain adds to `Remeshing_result`: each domain policy (a model of
 * `ParametricDomain`) fills them, and the writers (JSON report, the tool's summary) print them without
 * knowing which domain produced them, so that a new domain touches no writer.
 */
struct Domain_diagnostics {
  std::vector<Domain_figure> figures;  ///< in the order the domain added them
  /// the figures in words, one line, for the tool's summary (empty if the domain has nothing to say)
  std::string summary;

  /// appends a scalar figure
  void add(const std::string& key, double value, const std::string& description, bool integral = false)
  {
    figures.push_back(Domain_figure{key, {value}, 0, integral, description});
  }
  /// appends a vector (`columns == 0`) or a matrix by rows (`columns > 0`)
  void add(const std::string& key, std::vector<double> values, std::size_t columns, const std::string& description)
  {
    figures.push_back(Domain_figure{key, std::move(values), columns, false, description});
  }
  /// `true` if a figure named `key` is present
  bool has(const std::string& key) const
  {
    for(const Domain_figure& f : figures)
      if(f.key == key) return true;
    return false;
  }
  /*!
   * value `i` of the figure named `key`
   * \throws Invalid_input if there is no such figure or it has no value `i` (the caller asked for a
   *         figure of another domain)
   */
  double value(const std::string& key, std::size_t i = 0) const
  {
    for(const Domain_figure& f : figures)
      if(f.key == key) {
        if(i >= f.values.size())
          throw Invalid_input("Domain_diagnostics::value(): figure '" + key + "' has " + std::to_string(f.values.size()) +
                              " values, value " + std::to_string(i) + " was asked for");
        return f.values[i];
      }
    throw Invalid_input("Domain_diagnostics::value(): this domain has no figure '" + key + "'");
  }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_DOMAIN_DIAGNOSTICS_H
