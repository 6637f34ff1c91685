// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Concept documentation (read by Doxygen only; not a header to include).

/*!
 * \ingroup PkgAnisoConformalConcepts
 * The canonical domain a surface is conformally embedded in, with the background triangulation laid
 * out in it and the CVT density `rho = cf^2` over it.
 *
 * \cgalConcept
 *
 * The domain is the plane for a disk, the unit sphere for a closed surface of genus 0, the flat
 * torus for a closed surface of genus 1 and the hyperbolic plane modulo a Fuchsian group (points on the
 * hyperboloid, cells in the Klein disk) for higher genus. The generic stages use only the members listed here:
 * - `weighted_centroidal_Voronoi_tessellation()` (stage 4) calls `integrate()` for the energy, masses
 *   and centroids, `contains()` to reject L-BFGS steps that leave the domain, and `move_towards()` for
 *   Lloyd steps; it optimises the `Point`s coordinate by coordinate, and calls the optional hooks
 *   `project_to_tangent_plane()` and `project_to_domain()` of a curved domain if it has them (and the
 *   optional `line_search_halvings`);
 * - `extract_dual_mesh()` (stage 5) calls `dual_triangles()` for the output connectivity,
 *   `background_location()` to map every site back onto the input through the background
 *   `Intrinsic_triangulation`, and `number_of_fixed_sites()`;
 * - `remesh()` calls `initial_sites()` for the CVT's starting sites, which also decides
 *   `number_of_fixed_sites()`.
 *
 * How a model is built is its own business (each takes the `Intrinsic_triangulation` and the
 * embedding of its domain). A periodic domain's `Point` stands for its class: `integrate()` must
 * accept any translate (any image under the group) of a site and return the centroid next to that
 * translate, `dual_triangles()` must identify translates.
 *
 * Sites are ordered: the first `number_of_fixed_sites()` stay where they are (the boundary sites of a
 * planar domain; 0 for a closed domain); the CVT receives that number as its argument
 * `number_of_fixed_sites`.
 *
 * A curved domain embedded in the space of its `Point`s (the sphere in R^3) is optimised under the
 * constraint of staying on it: its cells' `centroid` is the centroid in the ambient space (so that
 * `2 mass_i (site_i - centroid_i)` is the ambient gradient of the energy), and the two optional hooks
 * below turn the unconstrained L-BFGS into a constrained one. A model without them (a flat domain) is optimised exactly
 * as before the hooks existed (the detection is at compile time). A domain whose distance is not the
 * ambient one (the hyperboloid, with the hyperbolic distance) gives its cells an optional member
 * `Point gradient`, the derivative of the cell's energy with respect to the site's ambient coordinates;
 * the CVT then uses it instead of `2 mass (site - centroid)`, and `centroid` serves Lloyd steps only.
 *
 * \cgalHasModel `Aniso_conformal::Planar_domain_traits`
 * \cgalHasModel `Aniso_conformal::Spherical_domain_traits`
 * \cgalHasModel `Aniso_conformal::Euclidean_periodic_domain_traits`
 * \cgalHasModel `Aniso_conformal::Hyperbolic_klein_domain_traits`
 */
class ParametricDomainTraits {
public:
  /// \name Types
  /// @{

  /*!
   * a point of the domain: a fixed-size Eigen column vector of `double` (`Eigen::Vector2d` for the
   * plane). `Point::RowsAtCompileTime` is the number of coordinates the CVT optimises per site.
   */
  typedef unspecified_type Point;

  /*!
   * the integrals of the density over one Voronoi cell restricted to the domain. Default
   * constructible and copyable, with (at least) these public data members.
   */
  struct Cell {
    double mass;     ///< integral of `rho` over the cell
    Point centroid;  ///< (integral of `rho y`) / `mass`, or the site itself when the mass is 0
    double energy;   ///< integral of `rho |y - site|^2` over the cell
  };

  /// @}

  /// \name Sites (stage 4)
  /// @{

