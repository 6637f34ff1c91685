// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_WRITE_SVG_H
#define ANISO_CONFORMAL_IO_WRITE_SVG_H

#include <Aniso_conformal/Exceptions.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

/// \file write_svg.h

namespace Aniso_conformal {
namespace IO {

namespace internal {
// red (low) -> yellow -> green (high)
inline std::string ramp(double t)
{
  t = std::min(1.0, std::max(0.0, t));
  const int r = t < 0.5 ? 230 : int(230 * (1 - t) * 2), g = t < 0.5 ? int(60 + 170 * t * 2) : 200;
  char buf[16];
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", std::max(0, r), std::min(255, g), 60);
  return buf;
}
inline std::string escape(const std::string& s)
{
  std::string o;
  for(char c : s) o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return o;
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
  for(int i = 0; i < 10; ++i) {  // legend
    std::snprintf(buf, sizeof(buf), "<rect x=\"%d\" y=\"%.0f\" width=\"30\" height=\"12\" fill=\"%s\"/>\n", 400 + 30 * i,
                  H + top + 18, internal::ramp((i + 0.5) / 10).c_str());
    out << buf;
  }
  std::snprintf(buf, sizeof(buf),
                "<text x=\"395\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\" text-anchor=\"end\">%.2f</text>\n"
                "<text x=\"705\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\">%.2f</text>\n",
                H + top + 29, vmin, H + top + 29, vmax);
  out << buf << "</svg>\n";
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

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_WRITE_SVG_H
