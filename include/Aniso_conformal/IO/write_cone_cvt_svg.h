// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_WRITE_CONE_CVT_SVG_H
#define ANISO_CONFORMAL_IO_WRITE_CONE_CVT_SVG_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/IO/write_svg.h>
#include <Aniso_conformal/internal/domains/convex_overlap_2.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

/// \file write_cone_cvt_svg.h
/// The picture of a CVT on the cone surface (issue 16), chart by chart.

namespace Aniso_conformal {
namespace IO {

/*!
 * \ingroup PkgAnisoConformalIO
 * draws a CVT on a flat surface with cone singularities (the cone domain of issue 16; the analogue of the
 * paper's Fig.\ 10 (a) and 11 (a)) as SVG: the charts of the atlas side by side at one scale (units of the
 * flat metric, so a chart's size shows the area distortion there), each clipped to its triangles, the
 * Voronoi cells in it (the chart's own sites and the copies of the sites around it) coloured by the value
 * of their site, the chart's outline (where it meets another chart) in bold, the own sites as dots, and the
 * cones as dots, red for an angle below `2 pi` (positive curvature) and blue above (negative), with a
 * legend and a title.
 *
 * \tparam ChartCells a type with the members of `Cone_domain_traits::Chart_cells` (`triangles`, `outline`,
 *         `points`, `sites`, `own`, `cells`, `cones`, `cone_angles`)
 * \param path the SVG file to write
 * \param charts the charts and their cells (`Cone_domain_traits::voronoi_cells()`)
 * \param values a value per site colouring its cells on the red-yellow-green ramp from the smallest to the
 *        largest value, shown in a legend; empty for uncoloured cells
 * \param title a line of text above the picture
 * \throws Invalid_input if there is no chart, a chart's `points`, `sites` and `cells` differ in size (or
 *         `own` exceeds them, or `cones` and `cone_angles` differ), a site index is not below the size of a
 *         non-empty `values`, a coordinate is not finite, or the file cannot be written
 */
template <typename ChartCells>
void write_cone_cvt_svg(const std::string& path, const std::vector<ChartCells>& charts, const std::vector<double>& values,
                        const std::string& title)
{
  const std::string me = "write_cone_cvt_svg(): ";
  if(charts.empty()) throw Invalid_input(me + "no chart to draw");
  // each chart's bounding box, packed in shelves (rows by decreasing height) into a near-square at one scale
  struct Box { double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300, ox = 0, oy = 0; };
  std::vector<Box> box(charts.size());
  double area = 0;
  std::size_t own = 0;
  for(std::size_t c = 0; c < charts.size(); ++c) {
    const ChartCells& cc = charts[c];
    if(cc.sites.size() != cc.points.size() || cc.cells.size() != cc.points.size() || cc.own > cc.points.size() ||
       cc.cone_angles.size() != cc.cones.size())
      throw Invalid_input(me + "chart " + std::to_string(c) + " has " + std::to_string(cc.points.size()) + " points, " +
                          std::to_string(cc.sites.size()) + " site indices, " + std::to_string(cc.cells.size()) + " cells, " +
                          std::to_string(cc.own) + " own sites, " + std::to_string(cc.cones.size()) + " cones and " +
                          std::to_string(cc.cone_angles.size()) + " cone angles");
    if(cc.triangles.empty()) throw Invalid_input(me + "chart " + std::to_string(c) + " has no triangle");
    for(std::size_t e = 0; e < cc.sites.size(); ++e)
      if(!values.empty() && cc.sites[e] >= values.size())
        throw Invalid_input(me + "chart " + std::to_string(c) + " refers to site " + std::to_string(cc.sites[e]) + " of " +
                            std::to_string(values.size()) + " values");
    own += cc.own;
    Box& b = box[c];
    for(const auto& t : cc.triangles)
      for(const Eigen::Vector2d& p : t) {
        if(!p.allFinite()) throw Invalid_input(me + "chart " + std::to_string(c) + " has a corner that is not finite");
        b.x0 = std::min(b.x0, p.x()); b.y0 = std::min(b.y0, p.y()); b.x1 = std::max(b.x1, p.x()); b.y1 = std::max(b.y1, p.y());
      }
    area += (b.x1 - b.x0) * (b.y1 - b.y0);
  }
  const double gap = 0.03 * std::sqrt(area / double(charts.size())), row_width = 1.2 * std::sqrt(area) + gap;
  std::vector<std::size_t> order(charts.size());
  for(std::size_t c = 0; c < order.size(); ++c) order[c] = c;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return box[a].y1 - box[a].y0 > box[b].y1 - box[b].y0; });
  double x = 0, y = 0, row_height = 0, used_width = 0;
  for(std::size_t c : order) {
    Box& b = box[c];
    if(x > 0 && x + (b.x1 - b.x0) > row_width) { x = 0; y += row_height + gap; row_height = 0; }
    b.ox = x - b.x0;  // picture x = p.x + ox
    b.oy = y + b.y1;  // picture y (down) = oy - p.y
    x += (b.x1 - b.x0) + gap;
    row_height = std::max(row_height, b.y1 - b.y0);
    used_width = std::max(used_width, x - gap);
  }
  const double total_height = y + row_height;
  const double scale = 1000 / std::max(used_width, 1e-300), left = 20, top = 40, bottom = 50;
  const double width = std::max(used_width * scale + 2 * left, 760.0), height = total_height * scale + top + bottom;
  char buf[256];
  const internal::Colour_classes classes(values);
  std::ofstream out = internal::open_svg(path, width, height, left, title);
  std::map<int, std::string> dots;
  std::string red, blue;
  for(std::size_t c = 0; c < charts.size(); ++c) {
    const ChartCells& cc = charts[c];
    const Box& b = box[c];
    auto xy = [&](const Eigen::Vector2d& p) {  // a tenth of a pixel: the picture has many small cells
      std::snprintf(buf, sizeof(buf), "%.1f,%.1f", left + (p.x() + b.ox) * scale, top + (b.oy - p.y()) * scale);
      return std::string(buf);
    };
    std::string region;
    for(const auto& t : cc.triangles) internal::append_polygon(region, t, xy);
    // the chart's triangles written once: the clip path and the background both use them
    out << "<defs><path id=\"region" << c << "\" d=\"" << region << "\"/><clipPath id=\"chart" << c << "\"><use href=\"#region" << c
        << "\"/></clipPath></defs>\n";
    out << "<use href=\"#region" << c << "\" fill=\"#eef2f8\"/>\n";
    // a cell that meets no triangle of the chart is clipped away whole and not written (most copies in
    // the band): the triangles listed on a 32 x 32 grid over the chart's box, a cell tested against those
    // of the grid squares its box meets
    const int G = 32;
    const double gx = (b.x1 - b.x0) / G, gy = (b.y1 - b.y0) / G;
    auto column = [&](double px) { return std::min(G - 1, std::max(0, int(std::floor((px - b.x0) / std::max(gx, 1e-300))))); };
    auto row = [&](double py) { return std::min(G - 1, std::max(0, int(std::floor((py - b.y0) / std::max(gy, 1e-300))))); };
    std::vector<std::vector<std::size_t>> square(std::size_t(G * G));
    for(std::size_t k = 0; k < cc.triangles.size(); ++k) {
      const auto& t = cc.triangles[k];
      for(int i = column(std::min({t[0].x(), t[1].x(), t[2].x()})); i <= column(std::max({t[0].x(), t[1].x(), t[2].x()})); ++i)
        for(int j = row(std::min({t[0].y(), t[1].y(), t[2].y()})); j <= row(std::max({t[0].y(), t[1].y(), t[2].y()})); ++j)
          square[std::size_t(j * G + i)].push_back(k);
    }
    std::vector<std::string> paths(static_cast<std::size_t>(classes.count));
    for(std::size_t e = 0; e < cc.cells.size(); ++e) {
      const std::vector<Eigen::Vector2d>& cell = cc.cells[e];
      if(cell.size() < 3 || std::any_of(cell.begin(), cell.end(), [](const Eigen::Vector2d& p) { return !p.allFinite(); })) continue;
      Box cb;
      for(const Eigen::Vector2d& p : cell) { cb.x0 = std::min(cb.x0, p.x()); cb.y0 = std::min(cb.y0, p.y()); cb.x1 = std::max(cb.x1, p.x()); cb.y1 = std::max(cb.y1, p.y()); }
      if(cb.x0 > b.x1 || cb.x1 < b.x0 || cb.y0 > b.y1 || cb.y1 < b.y0) continue;
      bool meets = false;
      for(int i = column(cb.x0); i <= column(cb.x1) && !meets; ++i)
        for(int j = row(cb.y0); j <= row(cb.y1) && !meets; ++j)
          for(std::size_t k : square[std::size_t(j * G + i)])
            if(Aniso_conformal::internal::convex_polygons_overlap(cell, cc.triangles[k])) { meets = true; break; }
      if(!meets) continue;
      internal::append_polygon(paths[std::size_t(classes.of(values, cc.sites[e]))], cell, xy);
    }
    out << "<g clip-path=\"url(#chart" << c << ")\" stroke=\"#333\" stroke-width=\"0.25\" stroke-linejoin=\"round\">\n";
    classes.write_paths(out, paths, 0, values.empty());
    out << "</g>\n";
    std::string outline;
    for(const auto& s : cc.outline) outline += "M" + xy(s[0]) + "L" + xy(s[1]);
    if(!outline.empty()) out << "<path fill=\"none\" stroke=\"black\" stroke-width=\"1\" stroke-linecap=\"round\" d=\"" << outline << "\"/>\n";
    for(std::size_t e = 0; e < cc.own; ++e)
      if(cc.points[e].allFinite()) dots[0] += "M" + xy(cc.points[e]) + "h0";
    for(std::size_t k = 0; k < cc.cones.size(); ++k)
      (cc.cone_angles[k] > 2 * 3.14159265358979323846 ? blue : red) += "M" + xy(cc.cones[k]) + "h0";
  }
  out << "<path fill=\"none\" stroke=\"black\" stroke-linecap=\"round\" stroke-width=\"1.6\" d=\"" << dots[0] << "\"/>\n";
  if(!red.empty()) out << "<path fill=\"none\" stroke=\"#d7191c\" stroke-linecap=\"round\" stroke-width=\"6\" d=\"" << red << "\"/>\n";
  if(!blue.empty()) out << "<path fill=\"none\" stroke=\"#2c7bb6\" stroke-linecap=\"round\" stroke-width=\"6\" d=\"" << blue << "\"/>\n";
  std::snprintf(buf, sizeof(buf),
                "<text x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\">%zu sites in %zu charts; cones: red below 360 "
                "degrees, blue above</text>\n",
                left, total_height * scale + top + 29, own, charts.size());
  out << buf;
  if(!values.empty()) internal::write_legend(out, width - 360, total_height * scale + top + 18, classes.vmin, classes.vmax);
  internal::close_svg(out, path);
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_WRITE_CONE_CVT_SVG_H
