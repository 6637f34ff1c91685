// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Shared by the libFuzzer targets: the readers take a path, so each input is written to a temporary
// file first (doc/fuzzing.md).

#ifndef ANISO_CONFORMAL_FUZZ_COMMON_H
#define ANISO_CONFORMAL_FUZZ_COMMON_H

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <unistd.h>

namespace aniso_fuzz {

// One file per process and extension, rewritten for every input and removed at exit. The process id
// keeps parallel runs (-jobs, -workers) apart; /dev/shm avoids disk writes at thousands of inputs a second.
class Temporary_file {
public:
  explicit Temporary_file(const std::string& extension)
  {
    const char* tmp = std::getenv("TMPDIR");
    const std::string dir = tmp && *tmp ? tmp : (access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp");
    m_path = dir + "/aniso_fuzz_" + std::to_string(getpid()) + "." + extension;
  }
  ~Temporary_file() { std::remove(m_path.c_str()); }

  // writes `size` bytes and returns the path; aborts if the file cannot be written (a broken set-up,
  // not a finding)
  const std::string& write(const std::uint8_t* data, std::size_t size)
  {
    std::FILE* f = std::fopen(m_path.c_str(), "wb");
    if(f == nullptr || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
      std::perror(m_path.c_str());
      std::abort();
    }
    return m_path;
  }

private:
  std::string m_path;
};

} // namespace aniso_fuzz

#endif // ANISO_CONFORMAL_FUZZ_COMMON_H
