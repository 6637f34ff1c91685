// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_WRITE_SVG_H
#define ANISO_CONFORMAL_IO_WRITE_SVG_H

#include <Aniso_conformal/Exceptions.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

/// \file write_svg.h

namespace Aniso_conformal {
namespace IO {

namespace internal {
// red (low) -> yellow -> green (high), as 0..255 components
inline std::array<int, 3> ramp_rgb(double t)
{
  t = std::min(1.0, std::max(0.0, t));
  const int r = t < 0.5 ? 230 : int(230 * (1 - t) * 2), g = t < 0.5 ? int(60 + 170 * t * 2) : 200;
  return {{std::max(0, r), std::min(255, g), 60}};
}
inline std::string hex_colour(const std::array<int, 3>& c)
{
  char buf[16];
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", c[0], c[1], c[2]);
  return buf;
}
// red (low) -> yellow -> green (high)
inline std::string ramp(double t) { return hex_colour(ramp_rgb(t)); }
inline std::string escape(const std::string& s)
{
  std::string o;
  for(char c : s) o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return o;
}
// the colour legend: ten boxes of the ramp from x = left to left + 300 at height y, vmin and vmax at its ends
inline void write_legend(std::ostream& out, double left, double y, double vmin, double vmax)
{
  char buf[256];
  for(int i = 0; i < 10; ++i) {
    std::snprintf(buf, sizeof(buf), "<rect x=\"%.0f\" y=\"%.0f\" width=\"30\" height=\"12\" fill=\"%s\"/>\n", left + 30 * i, y,
                  ramp((i + 0.5) / 10).c_str());
    out << buf;
  }
  std::snprintf(buf, sizeof(buf),
                "<text x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\" text-anchor=\"end\">%.2f</text>\n"
                "<text x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\">%.2f</text>\n",
                left - 5, y + 11, vmin, left + 305, y + 11, vmax);
  out << buf;
}

// the values of the cells of a CVT picture in colour classes: 20 classes from the smallest to the largest
// finite value on the ramp, or one pale class when there are no values
struct Colour_classes {
  double vmin = 1e300, vmax = -1e300;
  int count = 1;
  explicit Colour_classes(const std::vector<double>& values)
  {
    for(double v : values)
      if(std::isfinite(v)) { vmin = std::min(vmin, v); vmax = std::max(vmax, v); }
    if(vmin > vmax) vmin = vmax = 0;
    count = values.empty() ? 1 : 20;
  }
  // the class of `values[i]` (0 for a non-finite value, or when all values are equal)
  int of(const std::vector<double>& values, std::size_t i) const
  {
    if(values.empty() || !(vmax > vmin) || !std::isfinite(values[i])) return 0;
    return std::min(count - 1, std::max(0, int((values[i] - vmin) / (vmax - vmin) * count)));
  }
  // the filled paths of the classes, `paths[first + c]` for class c, skipping empty ones
  void write_paths(std::ostream& out, const std::vector<std::string>& paths, std::size_t first, bool pale) const
  {
    for(int c = 0; c < count; ++c) {
      const std::string& d = paths[first + std::size_t(c)];
      if(d.empty()) continue;
      out << "<path fill=\"" << (pale ? std::string("#eef2f8") : ramp((c + 0.5) / count)) << "\" d=\"" << d << "\"/>\n";
    }
  }
};

// appends a closed polygon to an SVG path: "M p0 L p1 p2 ... Z", each point as `xy` writes it
template <typename Polygon, typename XY>
void append_polygon(std::string& d, const Polygon& polygon, XY&& xy)
{
  for(std::size_t k = 0; k < polygon.size(); ++k) d += (k == 0 ? "M" : k == 1 ? "L" : " ") + xy(polygon[k]);
  d += "Z";
}

// opens an SVG picture of `width` x `height` on white with `title` in its top left corner at x = `left`
inline std::ofstream open_svg(const std::string& path, double width, double height, double left, const std::string& title)
{
  std::ofstream out(path);
  if(!out) throw Invalid_input("cannot write " + path);
  char buf[256];
  std::snprintf(buf, sizeof(buf), "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\">\n",
                width, height, width, height);
  out << buf << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<text x=\"" << left << "\" y=\"24\" font-family=\"sans-serif\" font-size=\"16\">" << escape(title) << "</text>\n";
  return out;
}

// closes the picture
inline void close_svg(std::ofstream& out, const std::string& path)
{
  out << "</svg>\n";
  if(!out) throw Invalid_input("cannot write " + path);
}
} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * draws a planar mesh (x, y; y up) as SVG, triangles filled by `face_values` on a red-yellow-green ramp
 * from `vmin` to `vmax`, with thin edges, a legend and a title.
 * \throws Invalid_input if the file cannot be written
 */
inline void write_svg(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                      const std::vector<std::array<std::size_t, 3>>& faces, const std::vector<double>& face_values,
                      double vmin, double vmax, const std::string& title)
{
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for(const auto& p : points) { x0 = std::min(x0, p.x()); y0 = std::min(y0, p.y()); x1 = std::max(x1, p.x()); y1 = std::max(y1, p.y()); }
  if(points.empty()) { x0 = y0 = 0; x1 = y1 = 1; }
  const double W = 800, scale = W / std::max(1e-300, x1 - x0), H = (y1 - y0) * scale, top = 40, bottom = 50;
  std::ofstream out(path);
  if(!out) throw Invalid_input("cannot write " + path);
  char buf[256];
  std::snprintf(buf, sizeof(buf), "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"-10 0 %.0f %.0f\">\n",
                W + 20, H + top + bottom, W + 20, H + top + bottom);
  out << buf << "<rect x=\"-10\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<text x=\"0\" y=\"24\" font-family=\"sans-serif\" font-size=\"16\">" << internal::escape(title) << "</text>\n";
  out << "<g stroke=\"#333\" stroke-width=\"0.4\" stroke-linejoin=\"round\">\n";
  for(std::size_t f = 0; f < faces.size(); ++f) {
    const double v = f < face_values.size() ? (face_values[f] - vmin) / std::max(1e-300, vmax - vmin) : 1.0;
    out << "<polygon points=\"";
    for(int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = points[faces[f][std::size_t(k)]];
      std::snprintf(buf, sizeof(buf), "%.2f,%.2f ", (p.x() - x0) * scale, top + (y1 - p.y()) * scale);
      out << buf;
    }
    out << "\" fill=\"" << internal::ramp(v) << "\"/>\n";
  }
  out << "</g>\n";
  internal::write_legend(out, 400, H + top + 18, vmin, vmax);
  out << "</svg>\n";
  if(!out) throw Invalid_input("cannot write " + path);
}

/*!
 * \ingroup PkgAnisoConformalIO
 * draws an angle histogram (bins of `bin_width` degrees from 0) as an SVG bar chart.
 * \throws Invalid_input if the file cannot be written
 */
inline void write_histogram_svg(const std::string& path, const std::vector<double>& counts, double bin_width,
                                const std::string& title)
{
  std::ofstream out(path);
  if(!out) throw Invalid_input("cannot write " + path);
  const double W = 720, H = 300, left = 50, top = 40;
  double total = 0, peak = 0;
  for(double c : counts) { total += c; peak = std::max(peak, c); }
  char buf[256];
  std::snprintf(buf, sizeof(buf), "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\">\n", W + left + 20, H + top + 50);
  out << buf << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<text x=\"" << left << "\" y=\"24\" font-family=\"sans-serif\" font-size=\"16\">" << internal::escape(title) << "</text>\n";
  const double bw = W / std::max<std::size_t>(1, counts.size());
  for(std::size_t i = 0; i < counts.size(); ++i) {
    const double h = peak > 0 ? counts[i] / peak * H : 0;
    std::snprintf(buf, sizeof(buf), "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"%s\" stroke=\"#333\" stroke-width=\"0.5\"/>\n",
                  left + i * bw, top + H - h, bw, h, (i + 1) * bin_width <= 30 ? "#e05050" : "#5090d0");
    out << buf;
  }
  for(int deg = 0; deg <= 180; deg += 30) {
    const double x = left + deg / (bin_width * std::max<std::size_t>(1, counts.size())) * W;
    std::snprintf(buf, sizeof(buf), "<text x=\"%.1f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\" text-anchor=\"middle\">%d</text>\n",
                  x, top + H + 16, deg);
    out << buf;
  }
  std::snprintf(buf, sizeof(buf),
                "<text x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\" text-anchor=\"middle\">angle (degrees), %.0f angles; peak bin %.1f %%</text>\n",
                left + W / 2, top + H + 36, total, total > 0 ? 100 * peak / total : 0.0);
  out << buf << "<line x1=\"" << left << "\" y1=\"" << top + H << "\" x2=\"" << left + W << "\" y2=\"" << top + H << "\" stroke=\"black\"/>\n</svg>\n";
  if(!out) throw Invalid_input("cannot write " + path);
}

/*!
 * \ingroup PkgAnisoConformalIO
 * draws a Voronoi tessellation of a hyperbolic surface in the Klein disk (the paper's Fig.\ 13 (a)) as
 * SVG: the unit circle, the cells (straight polygons: hyperbolic Voronoi cells are power cells in the
 * Klein model) coloured by `values`, the sites as dots, and the cut of the fundamental domain (the
 * edges glued by a non-trivial deck transformation) in bold.
 *
 * \param path the SVG file to write
 * \param sites the sites' Klein points (in the fundamental domain)
 * \param cells the cell of each site, a polygon of Klein points (`Hyperbolic_klein_domain_traits::voronoi_cells()`)
 * \param cut segments of the fundamental domain's boundary, Klein points (`Hyperbolic_klein_domain_traits::fundamental_domain_boundary()`)
 * \param values a value per site colouring its cell on the red-yellow-green ramp; empty for uncoloured cells
 * \param title a line of text above the picture
 * \throws Invalid_input if `cells` and `sites` (or a non-empty `values`) differ in size, or the file cannot be written
 */
inline void write_hyperbolic_cvt_svg(const std::string& path, const std::vector<Eigen::Vector2d>& sites,
                                     const std::vector<std::vector<Eigen::Vector2d>>& cells,
                                     const std::vector<std::array<Eigen::Vector2d, 2>>& cut, const std::vector<double>& values,
                                     const std::string& title)
{
  if(cells.size() != sites.size())
    throw Invalid_input("write_hyperbolic_cvt_svg(): " + std::to_string(cells.size()) + " cells for " + std::to_string(sites.size()) + " sites");
  if(!values.empty() && values.size() != sites.size())
    throw Invalid_input("write_hyperbolic_cvt_svg(): " + std::to_string(values.size()) + " values for " + std::to_string(sites.size()) + " sites");
  const double R = 440, left = 20, top = 40, width = 2 * R + 2 * left, height = 2 * R + top + 50;
  char buf[256];
  auto xy = [&](const Eigen::Vector2d& p) {
    std::snprintf(buf, sizeof(buf), "%.2f,%.2f", left + R + R * p.x(), top + R - R * p.y());
    return std::string(buf);
  };
  const internal::Colour_classes classes(values);
  std::vector<std::string> paths(static_cast<std::size_t>(classes.count));
  for(std::size_t i = 0; i < cells.size(); ++i) {
    const std::vector<Eigen::Vector2d>& cell = cells[i];
    if(cell.size() < 3) continue;
    bool finite = true;
    for(const auto& p : cell) finite = finite && p.allFinite() && p.squaredNorm() < 1;
    if(!finite) continue;
    internal::append_polygon(paths[std::size_t(classes.of(values, i))], cell, xy);
  }
  std::ofstream out = internal::open_svg(path, width, height, left, title);
  std::snprintf(buf, sizeof(buf), "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"#f6f6f6\" stroke=\"black\" stroke-width=\"1\"/>\n", left + R,
                top + R, R);
  out << buf << "<g stroke=\"#333\" stroke-width=\"0.25\" stroke-linejoin=\"round\">\n";
  classes.write_paths(out, paths, 0, values.empty());
  out << "</g>\n<path fill=\"none\" stroke=\"black\" stroke-linecap=\"round\" stroke-width=\"1.2\" d=\"";
  for(const Eigen::Vector2d& p : sites)
    if(p.allFinite()) out << "M" << xy(p) << "h0";
  out << "\"/>\n<path fill=\"none\" stroke=\"#1040c0\" stroke-width=\"1.5\" d=\"";
  for(const auto& s : cut) out << "M" << xy(s[0]) << "L" << xy(s[1]);
  out << "\"/>\n";
  std::snprintf(buf, sizeof(buf), "<text x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\">%zu sites; blue: the cut of the fundamental domain</text>\n",
                left, 2 * R + top + 29, sites.size());
  out << buf;
  if(!values.empty()) internal::write_legend(out, width - 360, 2 * R + top + 18, classes.vmin, classes.vmax);
  internal::close_svg(out, path);
}

/*!
 * \ingroup PkgAnisoConformalIO
 * draws a Voronoi tessellation of the flat torus `R^2 / L` (the paper's Fig.\ 11 (a)) as SVG: the
 * fundamental cell `{s a + t b : 0 <= s, t < 1}` of the lattice `L` spanned by `lattice = (a, b)`,
 * outlined, tiled by the Voronoi cells drawn with thin lines, and the sites as dots sized after their
 * cells (y up), with the lattice basis written below.
 *
 * The cells are those given by `Euclidean_periodic_domain_traits::voronoi_cells()`: one polygon per site,
 * around the site wrapped into the fundamental cell, which may stick out of it. Each cell is drawn with
 * every lattice translate that meets the fundamental cell, and the drawing is clipped to it, so the cell
 * picture inside the parallelogram is complete. Empty polygons are skipped.
 *
 * \param path the SVG file to write
 * \param lattice the lattice basis `(a, b)`, `det(a, b) != 0`
 * \param sites the sites, wrapped into the fundamental cell
 * \param cells the Voronoi cell of each site (the same order as `sites`)
 * \param values a value per site (for example the cell's mass) colouring its cell on the red-yellow-green
 *        ramp from the smallest to the largest value, shown in a legend; empty for uncoloured cells
 * \param title a line of text above the picture
 * \throws Invalid_input if the lattice is degenerate, `cells` and `sites` (or a non-empty `values`) differ
 *         in size, or the file cannot be written
 */
inline void write_periodic_cvt_svg(const std::string& path, const std::array<Eigen::Vector2d, 2>& lattice,
                                   const std::vector<Eigen::Vector2d>& sites,
                                   const std::vector<std::vector<Eigen::Vector2d>>& cells, const std::vector<double>& values,
                                   const std::string& title)
{
  const Eigen::Vector2d a = lattice[0], b = lattice[1];
  Eigen::Matrix2d basis;
  basis.col(0) = a;
  basis.col(1) = b;
  const double det = basis.determinant();
  if(!std::isfinite(det) || std::abs(det) <= 1e-300) throw Invalid_input("write_periodic_cvt_svg(): the lattice basis is degenerate");
  if(cells.size() != sites.size())
    throw Invalid_input("write_periodic_cvt_svg(): " + std::to_string(cells.size()) + " cells for " + std::to_string(sites.size()) + " sites");
  if(!values.empty() && values.size() != sites.size())
    throw Invalid_input("write_periodic_cvt_svg(): " + std::to_string(values.size()) + " values for " + std::to_string(sites.size()) + " sites");
  const Eigen::Matrix2d inverse = basis.inverse();

  // the fundamental cell fitted into a 900 x 900 box, y up
  const std::array<Eigen::Vector2d, 4> corner = {{Eigen::Vector2d::Zero(), a, Eigen::Vector2d(a + b), b}};
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for(const auto& p : corner) { x0 = std::min(x0, p.x()); y0 = std::min(y0, p.y()); x1 = std::max(x1, p.x()); y1 = std::max(y1, p.y()); }
  const double box = 900, scale = box / std::max(x1 - x0, y1 - y0), W = (x1 - x0) * scale, H = (y1 - y0) * scale;
  const double left = 20, top = 40, bottom = 50, width = std::max(W + 2 * left, 760.0), height = H + top + bottom;
  char buf[256];
  auto xy = [&](const Eigen::Vector2d& p) {
    std::snprintf(buf, sizeof(buf), "%.2f,%.2f", left + (p.x() - x0) * scale, top + (y1 - p.y()) * scale);
    return std::string(buf);
  };

  // cell polygons grouped by colour (20 classes of the value), each with the translates meeting the cell
  const internal::Colour_classes classes(values);
  std::vector<std::string> paths(static_cast<std::size_t>(classes.count));
  for(std::size_t i = 0; i < cells.size(); ++i) {
    const std::vector<Eigen::Vector2d>& cell = cells[i];
    if(cell.empty()) continue;
    double s0 = 1e300, s1 = -1e300, t0 = 1e300, t1 = -1e300;
    for(const auto& p : cell) {
      const Eigen::Vector2d st = inverse * p;
      s0 = std::min(s0, st.x()); s1 = std::max(s1, st.x()); t0 = std::min(t0, st.y()); t1 = std::max(t1, st.y());
    }
    if(!(std::isfinite(s0) && std::isfinite(s1) && std::isfinite(t0) && std::isfinite(t1))) continue;
    std::string& d = paths[std::size_t(classes.of(values, i))];
    for(int di = int(std::floor(-s1)); di <= int(std::ceil(1 - s0)); ++di)
      for(int dj = int(std::floor(-t1)); dj <= int(std::ceil(1 - t0)); ++dj) {
        if(!(s0 + di < 1 && s1 + di > 0 && t0 + dj < 1 && t1 + dj > 0)) continue;
        const Eigen::Vector2d shift = double(di) * a + double(dj) * b;
        internal::append_polygon(d, cell, [&](const Eigen::Vector2d& p) { return xy(p + shift); });
      }
  }

  std::ofstream out = internal::open_svg(path, width, height, left, title);
  std::string outline;
  for(int k = 0; k < 4; ++k) outline += (k ? " " : "") + xy(corner[std::size_t(k)]);
  out << "<defs><clipPath id=\"fundamental_cell\"><polygon points=\"" << outline << "\"/></clipPath></defs>\n";
  out << "<g clip-path=\"url(#fundamental_cell)\" stroke=\"#333\" stroke-width=\"0.25\" stroke-linejoin=\"round\">\n";
  classes.write_paths(out, paths, 0, values.empty());
  out << "</g>\n";
  // the sites as dots (zero-length segments with round caps) whose size follows their cell's, in classes of 0.1 px
  const double spacing = std::sqrt(std::abs(det) / double(std::max<std::size_t>(1, sites.size()))) * scale;
  std::map<int, std::string> dots;
  for(std::size_t i = 0; i < sites.size(); ++i) {
    if(!sites[i].allFinite()) continue;
    double area = 0;
    const std::vector<Eigen::Vector2d>& cell = cells[i];
    for(std::size_t k = 0; k < cell.size(); ++k) {
      const Eigen::Vector2d& p = cell[k];
      const Eigen::Vector2d& q = cell[(k + 1) % cell.size()];
      area += p.x() * q.y() - p.y() * q.x();
    }
    const double size = area != 0 && std::isfinite(area) ? std::sqrt(std::abs(area) / 2) * scale : spacing;
    dots[int(std::lround(10 * std::min(3.5, std::max(0.25, 0.3 * size))))] += "M" + xy(sites[i]) + "h0";
  }
  for(const auto& d : dots) {
    std::snprintf(buf, sizeof(buf), "<path fill=\"none\" stroke=\"black\" stroke-linecap=\"round\" stroke-width=\"%.1f\" d=\"", d.first / 10.0);
    out << buf << d.second << "\"/>\n";
  }
  out << "<polygon points=\"" << outline << "\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\"/>\n";
  std::snprintf(buf, sizeof(buf),
                "<text x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\">%zu sites; a = (%.3g, %.3g), b = (%.3g, %.3g)</text>\n",
                left, H + top + 29, sites.size(), a.x(), a.y(), b.x(), b.y());
  out << buf;
  if(!values.empty()) internal::write_legend(out, width - 360, H + top + 18, classes.vmin, classes.vmax);
  internal::close_svg(out, path);
}

/*!
 * \ingroup PkgAnisoConformalIO
 * draws a CVT on the unit sphere (the paper's Fig.\ 10 (a)) as SVG: two orthographic views side by side,
 * the hemisphere facing `view_direction` and the opposite one, each cell a polygon filled by its value on
 * the blue-red ramp (20 classes), with the sites as dots, the sphere's outline, a legend and a title.
 * A cell is drawn in the view its site faces; its far vertices are pushed to the outline, so cells along
 * the rim stay closed.
 *
 * \param path the SVG file to write
 * \param sites the sites, unit vectors
 * \param cells per site, its Voronoi cell on the sphere as a closed polygon of unit vectors (any orientation)
 * \param values a value per site for the colour (empty: all cells pale)
 * \param title a line of text above the picture
 * \param view_direction the direction from the sphere's centre towards the viewer of the left view
 * \throws Invalid_input if the counts differ, `view_direction` is zero or not finite, or the file cannot be written
 */
inline void write_spherical_cvt_svg(const std::string& path, const std::vector<Eigen::Vector3d>& sites,
                                    const std::vector<std::vector<Eigen::Vector3d>>& cells, const std::vector<double>& values,
                                    const std::string& title, const Eigen::Vector3d& view_direction = Eigen::Vector3d(0.3, -1.0, 0.5))
{
  if(cells.size() != sites.size())
    throw Invalid_input("write_spherical_cvt_svg(): " + std::to_string(cells.size()) + " cells for " + std::to_string(sites.size()) + " sites");
  if(!values.empty() && values.size() != sites.size())
    throw Invalid_input("write_spherical_cvt_svg(): " + std::to_string(values.size()) + " values for " + std::to_string(sites.size()) + " sites");
  if(!view_direction.allFinite() || !(view_direction.norm() > 0))
    throw Invalid_input("write_spherical_cvt_svg(): the view direction must be finite and non-zero");
  // the view frame: w towards the viewer, v the z axis projected (or y near the poles), u = v x w
  const Eigen::Vector3d w = view_direction.normalized();
  Eigen::Vector3d up = std::abs(w.z()) > 0.95 ? Eigen::Vector3d(0, 1, 0) : Eigen::Vector3d(0, 0, 1);
  const Eigen::Vector3d v = (up - up.dot(w) * w).normalized(), u = v.cross(w);
  const double R = 400, left = 20, top = 40, gap = 40, width = 2 * (2 * R) + gap + 2 * left, height = 2 * R + top + 60;
  char buf[256];
  const internal::Colour_classes classes(values);
  // per view (0 front, 1 back: mirrored so that the back is seen from behind), per colour class, the path
  std::vector<std::string> paths(std::size_t(2 * classes.count));
  std::string dots[2];
  for(int view = 0; view < 2; ++view) {
    const Eigen::Vector3d W = view == 0 ? w : Eigen::Vector3d(-w), U = view == 0 ? u : Eigen::Vector3d(-u);
    const double cx = left + R + view * (2 * R + gap), cy = top + R;
    auto xy = [&](Eigen::Vector3d p) {
      if(p.dot(W) < 0) {  // beyond the rim: push it onto the outline
        p -= p.dot(W) * W;
        if(p.norm() > 0) p.normalize();
      }
      std::snprintf(buf, sizeof(buf), "%.2f,%.2f", cx + R * p.dot(U), cy - R * p.dot(v));
      return std::string(buf);
    };
    for(std::size_t i = 0; i < sites.size(); ++i) {
      if(!sites[i].allFinite() || sites[i].dot(W) < 0 || cells[i].size() < 3) continue;
      internal::append_polygon(paths[std::size_t(view * classes.count + classes.of(values, i))], cells[i], xy);
      dots[view] += "M" + xy(sites[i]) + "h0";
    }
  }

  std::ofstream out = internal::open_svg(path, width, height, left, title);
  for(int view = 0; view < 2; ++view) {
    const double cx = left + R + view * (2 * R + gap), cy = top + R;
    out << "<g stroke=\"#333\" stroke-width=\"0.3\" stroke-linejoin=\"round\">\n";
    classes.write_paths(out, paths, std::size_t(view * classes.count), values.empty());
    out << "</g>\n";
    if(!dots[view].empty())
      out << "<path fill=\"none\" stroke=\"black\" stroke-linecap=\"round\" stroke-width=\"2\" d=\"" << dots[view] << "\"/>\n";
    std::snprintf(buf, sizeof(buf), "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\"/>\n", cx, cy, R);
    out << buf;
    std::snprintf(buf, sizeof(buf), "<text x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\">%s</text>\n", cx - R,
                  top + 2 * R + 20, view == 0 ? "front hemisphere" : "back hemisphere (seen from behind)");
    out << buf;
  }
  std::snprintf(buf, sizeof(buf), "<text x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\">%zu sites</text>\n", left,
                top + 2 * R + 40, sites.size());
  out << buf;
  if(!values.empty()) internal::write_legend(out, width - 360, top + 2 * R + 30, classes.vmin, classes.vmax);
  internal::close_svg(out, path);
}

/*!
 * \ingroup PkgAnisoConformalIO
 * draws a closed surface in 3D (the paper's Fig.\ 11 (c)) as SVG: an orthographic view along
 * `view_direction`, back faces culled, the other triangles painted from the farthest to the nearest
 * (sorted by the depth of their centroids), each filled by its value in `face_values` on a red-yellow-green
 * ramp from `vmin` to `vmax` shaded by the Lambert factor `|n.l|` of a light above the viewer's left
 * shoulder, with thin edges, a legend and a title.
 *
 * The triangles must be oriented outward (counterclockwise seen from outside). The picture's up direction
 * is the z axis projected on the view plane, or the y axis when the view is within 18 degrees of the z
 * axis, so that the default view shows a planar mesh as `write_svg()` does.
 *
 * \param path the SVG file to write
 * \param points the vertex positions
 * \param faces the triangles, indices into `points`
 * \param face_values a value per triangle (triangles without one are drawn as `vmax`)
 * \param vmin the value drawn red
 * \param vmax the value drawn green
 * \param title a line of text above the picture
 * \param view_direction the direction from the surface towards the viewer
 * \throws Invalid_input if `view_direction` is zero or not finite, a face has an index out of range, or the
 *         file cannot be written
 */
inline void write_surface_svg(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                              const std::vector<std::array<std::size_t, 3>>& faces, const std::vector<double>& face_values,
                              double vmin, double vmax, const std::string& title,
                              const Eigen::Vector3d& view_direction = Eigen::Vector3d(0, 0, 1))
{
  if(!view_direction.allFinite() || !(view_direction.norm() > 0))
    throw Invalid_input("write_surface_svg(): the view direction must be finite and non-zero");
  for(const auto& f : faces)
    for(std::size_t v : f)
      if(v >= points.size())
        throw Invalid_input("write_surface_svg(): a face has vertex index " + std::to_string(v) + " but there are " +
                            std::to_string(points.size()) + " points");
  // the view frame (u right, v up, w towards the viewer) and the light
  const Eigen::Vector3d w = view_direction.normalized();
  const Eigen::Vector3d up = std::abs(w.z()) < 0.95 ? Eigen::Vector3d(0, 0, 1) : Eigen::Vector3d(0, 1, 0);
  const Eigen::Vector3d u = up.cross(w).normalized(), v = w.cross(u);
  const Eigen::Vector3d light = (w + 0.6 * v - 0.5 * u).normalized();

  struct Visible {
    double depth;
    std::size_t face;
    double shade;
  };
  std::vector<Visible> visible;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for(std::size_t f = 0; f < faces.size(); ++f) {
    const Eigen::Vector3d& p = points[faces[f][0]];
    const Eigen::Vector3d& q = points[faces[f][1]];
    const Eigen::Vector3d& r = points[faces[f][2]];
    const Eigen::Vector3d n = (q - p).cross(r - p);
    const double len = n.norm();
    if(!(len > 0) || !(n.dot(w) > 0)) continue;  // degenerate or facing away
    visible.push_back({(p + q + r).dot(w) / 3, f, std::abs(n.dot(light)) / len});
    for(const Eigen::Vector3d* x : {&p, &q, &r}) {
      const double px = x->dot(u), py = x->dot(v);
      x0 = std::min(x0, px); x1 = std::max(x1, px); y0 = std::min(y0, py); y1 = std::max(y1, py);
    }
  }
  if(visible.empty()) { x0 = y0 = 0; x1 = y1 = 1; }
  std::stable_sort(visible.begin(), visible.end(), [](const Visible& l, const Visible& r) { return l.depth < r.depth; });

  const double box = 800, scale = box / std::max({1e-300, x1 - x0, y1 - y0}), W = (x1 - x0) * scale, H = (y1 - y0) * scale;
  const double left = 20, top = 40, bottom = 50, width = std::max(W + 2 * left, 760.0), height = H + top + bottom;
  const double offset = left + (width - 2 * left - W) / 2;  // centred
  std::ofstream out = internal::open_svg(path, width, height, left, title);
  char buf[256];
  out << "<g stroke=\"#222\" stroke-opacity=\"0.45\" stroke-width=\"0.25\" stroke-linejoin=\"round\">\n";
  for(const Visible& t : visible) {
    const double value =
        t.face < face_values.size() ? (face_values[t.face] - vmin) / std::max(1e-300, vmax - vmin) : 1.0;
    std::array<int, 3> rgb = internal::ramp_rgb(value);
    const double shade = 0.25 + 0.75 * t.shade;
    for(int& c : rgb) c = std::min(255, std::max(0, int(c * shade + 0.5)));
    out << "<path d=\"";
    for(int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = points[faces[t.face][std::size_t(k)]];
      std::snprintf(buf, sizeof(buf), "%s%.1f,%.1f", k == 0 ? "M" : k == 1 ? "L" : " ", offset + (p.dot(u) - x0) * scale,
                    top + (y1 - p.dot(v)) * scale);
      out << buf;
    }
    out << "Z\" fill=\"" << internal::hex_colour(rgb) << "\"/>\n";
  }
  out << "</g>\n";
  internal::write_legend(out, width - 360, H + top + 18, vmin, vmax);
  internal::close_svg(out, path);
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_WRITE_SVG_H
