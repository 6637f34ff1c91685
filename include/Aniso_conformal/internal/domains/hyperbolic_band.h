// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_DOMAINS_HYPERBOLIC_BAND_H
#define ANISO_CONFORMAL_INTERNAL_DOMAINS_HYPERBOLIC_BAND_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Intrinsic_triangulation.h>
#include <Aniso_conformal/internal/conformal/hyperbolic_geometry.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

// The images of the sites near the fundamental domain of a hyperbolic surface H^2 / G and their power
// diagram in the Klein disk (Hyperbolic_klein_domain_traits): the tiles across the cut are explored face
// by face (a Dijkstra over face copies, each reached through its side pairings), so their number grows
// with the width of the band, not exponentially with word length.

namespace Aniso_conformal {
namespace internal {

// The group elements and face copies (tiles) reached so far around the fundamental domain, grown on
// demand. A slot is the index of a background triangle in the traits' (Morton) order.
class Hyperbolic_band {
public:
  // a face copy: background triangle (slot) and group element; `distance` is the Dijkstra's distance
  // for the copies of the first band, -1 for those added to cover a Delaunay disk
  struct Face_copy {
    std::size_t slot;
    int element;
    double distance;
  };

  Hyperbolic_band() = default;
  // itri: the background; face_of_slot / slot_of_face: the traits' order of its faces; pairing: the side
  // pairing of every halfedge (identity inside the fundamental domain); corners: each face's corners on
  // the hyperboloid
  Hyperbolic_band(const Intrinsic_triangulation& itri, std::vector<int> face_of_slot, std::vector<std::size_t> slot_of_face,
                  std::vector<Eigen::Matrix3d> pairing, std::vector<std::array<Eigen::Vector3d, 3>> corners)
    : m_itri(&itri), m_face_of_slot(std::move(face_of_slot)), m_slot_of_face(std::move(slot_of_face)),
      m_pairing(std::move(pairing)), m_corners(std::move(corners)), m_group(1, Eigen::Matrix3d::Identity()),
      m_group_inverse(1, Eigen::Matrix3d::Identity())
  {
    // each face lies in the ball of radius m_face_radius around its centroid (balls are convex)
    m_centroid.resize(m_face_of_slot.size());
    m_face_radius.resize(m_face_of_slot.size());
    for(std::size_t i = 0; i < m_face_of_slot.size(); ++i) {
      const auto& c = m_corners[std::size_t(m_face_of_slot[i])];
      m_centroid[i] = normalize_on_hyperboloid(c[0] + c[1] + c[2]);
      m_face_radius[i] = std::max({hyperbolic_distance(m_centroid[i], c[0]), hyperbolic_distance(m_centroid[i], c[1]),
                                   hyperbolic_distance(m_centroid[i], c[2])});
    }
    m_cosh_face_radius.resize(m_face_radius.size());
    m_sinh_face_radius.resize(m_face_radius.size());
    for(std::size_t i = 0; i < m_face_radius.size(); ++i) {
      m_cosh_face_radius[i] = std::cosh(m_face_radius[i]);
      m_sinh_face_radius[i] = std::sinh(m_face_radius[i]);
    }
    m_on_cut.resize(m_pairing.size());
    for(std::size_t h = 0; h < m_pairing.size(); ++h) m_on_cut[h] = m_pairing[h] != Eigen::Matrix3d::Identity();
    m_seen_in_domain.assign(m_face_of_slot.size(), 0);
    m_copy_state.resize(m_face_of_slot.size());
    // the cut: the edges glued by a non-trivial deck transformation, as midpoints and half lengths
    for(std::size_t h = 0; h < m_pairing.size(); ++h) {
      if(!m_on_cut[h]) continue;
      const auto& c = m_corners[h / 3];
      const Eigen::Vector3d& a = c[h % 3];
      const Eigen::Vector3d& b = c[(h % 3 + 1) % 3];
      m_cut_midpoint.push_back(normalize_on_hyperboloid(a + b));
      m_cut_half_length.push_back(0.5 * hyperbolic_distance(a, b));
      // the side pairings, once each (the cut edges of one side share theirs, up to the layout's rounding)
      bool known = false;
      for(const Eigen::Matrix3d& P : m_generators)
        known = known || (P - m_pairing[h]).norm() <= 1e-6 * P.norm();
      if(!known) m_generators.push_back(m_pairing[h]);
    }
    m_distance_to_cut.assign(m_face_of_slot.size(), -1.0);
    // the point whose images tell the group elements apart (element_index()): the centroid of the face
    // nearest to the centre of the disk, and half the least distance between two of its images
    std::size_t ref = 0;
    for(std::size_t i = 1; i < m_centroid.size(); ++i)
      if(m_centroid[i].x() < m_centroid[ref].x()) ref = i;
    if(!m_centroid.empty()) {
      m_reference = m_centroid[ref];
      m_merge_tolerance = std::max(1e-3, distance_to_cut(ref));
    }
  }

