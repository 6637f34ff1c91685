// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_IO_READ_IMAGE_H
#define ANISO_CONFORMAL_IO_READ_IMAGE_H

#include <Aniso_conformal/Exceptions.h>

#include <Aniso_conformal/internal/printable.h>

#include <png.h>

#include <algorithm>
#include <cctype>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <new>
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

// ---- PNG, decoded by libpng (Debian's libpng-dev). libpng reports an error by calling our error function,
// which must not return: it copies the message and longjmps back to the setjmp of the step that called
// libpng. A longjmp that skips the destructor of a C++ object is undefined behaviour ([csetjmp.syn]), so
// the three steps below (png_step_*) hold only trivially destructible objects, the callbacks too, and
// everything that owns memory (the png_struct guard, the row buffer, the Image) lives in read_png(),
// which each step returns to normally (false on error). No C++ exception passes through libpng.

// What the callbacks share with read_png(); plain data, it is read after a longjmp.
struct Png_state {
  const unsigned char* data;
  std::size_t size;
  std::size_t position;
  char error[200];    // libpng's error message
  char warning[200];  // its last warning (libpng warns with the detail, e.g. which IHDR field, then errs)
};

inline void png_on_read(png_structp png, png_bytep out, std::size_t n)
{
  Png_state* s = static_cast<Png_state*>(png_get_io_ptr(png));
  if(n > s->size - s->position) png_error(png, "the file ends before its IEND chunk");
  std::memcpy(out, s->data + s->position, n);
  s->position += n;
}
inline void png_on_error(png_structp png, png_const_charp message)
{
  Png_state* s = static_cast<Png_state*>(png_get_error_ptr(png));
  std::snprintf(s->error, sizeof(s->error), "%s", message ? message : "unknown error");
  png_longjmp(png, 1);
}
// warnings are kept, never printed: the library writes nothing to stderr
inline void png_on_warning(png_structp png, png_const_charp message)
{
  Png_state* s = static_cast<Png_state*>(png_get_error_ptr(png));
  std::snprintf(s->warning, sizeof(s->warning), "%s", message ? message : "");
}

