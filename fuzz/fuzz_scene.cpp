// libFuzzer target over the scene loader and --set (issue 14): the input is a scene file,
// optionally followed by a line "%%" and then one --set assignment per line. Every input
// must end in a built scene or a scene::InputError (exit 2 in the program); any other
// exception, a crash, a sanitizer report or a hang is a finding. Run limits are checked as
// `run` does (core::check_run_limits) so that a value past them is refused, not simulated.
//
// Built by .ci/run with clang (-fsanitize=fuzzer,address,undefined); the seed corpus is
// scenes/*.toml. A finding becomes a file in fuzz/regressions/, which
// tests/reliability/test_fuzz_regressions.cpp loads on every test run.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/load_fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  stiction::fuzz::load_fuzz_input(std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}
