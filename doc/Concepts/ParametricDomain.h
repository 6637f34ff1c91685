// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Concept documentation (read by Doxygen only; not a header to include).

/*!
 * \ingroup PkgAnisoConformalConcepts
 * A canonical domain of the conformal embedding as a policy of the pipeline: everything that differs
 * from one domain to another, and nothing else. `remesh_in_domain<Domain>()` runs the six stages of
 * Zhong et al.\ 2014 with it; `remesh()` picks the model from the topology with one switch. A new
 * domain is one model of this concept plus one model of `ParametricDomainTraits` (its `Traits`), and
 * needs no change anywhere else: the writers print its `Domain_diagnostics` without knowing it.
 *
 * \cgalConcept
 *
 * What a model supplies, in pipeline order:
 * - the topologies it takes (`fits()`, `topology()`) and the fewest output vertices it can build for a
 *   given input (`check_number_of_vertices()`, which throws `Invalid_input` with the reason);
 * - stage 3, `embed()`: the conformal embedding of the background `Intrinsic_triangulation` (whose edges it
 *   may flip), returning its `Embedding`, which has at least the members `u`, `conformal_factor` (one per
 *   vertex of the triangulation, paper eq. 6), `iterations`, `residual` and `flips`;
 * - the domain of stages 4 and 5, `make_traits()`, a model of `ParametricDomainTraits` built from the
 *   triangulation and the embedding, whose `initial_sites(n, seed)` places the sites;
 * - for a closed domain, `corner_site()`: the site of a vertex of the triangulation in the domain, read from
 *   the embedding; the pipeline makes each corner of the input's feature graph (`detect_features()`) a
 *   fixed site there, which the dual maps back exactly onto the corner;
 * - for a closed domain, `vertices_kept()`: vertices of the triangulation that the domain itself needs as
 *   output vertices (fixed sites, like the corners): the cone domain's cones of negative curvature; none
 *   in the other domains;
 * - `diagnostics()`: what the domain measured, for `Remeshing_result::domain_diagnostics` (called after
 *   the CVT and the dual, so that the traits can report what they did);
 * - `inverted_triangles_hint()`: the most likely reason, on this domain, for an inverted output triangle
 *   (appended to the `Convergence_failure` that refuses such an output);
 * - `optimizes_on_the_surface_by_default`: `true` if the default `Surface_optimization::REPAIR` runs
 *   as `Surface_optimization::ALWAYS` in this domain (the cone domain, whose cells next to cones are
 *   approximate); `false` in the other four.
 *
 * All members are static: a model holds no state; the state of a run lives in its `Embedding` and
 * `Traits`.
 *
 * \cgalHasModel `Aniso_conformal::Planar_domain`
 * \cgalHasModel `Aniso_conformal::Spherical_domain`
 * \cgalHasModel `Aniso_conformal::Flat_torus_domain`
 * \cgalHasModel `Aniso_conformal::Hyperbolic_domain`
 */
class ParametricDomain {
public:
  /// \name Types
  /// @{

  /// the result of stage 3 (`Planar_embedding`, `Spherical_embedding`, ...)
  typedef unspecified_type Embedding;
  /// the domain of stages 4 and 5, a model of `ParametricDomainTraits`
  typedef unspecified_type Traits;
  /// @}

  /// its tag, as `parametric_domain()` and `Remeshing_result::domain` spell it
  static constexpr Aniso_conformal::Parametric_domain kind = unspecified;

  /// \name Topology
  /// @{

  /// the topologies the domain takes, in words, for messages ("closed surfaces of genus 0")
  static const char* topology();
  /// returns `true` if the domain takes the topology of `surface`
  static bool fits(const Aniso_conformal::Input_surface& surface);
  /// \throws Aniso_conformal::Invalid_input if `n` output vertices are too few for this domain and topology
  static void check_number_of_vertices(const Aniso_conformal::Input_surface& surface, std::size_t n);
  /// @}

  /// \name Stages
  /// @{
  /*!
   * stage 3: embeds `itri` (with valid metric lengths, after `adjust_edge_lengths()`) in the domain;
   * may flip its edges, never moves or adds vertices.
   * \throws Aniso_conformal::Convergence_failure if the embedding cannot be computed within its bounds
   */
  template <typename NamedParameters>
  static Embedding embed(Aniso_conformal::Intrinsic_triangulation& itri, const NamedParameters& np);
  /// the domain traits for stages 4 and 5; `threads` workers (0: all cores)
  static Traits make_traits(const Aniso_conformal::Intrinsic_triangulation& itri, const Embedding& embedding, unsigned threads);
  /*!
   * closed domains only: the site of vertex `v` of the triangulation (a corner of the input's feature
   * graph), which is corner `corner` of its face `face`, as `embedding` places it (on the sphere its
   * image; in a periodic domain the image of that face's corner, a point standing for its class)
   */
  static Traits::Point corner_site(const Embedding& embedding, int face, int corner, int v);
  /// closed domains only: the vertices of the triangulation that must be output vertices for the domain's
  /// sake (fixed sites at `corner_site()`), the most needed first (the pipeline keeps at most an eighth of
  /// the output vertices this way; the others are left to the dual)
  static std::vector<std::size_t> vertices_kept(const Embedding& embedding);
  /// the domain's own figures (scalars, vectors, matrices) and a one-line summary in words
  static Aniso_conformal::Domain_diagnostics diagnostics(const Embedding& embedding, const Traits& traits);
  /// the likely reason for an inverted output triangle on this domain, in words
  static const char* inverted_triangles_hint();
  /// `true` if the default surface optimisation (`Surface_optimization::REPAIR`) runs as `Surface_optimization::ALWAYS` here
  static constexpr bool optimizes_on_the_surface_by_default = false;
  /// @}
};
