// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// libFuzzer target: Aniso_conformal::IO::read_feature_file(). The first byte is the vertex count the
// caller expects (0 to 255: the count comes from the mesh, which the caller trusts); the rest is the file.

#include "fuzz_common.h"

#include <Aniso_conformal/IO/read_feature_file.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if(size == 0) return 0;
  static aniso_fuzz::Temporary_file file("features");
  try {
    const std::size_t n = data[0];
    const Aniso_conformal::IO::Marked_features m = Aniso_conformal::IO::read_feature_file(file.write(data + 1, size - 1), n);
    for(const auto& e : m.edges)  // what it returns names vertices of the mesh, never itself twice
      if(e[0] >= n || e[1] >= n || e[0] == e[1]) __builtin_trap();
    for(std::size_t v : m.vertices)
      if(v >= n) __builtin_trap();
  } catch(const Aniso_conformal::Error&) {
  }
  return 0;
}
