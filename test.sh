#!/usr/bin/env bash
# Installs the dependencies, builds everything (library tests, tool, examples as one compile check,
# benchmarks) in build/ and runs the whole Boost.Test suite through ctest.
#   ./test.sh --sanitize   builds the tests and the tool with AddressSanitizer and
#                          UndefinedBehaviorSanitizer in build-sanitize/ and runs the suite there
#   ./test.sh --sanitize-subset   the same for test_io and test_cli only, the tool they run under
#                          AddressSanitizer alone (CI runs it after the full suite)
set -euo pipefail
cd "$(dirname "$0")"
./scripts/install_dependencies.sh
# The sanitized builds: -O1 -g1 (line tables), the optimisation AddressSanitizer's documentation
# recommends; with CGAL's templates under ASan + UBSan the subset's three translation units took about
# 27 CPU-minutes at -O2 -g and 13 at -O1 -g1, for the same checks and stack traces with file and line;
# about 12 (730 user-s with its tests) since test_io compiles no remesher and test_cli compiles beside
# the tool (a CTest fixture, not a build dependency, brings the tool up to date before test_cli runs).
# -O0 halves the compilation (tool 764 -> 383 CPU-s) but test_cli then ran over 8 minutes instead of 75 s.
sanitize_flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG")
if [[ "${1:-}" == "--sanitize-subset" ]]; then
  # what CI adds to the full run: the readers of untrusted bytes and the command line (test_io, test_cli)
  # under AddressSanitizer and UndefinedBehaviorSanitizer, and the tool they run under AddressSanitizer
  # (with both its one translation unit took 764 CPU-s, CI's longest step; 424 with the first alone)
  cmake -S . -B build-sanitize "${sanitize_flags[@]}" -DANISO_CONFORMAL_SANITIZE=ON -DANISO_CONFORMAL_SANITIZE_TOOL_UNDEFINED=OFF \
        -DANISO_CONFORMAL_BUILD_TESTS=ON -DANISO_CONFORMAL_BUILD_TOOLS=ON \
        -DANISO_CONFORMAL_BUILD_EXAMPLES=OFF -DANISO_CONFORMAL_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build build-sanitize -j"$(nproc)" --target sanitizer_subset
  cd build-sanitize
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --output-on-failure -j"$(nproc)" -R '^(test_io|test_cli|test_cli_cones)$'
  exit 0
fi
if [[ "${1:-}" == "--sanitize" ]]; then
  cmake -S . -B build-sanitize "${sanitize_flags[@]}" -DANISO_CONFORMAL_SANITIZE=ON -DANISO_CONFORMAL_SANITIZE_TOOL_UNDEFINED=ON \
        -DANISO_CONFORMAL_BUILD_TESTS=ON -DANISO_CONFORMAL_BUILD_TOOLS=ON \
        -DANISO_CONFORMAL_BUILD_EXAMPLES=OFF -DANISO_CONFORMAL_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build build-sanitize -j"$(nproc)"
  cd build-sanitize
  # the install-and-consume test builds an unsanitized project: not meaningful here
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --output-on-failure -j1 -E find_package_consumer
  exit 0
fi
# explicit ON: ./run.sh configures the same build/ with only the tool. The examples are compiled as one
# check (examples/CMakeLists.txt: all of them in one translation unit, about 126 CPU-s instead of 700; no
# test runs them); `cmake -S . -B build -DANISO_CONFORMAL_EXAMPLES_COMPILE_CHECK_ONLY=OFF` then builds the
# example programs into build/bin/.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DANISO_CONFORMAL_BUILD_TESTS=ON -DANISO_CONFORMAL_BUILD_EXAMPLES=ON \
      -DANISO_CONFORMAL_EXAMPLES_COMPILE_CHECK_ONLY=ON \
      -DANISO_CONFORMAL_BUILD_TOOLS=ON -DANISO_CONFORMAL_BUILD_BENCHMARKS=ON >/dev/null
cmake --build build -j"$(nproc)"
cd build
ctest --output-on-failure -j"$(nproc)"  # the tests write distinct files: they run side by side