  /*!
   * returns `n` initial sites spread by the sites' density at the CVT's optimum, `rho^(1/2)` for a
   * density `rho` (Gersho), deterministic for a `seed`: the models sample the background triangles'
   * integrals of `rho^(1/2)` by evenly spaced quantiles along a space-filling curve with one random
   * offset (`internal::stratified_samples()`), and a planar domain first places its fixed
   * boundary sites. Non-const: it decides which (leading) sites are fixed, so call it before
   * `number_of_fixed_sites()`; a closed domain fixes none.
   * \throws Aniso_conformal::Invalid_input if `n` is too small for the domain (fewer than 3 or than the
   *         boundary's corners in the plane, 4 on the sphere, 1 on the torus and the hyperbolic surface)
   */
  std::vector<Point> initial_sites(std::size_t n, unsigned seed);

  /// @}

  /// \name Integration and moves (stage 4)
  /// @{

  /*!
   * computes the restricted Voronoi cell of every site: resizes `cells` to `sites.size()` and fills
   * `cells[i]` for `sites[i]`. The CVT energy is the sum of the cells' `energy`, its gradient with
   * respect to site `i` is `2 mass_i (site_i - centroid_i)`, so the integrals must be exact (or at
   * least consistent) for L-BFGS to converge.
   */
  void integrate(const std::vector<Point>& sites, std::vector<Cell>& cells) const;

  /// returns `true` if `p` is in the domain
  bool contains(const Point& p) const;

  /// returns `p` moved towards `target` as far as the domain allows (`target` itself if it is inside;
  /// on a curved domain, the constrained centroid: the sphere's `move_towards()` normalises `target`)
  Point move_towards(const Point& p, const Point& target) const;

  /// @}

  /// \name Optional hooks of a curved domain (stage 4)
  /// These are detected at compile time and need not exist; `Spherical_domain_traits` and
  /// `Hyperbolic_klein_domain_traits` have both.
  /// @{

  /*!
   * returns the point of the domain to which the trial point `p` is mapped back (a retraction): the
   * L-BFGS steps are taken in the ambient coordinates, then every trial site is passed through this
   * before `contains()` and `integrate()` (the sphere normalises `p`)
   */
  Point project_to_domain(const Point& p) const;

  /*!
   * returns the component of the vector `v` tangent to the domain at its point `x`: applied to each
   * site's energy gradient and L-BFGS direction, so that the optimisation moves along the domain (the
   * sphere returns `v - (x.v) x`)
   */
  Point project_to_tangent_plane(const Point& x, const Point& v) const;

  /*!
   * optional (detected at compile time): the most step lengths the L-BFGS line search tries (12 when
   * absent); when present, the L-BFGS memory is also forgotten after a shortened step. For a domain
   * whose energy jumps slightly where a site crosses a seam (`Cone_domain_traits`: 4).
   */
  static constexpr int line_search_halvings = 12;

  /// @}

  /// \name Dual mesh (stage 5)
  /// @{

  /// returns the number of leading sites that do not move (as decided by the last `initial_sites()`)
  std::size_t number_of_fixed_sites() const;

  /*!
   * returns the triangles of the Delaunay dual of `sites` in the domain (with the domain's boundary or
   * periodicity), as index triples into `sites`, oriented like the input; every site must be a vertex
   * of the result.
   * \throws Aniso_conformal::Convergence_failure if the triangles do not form a valid triangulation
   */
  std::vector<std::array<std::size_t, 3>> dual_triangles(const std::vector<Point>& sites) const;

  /*!
   * finds where site `i`, at `site`, lies on the background: sets `face` to the face of the background
   * `Intrinsic_triangulation` that contains it and `barycentric` to its barycentric coordinates with
   * respect to that face's `face_vertices()`. A coordinate exactly 1 means the site is that vertex.
   * \returns `false` if the site lies outside the domain
   */
  bool background_location(std::size_t i, const Point& site, int& face, Eigen::Vector3d& barycentric) const;

  /// @}
};
