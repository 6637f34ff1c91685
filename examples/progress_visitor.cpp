// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A visitor that prints each stage's time and the CVT energy, and cancels the run when it exceeds a
// time budget (returning false from on_iteration: remesh() throws Cancelled and leaves no output).
// Pass it with std::ref so that its state is shared with the caller.
// Usage: progress_visitor [number_of_vertices] [budget_seconds]

#include <Aniso_conformal/Analytic_metric_2.h>
#include <Aniso_conformal/Default_visitor.h>
#include <Aniso_conformal/Paper_metrics.h>
#include <Aniso_conformal/Planar_domain.h>
#include <Aniso_conformal/make_square_background.h>
#include <Aniso_conformal/remesh_in_domain.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <iostream>

namespace AC = Aniso_conformal;

struct Progress : AC::Default_visitor {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double budget_seconds = 60;
  void on_stage_finished(AC::Stage s, double seconds) { std::cout << "  " << AC::stage_name(s) << ": " << seconds << " s\n"; }
  bool on_iteration(AC::Stage s, std::size_t it, std::size_t bound, double value)
  {
    if(s == AC::Stage::CVT && it % 20 == 0) std::cout << "  CVT " << it << "/" << bound << ", energy " << value << "\n";
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < budget_seconds;
  }
};

int main(int argc, char** argv)
{
  const std::size_t n = argc > 1 ? std::size_t(std::atol(argv[1])) : 1000;
  Progress progress;
  if(argc > 2) progress.budget_seconds = std::atof(argv[2]);
  const auto metric = AC::make_analytic_metric_2(AC::Fig6_metric());
  try {
    const AC::Input_surface square = AC::make_square_background(metric, n);
    AC::Remeshing_result r;
    AC::remesh_in_domain<AC::Planar_domain>(square, metric, r,
                                            AC::parameters::number_of_vertices(n).visitor(std::ref(progress)));
    std::cout << "done: G_avg " << r.quality.G_avg << "\n";
  } catch(const AC::Cancelled&) {
    std::cout << "cancelled: over the budget of " << progress.budget_seconds << " s\n";
  } catch(const AC::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
