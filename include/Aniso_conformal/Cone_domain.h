// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_CONE_DOMAIN_H
#define ANISO_CONFORMAL_CONE_DOMAIN_H

#include <Aniso_conformal/Cone_domain_traits.h>
#include <Aniso_conformal/Domain_diagnostics.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/cone_embedding.h>
#include <Aniso_conformal/internal/domains/domain_policy_base.h>
#include <Aniso_conformal/parameters.h>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <vector>

/// \file Cone_domain.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalDomains
 * a flat metric with cone singularities, for closed surfaces of any genus whose uniformization metric
 * distorts area beyond what double precision or the CVT can carry (long limbs, thin handles; issue 16):
 * stage 3 is `cone_embedding()` (cones placed greedily until the range of the log scale factor is at most
 * 2, an atlas of planar charts), stages 4 and 5 run in `Cone_domain_traits`. Reports the cones, their
 * angles and the area distortion. `fits()` a closed surface of any genus; `check_number_of_vertices()`
 * throws `Invalid_input` below the smallest triangulation of the genus (4 for the sphere, 7 for the
 * torus, `Hyperbolic_domain::minimum_number_of_vertices()` above).
 *
 * The input's corners and crease sites are fixed sites at background vertices, as in the other closed
 * domains. A surface with several boundary loops, or a boundary and a genus, comes with its holes closed
 * by patches (`remesh_in_domain()`, as for the sphere, the flat torus and the hyperbolic disk): the
 * patches hold no CVT density, each loop is a chain of fixed sites, and a triangle the cone metric
 * flattens next to a loop (whose edges never flip) has its longest edge split before the placement is
 * tried again (`Cone_embedding::edge_splits`). A disk is refused (`fits()`): the plane takes it.
 *
 * \cgalModels `ParametricDomain`
 */
struct Cone_domain : internal::Closed_domain_policy_base<Cone_embedding, Cone_domain_traits, 0, std::numeric_limits<int>::max()> {
  static constexpr Parametric_domain kind = Parametric_domain::CONE;  ///< its tag

