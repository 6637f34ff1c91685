// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_READ_FEATURE_FILE_H
#define ANISO_CONFORMAL_IO_READ_FEATURE_FILE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/IO/Repair_report.h>

#include <array>
#include <cctype>
#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

/// \file read_feature_file.h

namespace Aniso_conformal {
namespace IO {

/*!
 * \ingroup PkgAnisoConformalIO
 * sharp features a user marks on an input mesh (issue 15, item 1): edges to keep as creases and vertices
 * to keep as corners, as indices of the mesh's vertices (`detect_features()`'s `marked_edges` and
 * `marked_vertices`; `remesh()`'s named parameters `feature_edges` and `feature_vertices`).
 */
struct Marked_features {
  std::vector<std::array<std::size_t, 2>> edges;  ///< crease edges, as pairs of vertex indices, in file order
  std::vector<std::size_t> vertices;              ///< corner vertices, in file order
};

namespace internal {

// the non-negative decimal integers of `line` (false if it holds anything else: a sign, a dot, a letter,
// a number above 2^63)
inline bool read_indices(const std::string& line, std::vector<std::size_t>& out)
{
  out.clear();
  std::size_t i = 0;
  while(i < line.size()) {
    const unsigned char c = static_cast<unsigned char>(line[i]);
    if(c == ' ' || c == '\t' || c == '\r') {
      ++i;
      continue;
    }
    if(!std::isdigit(c)) return false;
    unsigned long long v = 0;
    std::size_t digits = 0;
    while(i < line.size() && std::isdigit(static_cast<unsigned char>(line[i]))) {
      if(++digits > 18) return false;
      v = 10 * v + static_cast<unsigned long long>(line[i] - '0');
      ++i;
    }
    out.push_back(std::size_t(v));
  }
  return true;
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * reads a feature file: an ASCII file with one feature per line, two vertex indices for a crease edge
 * (`12 57`) or one for a corner (`8`), indices counted from 0 in the order of the mesh file's vertices.
 * Blank lines and everything after a `#` are skipped. Whether the edges exist is checked by
 * `detect_features()`, which knows the mesh.
 * \param path the file
 * \param number_of_vertices the mesh's vertex count: every index must be below it
 * \returns the marked edges and vertices, in file order
 * \throws Invalid_input naming the file and line (never quoting its bytes): unreadable file, a line with
 *         anything but one or two non-negative integers, an index of no vertex, an edge from a vertex to itself
 */
inline Marked_features read_feature_file(const std::string& path, std::size_t number_of_vertices)
{
  std::ifstream in(path);
  if(!in) throw Invalid_input("feature file " + path + ": cannot be opened");
  Marked_features m;
  std::string line;
  std::vector<std::size_t> v;
  for(std::size_t line_no = 1; std::getline(in, line); ++line_no) {
    const std::size_t hash = line.find('#');
    if(hash != std::string::npos) line.erase(hash);
    const std::string at = "feature file " + path + ", line " + std::to_string(line_no) + ": ";
    if(!internal::read_indices(line, v) || v.size() > 2)
      throw Invalid_input(at + "expected one vertex index (a corner) or two (a crease edge), non-negative integers");
    if(v.empty()) continue;
    for(std::size_t i : v)
      if(i >= number_of_vertices)
        throw Invalid_input(at + "vertex " + std::to_string(i) + " does not exist (the mesh has " + std::to_string(number_of_vertices) +
                            ", counted from 0)");
    if(v.size() == 1) {
      m.vertices.push_back(v[0]);
    } else {
      if(v[0] == v[1]) throw Invalid_input(at + "an edge from vertex " + std::to_string(v[0]) + " to itself");
      m.edges.push_back({{v[0], v[1]}});
    }
  }
  if(in.bad()) throw Invalid_input("feature file " + path + ": read error");
  return m;
}

/*!
 * \ingroup PkgAnisoConformalIO
 * reads a feature file written for the vertices of a mesh file that was repaired on reading
 * (`read_triangle_mesh(path, repairs)`): the indices are the mesh file's, and are mapped to the repaired
 * surface's vertices through `repairs.kept_vertex` (welded points become their shared vertex).
 * \throws Invalid_input as `read_feature_file(path, n)` with n the mesh file's point count, and if a
 *         feature names a point that was dropped (it belongs to no face), an edge's two points were welded
 *         into one vertex, or `repairs` holds no vertex map
 */
inline Marked_features read_feature_file(const std::string& path, const Repair_report& repairs)
{
  if(repairs.kept_vertex.empty())
    throw Invalid_input("read_feature_file(): the Repair_report has no vertex map (fill it with read_triangle_mesh(path, report))");
  const Marked_features file = read_feature_file(path, repairs.kept_vertex.size());
  auto kept = [&](std::size_t i) {
    const std::size_t k = repairs.kept_vertex[i];
    if(k == Repair_report::dropped)
      throw Invalid_input("feature file " + path + ": vertex " + std::to_string(i) + " belongs to no face of the mesh (it was dropped)");
    return k;
  };
  Marked_features m;
  for(std::size_t v : file.vertices) m.vertices.push_back(kept(v));
  for(const auto& e : file.edges) {
    const std::size_t a = kept(e[0]), b = kept(e[1]);
    if(a == b)
      throw Invalid_input("feature file " + path + ": the edge (" + std::to_string(e[0]) + ", " + std::to_string(e[1]) +
                          ") joins two points that were welded into one vertex");
    m.edges.push_back({{a, b}});
  }
  return m;
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_READ_FEATURE_FILE_H
