#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (build-fuzz/) and fuzzes for the given number of
# seconds in all (default 60): two thirds on fuzz_scene (scene files with optional URDF and
# --set lines, mutated as bytes with the dictionary fuzz/toml.dict, seeded with
# scenes/*.toml, fuzz/seeds/ and the earlier findings in fuzz/regressions/), one third on
# fuzz_toml_structure (deep and huge TOML structure appended to the bundled scenes).
# A crash, a sanitizer report, a timeout (10 s per input) or an out-of-memory (2 GB) fails;
# the input is saved in build-fuzz/artifacts/ and belongs in fuzz/regressions/ once fixed
# (docs/sanitizers_fuzzing.md says how).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
CXX=clang++-14 CC=clang-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTICTION_FUZZ=ON \
      -DSTICTION_BUILD_TESTS=OFF -DSTICTION_BUILD_BENCH=OFF -DSTICTION_BUILD_PYTHON=OFF \
      ${launcher[@]+"${launcher[@]}"} >&2
cmake --build build-fuzz -j"$(nproc)" --target fuzz_scene fuzz_toml_structure >&2
mkdir -p build-fuzz/corpus/scene build-fuzz/corpus/structure build-fuzz/artifacts
cp scenes/*.toml fuzz/seeds/* build-fuzz/corpus/scene/
find fuzz/regressions -maxdepth 1 -type f ! -name README.md -exec cp {} build-fuzz/corpus/scene/ \;
export ASAN_OPTIONS=detect_leaks=1
# The libraries whose own leaks are suppressed, and why: .ci/lsan.supp.
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
common=(-timeout=10 -rss_limit_mb=2048 -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1)
echo "== fuzz_scene for $((seconds * 2 / 3)) s" >&2
build-fuzz/fuzz/fuzz_scene -max_total_time=$((seconds * 2 / 3)) -dict=fuzz/toml.dict "${common[@]}" \
  build-fuzz/corpus/scene
echo "== fuzz_toml_structure for $((seconds - seconds * 2 / 3)) s" >&2
build-fuzz/fuzz/fuzz_toml_structure -max_total_time=$((seconds - seconds * 2 / 3)) -max_len=512 -len_control=0 "${common[@]}" \
  build-fuzz/corpus/structure
