// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// libFuzzer target: aniso_remesh::parse_command_line(). The input is split at NUL and newline bytes into
// arguments (argv never holds a NUL; newlines make the corpus readable).

#include "../tools/command_line.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::vector<std::string> args;
  std::string arg;
  for(std::size_t i = 0; i < size; ++i) {
    if(data[i] == '\0' || data[i] == '\n') {
      args.push_back(arg);
      arg.clear();
    } else {
      arg += char(data[i]);
    }
  }
  if(!arg.empty()) args.push_back(arg);
  try {
    const aniso_remesh::Options o = aniso_remesh::parse_command_line(args);
    (void)o;
  } catch(const Aniso_conformal::Error&) {
  }
  return 0;
}
