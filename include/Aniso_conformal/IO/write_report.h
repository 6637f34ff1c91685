// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_WRITE_REPORT_H
#define ANISO_CONFORMAL_IO_WRITE_REPORT_H

#include <Aniso_conformal/Remeshing_result.h>
#include <Aniso_conformal/Stage.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

/// \file write_report.h

namespace Aniso_conformal {
namespace IO {

namespace internal {
inline std::string json_number(double x)
{
  if(!std::isfinite(x)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.10g", x);
  return buf;
}
inline std::string json_array(const std::vector<double>& v)
{
  std::string s = "[";
  for(std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + json_number(v[i]);
  return s + "]";
}
inline std::string json_string(const std::string& x)
{
  std::string s = "\"";
  for(char c : x) {
    if(c == '"' || c == '\\') s += '\\';
    if(static_cast<unsigned char>(c) < 0x20) { s += ' '; continue; }
    s += c;
  }
  return s + "\"";
}
} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * writes `r` as a JSON object to `os`: input and output sizes, the quality in the metric (with the
 * angle histogram and the metric-conformity figures), the counts of flips and splits, the conformal
 * solver's iterations and residual, the CVT energy per iteration, and the wall time of every stage.
 * `extra` adds string-valued or numeric fields (already JSON-encoded values) at the top level, e.g.
 * the command line's parameters or the time spent building a background.
 */
inline void write_report_json(std::ostream& os, const Remeshing_result& r,
                              const std::map<std::string, std::string>& extra = {})
{
  using internal::json_array;
  using internal::json_number;
  const Quality_report& q = r.quality;
  os << "{\n";
  for(const auto& e : extra) os << "  " << internal::json_string(e.first) << ": " << e.second << ",\n";
  os << "  \"domain\": " << internal::json_string(domain_name(r.domain)) << ",\n";
  os << "  \"input\": {\"vertices\": " << r.input_vertices << ", \"faces\": " << r.input_faces << "},\n";
  os << "  \"background\": {\"vertices\": " << r.background_vertices << ", \"faces\": " << r.background_faces << "},\n";
  os << "  \"output\": {\"vertices\": " << q.number_of_vertices << ", \"triangles\": " << q.number_of_triangles
     << ", \"boundary_vertices\": " << r.boundary_sites << ", \"corners\": " << r.corners
     << ", \"inverted_triangles\": " << r.inverted_triangles
     << ", \"hausdorff_distance\": " << json_number(r.hausdorff_distance)
     << ", \"hausdorff_distance_relative\": " << json_number(r.hausdorff_distance_relative) << "},\n";
  os << "  \"quality\": {\"G_min\": " << json_number(q.G_min) << ", \"G_avg\": " << json_number(q.G_avg)
     << ", \"theta_min\": " << json_number(q.theta_min) << ", \"theta_avg\": " << json_number(q.theta_avg)
     << ", \"percent_below_30\": " << json_number(q.percent_below_30) << ", \"theta_max\": " << json_number(q.theta_max)
     << ",\n    \"angle_histogram\": {\"bin_width_degrees\": " << json_number(q.bin_width)
     << ", \"counts\": " << json_array(q.angle_histogram) << "},\n"
     << "    \"metric_edge_length\": {\"mean\": " << json_number(q.edge_length_mean)
     << ", \"normalized_stddev\": " << json_number(q.edge_length_stddev)
     << ", \"normalized_min\": " << json_number(q.edge_length_min)
     << ", \"normalized_max\": " << json_number(q.edge_length_max) << "}},\n";
  os << "  \"edge_adjustment\": {\"invalid_triangles_before\": " << r.adjustment.invalid_triangles_before
     << ", \"flips\": " << r.adjustment.flips << ", \"splits\": " << r.adjustment.splits
     << ", \"rounds\": " << r.adjustment.rounds
     << ", \"repaired_triangles\": " << r.adjustment.repaired_triangles
     << ", \"mollification\": " << json_number(r.adjustment.mollification)
     << ", \"flip_budget_hits\": " << r.adjustment.flip_budget_hits << "},\n";
  os << "  \"conformal_embedding\": {\"newton_iterations\": " << r.conformal_iterations
     << ", \"residual\": " << json_number(r.conformal_residual) << ", \"intrinsic_flips\": " << r.conformal_flips
     << ", \"conformal_factor_min\": " << json_number(r.conformal_factor_min)
     << ", \"conformal_factor_max\": " << json_number(r.conformal_factor_max);
  // the domain's own figures, whatever the domain: scalars, vectors, matrices by rows
  for(const Domain_figure& f : r.domain_diagnostics.figures) {
    auto number = [&](double x) { return f.integral ? std::to_string((long long)(x)) : json_number(x); };
    os << ", " << internal::json_string(f.key) << ": ";
    if(f.values.empty()) {
      os << "[]";
      continue;
    }
    if(f.columns == 0 && f.values.size() == 1) {
      os << number(f.values[0]);
      continue;
    }
    const std::size_t cols = f.columns == 0 ? f.values.size() : f.columns;
    os << (f.columns == 0 ? "" : "[");
    for(std::size_t i = 0; i < f.values.size(); ++i) {
      if(i % cols == 0) os << (i ? "], [" : "[");
      else os << ", ";
      os << number(f.values[i]);
    }
    os << "]" << (f.columns == 0 ? "" : "]");
  }
  os << "},\n";
  os << "  \"cvt\": {\"method\": \"" << (r.cvt.method == Cvt_method::LLOYD ? "lloyd" : "lbfgs")
     << "\", \"iterations\": " << r.cvt.iterations << ", \"energy_evaluations\": " << r.cvt.energy_evaluations
     << ", \"lloyd_fallbacks\": " << r.cvt.lloyd_fallbacks
     << ", \"relative_gradient_norm\": " << json_number(r.cvt.gradient_norm)
     << ",\n    \"energy\": " << json_array(r.cvt.energy) << "},\n";
  os << "  \"seconds\": {";
  for(int s = 0; s < number_of_stages; ++s)
    os << "\"" << stage_name(Stage(s)) << "\": " << json_number(r.seconds[s]) << ", ";
  os << "\"total\": " << json_number(r.total_seconds()) << "}\n}\n";
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_WRITE_REPORT_H
