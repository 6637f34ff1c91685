// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// libFuzzer target: Aniso_conformal::IO::read_triangle_mesh() on a .ply file.

#include "fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  return aniso_fuzz::read_mesh_bytes(data, size, "ply");
}
