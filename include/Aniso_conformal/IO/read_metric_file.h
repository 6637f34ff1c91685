// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_READ_METRIC_FILE_H
#define ANISO_CONFORMAL_IO_READ_METRIC_FILE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/IO/Repair_report.h>
#include <Aniso_conformal/Tensor_field_metric.h>
#include <Aniso_conformal/internal/printable.h>

#include <Eigen/Core>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

/// \file read_metric_file.h

namespace Aniso_conformal {
namespace IO {

/*!
 * \ingroup PkgAnisoConformalIO
 * reads a metric file: an ASCII file whose first line is the number of vertices, then one line per
 * vertex, in input order, `m11 m12 m13 m22 m23 m33` (the symmetric 3x3 tensor; z parts 0 for planar
 * input). Blank lines and lines starting with `#` are skipped.
 * Positive definiteness on the tangent plane is checked later by the pipeline, which knows the normals.
 * \throws Invalid_input naming the file and line: unreadable file, bad header, a count different from
 *         `expected_vertices`, a line without exactly six numbers, a non-finite entry, missing or extra rows
 */
inline Tensor_field_metric read_metric_file(const std::string& path, std::size_t expected_vertices)
{
  std::ifstream in(path);
  if(!in) throw Invalid_input("metric file " + path + ": cannot be opened");
  std::string line;
  std::size_t line_no = 0;
  auto next_line = [&](std::string& out) {
    while(std::getline(in, out)) {
      ++line_no;
      const std::size_t k = out.find_first_not_of(" \t\r");
      if(k == std::string::npos || out[k] == '#') continue;
      return true;
    }
    return false;
  };
  const std::string where = "metric file " + path + ", line ";
  if(!next_line(line)) throw Invalid_input("metric file " + path + ": empty");
  std::istringstream header(line);
  long long declared = -1;
  std::string rest;
  if(!(header >> declared) || (header >> rest) || declared < 0)
    throw Invalid_input(where + std::to_string(line_no) + ": the first line must be the number of vertices");
  if(std::size_t(declared) != expected_vertices)
    throw Invalid_input("metric file " + path + " declares " + std::to_string(declared) + " tensors but the mesh has " +
                        std::to_string(expected_vertices) + " vertices");
  std::vector<Eigen::Matrix3d> tensors;
  tensors.reserve(expected_vertices);
  while(next_line(line)) {
    const std::string at = where + std::to_string(line_no) + " (vertex " + std::to_string(tensors.size()) + ")";
    if(tensors.size() == expected_vertices)
      throw Invalid_input(where + std::to_string(line_no) + ": more rows than the " + std::to_string(declared) + " declared");
    std::istringstream row(line);
    std::vector<double> v;
    std::string token;
    while(row >> token) {
      errno = 0;
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      // the whole token must be the number (a NUL byte inside it too); a quoted token is cut to 40 bytes
      // with the non-printable ones escaped: the file may be anything
      if(end != token.c_str() + token.size()) throw Invalid_input(at + ": '" + Aniso_conformal::internal::printable(token, 40) + "' is not a number");
      if(!std::isfinite(x) || errno == ERANGE)
        throw Invalid_input(at + ": non-finite entry '" + Aniso_conformal::internal::printable(token, 40) + "'");
      v.push_back(x);
    }
    if(v.size() != 6)
      throw Invalid_input(at + ": " + std::to_string(v.size()) + " numbers, expected 6 (m11 m12 m13 m22 m23 m33)");
    Eigen::Matrix3d M;
    M << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
    tensors.push_back(M);
  }
  if(tensors.size() != expected_vertices)
    throw Invalid_input("metric file " + path + ": " + std::to_string(tensors.size()) + " rows, but " +
                        std::to_string(declared) + " declared");
  return Tensor_field_metric(std::move(tensors));
}

/*!
 * \ingroup PkgAnisoConformalIO
 * reads a metric file written for the vertices of a mesh file that was repaired on reading
 * (`read_triangle_mesh(path, repairs)`): the file has one row per vertex of the mesh file, in its order
 * (`repairs.kept_vertex.size()` rows, every one checked as `read_metric_file(path, n)` does), and the
 * metric returned has one tensor per vertex of the repaired surface: the row of the vertex it was kept
 * as, or, for points welded into one, the row of the first of them. The rows of dropped vertices (points
 * of no face) are ignored.
 * \throws Invalid_input as `read_metric_file(path, n)` with `n` the mesh file's vertex count, or if
 *         `repairs` holds no vertex map (it was not filled by a repair)
 */
inline Tensor_field_metric read_metric_file(const std::string& path, const Repair_report& repairs)
{
  if(repairs.kept_vertex.empty() || repairs.input_vertex.empty())
    throw Invalid_input("read_metric_file(): the Repair_report has no vertex map (fill it with read_triangle_mesh(path, report))");
  const Tensor_field_metric all = read_metric_file(path, repairs.kept_vertex.size());
  std::vector<Tensor_field_metric::Tensor> kept;
  kept.reserve(repairs.input_vertex.size());
  for(std::size_t i : repairs.input_vertex) kept.push_back(all.tensors().at(i));
  return Tensor_field_metric(std::move(kept));
}

/*!
 * \ingroup PkgAnisoConformalIO
 * writes `tensors` in the format `read_metric_file()` reads (the upper triangle of each tensor).
 * \throws Invalid_input if the file cannot be written
 */
inline void write_metric_file(const std::string& path, const std::vector<Eigen::Matrix3d>& tensors)
{
  std::ofstream out(path);
  out << tensors.size() << "\n" << std::setprecision(17);
  for(const auto& M : tensors)
    out << M(0, 0) << ' ' << M(0, 1) << ' ' << M(0, 2) << ' ' << M(1, 1) << ' ' << M(1, 2) << ' ' << M(2, 2) << '\n';
  if(!out) throw Invalid_input("cannot write " + path);
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_READ_METRIC_FILE_H
