// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The three mesh targets (fuzz_mesh_off, fuzz_mesh_obj, fuzz_mesh_ply) share one compiled reader.

#ifndef ANISO_CONFORMAL_FUZZ_MESH_H
#define ANISO_CONFORMAL_FUZZ_MESH_H

#include <cstddef>
#include <cstdint>

namespace aniso_fuzz {
// reads `data` as a mesh file with extension `extension` ("off", "obj" or "ply"); lets through any
// exception that is not an Aniso_conformal::Error, so that libFuzzer reports it
int read_mesh_bytes(const std::uint8_t* data, std::size_t size, const char* extension);
} // namespace aniso_fuzz

#endif // ANISO_CONFORMAL_FUZZ_MESH_H