// step 1: the chunks up to the image data (IHDR, PLTE, ancillary chunks); nothing sized by the image yet
inline bool png_step_header(png_structp png, png_infop info)
{
  if(setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  return true;
}
// step 2: one byte per sample below 8 bits, unscaled (16-bit samples stay big-endian; no gamma, palette or
// alpha transform: the samples are converted as they are), interlacing undone; `*rowbytes` after that
inline bool png_step_transforms(png_structp png, png_infop info, int bit_depth, std::size_t* rowbytes)
{
  if(setjmp(png_jmpbuf(png))) return false;
  if(bit_depth < 8) png_set_packing(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  *rowbytes = png_get_rowbytes(png, info);
  return true;
}
// step 3: the rows, then the chunks after them up to IEND (CRCs checked)
inline bool png_step_rows(png_structp png, png_bytepp rows)
{
  if(setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

// libpng 1.6 only warns (a "benign error" on read) when a chunk declares more than its 8 MB chunk limit,
// then allocates the declared length: fuzzing found a 68-byte file with a tEXt chunk of 1.1 GB that made it
// allocate that much. A chunk cannot be longer than the file, so each chunk's length is checked against
// the bytes left before libpng sees the file (up to IEND; what follows is libpng's to judge).
inline void check_png_chunk_lengths(const std::string& path, const std::vector<unsigned char>& b)
{
  auto be32 = [&](std::size_t p) {
    return std::uint32_t(b[p]) << 24 | std::uint32_t(b[p + 1]) << 16 | std::uint32_t(b[p + 2]) << 8 | std::uint32_t(b[p + 3]);
  };
  // each chunk: length, type, data, CRC; libpng allocates the data once it has read length and type
  for(std::size_t pos = 8; b.size() - pos >= 8;) {
    const std::uint32_t length = be32(pos);
    const std::string type(b.begin() + std::ptrdiff_t(pos + 4), b.begin() + std::ptrdiff_t(pos + 8));
    if(std::uint64_t(length) + 12 > b.size() - pos)
      throw Invalid_input("image " + path + ": invalid PNG: chunk '" + Aniso_conformal::internal::printable(type, 4) + "' of " +
                          std::to_string(length) + " bytes runs past the end of the file");
    if(type == "IEND") return;
    pos += 12 + std::size_t(length);
  }
}

// owns libpng's structures
struct Png_reader {
  png_structp png = nullptr;
  png_infop info = nullptr;
  Png_reader(const Png_reader&) = delete;
  Png_reader& operator=(const Png_reader&) = delete;
  explicit Png_reader(Png_state* state)
  {
    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, state, png_on_error, png_on_warning);
    if(png != nullptr) info = png_create_info_struct(png);
    if(png != nullptr) png_set_read_fn(png, state, png_on_read);
  }
  ~Png_reader() { png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr); }
};

inline Image read_png(const std::string& path, const std::vector<unsigned char>& b)
{
  const std::string bad = "image " + path + ": ";
  Png_state state{b.data(), b.size(), 0, {0}, {0}};
  auto failure = [&]() {
    std::string m = bad + "invalid PNG: " + Aniso_conformal::internal::printable(state.error, 120);
    if(state.warning[0] != '\0' && std::strcmp(state.warning, state.error) != 0)
      m += " (" + Aniso_conformal::internal::printable(state.warning, 120) + ")";
    return Invalid_input(m);
  };
  check_png_chunk_lengths(path, b);
  Png_reader reader(&state);
  if(reader.png == nullptr || reader.info == nullptr) throw std::bad_alloc();
  png_set_user_limits(reader.png, 1u << 28, 1u << 28);  // check_size() has the last word
  if(!png_step_header(reader.png, reader.info)) throw failure();

  const long long w = png_get_image_width(reader.png, reader.info), h = png_get_image_height(reader.png, reader.info);
  const int depth = png_get_bit_depth(reader.png, reader.info), color = png_get_color_type(reader.png, reader.info);
  const std::size_t samples = png_get_channels(reader.png, reader.info);  // per pixel: 1 grey or index .. 4 RGBA
  check_size(path, w, h);
  // deflate expands at most 1032 times: refuse a header asking for more than the file can hold before
  // allocating it (a 69-byte file asked for 2 GB)
  const std::size_t raw_size = ((std::size_t(w) * samples * std::size_t(depth) + 7) / 8 + 1) * std::size_t(h);
  if(raw_size / 1032 > b.size()) throw Invalid_input(bad + "corrupt or truncated PNG image data");
  std::size_t rowbytes = 0;
  if(!png_step_transforms(reader.png, reader.info, depth, &rowbytes)) throw failure();
  const std::size_t bytes = depth == 16 ? 2 : 1;
  if(rowbytes != std::size_t(w) * samples * bytes)
    throw Internal_error(bad + "libpng gives rows of " + std::to_string(rowbytes) + " bytes, " +
                         std::to_string(std::size_t(w) * samples * bytes) + " expected");
  std::vector<unsigned char> pixels(rowbytes * std::size_t(h));
  std::vector<png_bytep> rows(static_cast<std::size_t>(h));
  for(std::size_t y = 0; y < rows.size(); ++y) rows[y] = pixels.data() + y * rowbytes;
  if(!png_step_rows(reader.png, rows.data())) throw failure();

  png_colorp palette = nullptr;
  int palette_size = 0;
  if(color == PNG_COLOR_TYPE_PALETTE && png_get_PLTE(reader.png, reader.info, &palette, &palette_size) == 0)
    throw Invalid_input(bad + "palette PNG without a palette");
  Image img;
  img.width = int(w);
  img.height = int(h);
  img.channels = (color == PNG_COLOR_TYPE_GRAY || color == PNG_COLOR_TYPE_GRAY_ALPHA) ? 1 : 3;  // alpha dropped
  img.data.resize(std::size_t(w) * std::size_t(h) * std::size_t(img.channels));
  const double maxv = double((1u << depth) - 1);
  std::size_t k = 0;
  for(std::size_t y = 0; y < std::size_t(h); ++y)
    for(std::size_t x = 0; x < std::size_t(w); ++x) {
      const unsigned char* p = rows[y] + x * samples * bytes;
      if(color == PNG_COLOR_TYPE_PALETTE) {
        if(p[0] >= palette_size) throw Invalid_input(bad + "palette index out of range");
        const png_color& c = palette[p[0]];
        for(const png_byte v : {c.red, c.green, c.blue}) img.data[k++] = float(v / 255.0);
      } else {
        for(std::size_t c = 0; c < std::size_t(img.channels); ++c)
          img.data[k++] = float((bytes == 2 ? unsigned(p[2 * c]) << 8 | p[2 * c + 1] : p[c]) / maxv);
      }
    }
  return img;
}

} // namespace internal

/*!
 * \ingroup PkgAnisoConformalIO
 * reads a PNG (any bit depth, colour type and interlacing; decoded by libpng, CRCs checked) or a
 * PPM/PGM (P2, P3, P5, P6) image. Samples are scaled to [0, 1] by the largest value of their bit depth
 * (or maxval), with no gamma correction; alpha and transparency are dropped; grey images have 1 channel,
 * colour and palette images 3.
 * \throws Invalid_input naming the file and the problem (libpng's message for a PNG, its bytes escaped):
 *         missing, unknown format, truncated or corrupt data, a palette index out of range, zero or
 *         absurd size (more than 2^28 pixels, or more pixels than the compressed data can hold)
 * \throws Internal_error if libpng's row size disagrees with the one computed from the header
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
