// libFuzzer target over contacts between bodies (issue 39 item 8): the bytes are a recipe
// (fuzz/pairs_recipe.hpp) for a scene of spheres and boxes with pair contacts, hostile
// numbers, coincident and nested bodies and up to 2016 pairs. Each input must end in an
// InputError, or a built scene that then steps briefly (fuzz/step_fuzz_scene.hpp) and ends
// unstable, on a model fault, or with only finite numbers: never a crash, a sanitizer report,
// a hang, or a finished run with a non-finite number (NonFiniteFinish, not caught here).
//
// A finding is bytes; its scene (plain TOML, which test_fuzz_regressions replays and steps):
//   STICTION_FUZZ_WRITE=fuzz/regressions/NAME.toml build-fuzz/fuzz/fuzz_pairs CRASH
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "fuzz/load_fuzz_input.hpp"
#include "fuzz/pairs_recipe.hpp"
#include "fuzz/step_fuzz_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stiction::fuzz;
  tally().target = "fuzz_pairs";
  ByteReader in(data, size);
  const std::string document = pairs_scene(in);
  if (const char* path = std::getenv("STICTION_FUZZ_WRITE")) {
    std::ofstream(path, std::ios::binary) << document;
  }
  ++tally().inputs;
  std::optional<stiction::scene::Scene> scene = load_fuzz_scene(document);
  if (!scene) {
    ++tally().refused;
    return 0;
  }
  ++tally().built;
  step_briefly(*scene);
  return 0;
}
