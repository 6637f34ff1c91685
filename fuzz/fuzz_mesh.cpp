// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "fuzz_common.h"
#include "fuzz_mesh.h"

#include <Aniso_conformal/IO/read_triangle_mesh.h>

#include <map>
#include <string>

namespace aniso_fuzz {

int read_mesh_bytes(const std::uint8_t* data, std::size_t size, const char* extension)
{
  static std::map<std::string, Temporary_file> files;
  auto it = files.try_emplace(extension, extension).first;
  try {
    const Aniso_conformal::Input_surface s = Aniso_conformal::IO::read_triangle_mesh(it->second.write(data, size));
    // a mesh that passed validation must be usable: touch what the pipeline reads first
    (void)s.number_of_vertices();
    (void)s.number_of_faces();
  } catch(const Aniso_conformal::Error&) {
    // the documented outcome of a bad file
  }
  return 0;
}

} // namespace aniso_fuzz
