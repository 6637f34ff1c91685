#!/usr/bin/env bash
# Installs the dependencies, builds everything (library tests, tool, examples, benchmarks) in build/
# and runs the whole Boost.Test suite through ctest.
set -euo pipefail
cd "$(dirname "$0")"
./scripts/install_dependencies.sh
# explicit ON: ./run.sh configures the same build/ with only the tool
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DANISO_CONFORMAL_BUILD_TESTS=ON -DANISO_CONFORMAL_BUILD_EXAMPLES=ON \
      -DANISO_CONFORMAL_BUILD_TOOLS=ON -DANISO_CONFORMAL_BUILD_BENCHMARKS=ON >/dev/null
cmake --build build -j"$(nproc)"
cd build
ctest --output-on-failure -j1
