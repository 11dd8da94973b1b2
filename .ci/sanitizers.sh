#!/usr/bin/env bash
# Builds everything with AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/ and runs
# the test suite under it (STICTION_ASAN_EXCLUDE, a ctest regex, leaves tests out if CI time
# requires; see docs/sanitizers_fuzzing.md). Any report fails: UBSan aborts on the first
# error, ASan on any memory error, LeakSanitizer at exit on any leak not in libOSMesa
# (.ci/lsan.supp: Mesa keeps 480 bytes of its own at exit, outside our control).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTICTION_SANITIZE=ON \
      -DSTICTION_BUILD_BENCH=OFF "$@" >&2
# (No -Werror here: GCC 12 under -fsanitize reports false -Wmaybe-uninitialized inside
# libstdc++'s <regex>; the Release build keeps warnings as errors.)
cmake --build build-asan -j"$(nproc)" >&2
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j2 --timeout 1200 -E "${STICTION_ASAN_EXCLUDE:-^$}"
