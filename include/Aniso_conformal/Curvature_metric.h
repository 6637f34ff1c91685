// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_CURVATURE_METRIC_H
#define ANISO_CONFORMAL_CURVATURE_METRIC_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/Surface_point.h>
#include <Aniso_conformal/Tensor_field_metric.h>
#include <Aniso_conformal/internal/directed_edges.h>
#include <Aniso_conformal/internal/metric_gradation.h>
#include <Aniso_conformal/internal/parallel_for.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

/// \file Curvature_metric.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMetrics
 * the options of `Curvature_metric`
 */
struct Curvature_metric_options {
  double stretch_max = 10;       ///< bound on the stretch ratio `s_big / s_small` (>= 1)
  /// rounds of k-ring log-Euclidean averaging of the tensor field that give the directions (>= 0)
  int smoothing_iterations = 10;
  int smoothing_rings = 2;       ///< k of the k-ring neighbourhood of both averagings (>= 1)
  /// rounds of k-ring averaging of the logarithms of the two scales (>= 0); fewer rounds keep more of the
  /// stretch of narrow bands (Table 2 cyclide, bound 29, realised: 10 rounds [1, 7.4], 3 [1, 10],
  /// 1 [1, 12.8], 0 [1, 29]) but give a rougher field, harder to remesh (see the manual, Table 2)
  int scale_smoothing_iterations = 10;
  double flat_floor = 0.05;      ///< `s_big >= flat_floor * rms(s_big)`: flat parts become isotropic (>= 0)
  /// degrees, in (0, 180]: an edge whose dihedral angle (between the normals of its two faces) is above
  /// this is a crease, and the smoothing does not average across it (180 = no crease)
  double feature_angle = 60;
  /// threads of the per-vertex work (0 = every core); the field does not depend on it
  unsigned number_of_threads = 0;
  /// size gradation (Borouchaki, Hecht and Frey 1998; MMG's `-hgrad`, whose default is 1.3): a ratio `> 1`;
  /// along an edge of metric length `l` (step 4) the size that the metric prescribes grows by at most a
  /// factor `1 + (gradation - 1) l`. `0` or `+infinity`: no gradation (the field of steps 1 to 3, bit for
  /// bit). Smaller values give a smoother field (refined around creases and strongly curved bands) at the
  /// cost of the stretch there. The default 1.8 was chosen on CGAL's corpus at 2000 vertices
  /// (`benchmark/corpus.md`): it remeshes the CAD meshes the jumps refused without losing another, lifts
  /// the corpus's smallest G_avg from 0.792 (at 2.2) to 0.826, and leaves the Table 2 cyclide's field
  /// (stretch 29, 25920 vertices) unchanged bit for bit, with the lengths of the input's vertex count or
  /// of 8000 output vertices (1.65 would change 303 of its tensors, by up to 7 %)
  double gradation = 1.8;
  /// the number of output vertices that the metric lengths of the gradation refer to: the field is
  /// scaled, for the gradation only, so that its area is `gradation_vertices * sqrt(3) / 2` (that of
  /// about `gradation_vertices` vertices with unit edges). 0: the input's vertex count
  std::size_t gradation_vertices = 0;
};

