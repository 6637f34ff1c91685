// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_READ_IMAGE_H
#define ANISO_CONFORMAL_IO_READ_IMAGE_H

#include <Aniso_conformal/Exceptions.h>

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

/// \file read_image.h

namespace Aniso_conformal {
namespace IO {

/*!
 * \ingroup PkgAnisoConformalIO
 * an image with 1 (grey) or 3 (RGB) channels, values in [0, 1], rows stored top row first
 */
struct Image {
  int width = 0;              ///< columns
  int height = 0;             ///< rows
  int channels = 0;           ///< 1 or 3
  std::vector<float> data;    ///< `channels` values per pixel, row-major
  /// the value of channel `c` at column `x`, row `y` (row 0 at the top)
  float at(int x, int y, int c) const { return data[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels) + std::size_t(c)]; }
};

namespace internal {

inline std::vector<unsigned char> read_bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if(!in) throw Invalid_input("image " + path + ": cannot be opened");
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void check_size(const std::string& path, long long w, long long h)
{
  if(w <= 0 || h <= 0) throw Invalid_input("image " + path + ": zero size");
  // w * h overflows for header values near 2^32 (PNG) or 2^40 (PNM): divide instead
  if(w > (1LL << 28) / h) throw Invalid_input("image " + path + ": too large (" + std::to_string(w) + " x " + std::to_string(h) + ")");
}

// ---- Netpbm: P2/P3 (ASCII) and P5/P6 (binary), maxval up to 65535
inline Image read_pnm(const std::string& path, const std::vector<unsigned char>& b)
{
  std::size_t pos = 2;
  auto skip = [&]() {
    while(pos < b.size()) {
      if(std::isspace(b[pos])) ++pos;
      else if(b[pos] == '#') { while(pos < b.size() && b[pos] != '\n') ++pos; }
      else break;
    }
  };
  auto number = [&]() -> long long {
    skip();
    if(pos >= b.size() || !std::isdigit(b[pos])) throw Invalid_input("image " + path + ": truncated or malformed header or data");
    long long v = 0;
    while(pos < b.size() && std::isdigit(b[pos])) {
      v = v * 10 + (b[pos++] - '0');
      if(v > (1LL << 40)) throw Invalid_input("image " + path + ": number too large");
    }
    return v;
  };
  const char kind = char(b[1]);
  Image img;
  img.channels = (kind == '3' || kind == '6') ? 3 : 1;
  const long long w = number(), h = number(), maxval = number();
  check_size(path, w, h);
  if(maxval <= 0 || maxval > 65535) throw Invalid_input("image " + path + ": maxval " + std::to_string(maxval) + " out of range");
  img.width = int(w);
  img.height = int(h);
  const std::size_t n = std::size_t(w) * std::size_t(h) * std::size_t(img.channels);
  // check that the file holds the samples before allocating them: a 20-byte header could ask for gigabytes
  // (found by fuzzing). ASCII samples take at least a digit and a separator each, binary 1 or 2 bytes.
  const std::size_t bytes = maxval > 255 ? 2 : 1;
  const std::size_t left = b.size() - std::min(b.size(), pos);
  if((kind == '2' || kind == '3') ? n > left / 2 + 1 : (left == 0 || n > (left - 1) / bytes))
    throw Invalid_input("image " + path + ": truncated pixel data");
  img.data.resize(n);
  if(kind == '2' || kind == '3') {
    for(std::size_t i = 0; i < n; ++i) {
      const long long v = number();
      if(v > maxval) throw Invalid_input("image " + path + ": sample above maxval");
      img.data[i] = float(double(v) / double(maxval));
    }
  } else {
    ++pos;  // the single whitespace after maxval
    for(std::size_t i = 0; i < n; ++i) {
      const unsigned v = bytes == 2 ? (unsigned(b[pos + 2 * i]) << 8 | b[pos + 2 * i + 1]) : b[pos + i];
      img.data[i] = float(std::min(1.0, double(v) / double(maxval)));
    }
  }
  return img;
}

// ---- PNG: all bit depths and colour types, non-interlaced
inline std::uint32_t be32(const unsigned char* p)
{
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | std::uint32_t(p[3]);
}

inline Image read_png(const std::string& path, const std::vector<unsigned char>& b)
{
  const std::string bad = "image " + path + ": ";
  std::size_t pos = 8;
  long long w = 0, h = 0;
  int depth = 0, color = -1;
  std::vector<unsigned char> idat, palette;
  bool header = false, end = false;
  while(!end) {
    if(b.size() - pos < 12) throw Invalid_input(bad + "truncated PNG chunk");
    const std::uint32_t len = be32(&b[pos]);
    const std::string type(reinterpret_cast<const char*>(&b[pos + 4]), 4);
    if(len > b.size() - pos - 12) throw Invalid_input(bad + "PNG chunk '" + type + "' runs past the end of the file");
    const unsigned char* d = &b[pos + 8];
    if(type == "IHDR") {
      if(len != 13) throw Invalid_input(bad + "bad PNG header");
      w = be32(d);
      h = be32(d + 4);
      depth = d[8];
      color = d[9];
      if(d[10] != 0 || d[11] != 0) throw Invalid_input(bad + "unknown PNG compression or filter method");
      if(d[12] != 0) throw Invalid_input(bad + "interlaced PNG is not supported");
      header = true;
    } else if(type == "PLTE") {
      palette.assign(d, d + len);
    } else if(type == "IDAT") {
      idat.insert(idat.end(), d, d + len);
    } else if(type == "IEND") {
      end = true;
    }
    pos += 12 + len;
  }
  if(!header) throw Invalid_input(bad + "PNG without header");
  check_size(path, w, h);
  int samples = 0;
  switch(color) {
  case 0: samples = 1; break;
  case 2: samples = 3; break;
  case 3: samples = 1; break;
  case 4: samples = 2; break;
  case 6: samples = 4; break;
  default: throw Invalid_input(bad + "unknown PNG colour type " + std::to_string(color));
  }
  const bool depth_ok = (depth == 8 || depth == 16) || ((color == 0 || color == 3) && (depth == 1 || depth == 2 || depth == 4));
  if(!depth_ok || (color == 3 && depth == 16)) throw Invalid_input(bad + "invalid PNG bit depth " + std::to_string(depth));
  if(color == 3 && (palette.empty() || palette.size() % 3 != 0)) throw Invalid_input(bad + "palette PNG without a valid palette");
  const std::size_t bits = std::size_t(samples) * std::size_t(depth);
  const std::size_t stride = (std::size_t(w) * bits + 7) / 8, bpp = std::max<std::size_t>(1, bits / 8);
  const std::size_t raw_size = (stride + 1) * std::size_t(h);
  // deflate expands at most 1032 times: refuse a header asking for more than the data can hold before
  // allocating it (a 100-byte file asked for 2 GB)
  if(raw_size / 1032 > idat.size()) throw Invalid_input(bad + "corrupt or truncated PNG image data");
  std::vector<unsigned char> raw(raw_size);
  uLongf out_len = uLongf(raw_size);
  const int zr = uncompress(raw.data(), &out_len, idat.data(), uLong(idat.size()));
  if(zr != Z_OK || out_len != raw_size) throw Invalid_input(bad + "corrupt or truncated PNG image data");
  // undo the per-row filters (PNG spec 9)
  std::vector<unsigned char> pix(stride * std::size_t(h));
  for(std::size_t y = 0; y < std::size_t(h); ++y) {
    const unsigned char filter = raw[y * (stride + 1)];
    const unsigned char* src = &raw[y * (stride + 1) + 1];
    unsigned char* row = &pix[y * stride];
    const unsigned char* up = y ? &pix[(y - 1) * stride] : nullptr;
    for(std::size_t i = 0; i < stride; ++i) {
      const int a = i >= bpp ? row[i - bpp] : 0, u = up ? up[i] : 0, c = (up && i >= bpp) ? up[i - bpp] : 0;
      int v = src[i];
      switch(filter) {
      case 0: break;
      case 1: v += a; break;
      case 2: v += u; break;
      case 3: v += (a + u) / 2; break;
      case 4: {
        const int p = a + u - c, pa = std::abs(p - a), pb = std::abs(p - u), pc = std::abs(p - c);
        v += (pa <= pb && pa <= pc) ? a : (pb <= pc ? u : c);
        break;
      }
      default: throw Invalid_input(bad + "unknown PNG row filter " + std::to_string(filter));
      }
      row[i] = static_cast<unsigned char>(v & 0xff);
    }
  }
  auto sample = [&](std::size_t y, std::size_t x, std::size_t s) -> unsigned {
    const std::size_t bit = (x * std::size_t(samples) + s) * std::size_t(depth);
    const unsigned char* row = &pix[y * stride];
    if(depth == 16) return unsigned(row[bit / 8]) << 8 | row[bit / 8 + 1];
    if(depth == 8) return row[bit / 8];
    return (row[bit / 8] >> (8 - depth - bit % 8)) & ((1u << depth) - 1);
  };
  Image img;
  img.width = int(w);
  img.height = int(h);
  img.channels = (color == 0 || color == 4) ? 1 : 3;
  img.data.resize(std::size_t(w) * std::size_t(h) * std::size_t(img.channels));
  const double maxv = double((1u << depth) - 1);
  std::size_t k = 0;
  for(std::size_t y = 0; y < std::size_t(h); ++y)
    for(std::size_t x = 0; x < std::size_t(w); ++x) {
      if(color == 3) {
        const std::size_t i = sample(y, x, 0);
        if(3 * i + 2 >= palette.size()) throw Invalid_input(bad + "palette index out of range");
        for(int c = 0; c < 3; ++c) img.data[k++] = float(palette[3 * i + std::size_t(c)] / 255.0);
      } else {
        for(int c = 0; c < img.channels; ++c) img.data[k++] = float(sample(y, x, std::size_t(c)) / maxv);
      }
    }
  return img;
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * reads a PNG (any bit depth and colour type, not interlaced) or a PPM/PGM (P2, P3, P5, P6) image.
 * Alpha is dropped; grey images have 1 channel, colour and palette images 3.
 * \throws Invalid_input naming the file: missing, unknown format, truncated or corrupt data, zero or
 *         absurd size (more than 2^28 pixels), interlaced PNG
 */
inline Image read_image(const std::string& path)
{
  const std::vector<unsigned char> b = internal::read_bytes(path);
  static const unsigned char png_magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if(b.size() >= 8 && std::equal(png_magic, png_magic + 8, b.begin())) return internal::read_png(path, b);
  if(b.size() >= 2 && b[0] == 'P' && (b[1] == '2' || b[1] == '3' || b[1] == '5' || b[1] == '6'))
    return internal::read_pnm(path, b);
  throw Invalid_input("image " + path + ": not a PNG, PGM or PPM file");
}

/*!
 * \ingroup PkgAnisoConformalIO
 * writes `img` as binary PGM (1 channel) or PPM (3 channels), 8 bits.
 * \throws Invalid_input if the file cannot be written or the image is inconsistent
 */
inline void write_pnm(const Image& img, const std::string& path)
{
  if(img.data.size() != std::size_t(img.width) * std::size_t(img.height) * std::size_t(img.channels) ||
     (img.channels != 1 && img.channels != 3))
    throw Invalid_input("write_pnm(): inconsistent image");
  std::ofstream out(path, std::ios::binary);
  out << (img.channels == 1 ? "P5\n" : "P6\n") << img.width << ' ' << img.height << "\n255\n";
  for(float v : img.data) out.put(char(static_cast<unsigned char>(std::min(255.0f, std::max(0.0f, v * 255.0f + 0.5f)))));
  if(!out) throw Invalid_input("cannot write " + path);
}

} // namespace IO
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_IO_READ_IMAGE_H