  // a lower bound on the distance from any point of the face in `slot` to the cut (the boundary of the
  // fundamental domain): d(centroid, midpoint) - half length - face radius, over the cut edges; cached
  double distance_to_cut(std::size_t slot)
  {
    double& d = m_distance_to_cut[slot];
    if(d < 0) {
      d = std::numeric_limits<double>::infinity();
      for(std::size_t e = 0; e < m_cut_midpoint.size(); ++e)
        d = std::min(d, hyperbolic_distance(m_centroid[slot], m_cut_midpoint[e]) - m_cut_half_length[e]);
      d = std::max(0.0, d - m_face_radius[slot]);
    }
    return d;
  }

  const std::vector<Eigen::Matrix3d>& elements() const { return m_group; }          // element 0 is the identity
  const std::vector<Eigen::Matrix3d>& inverse_elements() const { return m_group_inverse; }
  const std::vector<Face_copy>& copies() const { return m_copies; }                  // without element 0
  double reached() const { return m_band_reached; }                                  // the first band explored so far
  const std::vector<Eigen::Matrix3d>& pairing() const { return m_pairing; }
  const std::vector<Eigen::Matrix3d>& side_pairings() const { return m_generators; }  // the distinct non-trivial pairings
  const std::vector<std::array<Eigen::Vector3d, 3>>& corners() const { return m_corners; }
  std::size_t cap() const { return 60 * m_face_of_slot.size(); }                     // the most copies the band holds
  // per element g, g applied to the reference point (element_index(); empty until its first call), and
  // a bound on the distance from the reference point to any point of the fundamental domain D (each
  // face lies within its radius of its centroid) plus the largest face radius: a point p that lies in
  // the tile g D, or that a location with a tolerance of a small part of a face takes for a point of it,
  // is within that distance of g reference
  const std::vector<Eigen::Vector3d>& reference_images() const { return m_reference_image; }
  double reach_of_domain() const
  {
    double r = 0, largest = 0;
    for(std::size_t i = 0; i < m_centroid.size(); ++i) {
      r = std::max(r, hyperbolic_distance(m_reference, m_centroid[i]) + m_face_radius[i]);
      largest = std::max(largest, m_face_radius[i]);
    }
    return r + largest;
  }

