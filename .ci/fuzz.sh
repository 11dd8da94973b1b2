#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (build-fuzz/) and fuzzes for the given number of
# seconds in all (default 60), split among them (docs/sanitizers_fuzzing.md has the figures
# of longer runs):
#   fuzz_scene           1/3 (21 of 60 s): scene files with optional URDF and --set lines, mutated as bytes
#                        with the dictionary fuzz/toml.dict, seeded with scenes/*.toml,
#                        fuzz/seeds/ and the earlier findings in fuzz/regressions/;
#   fuzz_toml_structure  1/10: deep and huge TOML structure appended to the bundled scenes;
#   fuzz_pairs           2/15: bodies in contact with one another (pair contacts), stepped;
#   fuzz_urdf            2/15: URDF robots with meshes, limits and odd inertias, stepped, no
#                        file opened outside the input's folder;
#   fuzz_sweep_plan      1/20: sweep plans (--vary, --zip, --shard, Slurm variables);
#   fuzz/fuzz_python.py  1/10: the Python module's elements and laws (fixed seed), when
#                        the Release build has built the module (build/python); otherwise
#                        its share goes to fuzz_scene.
# A crash, a sanitizer report, a timeout (10 s per input), an out-of-memory (2 GB) or, for
# the stepped targets, a run that ends as a success with a non-finite number fails; the
# input is saved in build-fuzz/artifacts/ and belongs in fuzz/regressions/ once fixed
# (docs/sanitizers_fuzzing.md says how).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
CXX=clang++-14 CC=clang-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTICTION_FUZZ=ON \
      -DSTICTION_BUILD_TESTS=OFF -DSTICTION_BUILD_BENCH=OFF -DSTICTION_BUILD_PYTHON=OFF \
      ${launcher[@]+"${launcher[@]}"} >&2
cmake --build build-fuzz -j"$(nproc)" --target fuzz_scene fuzz_toml_structure fuzz_pairs fuzz_urdf \
      fuzz_sweep_plan >&2
for c in scene structure pairs urdf sweep; do mkdir -p build-fuzz/corpus/$c; done
mkdir -p build-fuzz/artifacts
cp scenes/*.toml fuzz/seeds/* build-fuzz/corpus/scene/
find fuzz/regressions -maxdepth 1 -type f ! -name README.md -exec cp {} build-fuzz/corpus/scene/ \;
cp fuzz/seeds-pairs/* build-fuzz/corpus/pairs/
cp fuzz/seeds-urdf/* build-fuzz/corpus/urdf/
cp fuzz/seeds-sweep/* build-fuzz/corpus/sweep/
export ASAN_OPTIONS=detect_leaks=1
# The libraries whose own leaks are suppressed, and why: .ci/lsan.supp.
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
common=(-timeout=10 -rss_limit_mb=2048 -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1)

python_seconds=$((seconds / 10))
module=$(ls build/python/stiction/_stiction*.so 2>/dev/null | head -n 1 || true)
python=/usr/bin/python3
[ -x "$python" ] || python=python3
if [ -z "$module" ]; then
  echo "== fuzz_python skipped: no build/python/stiction/_stiction*.so (the Release build makes it)" >&2
  python_seconds=0
fi
# libFuzzer finishes the input it is on and starts with its corpus: each target overruns its
# share by 1-6 s (a stepped pile of bodies takes seconds instrumented), so 2/15 of the time
# is left as a margin and the whole step stays near SECONDS.
structure=$((seconds / 10)) pairs=$((seconds * 2 / 15)) urdf=$((seconds * 2 / 15)) sweep=$((seconds / 20))
scene=$((seconds - seconds * 2 / 15 - structure - pairs - urdf - sweep - python_seconds))
run() {  # NAME SECONDS CORPUS [OPTIONS...]
  local name=$1 time=$2 corpus=$3
  shift 3
  [ "$time" -gt 0 ] || return 0
  echo "== $name for $time s" >&2
  "build-fuzz/fuzz/$name" -max_total_time="$time" "${common[@]}" "$@" "build-fuzz/corpus/$corpus"
}
run fuzz_scene "$scene" scene -dict=fuzz/toml.dict
run fuzz_toml_structure "$structure" structure -max_len=512 -len_control=0
# One implicit step of a pile of boxes cannot be cut short: 0.1 s in Release, 3 s
# instrumented, 10-15 s on a loaded machine (2 boxes, dt = 0.1 s, 2026-12-06): 30 s an input,
# which still fails a step that never ends.
run fuzz_pairs "$pairs" pairs -max_len=1024 -timeout=30
run fuzz_urdf "$urdf" urdf -max_len=2048 -timeout=30
# A plan at the documented maximum (1000000 points) takes seconds instrumented: 30 s an input.
run fuzz_sweep_plan "$sweep" sweep -dict=fuzz/sweep.dict -max_len=512 -timeout=30
if [ "$python_seconds" -gt 0 ]; then
  echo "== fuzz_python for $python_seconds s (seed 1)" >&2
  PYTHONPATH=build/python STICTION_CACHE_DIR=off "$python" fuzz/fuzz_python.py --seed 1 \
    --cases 100000 --seconds "$python_seconds"
fi
