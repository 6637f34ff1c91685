#!/usr/bin/env bash
# Installs the dependencies, builds everything (library tests, tool, examples, benchmarks) in build/
# and runs the whole Boost.Test suite through ctest.
set -euo pipefail
cd "$(dirname "$0")"
./scripts/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
cd build
ctest --output-on-failure -j1