  /// `true`: the default surface optimisation (`Surface_optimization::REPAIR`) runs always here, as
  /// `Surface_optimization::ALWAYS`. The Voronoi cells next to cones are approximate (one sheet of the
  /// plane around a cone of negative curvature holds one turn of it), and the CVT's dual alone leaves thin
  /// triangles there (CGAL's limb models at 3000 vertices: theta_min 5 to 17 degrees, 0.2 to 0.9 % below
  /// 30 degrees; with the stage: 16 to 31 degrees, at most 0.15 %; `benchmark/cones.md`)
  static constexpr bool optimizes_on_the_surface_by_default = true;
  /// `true`: the default curvature sizing (`Curvature_sizing::CONES`) scales the metric here, where the
  /// limbs and tips are (CGAL's limb models at 3000 vertices: theta_min 18.6-34.1 -> 30.3-33.5, Hausdorff
  /// distance 1.23-1.86 -> 0.63-1.25 % of the diagonal; `benchmark/cones.md`, "Thin parts and tips")
  static constexpr bool sizes_by_curvature_by_default = true;
  /// the topologies it takes, in words
  static const char* topology() { return "closed surfaces of any genus, and surfaces with several boundary loops or a boundary and a genus (holes closed by patches); not disks"; }
  /// stage 3: `cone_embedding()`
  template <typename NamedParameters>
  static Embedding embed(Intrinsic_triangulation& itri, const NamedParameters& np)
  {
    return cone_embedding(itri, np);
  }
  /// the fixed site at corner `corner` of background face `face`: that corner's position in the face's chart
  /// (`Cone_domain_traits::initial_sites_after()` takes it in that frame)
  static Traits::Point corner_site(const Embedding& emb, int face, int corner, int /*v*/)
  {
    return emb.corner_uv[std::size_t(face)][std::size_t(corner)];
  }
  /*!
   * the cones of negative curvature (angle above `2 pi`), each kept as an output vertex (a fixed site at
   * the cone): the Delaunay triangulation of free sites around such a cone joins sites over its several
   * sheets (a cone of 629 degrees on CGAL's femur, a genus-2 bone) and cannot be merged into one site; a
   * vertex there, of degree about angle / 60 degrees, is what a mesh of a saddle-like cone needs. The
   * widest first; the cones of positive curvature are merged into their nearest site by the dual
   * (`Cone_domain_traits`). Fixed for the CVT and the dual only: the surface optimisation moves them
   * (`Remeshed_surface::released_vertices`).
   */
  static std::vector<std::size_t> vertices_kept(const Embedding& emb)
  {
    std::vector<std::pair<double, std::size_t>> negative;
    for(std::size_t i = 0; i < emb.cones.size(); ++i)
      if(emb.cone_angles[i] > 2 * 3.14159265358979323846 * (1 + 1e-9)) negative.emplace_back(-emb.cone_angles[i], std::size_t(emb.cones[i]));
    std::sort(negative.begin(), negative.end());  // the widest first
    std::vector<std::size_t> kept;
    for(const auto& c : negative) kept.push_back(c.second);
    return kept;
  }
  /// the cones, their angles, the area distortion and the atlas
  static Domain_diagnostics diagnostics(const Embedding& emb, const Traits& traits)
  {
    const double deg = 180 / 3.14159265358979323846;
    Domain_diagnostics d;
    d.add("cones", double(emb.cones.size()), "cone singularities placed", true);
    double lo = 0, hi = 0;
    if(!emb.cone_angles.empty()) {
      lo = *std::min_element(emb.cone_angles.begin(), emb.cone_angles.end()) * deg;
      hi = *std::max_element(emb.cone_angles.begin(), emb.cone_angles.end()) * deg;
    }
    d.add("cone_angle_range", {lo, hi}, 2, "smallest and largest cone angle (degrees)");
    d.add("negative_cones", double(vertices_kept(emb).size()),
          "cones of angle above 360 degrees, each a fixed site (an output vertex) unless a corner or a wider one lies within half an edge length",
          true);
    std::vector<double> table;
    for(std::size_t i = 0; i < emb.cones.size(); ++i) {
      const Eigen::Vector3d& x = traits.background().position(emb.cones[i]);
      table.insert(table.end(), {x.x(), x.y(), x.z(), i < emb.cone_angles.size() ? emb.cone_angles[i] * deg : 0.0});
    }
    d.add("cone_table", std::move(table), 4, "one row per cone: its position x, y, z on the input and its angle (degrees)");
    d.add("log_scale_factor_range", emb.u_range, "max u - min u of the cone metric (area distortion exp(2 range))");
    d.add("start_log_scale_factor_range", emb.start_u_range,
          "the same with the starting cones only (four extreme points on genus 0), linearised (Poisson equation)");
    d.add("linearised_cones", double(emb.linearised_cones), "cones placed by the linearised rounds (one factorisation)", true);
    d.add("placement_solves", double(emb.solves), "Newton solves of the placement (nonlinear rounds)", true);
    d.add("charts", double(traits.number_of_charts()), "planar charts of the atlas", true);
    if(emb.double_edges)
      d.add("double_edge_flips", 1.0, "1: the placement was solved again with Delaunay flips that may double an edge (a try without ended with flat triangles)", true);
    if(emb.edge_splits > 0)
      d.add("edge_splits", double(emb.edge_splits), "edges split after a placement that flattened a triangle next to a hole's loop", true);
    const std::size_t grown = traits.dual_statistics().grown_fans;
    if(grown > 0)
      d.add("dual_grown_fans", double(grown),
            "sites of the dual re-starred over a region grown past a cone or a tangle (thin parts narrower than the site spacing)", true);
    const std::size_t moved = traits.dual_statistics().moved;
    if(moved > 0)
      d.add("dual_moved_sites", double(moved),
            "free sites the dual moved onto a cone that no site could be merged into (thin parts narrower than the site spacing); their output vertices lie at the cones",
            true);
    char text[200];
    std::snprintf(text, sizeof(text),
                  "%zu cones of %.0f to %.0f degrees (%zu linearised, %zu Newton solves); area distortion %.1f (about %.3g with the "
                  "starting cones)",
                  emb.cones.size(), lo, hi, emb.linearised_cones, emb.solves, std::exp(2 * emb.u_range), std::exp(2 * emb.start_u_range));
    d.summary = text;
    if(emb.double_edges) d.summary += "; solved with flips that double edges";
    if(emb.edge_splits > 0) d.summary += "; " + std::to_string(emb.edge_splits) + " edges split (a triangle flattened next to a hole's loop)";
    if(grown > 0) d.summary += "; dual: " + std::to_string(grown) + " sites re-starred at thin parts";
    if(moved > 0) d.summary += "; dual: " + std::to_string(moved) + (moved == 1 ? " site moved onto a cone" : " sites moved onto cones") + " at thin parts";
    return d;
  }
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_CONE_DOMAIN_H