  // the index of group element G, added if new. Elements differ by where they take the reference point
  // p (a face centroid inside the fundamental domain D, near its centre): the group acts freely, so two
  // elements g != h take it at least 2 inj(p) >= 2 d(p, boundary of D) apart (their tiles gD and hD do
  // not overlap), while one element reached along two paths differs by the layout's rounding carried
  // out along the paths. Within `m_merge_tolerance` = d(p, boundary of D) (a lower bound from
  // distance_to_cut(), at least 1e-3) two images are one element: a computed bound, where the fixed 1e-3
  // let the rounding of CGAL's couplingdown (relation error 1.7e-2, images of p 0.002 to 0.05 apart
  // 10 units out) create 13000 spurious elements and the band of images overflow its cap. Searched among
  // the elements whose image of p has nearly the same x0 = cosh(distance to the apex): within `tol`,
  // x0 differs by less than tol e^tol x0.
  //
  // The search is a box query on the image's hyperboloid coordinates (x0, y, z): within `tol`, x0 and
  // (y, z) both differ by less than `slack` = tol e^tol x0 (cosh(r + tol) <= e^tol cosh r bounds how
  // fast (y, z) moves along a geodesic). The images are hashed by the level floor(log2 x0) and a grid
  // on (y, z) of cell 2^(level + 1) tol e^tol, at least the slack of the level, so a query visits a few
  // cells of each level its x0 window meets (three when tol is small; with tol near 1 every level down to
  // 0, each clamped to its own extent, a few cells). (An ordered map on x0 alone, visited over the x0 window, cost 60 % of
  // CGAL's turbine.off, genus 11, where many far elements share their x0.)
  int element_index(const Eigen::Matrix3d& G)
  {
    const Eigen::Vector3d o = G * m_reference;
    if(m_reference_image.empty()) {  // the identity
      m_reference_image.assign(1, m_reference);
      m_by_cell[cell_key(level_of(m_reference.x()), m_reference)].push_back(0);
    }
    const double tol = m_merge_tolerance;
    const double slack = tol * std::exp(tol) * o.x() + 1e-9;
    if(!std::isfinite(o.x()) || !std::isfinite(slack) || !std::isfinite(o.y()) || !std::isfinite(o.z())) {
      // an image beyond double precision (a far element of a high genus): equal to none (its distance to
      // any image is not a number), and not hashed
      m_group.push_back(G);
      m_group_inverse.push_back(lorentz_inverse(G));
      m_reference_image.push_back(o);
      return int(m_group.size() - 1);
    }
    int found = -1;
    for(int level = level_of(o.x() - slack); level <= level_of(o.x() + slack); ++level) {
      // the images of this level have |y|, |z| <= sinh r < x0 < 2^(level + 1): the box clamped to that
      // (with a tolerance as wide as the level, each level's whole extent is a few cells)
      const double c = cell_size(level), extent = std::ldexp(1.0, level + 1);
      const double y0 = std::max(o.y() - slack, -extent), y1 = std::min(o.y() + slack, extent);
      const double z0 = std::max(o.z() - slack, -extent), z1 = std::min(o.z() + slack, extent);
      if(y0 > y1 || z0 > z1) continue;
      const long long i0 = cell_coordinate(y0, c), i1 = cell_coordinate(y1, c);
      const long long j0 = cell_coordinate(z0, c), j1 = cell_coordinate(z1, c);
      for(long long i = i0; i <= i1; ++i)
        for(long long j = j0; j <= j1; ++j) {
          const auto it = m_by_cell.find(pack_cell(level, i, j));
          if(it == m_by_cell.end()) continue;
          for(int e : it->second)
            if((found < 0 || e < found) && hyperbolic_distance(m_reference_image[std::size_t(e)], o) < tol) found = e;
        }
    }
    if(found >= 0) return found;
    m_group.push_back(G);
    m_group_inverse.push_back(lorentz_inverse(G));
    m_reference_image.push_back(o);
    m_by_cell[cell_key(level_of(o.x()), o)].push_back(int(m_group.size() - 1));
    return int(m_group.size() - 1);
  }

  // the copy across halfedge k of the face in `slot` from the copy (slot, element)
  std::pair<std::size_t, int> neighbour(std::size_t slot, int element, int k)
  {
    const int f = m_face_of_slot[slot];
    const int h = 3 * f + k, t = m_itri->twin(h);
    const std::size_t next_slot = m_slot_of_face[std::size_t(Intrinsic_triangulation::face(t))];
    if(!m_on_cut[std::size_t(h)]) return {next_slot, element};
    const std::uint64_t key = (std::uint64_t(std::uint32_t(element)) << 32) | std::uint64_t(std::uint32_t(h));
    auto it = m_step.find(key);
    if(it == m_step.end()) it = m_step.emplace(key, element_index(m_group[std::size_t(element)] * m_pairing[std::size_t(h)])).first;
    return {next_slot, it->second};
  }