/*!
 * \ingroup PkgAnisoConformalMetrics
 * the curvature metric of the paper's eq.\ 4, with the cleanups of DESIGN.md 3:
 * `M = s_min^2 d_min d_min^T + s_max^2 d_max d_max^T` with `s = sqrt(|kappa|)` along each principal
 * direction (zero along the normal), so edges are short across strong curvature.
 *
 * 1. Principal curvatures and directions come from the normal-cycle estimator of Cohen-Steiner and
 *    Morvan: at vertex v, `T = (1/A_v) sum_{e at v} beta(e) |e|/2 e_hat e_hat^T` (`beta` the signed dihedral
 *    angle, `A_v` a third of the area of the faces at v), restricted to the tangent plane. Its eigenvector
 *    of largest |eigenvalue| is the direction of *minimum* curvature; that eigenvalue is `kappa_max`.
 * 2. A floor `s_big >= flat_floor * rms(s_big) = f` makes flat parts isotropic (`s_small >= f^2 / s_big`
 *    too, so the stretch is at most `(s_big / f)^2`: 1 at the floor, growing continuously above it), and
 *    the stretch bound `s_small >= s_big / stretch_max` limits the anisotropy.
 * 3. The directions and the scales are smoothed separately, over `smoothing_rings`-rings. The directions
 *    by log-Euclidean averaging (Arsigny, Fillard, Pennec and Ayache, "Log-Euclidean metrics for fast and
 *    simple calculus on diffusion tensors", Magn. Reson. Med. 56(2), 2006): each vertex tensor is replaced
 *    by its logarithm on the tangent plane, `L = 2 log(s_big) d_max d_max^T + 2 log(s_small) d_min d_min^T`;
 *    `smoothing_iterations` rounds average `L` (the paper needed heavy smoothing, its Fig. 5), each
 *    neighbour's `L` first rotated into the vertex's tangent plane (the rotation taking its normal to the
 *    vertex's) and the mean projected on that plane; the eigenvectors of the smoothed `L` are the new
 *    `d_max`, `d_min` (where the directions disagree, at umbilics or in noise, each weighs by its
 *    anisotropy). The scales: `scale_smoothing_iterations` rounds average `log s_big` and `log s_small`
 *    as numbers, so the stretch ratio becomes the geometric mean of the neighbours' whatever their
 *    directions. Step 2 is then applied again to `s_big^2 d_max d_max^T + s_small^2 d_min d_min^T`.
 *    Why: averaging the tensors themselves (the method before this one: 10 rounds of 2-ring averages of
 *    `M`) is dominated by the largest `s_small^2` of each ring, and dropped the Dupin cyclide's stretch at
 *    bound 29 to [1, 4.7]; the geometric means keep [1, 7.4] with the defaults. The curvature of that
 *    surface supports more only on bands one or two vertices wide, where a principal curvature changes
 *    sign: `scale_smoothing_iterations = 0` keeps them ([1, 29], 95th percentile 5.7, the curvature's own),
 *    a field that the stages before the final optimisation do not remesh without inverted triangles at
 *    8000 vertices.
 *    Creases stay out of their neighbours' smoothing (directions and scales): an edge whose dihedral angle
 *    is above `feature_angle` is a crease, a vertex on one is a crease vertex; the rings of a crease vertex
 *    follow crease edges only, those of other vertices never enter a crease vertex.
 *    The result is scaled so that the median `s_big` is 1 (only the shape matters; before step 4).
 * 4. Size gradation (Borouchaki, Hecht and Frey, "Mesh gradation control", Int. J. Numer. Meth. Engng
 *    43(6), 1998; MMG's `-hgrad`), unless `gradation` is 0 or infinite: along every edge (i, j) of the
 *    surface, of length `l` in the field scaled to `gradation_vertices` vertices of unit edges,
 *    `M_j <- M_j ∩ (1 + (gradation - 1) l)^-2 M_i` (M_i carried into j's tangent plane by the rotation
 *    between the normals; `∩` the intersection by simultaneous reduction of Alauzet and Frey, the largest
 *    metric below neither) and the floor and the stretch bound applied again, over a queue of the vertices
 *    until no tensor grows by more than 1e-3 (it converges, in a few sweeps in practice). The size
 *    `det(M)^(-1/4)` then grows by at most a factor `1 + (gradation - 1) l` along an edge, across creases too:
 *    the metric no longer jumps where a crease or a flat face meets a curved band, which the stages after
 *    it (background refinement, the embeddings) could not resolve on CAD meshes. It only ever refines
 *    (sizes shrink), so the same number of output vertices is spread differently. Without it (gradation
 *    0), the field of steps 1 to 3 bit for bit.
 *
 * What is realised: `stretch_ratios()` lies in `[1, stretch_max]`; with `scale_smoothing_iterations = 0`
 * it is `min(stretch_max, sqrt|kappa_max / kappa_min|, (s_big / f)^2)` at each vertex, so it reaches the
 * bound wherever the curvature ratio exceeds `stretch_max^2`; with smoothed scales, wherever it does so
 * over the smoothing's neighbourhood (without gradation; the gradation lowers it next to creases and
 * flat parts). `Quality_report::stretch_min` ... `stretch_max` give what an output mesh realises.
 *
 * Time and memory linear in the size of the surface (about `smoothing_iterations * ring size` 2 x 2
 * rotations of a tangent-frame tensor per vertex, one rotation of 16 bytes stored per ring entry while
 * smoothing, about 300 bytes per vertex at 2-rings, and a few 2 x 2 generalised eigenproblems per edge
 * and sweep of the gradation, which is sequential); the per-vertex work runs on `number_of_threads`
 * threads. 1.66M vertices: about 7 s on two cores (`benchmark/scaling.md`).
 * \throws Invalid_input for options out of range (`gradation` neither 0, infinity nor a number > 1
 * included)
 * \throws Internal_error if the gradation does not converge (a broken invariant)
 *
 * \cgalModels `AnisotropicMetric`
 */
