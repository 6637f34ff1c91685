// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_PRINTABLE_H
#define ANISO_CONFORMAL_INTERNAL_PRINTABLE_H

#include <cstddef>
#include <cstdio>
#include <string>

namespace Aniso_conformal {
namespace internal {

// `text` with every byte that is not printable ASCII (control characters, DEL, bytes >= 0x80) written
// as \xNN, and cut to `max_length` bytes of the original (then "..."): what a message may quote of an
// untrusted file, so that a garbage file never puts raw binary into a terminal or a log.
inline std::string printable(const std::string& text, std::size_t max_length = std::string::npos)
{
  static const char* hex = "0123456789abcdef";
  std::string out;
  const std::size_t n = text.size() < max_length ? text.size() : max_length;
  out.reserve(n);
  for(std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if(c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if(n < text.size()) out += "...";
  return out;
}

// a number in the %.3g format, for messages: std::to_string writes 4e-14 (and a tolerance of 1e-9) as
// 0.000000
inline std::string short_number(double x)
{
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_PRINTABLE_H
