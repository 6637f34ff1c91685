// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
// Concept documentation (Doxygen only).

/*!
 * \ingroup PkgAnisoConformalConcepts
 * \cgalConcept
 *
 * The canonical domain a surface is conformally embedded in (the plane for a disk; the sphere, the flat
 * torus and the hyperbolic disk for closed surfaces), with the laid-out background triangulation and
 * the CVT density `rho = cf^2` over it. The generic stages use only what this concept lists:
 * `weighted_centroidal_Voronoi_tessellation()` (integration, domain membership, Lloyd moves) and
 * `extract_dual_mesh()` (the dual triangles and where each site lies on the background).
 *
 * Sites are ordered: the first `number_of_fixed_sites()` stay where they are (the boundary sites of a
 * planar domain; 0 for closed domains).
 *
 * \cgalHasModel `Aniso_conformal::Planar_domain_traits`
 */
class ParametricDomainTraits {
public:
  /// a point of the domain: an `Eigen` fixed-size column vector (`Eigen::Vector2d` for the plane);
  /// its `RowsAtCompileTime` is the number of coordinates the CVT optimises per site
  typedef unspecified_type Point;
  /// integrals of the density over one Voronoi cell restricted to the domain
  struct Cell {
    double mass;      ///< integral of `rho`
    Point centroid;   ///< (integral of `rho y`) / mass, or the site when the mass is 0
    double energy;    ///< integral of `rho |y - site|^2`
  };
  /// computes the restricted Voronoi cell of every site (one `Cell` per site, same order), exactly
  void integrate(const std::vector<Point>& sites, std::vector<Cell>& cells) const;
  /// `true` if `p` is in the domain
  bool contains(const Point& p) const;
  /// moves `p` towards `target` as far as the domain allows (Lloyd steps and rejected L-BFGS steps)
  Point move_towards(const Point& p, const Point& target) const;
  /// the number of leading sites that do not move
  std::size_t number_of_fixed_sites() const;
  /// the triangles of the Delaunay dual of `sites` in the domain, as indices into `sites`, oriented
  /// like the input; throws `Aniso_conformal::Convergence_failure` if they do not form a valid triangulation
  std::vector<std::array<std::size_t, 3>> dual_triangles(const std::vector<Point>& sites) const;
  /// the face of the background `Intrinsic_triangulation` that contains site `i` at `site` and the
  /// barycentric coordinates in it (with respect to its `face_vertices()`); `false` if it is outside
  bool background_location(std::size_t i, const Point& site, int& face, Eigen::Vector3d& barycentric) const;
};