  // Explores the tiles across the cut up to `band` from the fundamental domain: a Dijkstra over face
  // copies, the distance of a copy being that of its centroid to the point where the path left the
  // fundamental domain. The copies added by cover_disk() are kept. Bounded: at most cap() copies.
  // \throws Convergence_failure if the band needs more copies
  void ensure(double band)
  {
    if(band <= m_band_reached) return;
    const std::size_t nf = m_face_of_slot.size();
    typedef std::pair<std::size_t, int> Key;
    std::map<Key, double> best;
    std::map<Key, Eigen::Vector3d> source;
    typedef std::pair<double, Key> Entry;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    for(std::size_t s = 0; s < nf; ++s) queue.push({0.0, {s, 0}});
    for(std::size_t s = 0; s < nf; ++s) best[{s, 0}] = 0.0;
    std::vector<Face_copy> kept;  // the copies cover_disk() added
    for(const Face_copy& c : m_copies)
      if(c.distance < 0) kept.push_back(c);
    m_copies.clear();
    for(auto& states : m_copy_state) states.clear();  // no copy is a member; cover_disk()'s stamps are not needed between its calls
    while(!queue.empty()) {
      const Entry top = queue.top();
      queue.pop();
      const Key key = top.second;
      if(top.first > best[key]) continue;
      if(key.second != 0) add_copy({key.first, key.second, top.first}, band);
      for(int k = 0; k < 3; ++k) {
        const Key next = neighbour(key.first, key.second, k);
        if(next.second == 0) continue;  // back in the fundamental domain
        Eigen::Vector3d src;
        if(key.second == 0) {  // leaving the fundamental domain through edge k
          const auto& c = m_corners[std::size_t(m_face_of_slot[key.first])];
          src = normalize_on_hyperboloid(c[std::size_t(k)] + c[std::size_t((k + 1) % 3)]);
        } else {
          src = source[key];
        }
        // the centroid's distance, less the radius of the face around it: every copy across the edge it
        // left by is kept, and a copy is kept when it may reach within `band` of that edge
        const double d = std::max(0.0, hyperbolic_distance(src, copy_centroid(next.first, next.second)) - m_face_radius[next.first]);
        if(d > band) continue;
        auto it = best.find(next);
        if(it != best.end() && it->second <= d) continue;
        best[next] = d;
        source[next] = src;
        queue.push({d, next});
      }
    }
    for(const Face_copy& c : kept)
      if(!is_member(c.slot, c.element)) add_copy(c, band);
    m_band_reached = band;
  }

  // Adds every copy that meets the closed hyperbolic disk of centre `centre` and radius `radius`,
  // found breadth-first from the copy (slot, 0) of the fundamental domain, which must meet the disk
  // (a copy is taken to meet it when the ball around its centroid holding it does). Returns the
  // number of copies added: 0 when every image in the disk was already a point of the band.
  // \throws Convergence_failure if the band would exceed cap() copies
  std::size_t cover_disk(const Eigen::Vector3d& centre, double radius, std::size_t slot)
  {
    typedef std::pair<std::size_t, int> Key;
    // a copy is within reach when d(centre, its centroid y) - R <= radius (R: its face's radius), that is
    // when -<centre, y> <= cosh(radius + R) |y|_M: no inverse hyperbolic function per test
    const double ch = std::cosh(radius), sh = std::sinh(radius);
    // the copies seen by this call: stamped, per slot for the fundamental domain, hashed for the others
    if(++m_stamp == member_bit) {
      std::fill(m_seen_in_domain.begin(), m_seen_in_domain.end(), 0u);
      for(auto& states : m_copy_state)
        for(auto& e : states) e.second &= member_bit;
      m_stamp = 1;
    }
    // false if this call saw the copy already; else marks it, and `member` tells whether it is in the band
    bool member = false;
    auto first_visit = [&](const Key& key) {
      if(key.second == 0) {
        if(m_seen_in_domain[key.first] == m_stamp) return false;
        m_seen_in_domain[key.first] = m_stamp;
        member = false;
        return true;
      }
      std::uint32_t& state = copy_state(key.first, key.second);
      if((state & ~member_bit) == m_stamp) return false;
      member = (state & member_bit) != 0;
      state = (state & member_bit) | m_stamp;
      return true;
    };
    std::vector<std::pair<Key, bool>> stack;
    first_visit(Key(slot, 0));
    stack.emplace_back(Key(slot, 0), false);
    std::size_t added = 0;
    while(!stack.empty()) {
      const Key key = stack.back().first;
      const bool in_band = stack.back().second;
      stack.pop_back();
      if(key.second != 0 && !in_band) {
        add_copy({key.first, key.second, -1.0}, radius);
        ++added;
      }
      for(int k = 0; k < 3; ++k) {
        const Key next = neighbour(key.first, key.second, k);
        if(!first_visit(next)) continue;  // tested already: whether a copy is within reach depends on it alone
        const Eigen::Vector3d y = next.second == 0 ? m_centroid[next.first]
                                                    : Eigen::Vector3d(m_group[std::size_t(next.second)] * m_centroid[next.first]);
        const double reach = ch * m_cosh_face_radius[next.first] + sh * m_sinh_face_radius[next.first];
        if(-minkowski_dot(centre, y) > reach * std::sqrt(std::max(0.0, -minkowski_dot(y, y)))) continue;
        stack.emplace_back(next, member);
      }
    }
    return added;
  }

private:
  // the state of the copy (slot, element), added (0) if it is not known yet
  std::uint32_t& copy_state(std::size_t slot, int element)
  {
    auto& states = m_copy_state[slot];
    for(auto& e : states)
      if(e.first == element) return e.second;
    states.emplace_back(element, 0u);
    return states.back().second;
  }

