#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Builds the libFuzzer targets with clang in build-fuzz/ and runs each for a bounded time (doc/fuzzing.md).
#   fuzz/run_fuzzers.sh [seconds] [target...]    default: 60 s for each of the seven targets
# One fuzzer at a time, on one core. New corpus entries go to build-fuzz/corpus/<target>/ (the committed
# seeds in fuzz/corpus/<target>/ are only read), crashes to build-fuzz/artifacts/<target>/, logs to
# build-fuzz/logs/<target>.log. Exit status 1 if any target found something.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-60}"
shift || true
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  targets=(fuzz_mesh_off fuzz_mesh_obj fuzz_mesh_ply fuzz_metric_file fuzz_feature_file fuzz_image fuzz_command_line)
fi
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [[ "$seconds" -eq 0 ]]; then
  echo "usage: $0 [seconds] [target...]" >&2
  exit 2
fi

# clang and its libFuzzer runtime come from Debian's archive; only this script needs them.
if ! command -v clang++ >/dev/null || ! echo 'extern "C" int LLVMFuzzerTestOneInput(const char*, long) { return 0; }' |
     clang++ -x c++ -fsanitize=fuzzer - -o /dev/null 2>/dev/null; then
  echo "== installing clang (Debian packages clang, libclang-rt-dev)"
  apt_get="apt-get"
  [[ $(id -u) -eq 0 ]] || apt_get="sudo apt-get"
  $apt_get update -qq
  DEBIAN_FRONTEND=noninteractive $apt_get install -y -qq clang libclang-rt-dev
fi

echo "== building the fuzz targets in build-fuzz/"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DANISO_CONFORMAL_BUILD_FUZZERS=ON -DANISO_CONFORMAL_BUILD_TESTS=OFF -DANISO_CONFORMAL_BUILD_EXAMPLES=OFF \
  -DANISO_CONFORMAL_BUILD_TOOLS=OFF -DANISO_CONFORMAL_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz --target "${targets[@]}" -j1

# stack traces for UBSan reports too (ASan prints them anyway)
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
status=0
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/artifacts/$t" build-fuzz/logs
  log="build-fuzz/logs/$t.log"
  echo "== $t for $seconds s (log: $log)"
  # -rss_limit_mb also bounds single allocations (-malloc_limit_mb defaults to it): a file that makes the
  # reader allocate gigabytes is a finding. -timeout=10: an input taking longer is a hang.
  if "build-fuzz/bin/$t" "build-fuzz/corpus/$t" "fuzz/corpus/$t" \
       -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
       -artifact_prefix="build-fuzz/artifacts/$t/" >"$log" 2>&1; then
    echo "   clean: $(grep -m1 -o 'Done [0-9]* runs in [0-9]* second(s)' "$log" || echo 'see log')"
  else
    status=1
    echo "   FOUND SOMETHING: $(grep -m1 -E 'ERROR:|runtime error|deadly signal|timeout|out-of-memory' "$log" || true)"
    ls "build-fuzz/artifacts/$t/"
  fi
done
exit $status
