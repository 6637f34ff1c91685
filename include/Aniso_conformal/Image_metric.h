// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IMAGE_METRIC_H
#define ANISO_CONFORMAL_IMAGE_METRIC_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/IO/read_image.h>
#include <Aniso_conformal/Surface_point.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

/// \file Image_metric.h

namespace Aniso_conformal {

/*!
 * \ingroup PkgAnisoConformalMetrics
 * the metric of the paper's image meshing (eq.\ 9): a pixel `x` is embedded as
 * `phi(x) = [x, y, s r, s g, s b]` (or `[x, y, s i]` for grey images), and lengths are measured in that
 * space, which is the pull-back metric `M = I + s^2 J^T J`, `J` the Jacobian of the colour with respect
 * to the domain coordinates.
 *
 * The domain is the image rectangle scaled to unit width: pixel (column c, row r) has its centre at
 * `x = c / (W - 1)`, `y = (H - 1 - r) / (W - 1)` (y up, so the image is upright). Colours are in [0, 1].
 * The channels are Gaussian-smoothed (`sigma` pixels) before central differences, then the per-pixel
 * tensors are interpolated bilinearly.
 *
 * \cgalModels `AnisotropicMetric`
 */
class Image_metric {
public:
  /// the tensor type
  typedef Eigen::Matrix3d Tensor;
  /// builds the metric of `img` with anisotropy `s` (the paper uses 0.1 for colour, 0.5 for grey images)
  Image_metric(const IO::Image& img, double s, double sigma = 1.0) : m_w(img.width), m_h(img.height)
  {
    if(!(std::isfinite(s) && s > 0)) throw Invalid_input("image metric: the anisotropy s must be positive and finite");
    if(!(sigma >= 0 && std::isfinite(sigma))) throw Invalid_input("image metric: the smoothing sigma must be >= 0");
    if(img.width < 2 || img.height < 2) throw Invalid_input("image metric: the image must be at least 2 x 2 pixels");
    const std::size_t W = std::size_t(m_w), H = std::size_t(m_h);
    m_t.assign(W * H, Eigen::Matrix2d::Identity());
    const double scale = double(m_w - 1);  // pixel differences per unit of domain length
    std::vector<double> ch(W * H), tmp(W * H);
    for(int c = 0; c < img.channels; ++c) {
      for(std::size_t i = 0; i < W * H; ++i) ch[i] = img.data[i * std::size_t(img.channels) + std::size_t(c)];
      smooth(ch, tmp, sigma);
      for(int r = 0; r < m_h; ++r)
        for(int col = 0; col < m_w; ++col) {
          auto at = [&](int cc, int rr) { return ch[std::size_t(rr) * W + std::size_t(cc)]; };
          const int c0 = std::max(0, col - 1), c1 = std::min(m_w - 1, col + 1);
          const int r0 = std::max(0, r - 1), r1 = std::min(m_h - 1, r + 1);
          const double dx = (at(c1, r) - at(c0, r)) / double(c1 - c0) * scale;
          const double dy = -(at(col, r1) - at(col, r0)) / double(r1 - r0) * scale;  // rows go down, y goes up
          const Eigen::Vector2d g(dx, dy);
          m_t[std::size_t(r) * W + std::size_t(col)] += s * s * g * g.transpose();
        }
    }
  }

  /// the tensor at `p` (bilinear in the per-pixel tensors, clamped to the image rectangle)
  Tensor tensor(const Surface_point& p) const
  {
    const double fx = std::min(double(m_w - 1), std::max(0.0, p.position.x() * (m_w - 1)));
    const double fy = std::min(double(m_h - 1), std::max(0.0, double(m_h - 1) - p.position.y() * (m_w - 1)));
    const int x0 = std::min(m_w - 2, int(fx)), y0 = std::min(m_h - 2, int(fy));
    const double ax = fx - x0, ay = fy - y0;
    auto T = [&](int x, int y) -> const Eigen::Matrix2d& { return m_t[std::size_t(y) * std::size_t(m_w) + std::size_t(x)]; };
    const Eigen::Matrix2d m = (1 - ax) * (1 - ay) * T(x0, y0) + ax * (1 - ay) * T(x0 + 1, y0) +
                              (1 - ax) * ay * T(x0, y0 + 1) + ax * ay * T(x0 + 1, y0 + 1);
    Tensor M = Tensor::Zero();
    M.topLeftCorner<2, 2>() = m;
    return M;
  }

private:
  // separable Gaussian blur with clamped borders
  void smooth(std::vector<double>& a, std::vector<double>& tmp, double sigma) const
  {
    if(sigma <= 0) return;
    const int R = std::max(1, int(std::ceil(3 * sigma)));
    std::vector<double> k(std::size_t(2 * R + 1));
    double sum = 0;
    for(int i = -R; i <= R; ++i) sum += k[std::size_t(i + R)] = std::exp(-0.5 * i * i / (sigma * sigma));
    for(double& x : k) x /= sum;
    const std::size_t W = std::size_t(m_w);
    for(int y = 0; y < m_h; ++y)
      for(int x = 0; x < m_w; ++x) {
        double v = 0;
        for(int i = -R; i <= R; ++i) v += k[std::size_t(i + R)] * a[std::size_t(y) * W + std::size_t(std::min(m_w - 1, std::max(0, x + i)))];
        tmp[std::size_t(y) * W + std::size_t(x)] = v;
      }
    for(int y = 0; y < m_h; ++y)
      for(int x = 0; x < m_w; ++x) {
        double v = 0;
        for(int i = -R; i <= R; ++i) v += k[std::size_t(i + R)] * tmp[std::size_t(std::min(m_h - 1, std::max(0, y + i))) * W + std::size_t(x)];
        a[std::size_t(y) * W + std::size_t(x)] = v;
      }
  }

  int m_w, m_h;
  std::vector<Eigen::Matrix2d> m_t;
};

} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IMAGE_METRIC_H
