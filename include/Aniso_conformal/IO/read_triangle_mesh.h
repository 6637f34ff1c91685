// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_READ_TRIANGLE_MESH_H
#define ANISO_CONFORMAL_IO_READ_TRIANGLE_MESH_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/IO/Repair_report.h>
#include <Aniso_conformal/IO/repair_polygon_soup.h>
#include <Aniso_conformal/Input_surface.h>
#include <Aniso_conformal/internal/printable.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

/// \file read_triangle_mesh.h

namespace Aniso_conformal {
namespace IO {

namespace internal {
typedef CGAL::Simple_cartesian<double>::Point_3 Soup_point;

// what a message may quote of a file: its first 40 bytes, non-printable ones escaped (a garbage file must
// not put raw binary into a terminal or a log)
inline std::string quote(const std::string& token) { return Aniso_conformal::internal::printable(token, 40); }

inline std::string extension_of(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for(char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// Keep the two hardened readers below (our OFF parser, our PLY header check): they work around bugs that
// the fuzzers (doc/fuzzing.md, fuzz/) found in CGAL 5.5's OFF and PLY readers, which we do not patch, and
// test_io.cpp replays those inputs (fuzz_regressions_off, fuzz_regressions_ply).
//
// ASCII OFF is read here, not by CGAL's File_scanner_OFF: fuzzing (doc/fuzzing.md) found that one reads
// out of bounds on texture (ST) vertices, casts any double of a face line to a vertex count, and sizes its
// arrays from header counts before reading anything. This parser is strict and line based: it accepts
// OFF, COFF, NOFF and CNOFF (extra numbers after the coordinates or after a face's indices, such as
// normals and colours, are ignored) and checks every count against what the file can hold.
inline void read_off_soup(const std::string& path, std::vector<Soup_point>& points,
                          std::vector<std::vector<std::size_t>>& polygons)
{
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream lines(text);
  std::string line;
  std::size_t line_no = 0;
  auto fail = [&](const std::string& what) -> void {
    throw Invalid_input("file " + path + ", line " + std::to_string(line_no) + ": " + what);
  };
  // the whitespace-separated tokens of the next line with something before its '#'
  auto next_tokens = [&](std::vector<std::string>& tokens) {
    tokens.clear();
    while(tokens.empty() && std::getline(lines, line)) {
      ++line_no;
      std::istringstream ls(line.substr(0, line.find('#')));
      for(std::string t; ls >> t;) tokens.push_back(t);
    }
    return !tokens.empty();
  };
  auto to_index = [&](const std::string& t, const char* what) -> std::size_t {
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(t.c_str(), &end, 10);
    if(t.empty() || end != t.c_str() + t.size() || errno == ERANGE || v < 0)  // all of it, NUL bytes too
      fail("'" + quote(t) + "' is not a valid " + what);
    return std::size_t(v);
  };
  std::vector<std::string> tok;
  if(!next_tokens(tok)) throw Invalid_input("file " + path + ": empty");
  const std::string magic = tok[0];
  if(magic != "OFF" && magic != "COFF" && magic != "NOFF" && magic != "CNOFF")
    fail("'" + quote(magic) + "' is not a supported OFF header (ASCII OFF, COFF, NOFF or CNOFF)");
  tok.erase(tok.begin());
  if(!tok.empty() && tok[0] == "BINARY") fail("binary OFF is not supported (use ASCII OFF, OBJ or PLY)");
  if(tok.empty() && !next_tokens(tok)) fail("missing vertex and face counts");
  if(tok.size() < 2) fail("expected the vertex and face counts");
  const std::size_t nv = to_index(tok[0], "vertex count"), nf = to_index(tok[1], "face count");
  // a vertex line takes at least 5 bytes ("0 0 0"), a face at least 7 ("3 0 1 2"): a header claiming
  // more than the file can hold is refused before anything is allocated
  if(nv > text.size() / 5 || nf > text.size() / 7 || 5 * nv + 7 * nf > text.size())
    fail("the header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) + " faces, more than the " +
         std::to_string(text.size()) + "-byte file can hold");
  points.reserve(nv);
  for(std::size_t i = 0; i < nv; ++i) {
    if(!next_tokens(tok)) fail("truncated after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    if(tok.size() < 3) fail("vertex " + std::to_string(i) + " has fewer than 3 coordinates");
    double x[3];
    for(int k = 0; k < 3; ++k) {
      const std::string& t = tok[std::size_t(k)];
      char* end = nullptr;
      x[k] = std::strtod(t.c_str(), &end);
      if(end != t.c_str() + t.size()) fail("vertex " + std::to_string(i) + ": '" + quote(t) + "' is not a number");  // NUL bytes too
    }
    points.emplace_back(x[0], x[1], x[2]);
  }
  polygons.reserve(nf);
  for(std::size_t f = 0; f < nf; ++f) {
    if(!next_tokens(tok)) fail("truncated after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const std::size_t k = to_index(tok[0], "face size");
    if(k == 0 || k >= tok.size())
      fail("face " + std::to_string(f) + " declares " + std::to_string(k) + " vertices but lists " + std::to_string(tok.size() - 1));
    std::vector<std::size_t> poly(k);
    for(std::size_t j = 0; j < k; ++j) {
      poly[j] = to_index(tok[j + 1], "vertex index");
      if(poly[j] >= nv)
        fail("face " + std::to_string(f) + " refers to vertex " + quote(tok[j + 1]) + ", but the file has " + std::to_string(nv) + " vertices");
    }
    polygons.push_back(std::move(poly));
  }
}

// CGAL's PLY_reader trusts the header: fuzzing found that a property before any element reads the back of
// an empty vector, and by reading the code, element counts and 32-bit list lengths size its arrays before
// any data is read and a floating-point list length is cast to an integer. This checks the header first:
// known keywords and types only, list lengths of 8 or 16 bits, and element counts that fit the file.
inline void check_ply_header(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const std::streamoff file_size = in.tellg();
  in.seekg(0);
  const std::string bad = "file " + path + ": ";
  auto scalar_size = [](const std::string& t) -> std::size_t {
    if(t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if(t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if(t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
    if(t == "double" || t == "float64") return 8;
    return 0;
  };
  struct Element { std::string name; std::size_t count, min_bytes; std::vector<std::pair<std::string, std::string>> properties; };
  std::vector<Element> elements;
  std::string line, word;
  bool binary = false, ended = false;
  for(std::size_t line_no = 1; !ended && std::getline(in, line); ++line_no) {
    const std::string at = bad + "PLY header line " + std::to_string(line_no) + ": ";
    std::istringstream ls(line);
    if(!(ls >> word)) throw Invalid_input(at + "empty line");
    if(line_no == 1) {
      if(word != "ply") throw Invalid_input(bad + "not a PLY file (no 'ply' magic)");
    } else if(line_no == 2) {
      std::string format, version;
      if(word != "format" || !(ls >> format >> version) ||
         (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian"))
        throw Invalid_input(at + "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      binary = format != "ascii";
    } else if(word == "comment" || word == "obj_info") {
    } else if(word == "element") {
      std::string name, count;
      if(!(ls >> name >> count) || count.find_first_not_of("0123456789") != std::string::npos || count.size() > 18)
        throw Invalid_input(at + "expected 'element NAME COUNT'");
      elements.push_back({name, std::size_t(std::stoull(count)), 0, {}});
    } else if(word == "property") {
      if(elements.empty()) throw Invalid_input(at + "a property before any element");
      std::string type, size_type, name;
      if(!(ls >> type)) throw Invalid_input(at + "expected 'property TYPE NAME'");
      if(type == "list") {
        if(!(ls >> size_type >> type >> name)) throw Invalid_input(at + "expected 'property list COUNT_TYPE TYPE NAME'");
        if(scalar_size(size_type) == 0 || scalar_size(size_type) > 2)
          throw Invalid_input(at + "list length type '" + quote(size_type) +
                              "' not supported (use uchar or ushort)");
      } else if(!(ls >> name)) {
        throw Invalid_input(at + "expected 'property TYPE NAME'");
      }
      if(scalar_size(type) == 0) throw Invalid_input(at + "unknown property type '" + quote(type) + "'");
      elements.back().properties.emplace_back(name, size_type.empty() ? type : "list");
      // the least an item can take: the fixed sizes in binary, a digit per property in ASCII
      elements.back().min_bytes += binary ? (size_type.empty() ? scalar_size(type) : scalar_size(size_type)) : 1;
    } else if(word == "end_header") {
      ended = true;
    } else {
      throw Invalid_input(at + "unknown keyword '" + quote(word) + "'");
    }
  }
  if(!ended) throw Invalid_input(bad + "PLY header without end_header");
  // CGAL reads these properties by name and casts them to one type without checking (a null dereference,
  // found by fuzzing, when x is not a float or double)
  for(const Element& e : elements) {
    const bool vertex = e.name == "vertex" || e.name == "vertices", face = e.name == "face" || e.name == "faces";
    int xyz = 0;
    for(const auto& [name, type] : e.properties) {
      const bool coordinate = vertex && (name == "x" || name == "y" || name == "z");
      const bool colour = (vertex || face) && (name == "red" || name == "green" || name == "blue" || name == "r" ||
                                               name == "g" || name == "b");
      const bool halfedge_id = e.name == "halfedge" && (name == "source" || name == "target");
      const bool halfedge_uv = e.name == "halfedge" && (name == "u" || name == "v");
      const bool ok = coordinate ? (type == "float" || type == "float32" || type == "double" || type == "float64")
                    : colour ? (type == "uchar" || type == "uint8")
                    : halfedge_id ? (type == "uint" || type == "uint32")
                    : halfedge_uv ? (type == "float" || type == "float32") : true;
      if(!ok)
        throw Invalid_input(bad + "PLY property '" + quote(name) + "' of element '" + quote(e.name) + "' cannot have type " + quote(type));
      xyz += coordinate;
    }
    if(vertex && xyz != 3) throw Invalid_input(bad + "PLY element '" + quote(e.name) + "' needs the properties x, y and z once each");
  }
  const std::streamoff body = in.tellg() < 0 ? 0 : file_size - in.tellg();
  std::size_t left = std::size_t(std::max<std::streamoff>(body, 0));
  for(const Element& e : elements) {
    if(e.count == 0) continue;
    if(e.min_bytes == 0 || e.count > left / e.min_bytes)
      throw Invalid_input(bad + "PLY element '" + quote(e.name) + "' declares " + std::to_string(e.count) +
                          " items, more than the " + std::to_string(left) + " bytes left in the file can hold");
    left -= e.count * e.min_bytes;
  }
}
} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * reads the polygon soup of an OFF, OBJ or PLY file (by extension): positions and polygons of any size,
 * as they are in the file (nothing is checked but the syntax and the counts). OFF files are ASCII `OFF`,
 * `COFF`, `NOFF` or `CNOFF` (extra numbers on a line are ignored), read by our own parser; OBJ and PLY
 * by CGAL's (`CGAL::IO::read_polygon_soup()`), after a check of the PLY header.
 * \throws Invalid_input naming the file if it cannot be opened or parsed, has an unsupported extension,
 *         declares more vertices or faces than it can hold, or holds no vertex or no face
 */
inline void read_polygon_soup(const std::string& path, std::vector<Eigen::Vector3d>& points,
                              std::vector<std::vector<std::size_t>>& polygons)
{
  const std::string ext = internal::extension_of(path);
  if(ext != "off" && ext != "obj" && ext != "ply")
    throw Invalid_input("file " + path + ": unsupported extension (use .off, .obj or .ply)");
  if(!std::ifstream(path).good()) throw Invalid_input("file " + path + ": cannot be opened");
  std::vector<internal::Soup_point> soup_points;
  std::vector<std::vector<std::size_t>> soup_polygons;
  bool ok = false;
  try {
    if(ext == "off") {
      internal::read_off_soup(path, soup_points, soup_polygons);
      ok = true;
    } else {
      if(ext == "ply") internal::check_ply_header(path);
      ok = CGAL::IO::read_polygon_soup(path, soup_points, soup_polygons, CGAL::parameters::verbose(false));
    }
  } catch(const Invalid_input&) {
    throw;
  } catch(const std::exception& e) {
    throw Invalid_input("file " + path + ": cannot be parsed (" + Aniso_conformal::internal::printable(e.what(), 200) + ")");
  }
  if(!ok) throw Invalid_input("file " + path + ": cannot be parsed as " + ext);
  if(soup_points.empty() || soup_polygons.empty()) throw Invalid_input("file " + path + ": the mesh is empty");
  points.clear();
  points.reserve(soup_points.size());
  for(const auto& p : soup_points) points.emplace_back(p.x(), p.y(), p.z());
  polygons = std::move(soup_polygons);
}

/*!
 * \ingroup PkgAnisoConformalIO
 * reads a mesh from an OFF, OBJ or PLY file (`read_polygon_soup()`), repairs it
 * (`repair_polygon_soup()` with `options`: polygons triangulated, duplicated points welded, points of no
 * face dropped, faces oriented consistently, outward if closed, a clockwise planar input handed over
 * counter-clockwise) and validates it (`Input_surface`). The file is only read.
 *
 * A metric file indexed by the file's vertices lines up with the result through `report.kept_vertex`
 * (`read_metric_file(path, report)`), and a remeshed output gets the input's orientation back with
 * `restore_input_orientation(faces, report)`.
 * \param path the file
 * \param report receives what was repaired and the index maps (written only on success)
 * \param options the repairs to make (default: all; `Repair_options::none()`: none, as `read_triangle_mesh(path)`)
 * \throws Invalid_input naming the file, as `read_polygon_soup()`, `repair_polygon_soup()` and
 *         `Input_surface` do (vertices and faces by their index in the file); when the repairs are off,
 *         a fault that one of them would have repaired says that the file was read without repairs
 */
inline Input_surface read_triangle_mesh(const std::string& path, Repair_report& report,
                                        const Repair_options& options = Repair_options())
{
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<std::size_t>> polygons;
  read_polygon_soup(path, points, polygons);
  try {
    return input_surface_from_polygon_soup(std::move(points), std::move(polygons), report, options);
  } catch(const Invalid_input& e) {
    throw Invalid_input("file " + path + ": " + e.what() + (options.any() ? "" : " (the file was read without repairs)"));
  }
}

/*!
 * \ingroup PkgAnisoConformalIO
 * reads a triangle mesh from an OFF, OBJ or PLY file (by extension) and validates it (`Input_surface`),
 * repairing nothing: the file must hold a valid triangle mesh as it is. `read_triangle_mesh(path, report)`
 * repairs what a user expects to be repaired.
 * \throws Invalid_input naming the file if it cannot be opened or parsed, has an unsupported extension,
 *         declares more vertices or faces than it can hold, or has a face that is not a triangle; and as
 *         `Input_surface` does for a broken mesh
 */
inline Input_surface read_triangle_mesh(const std::string& path)
{
  Repair_report report;
  return read_triangle_mesh(path, report, Repair_options::none());
}

/*!
 * \ingroup PkgAnisoConformalIO
 * writes a triangle mesh as OFF, OBJ or PLY (by extension), with full double precision.
 * \throws Invalid_input if the extension is not supported or the file cannot be written
 */
inline void write_polygon_soup(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                               const std::vector<std::array<std::size_t, 3>>& faces)
{
  const std::string ext = internal::extension_of(path);
  if(ext != "off" && ext != "obj" && ext != "ply")
    throw Invalid_input("cannot write " + path + ": unsupported extension (use .off, .obj or .ply)");
  std::vector<internal::Soup_point> pts;
  pts.reserve(points.size());
  for(const auto& p : points) pts.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<std::size_t>> polys;
  polys.reserve(faces.size());
  for(const auto& f : faces) polys.push_back({f[0], f[1], f[2]});
  bool ok = false;
  try {
    ok = CGAL::IO::write_polygon_soup(path, pts, polys, CGAL::parameters::stream_precision(17));
  } catch(const std::exception&) {
    ok = false;
  }
  if(!ok) throw Invalid_input("cannot write " + path);
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_READ_TRIANGLE_MESH_H
