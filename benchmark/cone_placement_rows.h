// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `bench_paper --cones`: the cone metric of issue 16 on the limb models of CGAL's data set
// (benchmark/cones.md): per model, the greedy cone placement (internal/conformal/cone_metric.h) on the
// input's background with the isotropic metric (adjust_edge_lengths(), no refinement), then
// solve_cone_metric() with the cones and angles found (it must give the same u), next to the spherical
// embedding of the same background (its conformal factor's range as a log scale, 0.5 log(cf_max / cf_min),
// or its failure message). A part of bench_paper rather than a program of its own: it compiled the cone
// and sphere solvers again (82 CPU-s of every build of ./test.sh).
//
// usage: bench_paper --cones [--budget 2.0] [--max-cones 64] model.off ...   (a markdown row per model)

#ifndef ANISO_CONFORMAL_BENCHMARK_CONE_PLACEMENT_ROWS_H
#define ANISO_CONFORMAL_BENCHMARK_CONE_PLACEMENT_ROWS_H

#include <Aniso_conformal/IO/read_triangle_mesh.h>
#include <Aniso_conformal/Uniform_metric.h>
#include <Aniso_conformal/adjust_edge_lengths.h>
#include <Aniso_conformal/compute_metric_edge_lengths.h>
#include <Aniso_conformal/internal/conformal/cone_metric.h>
#include <Aniso_conformal/spherical_embedding.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace cone_placement_rows {

namespace AC = Aniso_conformal;

inline double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

inline std::string sphere_figure(AC::Intrinsic_triangulation t)
{
  try {
    const AC::Spherical_embedding emb = AC::spherical_embedding(t);
    const auto mm = std::minmax_element(emb.conformal_factor.begin(), emb.conformal_factor.end());
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f", 0.5 * std::log(*mm.second / *mm.first));
    return buf;
  } catch(const AC::Error& e) {  // its message without the advice in parentheses
    const std::string what = e.what();
    return "fails: " + what.substr(0, what.find(" ("));
  }
}

inline void run(const std::string& path, const AC::internal::Cone_placement_options& options)
{
  const AC::Input_surface s = AC::IO::read_triangle_mesh(path);
  AC::Intrinsic_triangulation t(s, AC::compute_metric_square_roots(s, AC::Uniform_metric()));
  AC::adjust_edge_lengths(t, s);
  const AC::Intrinsic_triangulation t_sphere = t, t_check = t;
  const std::string name = path.substr(path.find_last_of('/') + 1);
  const auto t0 = std::chrono::steady_clock::now();
  AC::internal::Cone_metric m;
  try {
    m = AC::internal::place_cones(t, options, AC::parameters::default_values());
  } catch(const AC::Error& e) {
    std::printf("| %s | %zu | fails: %s | | | | | | | %s |\n", name.c_str(), s.number_of_vertices(), e.what(), sphere_figure(t_sphere).c_str());
    return;
  }
  const double time = seconds_since(t0);
  const auto mm = std::minmax_element(m.cone_angles.begin(), m.cone_angles.end());
  // the cone metric solve with the cones and angles found, on a fresh copy: the same u
  AC::Intrinsic_triangulation t2 = t_check;
  const auto t1 = std::chrono::steady_clock::now();
  const AC::internal::Cone_metric check = AC::internal::solve_cone_metric(t2, m.cones, m.cone_angles, AC::parameters::default_values());
  const double time2 = seconds_since(t1);
  double du = 0;
  for(std::size_t v = 0; v < m.u.size(); ++v) du = std::max(du, std::abs(m.u[v] - check.u[v]));
  const double deg = 180 / 3.14159265358979323846;
  std::printf("| %s | %zu | %zu | %.1f - %.1f | %.2f | %.2f | %zu / %zu | %.2f | %.2f s, %zu it, max diff %.1e | %s |\n", name.c_str(),
              s.number_of_vertices(), m.cones.size(), m.cones.empty() ? 0.0 : *mm.first * deg, m.cones.empty() ? 0.0 : *mm.second * deg,
              m.start_u_range, m.u_range, m.solves, m.iterations, time, time2, check.iterations, du,
              sphere_figure(t_sphere).c_str());
  std::fflush(stdout);
}

// the table of `bench_paper --cones ARGS`, `args` the arguments after --cones; returns the exit status
inline int run_all(const std::vector<std::string>& args)
{
  AC::internal::Cone_placement_options options;
  std::vector<std::string> files;
  for(std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if(a == "--budget" && i + 1 < args.size()) options.max_log_range = std::stod(args[++i]);
    else if(a == "--max-cones" && i + 1 < args.size()) options.max_cones = std::size_t(std::stoul(args[++i]));
    else files.push_back(a);
  }
  std::printf("| model | vertices | cones | cone angles (deg) | range of u, 4 start cones | range of u | solves / Newton it. | time (s) | "
              "solve_cone_metric() with those cones: time, Newton it., u vs placement | sphere: range of u |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for(const std::string& f : files) {
    try {
      run(f, options);
    } catch(const AC::Error& e) {
      std::printf("| %s | error: %s |\n", f.c_str(), e.what());
    }
  }
  return 0;
}

} // namespace cone_placement_rows

#endif // ANISO_CONFORMAL_BENCHMARK_CONE_PLACEMENT_ROWS_H