  void add_copy(const Face_copy& c, double band)
  {
    if(m_copies.size() >= cap())
      throw Convergence_failure("hyperbolic domain: the band of images around the fundamental domain (reaching " + std::to_string(band) +
                                    ") needs more than " + std::to_string(cap()) + " face copies (too few sites for this surface and metric)",
                                band);
    copy_state(c.slot, c.element) |= member_bit;
    m_copies.push_back(c);
  }

  Eigen::Vector3d copy_centroid(std::size_t slot, int element) const
  {
    return element == 0 ? m_centroid[slot] : Eigen::Vector3d(normalize_on_hyperboloid(m_group[std::size_t(element)] * m_centroid[slot]));
  }

  const Intrinsic_triangulation* m_itri = nullptr;
  std::vector<int> m_face_of_slot;
  std::vector<std::size_t> m_slot_of_face;
  std::vector<Eigen::Matrix3d> m_pairing;
  std::vector<Eigen::Matrix3d> m_generators;  // the distinct non-trivial side pairings (they generate the group)
  std::vector<std::array<Eigen::Vector3d, 3>> m_corners;
  std::vector<Eigen::Vector3d> m_centroid;  // per slot, the centroid of its face
  std::vector<double> m_face_radius;        // per slot, the largest distance from that centroid to a corner
  std::vector<double> m_cosh_face_radius, m_sinh_face_radius;  // and its cosh and sinh (cover_disk())
  std::vector<char> m_on_cut;               // per halfedge, whether its side pairing is not the identity
  // cover_disk()'s copies of the fundamental domain seen, stamped with the call's number (m_copy_state elsewhere)
  std::vector<std::uint32_t> m_seen_in_domain;
  std::uint32_t m_stamp = 0;
  std::vector<Eigen::Vector3d> m_cut_midpoint;  // per edge of the cut, its midpoint ...
  std::vector<double> m_cut_half_length;        // ... and half its length
  std::vector<double> m_distance_to_cut;        // per slot, distance_to_cut() once computed (-1 before)
  std::vector<Eigen::Matrix3d> m_group, m_group_inverse;
  // element_index()'s hash: the elements by the level and (y, z) cell of their image of the reference point
  std::unordered_map<std::uint64_t, std::vector<int>> m_by_cell;
  static int level_of(double x0) { return x0 < 2 ? 0 : std::ilogb(x0); }
  double cell_size(int level) const { return std::ldexp(m_merge_tolerance * std::exp(m_merge_tolerance), level + 1); }
  static long long cell_coordinate(double y, double cell) { return static_cast<long long>(std::floor(y / cell)); }
  static std::uint64_t pack_cell(int level, long long i, long long j)
  {
    // distinct cells may share a key (a wider bucket: the distance test decides); never a wrong answer
    return (std::uint64_t(level) << 56) ^ ((std::uint64_t(i) & 0xFFFFFFFULL) << 28) ^ (std::uint64_t(j) & 0xFFFFFFFULL);
  }
  std::uint64_t cell_key(int level, const Eigen::Vector3d& p) const
  {
    const double c = cell_size(level);
    return pack_cell(level, cell_coordinate(p.y(), c), cell_coordinate(p.z(), c));
  }
  Eigen::Vector3d m_reference = Eigen::Vector3d::UnitX();  // the point whose images tell the elements apart
  std::vector<Eigen::Vector3d> m_reference_image;          // per element, its image of m_reference
  double m_merge_tolerance = 1e-3;                         // images of it nearer than this: one element
  std::vector<Face_copy> m_copies;
  // per copy (element, slot) outside the fundamental domain met so far: member_bit if it is in the band,
  // ored with the number of the last cover_disk() call that saw it
  static constexpr std::uint32_t member_bit = 0x80000000u;
  // (per slot, the list of its copies met so far, scanned: the copies of a face are those of the few
  // tiles near it, where a hash map over (slot, element) was 11 % of CGAL's couplingdown)
  std::vector<std::vector<std::pair<int, std::uint32_t>>> m_copy_state;
  bool is_member(std::size_t slot, int element) const
  {
    for(const auto& e : m_copy_state[slot])
      if(e.first == element) return (e.second & member_bit) != 0;
    return false;
  }
  std::unordered_map<std::uint64_t, int> m_step;          // (element, halfedge) -> element across it
  double m_band_reached = 0;
};

// CGAL's regular triangulation of the Klein disk with the point index as vertex info
typedef CGAL::Exact_predicates_inexact_constructions_kernel Klein_kernel;
typedef CGAL::Triangulation_vertex_base_with_info_2<int, Klein_kernel, CGAL::Regular_triangulation_vertex_base_2<Klein_kernel>> Klein_vb;
typedef CGAL::Triangulation_data_structure_2<Klein_vb, CGAL::Regular_triangulation_face_base_2<Klein_kernel>> Klein_tds;
typedef CGAL::Regular_triangulation_2<Klein_kernel, Klein_tds> Klein_regular_triangulation;

// the sites in the fundamental domain (indices 0 .. n-1) and their images in the band, with their power diagram
struct Hyperbolic_power_diagram {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> original, element;  // site and group element of each point
  Klein_regular_triangulation rt;
  std::vector<Klein_regular_triangulation::Vertex_handle> handle;

