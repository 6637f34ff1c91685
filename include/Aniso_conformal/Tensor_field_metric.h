// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_TENSOR_FIELD_METRIC_H
#define ANISO_CONFORMAL_TENSOR_FIELD_METRIC_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/Surface_point.h>

#include <CGAL/boost/graph/named_params_helper.h>

#include <Eigen/Core>

#include <string>
#include <vector>

/// \file Tensor_field_metric.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMetrics
 * a metric given by one symmetric 3x3 tensor per input vertex, interpolated linearly inside the
 * triangles. On a surface a tensor may be singular along the normal (paper eq. 4); it must be
 * positive definite on the tangent plane (`remesh()` checks this and throws `Invalid_input`).
 *
 * \cgalModels `AnisotropicMetric`
 */
class Tensor_field_metric {
public:
  /// the tensor type
  typedef Eigen::Matrix3d Tensor;

  /// builds the metric from `tensors[i]`, the tensor at the input vertex of index `i`
  explicit Tensor_field_metric(std::vector<Tensor> tensors) : m_tensors(std::move(tensors)) {}

  /*!
   * builds the metric from a property map `tensor_map` (vertex descriptor to a type with `operator()(i,j)`,
   * e.g.\ `Eigen::Matrix3d`) on the mesh `tm`, indexed like `remesh()` indexes vertices (the vertex index map of `np`).
   */
  template <typename TriangleMesh, typename TensorMap, typename NamedParameters = CGAL::parameters::Default_named_parameters>
  Tensor_field_metric(const TriangleMesh& tm, TensorMap tensor_map,
                      const NamedParameters& np = CGAL::parameters::default_values())
  {
    auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    m_tensors.resize(num_vertices(tm));
    for(auto v : vertices(tm)) {
      const auto& t = get(tensor_map, v);
      Tensor M;
      for(int i = 0; i < 3; ++i)
        for(int j = 0; j < 3; ++j) M(i, j) = t(i, j);
      m_tensors[get(vim, v)] = M;
    }
  }

  /// the tensor at `p`: the barycentric combination of the tensors at the corners of its triangle
  Tensor tensor(const Surface_point& p) const
  {
    Tensor M = Tensor::Zero();
    for(int k = 0; k < 3; ++k) {
      if(p.barycentric[k] == 0) continue;
      if(p.vertices[k] >= m_tensors.size())
        throw Invalid_input("the tensor field has " + std::to_string(m_tensors.size()) +
                            " tensors but the mesh refers to vertex " + std::to_string(p.vertices[k]));
      M += p.barycentric[k] * m_tensors[p.vertices[k]];
    }
    return M;
  }

  /// number of tensors (must equal the number of input vertices)
  std::size_t size() const { return m_tensors.size(); }
  /// the tensors, indexed by vertex index
  const std::vector<Tensor>& tensors() const { return m_tensors; }

private:
  std::vector<Tensor> m_tensors;
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_TENSOR_FIELD_METRIC_H
