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
# loader and its fuzz regressions (scene, reliability), signals, limits and the output
# directory with the real binary (reliability), events, physics, the renderer with its video
# and images (render), components, contacts (the body pairs), sources, extremes and the
# command line (app, which also draws every kind of figure with the instrumented binary).
# The URDF loader's tests are in scene. Left out to keep CI within its time: the folders
# made of whole trial runs repeated many times over (ci: suggested steps and verify; study;
# scenarios), minutes each under ASan; plot (13 programs of layout arithmetic: ticks, labels,
# legends, whose drawing code app's figure tests already run instrumented); cluster (Slurm).
# See docs/sanitizers_fuzzing.md.
set(STICTION_SANITIZE_TESTS
    "app;components;contacts;events;extremes;physics;reliability;render;scene;sources"
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
