# Instrumented builds for CI (.ci/run, docs/sanitizers_fuzzing.md):
# - STICTION_SANITIZE: everything with AddressSanitizer + UndefinedBehaviorSanitizer (g++ or
#   clang); any UB report aborts. Leaks are checked by LeakSanitizer with
#   .ci/lsan.supp, which names libOSMesa only.
# - STICTION_FUZZ: the libFuzzer target fuzz/fuzz_scene, clang only; the libraries it uses
#   are built with coverage instrumentation and the same sanitizers.
option(STICTION_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(STICTION_FUZZ "Build the libFuzzer target fuzz_scene (clang)" OFF)

set(STICTION_SANITIZER_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=undefined
                             -fno-omit-frame-pointer)
# The test folders the instrumented build builds and runs (tests/CMakeLists.txt): the scene
# loader, the URDF loader and the fuzz regressions (scene, reliability), signals, limits and
# the output directory with the real binary (reliability), components, contacts (the body
# pairs) and the command line (app, which also runs the renderer with its video and frames,
# draws every kind of figure and runs every kind of source through the bundled scenes with the
# instrumented binary). Left out to keep CI
# within its time (every one still runs in the Release step): the folders made of whole
# trial runs repeated many times over (ci, study, scenarios, and since 2026-12-05 events,
# extremes and physics: closed-form checks whose code paths components and contacts run
# instrumented on small scenes), render (its image comparisons; app renders videos and
# frames instrumented), plot (layout arithmetic; app draws figures instrumented), sources
# (since 2026-12-07: prescribed forces, torques and moving surfaces, which app's runs of the
# bundled scenes drive instrumented), cluster (Slurm). See docs/sanitizers_fuzzing.md.
set(STICTION_SANITIZE_TESTS
    "app;components;contacts;reliability;scene"
    CACHE STRING "With STICTION_SANITIZE: the tests/ folders to build and run")

if(STICTION_SANITIZE OR STICTION_FUZZ)
  add_compile_options(${STICTION_SANITIZER_FLAGS})
  add_link_options(-fsanitize=address,undefined)
endif()
if(STICTION_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "STICTION_FUZZ needs clang (libFuzzer): CXX=clang++-14")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
