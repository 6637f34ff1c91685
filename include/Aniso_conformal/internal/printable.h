// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_PRINTABLE_H
#define ANISO_CONFORMAL_INTERNAL_PRINTABLE_H

#include <cstddef>
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

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_PRINTABLE_H
