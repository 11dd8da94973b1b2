#!/usr/bin/env bash
# Builds the libFuzzer target with clang (build-fuzz/) and fuzzes the scene loader and --set
# for the given number of seconds (default 60), seeded with scenes/*.toml and the earlier
# findings in fuzz/regressions/. A crash, a sanitizer report, a timeout (10 s per input) or
# an out-of-memory (2 GB) fails; the input is saved in build-fuzz/artifacts/ and belongs in
# fuzz/regressions/ once fixed.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
CXX=clang++-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTICTION_FUZZ=ON \
      -DSTICTION_BUILD_TESTS=OFF -DSTICTION_BUILD_BENCH=OFF -DSTICTION_BUILD_PYTHON=OFF >&2
cmake --build build-fuzz -j"$(nproc)" --target fuzz_scene >&2
corpus=build-fuzz/corpus
mkdir -p "$corpus" build-fuzz/artifacts
cp scenes/*.toml "$corpus"/
find fuzz/regressions -type f ! -name README.md -exec cp {} "$corpus"/ \;
export ASAN_OPTIONS=detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
build-fuzz/fuzz/fuzz_scene -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1 "$corpus"
