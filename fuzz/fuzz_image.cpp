// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// libFuzzer target: Aniso_conformal::IO::read_image() (PNG, PGM, PPM; the format comes from the magic
// bytes, not the extension).

#include "fuzz_common.h"

#include <Aniso_conformal/IO/read_image.h>

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static aniso_fuzz::Temporary_file file("img");
  try {
    const Aniso_conformal::IO::Image img = Aniso_conformal::IO::read_image(file.write(data, size));
    // what Image_metric relies on: a consistent size and samples in [0, 1]
    if((img.channels != 1 && img.channels != 3) || img.width <= 0 || img.height <= 0 ||
       img.data.size() != std::size_t(img.width) * std::size_t(img.height) * std::size_t(img.channels))
      std::abort();
    for(float v : img.data)
      if(!(v >= 0.0f && v <= 1.0f)) std::abort();
  } catch(const Aniso_conformal::Error&) {
  }
  return 0;
}