class Curvature_metric {
public:
  /// the tensor type
  typedef Eigen::Matrix3d Tensor;

  /// computes the metric of `s`
  explicit Curvature_metric(const Input_surface& s, const Curvature_metric_options& o = Curvature_metric_options())
    : m_field(std::vector<Tensor>())
  {
    if(!(std::isfinite(o.stretch_max) && o.stretch_max >= 1))
      throw Invalid_input("curvature metric: stretch_max must be a finite number >= 1");
    if(o.smoothing_iterations < 0 || o.smoothing_rings < 1 || o.scale_smoothing_iterations < 0)
      throw Invalid_input("curvature metric: smoothing_iterations and scale_smoothing_iterations must be >= 0 and "
                          "smoothing_rings >= 1");
    if(!(std::isfinite(o.flat_floor) && o.flat_floor >= 0)) throw Invalid_input("curvature metric: flat_floor must be >= 0");
    if(!(o.feature_angle > 0 && o.feature_angle <= 180))
      throw Invalid_input("curvature metric: feature_angle must be in (0, 180] degrees");
    if(!(o.gradation == 0 || o.gradation > 1))  // +infinity passes (no gradation), NaN does not
      throw Invalid_input("curvature metric: gradation must be a ratio > 1, or 0 or infinity for none");
    const std::size_t n = s.number_of_vertices();
    const auto& N = s.vertex_normals();
    const unsigned threads = o.number_of_threads;

    // 1. normal-cycle curvature tensors, and the crease edges and vertices (dihedral angle above feature_angle)
    const Directed_edges out(s.number_of_vertices(), s.faces(), s.number_of_faces());
    std::vector<Tensor> T;
    std::vector<double> area;
    std::vector<char> crease_edge, crease_vertex;
    normal_cycle_tensors(s, out, o.feature_angle, T, area, crease_edge, crease_vertex);
    m_kmin.resize(n);
    m_kmax.resize(n);
    std::vector<Tensor> M(n);
    std::vector<double> sbig(n);
    internal::parallel_for(n, threads, [&](std::size_t v) {
      Eigen::Vector2d lambda;
      Eigen::Matrix<double, 3, 2> E;
      tangent_eigen(T[v] / std::max(area[v], 1e-300), N[v], lambda, E);
      // column 0: largest |eigenvalue| (kappa_max), its eigenvector is the min-curvature direction
      m_kmax[v] = lambda[0];
      m_kmin[v] = lambda[1];
      const double s_big = std::sqrt(std::abs(lambda[0])), s_small = std::sqrt(std::abs(lambda[1]));
      sbig[v] = s_big;
      // d_max = E.col(1) gets s_big, d_min = E.col(0) gets s_small
      M[v] = s_big * s_big * E.col(1) * E.col(1).transpose() + s_small * s_small * E.col(0) * E.col(0).transpose();
    });
    std::vector<Tensor>().swap(T);
    double rms = 0;
    for(double x : sbig) rms += x * x;
    rms = std::sqrt(rms / double(std::max<std::size_t>(1, n)));
    const double floor_value = o.flat_floor * rms > 0 ? o.flat_floor * rms : 1.0;
    internal::parallel_for(n, threads, [&](std::size_t v) { M[v] = bounded(M[v], N[v], floor_value, o.stretch_max); });

    // 3. smoothing over k-rings, not across creases: the directions by log-Euclidean averaging, the
    // logarithms of the two scales as numbers
    if(o.smoothing_iterations > 0 || o.scale_smoothing_iterations > 0)
      smooth(s, out, crease_edge, crease_vertex, o, floor_value, M);

    // scale: median s_big = 1
    std::vector<double> big(n);
    m_stretch.resize(n);
    internal::parallel_for(n, threads, [&](std::size_t v) {
      Eigen::Vector2d l;
      Eigen::Matrix<double, 3, 2> E;
      tangent_eigen(M[v], N[v], l, E);
      big[v] = std::sqrt(std::abs(l[0]));
      m_stretch[v] = std::sqrt(std::abs(l[0]) / std::max(std::abs(l[1]), 1e-300));
    });
    std::vector<double> sorted = big;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(n / 2), sorted.end());
    const double median = n ? sorted[n / 2] : 1.0;
    const double median2 = median * median > 0 ? median * median : 1.0;
    for(auto& m : M) m /= median2;