  bool has_vertex(std::size_t i) const
  {
    return handle[i] != Klein_regular_triangulation::Vertex_handle() && handle[i]->info() == int(i);
  }
};

// the points and their power diagram: the point x becomes the weighted point ((x1, x2) / 2,
// (x1^2 + x2^2) / 4 - x0), whose power at the Klein point k orders the points as their hyperbolic
// distance to k does (Nielsen and Nock)
inline void build_power_diagram(Hyperbolic_power_diagram& pr)
{
  typedef Klein_kernel K;
  pr.rt.clear();
  std::vector<std::pair<K::Weighted_point_2, int>> pts;
  pts.reserve(pr.points.size());
  for(std::size_t e = 0; e < pr.points.size(); ++e) {
    const Eigen::Vector3d& x = pr.points[e];
    const double cx = 0.5 * x.y(), cy = 0.5 * x.z();
    pts.emplace_back(K::Weighted_point_2(K::Point_2(cx, cy), cx * cx + cy * cy - x.x()), int(e));
  }
  pr.rt.insert(pts.begin(), pts.end());
  pr.handle.assign(pr.points.size(), Klein_regular_triangulation::Vertex_handle());
  for(auto v = pr.rt.finite_vertices_begin(); v != pr.rt.finite_vertices_end(); ++v) pr.handle[std::size_t(v->info())] = v;
}

/*
 * The power diagram of the sites `wrapped` (in the fundamental domain; slot[i]: the background triangle
 * holding site i) and of enough of their images around the fundamental domain. The band starts at three
 * site spacings (sqrt(area / n)); then every Delaunay face at an original site is checked: every copy
 * of a background face that meets its circumscribed disk must be in the band (Hyperbolic_band::cover_disk()
 * adds those missing), so that no missing image can lie in the disk and the face is a face of the
 * Delaunay triangulation of all the images. A face whose circumcentre is not a point of the hyperbolic
 * plane (no image beyond it yet), or whose circle is wider than this round's limit (two site spacings,
 * doubled at each round), gets instead the copies in the disk of that limit around its original site.
 * Faces whose disk stays nearer to their site than the cut are skipped. The band thus follows the local size of the Voronoi cells (which
 * differs by orders of magnitude over a surface with thin parts, where the conformal factor is small)
 * instead of one width for the whole boundary of the fundamental domain. Bounded: 16 rounds, and the
 * band's cap on copies.
 * \throws Convergence_failure if the band does not close within these bounds
 */
inline void build_hyperbolic_power_diagram(Hyperbolic_band& band, const std::vector<Eigen::Vector3d>& wrapped,
                                           const std::vector<std::size_t>& slot, std::size_t number_of_slots, double area,
                                           Hyperbolic_power_diagram& pr, std::size_t max_rounds = 16)
{
  const std::size_t ns = wrapped.size();
  const double spacing = std::sqrt(area / double(ns));
  band.ensure(3 * spacing);
  // an image of site s by element g lies in the copy (slot of s, g)
  std::vector<std::vector<std::size_t>> by_slot(number_of_slots);
  for(std::size_t i = 0; i < ns; ++i) by_slot[slot[i]].push_back(i);
  for(std::size_t round = 0; round < max_rounds; ++round) {
    pr.points.assign(wrapped.begin(), wrapped.end());
    pr.original.resize(ns);
    pr.element.assign(ns, 0);
    for(std::size_t i = 0; i < ns; ++i) pr.original[i] = int(i);
    for(const Hyperbolic_band::Face_copy& c : band.copies())
      for(std::size_t s : by_slot[c.slot]) {
        pr.points.push_back(normalize_on_hyperboloid(band.elements()[std::size_t(c.element)] * wrapped[s]));
        pr.original.push_back(int(s));
        pr.element.push_back(c.element);
      }
    build_power_diagram(pr);
    std::size_t added = 0;
    bool unbounded = false;
    for(auto f = pr.rt.finite_faces_begin(); f != pr.rt.finite_faces_end(); ++f) {
      int s = -1;
      for(int k = 0; k < 3 && s < 0; ++k)
        if(f->vertex(k)->info() < int(ns)) s = f->vertex(k)->info();
      if(s < 0) continue;
      const Eigen::Vector3d& x = pr.points[std::size_t(s)];
      // the disk this round may cover, doubling from two site spacings: a wider circle (or none) means
      // that images are missing beyond it, which the growing disk around the site finds first, without
      // covering more than twice the largest Voronoi cell
      const double limit = std::ldexp(2 * spacing, int(round));
      const Klein_kernel::Point_2 c = pr.rt.weighted_circumcenter(f);
      const Eigen::Vector2d k(c.x(), c.y());
      const Eigen::Vector3d centre = k.squaredNorm() < 1 ? from_klein(k) : Eigen::Vector3d::Zero();
      const double r = k.squaredNorm() < 1 ? hyperbolic_distance(centre, x) * (1 + 1e-9) : std::numeric_limits<double>::infinity();
      // the disk lies within 2 r of the site: inside the fundamental domain when that is nearer than the cut
      if(2 * r < band.distance_to_cut(slot[std::size_t(s)])) continue;
      if(r <= limit) {
        added += band.cover_disk(centre, r, slot[std::size_t(s)]);
      } else {  // not a hyperbolic circle, or one far wider than its triangle: an image is missing beyond it
        unbounded = true;
        added += band.cover_disk(x, limit, slot[std::size_t(s)]);
      }
    }
    if(added == 0 && !unbounded) return;
  }
  throw Convergence_failure("hyperbolic domain: the band of images around the fundamental domain did not close around the Voronoi cells of " +
                                std::to_string(ns) + " sites within " + std::to_string(max_rounds) + " rounds",
                            double(ns));
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_DOMAINS_HYPERBOLIC_BAND_H
