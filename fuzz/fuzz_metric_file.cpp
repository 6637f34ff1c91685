// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// libFuzzer target: Aniso_conformal::IO::read_metric_file(). The first byte is the vertex count the
// caller expects (0 to 255: the count comes from the mesh, which the caller trusts); the rest is the file.

#include "fuzz_common.h"

#include <Aniso_conformal/IO/read_metric_file.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if(size == 0) return 0;
  static aniso_fuzz::Temporary_file file("metric");
  try {
    const Aniso_conformal::Tensor_field_metric m = Aniso_conformal::IO::read_metric_file(file.write(data + 1, size - 1), data[0]);
    (void)m;
  } catch(const Aniso_conformal::Error&) {
  }
  return 0;
}