    // 4. gradation (Borouchaki, Hecht and Frey 1998) along the edges, in the field scaled to
    // `gradation_vertices` unit edges; only ever refines; the floor and the stretch bound kept
    if(o.gradation > 1 && std::isfinite(o.gradation)) {
      grade(s, out, o, floor_value / median, M);
      internal::parallel_for(n, threads, [&](std::size_t v) {
        Eigen::Vector2d l;
        Eigen::Matrix<double, 3, 2> E;
        tangent_eigen(M[v], N[v], l, E);
        m_stretch[v] = std::sqrt(std::abs(l[0]) / std::max(std::abs(l[1]), 1e-300));
      });
    }
    m_field = Tensor_field_metric(std::move(M));
  }

  /// the tensor at `p` (barycentric interpolation of the vertex tensors)
  Tensor tensor(const Surface_point& p) const { return m_field.tensor(p); }
  /// the vertex tensors
  const std::vector<Tensor>& tensors() const { return m_field.tensors(); }
  /// per vertex, the estimated principal curvature of largest magnitude (signed, before smoothing)
  const std::vector<double>& max_curvatures() const { return m_kmax; }
  /// per vertex, the other estimated principal curvature (signed, before smoothing)
  const std::vector<double>& min_curvatures() const { return m_kmin; }
  /// per vertex, the stretch ratio `s_big / s_small` of the final field, after the gradation (in [1, stretch_max])
  const std::vector<double>& stretch_ratios() const { return m_stretch; }

private:
  // the directed edges of the faces, by tail vertex (CSR), each list in face order: head, face on the left
  typedef internal::Directed_edges<std::uint32_t> Directed_edges;

  // the k-rings of the smoothing (CSR): v first, then breadth-first over the neighbours in face order,
  // following only the edges (x, y) for which `usable(x, y)` holds
  struct Rings {
    std::vector<std::uint32_t> start, vertex;
    template <typename Usable>
    Rings(const Input_surface& s, int rings, unsigned threads, const Usable& usable)
    {
      const std::size_t n = s.number_of_vertices();
      // the neighbours of each vertex in the order its faces list them
      std::vector<std::uint32_t> astart(n + 1, 0), adj;
      for(const auto& t : s.faces())
        for(int k = 0; k < 3; ++k)
          if(usable(t[k], t[(k + 1) % 3])) ++astart[t[k] + 1];
      for(std::size_t v = 0; v < n; ++v) astart[v + 1] += astart[v];
      adj.resize(astart[n]);
      {
        std::vector<std::uint32_t> fill(astart.begin(), astart.end() - 1);
        for(const auto& t : s.faces())
          for(int k = 0; k < 3; ++k)
            if(usable(t[k], t[(k + 1) % 3])) adj[fill[t[k]]++] = std::uint32_t(t[(k + 1) % 3]);
      }
      // twice: the sizes, then the vertices; each block with its own marks
      start.assign(n + 1, 0);
      for(int pass = 0; pass < 2; ++pass) {
        internal::parallel_blocks(n, threads, [&](std::size_t begin, std::size_t end, std::size_t) {
          std::vector<std::uint32_t> mark(n, std::uint32_t(-1)), frontier, next, ring;
          for(std::size_t v = begin; v < end; ++v) {
            ring.assign(1, std::uint32_t(v));
            frontier.assign(1, std::uint32_t(v));
            mark[v] = std::uint32_t(v);
            for(int r = 0; r < rings; ++r) {
              next.clear();
              for(std::uint32_t x : frontier)
                for(std::uint32_t i = astart[x]; i < astart[x + 1]; ++i) {
                  const std::uint32_t y = adj[i];
                  if(mark[y] != v) {
                    mark[y] = std::uint32_t(v);
                    next.push_back(y);
                    ring.push_back(y);
                  }
                }
              frontier.swap(next);
            }
            if(pass == 0) start[v + 1] = std::uint32_t(ring.size());
            else std::copy(ring.begin(), ring.end(), vertex.begin() + start[v]);
          }
        });
        if(pass == 0) {
          for(std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
          vertex.resize(start[n]);
        }
      }
    }
  };

  // eigen-decomposition of M restricted to the tangent plane of n: lambda[0] has the largest |value|
  // the normal-cycle curvature tensor of every vertex (Cohen-Steiner and Morvan 2003: sum over the edges
  // around it of beta |e| / 2 e e^T, beta the signed dihedral angle), not yet divided by `area` (a third of
  // the area of its triangles); the crease edges (both halves) and vertices: |beta| above `feature_angle`
  // degrees (none at 180)
  static void normal_cycle_tensors(const Input_surface& s, const Directed_edges& out, double feature_angle, std::vector<Tensor>& T,
                                   std::vector<double>& area, std::vector<char>& crease_edge, std::vector<char>& crease_vertex)
  {
    const std::size_t n = s.number_of_vertices();
    const auto& P = s.points();
    T.assign(n, Tensor::Zero());
    area.assign(n, 0.0);
    std::vector<Eigen::Vector3d> fn(s.number_of_faces());
    for(std::size_t f = 0; f < s.number_of_faces(); ++f) {
      const auto& t = s.faces()[f];
      const Eigen::Vector3d c = (P[t[1]] - P[t[0]]).cross(P[t[2]] - P[t[0]]);
      fn[f] = c.normalized();
      for(int k = 0; k < 3; ++k) area[t[k]] += c.norm() / 6;
    }
    // each interior edge once, in the order of its (smaller, larger) end, with the faces on its two sides
    const double crease_angle = feature_angle * 3.14159265358979323846 / 180;
    crease_edge.assign(out.head.size(), 0);
    crease_vertex.assign(n, 0);
    for(std::size_t a = 0; a < n; ++a)
      for(std::uint32_t i = out.start[a]; i < out.start[a + 1]; ++i) {
        const std::size_t b = out.head[i];
        if(a > b) continue;
        const std::uint32_t twin = out.find(b, a);
        if(twin == out.none) continue;  // boundary edge: no dihedral angle
        const Eigen::Vector3d d = P[b] - P[a];
        const double len = d.norm();
        const Eigen::Vector3d u = d / len, n1 = fn[out.face[i]], n2 = fn[out.face[twin]];
        const double beta = std::atan2(n1.cross(n2).dot(u), n1.dot(n2));
        if(std::abs(beta) > crease_angle && feature_angle < 180) {
          crease_edge[i] = crease_edge[twin] = 1;
          crease_vertex[a] = crease_vertex[b] = 1;
        }
        const Tensor contribution = beta * len / 2 * u * u.transpose();
        T[a] += contribution;
        T[b] += contribution;
      }
  }

  // stage 3 of the constructor: `M` smoothed over `o.smoothing_rings`-rings that follow no edge between a
  // crease vertex and an ordinary one (crease vertices follow crease edges only), the directions by
  // `o.smoothing_iterations` rounds of log-Euclidean averaging (Arsigny et al. 2006) transported into each
  // tangent plane, the logarithms of the two scales by `o.scale_smoothing_iterations` rounds of plain
  // averaging; then bounded again
  static void smooth(const Input_surface& s, const Directed_edges& out, const std::vector<char>& crease_edge,
                     const std::vector<char>& crease_vertex, const Curvature_metric_options& o, double floor_value, std::vector<Tensor>& M)
  {
    const std::size_t n = s.number_of_vertices();
    const auto& N = s.vertex_normals();
    const unsigned threads = o.number_of_threads;
    // an edge is followed by the rings if it joins two ordinary vertices or is a crease edge
    const auto usable = [&](std::size_t x, std::size_t y) {
      if(crease_vertex[x] != crease_vertex[y]) return false;
      if(!crease_vertex[x]) return true;
      const std::uint32_t i = out.find(x, y);
      return i != out.none ? crease_edge[i] != 0 : crease_edge[out.find(y, x)] != 0;
    };
    // each vertex's tangent frame (t1, t2 = N x t1); L is kept in it as a symmetric 2 x 2 matrix (a, b, c):
    // the tensors are tangent, so this is the 3 x 3 computation without its normal row and column
    std::vector<Eigen::Vector3d> T1(n), T2(n);
    std::vector<Eigen::Vector3d> L(n), tmp(n);
    std::vector<double> log_big(n), log_small(n);
    internal::parallel_for(n, threads, [&](std::size_t v) {
      T1[v] = N[v].unitOrthogonal();
      T2[v] = N[v].cross(T1[v]);
      Eigen::Vector2d l;
      Eigen::Matrix<double, 3, 2> E;
      tangent_eigen(M[v], N[v], l, E);  // both eigenvalues > 0 after `bounded`, l[0] the larger
      log_big[v] = 0.5 * std::log(l[0]);
      log_small[v] = 0.5 * std::log(l[1]);
      const Eigen::Vector2d e0(T1[v].dot(E.col(0)), T2[v].dot(E.col(0))), e1(T1[v].dot(E.col(1)), T2[v].dot(E.col(1)));
      const double g0 = std::log(l[0]), g1 = std::log(l[1]);
      L[v] = Eigen::Vector3d(g0 * e0.x() * e0.x() + g1 * e1.x() * e1.x(), g0 * e0.x() * e0.y() + g1 * e1.x() * e1.y(),
                             g0 * e0.y() * e0.y() + g1 * e1.y() * e1.y());
    });
    const Rings ring(s, o.smoothing_rings, threads, usable);
    if(o.smoothing_iterations > 0) {
      // L[w] is transported into v's tangent plane before it is averaged there (the rotation R taking N[w] to
      // N[v]): averaging tensors of differently oriented tangent planes in space would leak their strong part
      // into the normal and lose anisotropy. In the frames, R t1(w) = cos t1(v) + sin t2(v) and R t2(w) =
      // N[v] x R t1(w): each ring entry's (cos, sin), the same in every round, computed once; (0, 0) for a
      // folded neighbourhood (N[w].N[v] <= -0.5), whose tensor does not describe v and is not averaged.
      std::vector<Eigen::Vector2d> rotation(ring.vertex.size());
      std::vector<std::uint32_t> used(n);
      internal::parallel_for(n, threads, [&](std::size_t v) {
        std::uint32_t u = 0;
        for(std::uint32_t r = ring.start[v]; r < ring.start[v + 1]; ++r) {
          const std::size_t w = ring.vertex[r];
          const Eigen::Vector3d k = N[w].cross(N[v]);
          const double c = N[w].dot(N[v]);
          if(c <= -0.5) {
            rotation[r] = Eigen::Vector2d::Zero();
            continue;
          }
          const Eigen::Vector3d kt = k.cross(T1[w]);
          const Eigen::Vector3d q = T1[w] + kt + k.cross(kt) / (1 + c);
          const Eigen::Vector2d cs_sn(T1[v].dot(q), T2[v].dot(q));
          rotation[r] = cs_sn / cs_sn.norm();
          ++u;
        }
        used[v] = u;  // v itself is always used
      }, 512);
      for(int it = 0; it < o.smoothing_iterations; ++it) {
        internal::parallel_for(n, threads, [&](std::size_t v) {
          Eigen::Vector3d acc = Eigen::Vector3d::Zero();
          for(std::uint32_t r = ring.start[v]; r < ring.start[v + 1]; ++r) {
            const Eigen::Vector3d& m = L[ring.vertex[r]];
            const double cs = rotation[r].x(), sn = rotation[r].y();
            const double cc = cs * cs, ss = sn * sn, cn = cs * sn;
            acc += Eigen::Vector3d(cc * m[0] - 2 * cn * m[1] + ss * m[2], cn * (m[0] - m[2]) + (cc - ss) * m[1],
                                   ss * m[0] + 2 * cn * m[1] + cc * m[2]);
          }
          tmp[v] = acc / double(used[v]);
        }, 512);
        L.swap(tmp);
      }
    }
    if(o.scale_smoothing_iterations > 0) {
      std::vector<double> next_big(n), next_small(n);
      for(int it = 0; it < o.scale_smoothing_iterations; ++it) {
        internal::parallel_for(n, threads, [&](std::size_t v) {
          double big = 0, small = 0;
          for(std::uint32_t r = ring.start[v]; r < ring.start[v + 1]; ++r) {
            big += log_big[ring.vertex[r]];
            small += log_small[ring.vertex[r]];
          }
          next_big[v] = big / double(ring.start[v + 1] - ring.start[v]);
          next_small[v] = small / double(ring.start[v + 1] - ring.start[v]);
        });
        log_big.swap(next_big);
        log_small.swap(next_small);
      }
    }
    internal::parallel_for(n, threads, [&](std::size_t v) {
      // the smoothed directions: the eigenvectors of L on the tangent plane, the larger eigenvalue's
      // taking the larger scale
      Eigen::Matrix2d l2;
      l2 << L[v][0], L[v][1], L[v][1], L[v][2];
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
      es.computeDirect(l2);  // closed form: the iterative solver was a tenth of the metric's time
      const Eigen::Vector3d d_small = T1[v] * es.eigenvectors()(0, 0) + T2[v] * es.eigenvectors()(1, 0);
      const Eigen::Vector3d d_big = T1[v] * es.eigenvectors()(0, 1) + T2[v] * es.eigenvectors()(1, 1);
      const double big = std::exp(log_big[v]), small = std::exp(log_small[v]);
      M[v] = bounded(big * big * d_big * d_big.transpose() + small * small * d_small * d_small.transpose(), N[v],
                     floor_value, o.stretch_max);
    });
  }

  // stage 4 of the constructor: the gradation of `M` (already scaled) along the edges of `s`, the metric
  // lengths those of `M` scaled to an area of `gradation_vertices * sqrt(3) / 2`
  static void grade(const Input_surface& s, const Directed_edges& out, const Curvature_metric_options& o, double floor_value,
                    std::vector<Tensor>& M)
  {
    const std::size_t n = s.number_of_vertices();
    const auto& N = s.vertex_normals();
    const auto& P = s.points();
    // the metric area: sum over the vertices of a third of their faces' area times sqrt(det) on the tangent plane
    std::vector<double> area(n, 0.0);
    for(const auto& t : s.faces()) {
      const double a = (P[t[1]] - P[t[0]]).cross(P[t[2]] - P[t[0]]).norm() / 6;
      for(int k = 0; k < 3; ++k) area[t[k]] += a;
    }
    // the neighbours of each vertex, sorted (CSR), in linear time from `out`
    std::vector<std::uint32_t> start, adj;
    internal::vertex_neighbours(out, n, start, adj);
    double metric_area = 0;
    for(std::size_t v = 0; v < n; ++v) {
      Eigen::Vector2d l;
      Eigen::Matrix<double, 3, 2> E;
      tangent_eigen(M[v], N[v], l, E);
      metric_area += area[v] * std::sqrt(std::abs(l[0] * l[1]));
    }
    const double vertices = double(o.gradation_vertices > 0 ? o.gradation_vertices : n);
    const double scale = metric_area > 0 ? vertices * std::sqrt(3.0) / 2 / metric_area : 1.0;
    internal::grade_metric(M, P, N, start, adj, scale, o.gradation, [&](const Tensor& T, const Eigen::Vector3d& normal) {
      return bounded(T, normal, floor_value, o.stretch_max);
    });
  }

  static void tangent_eigen(const Tensor& M, const Eigen::Vector3d& n, Eigen::Vector2d& lambda, Eigen::Matrix<double, 3, 2>& E)
  {
    const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    Eigen::Matrix<double, 3, 2> B;
    B.col(0) = t1;
    B.col(1) = t2;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
    es.computeDirect(B.transpose() * (0.5 * (M + M.transpose())) * B);  // closed form
    const int big = std::abs(es.eigenvalues()[0]) >= std::abs(es.eigenvalues()[1]) ? 0 : 1;
    lambda = Eigen::Vector2d(es.eigenvalues()[big], es.eigenvalues()[1 - big]);
    E.col(0) = B * es.eigenvectors().col(big);
    E.col(1) = B * es.eigenvectors().col(1 - big);
  }

  // projects on the tangent plane and applies the floor and the stretch bound
  static Tensor bounded(const Tensor& M, const Eigen::Vector3d& n, double floor_value, double stretch_max)
  {
    Eigen::Vector2d l;
    Eigen::Matrix<double, 3, 2> E;
    tangent_eigen(M, n, l, E);
    double big = std::max(std::sqrt(std::abs(l[0])), floor_value);
    double small = std::max(std::sqrt(std::abs(l[1])), big / stretch_max);
    small = std::max(small, floor_value * floor_value / big);  // isotropic where big is at the floor
    small = std::min(small, big);
    return big * big * E.col(0) * E.col(0).transpose() + small * small * E.col(1) * E.col(1).transpose();
  }

  Tensor_field_metric m_field;
  std::vector<double> m_kmin, m_kmax, m_stretch;
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_CURVATURE_METRIC_H
