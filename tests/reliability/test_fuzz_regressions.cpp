// Replays what the fuzzer found (fuzz/regressions/*) and its seed corpus (scenes/*.toml)
// through the same loader as the fuzz target: each input ends in a scene or an InputError,
// never another exception or a crash. Under the sanitizer build (.ci/run) this also checks
// them for memory errors and undefined behaviour.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include <catch2/catch.hpp>

#include "fuzz/load_fuzz_input.hpp"
#include "fuzz/step_fuzz_scene.hpp"

namespace fs = std::filesystem;

namespace {

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("fuzz findings and seeds load or are refused as input errors", "[fuzz]") {
  int inputs = 0, built = 0;
  for (const char* dir : {"fuzz/regressions", "scenes"}) {
    for (const auto& entry : fs::directory_iterator(fs::path(STICTION_SOURCE_DIR) / dir)) {
      if (!entry.is_regular_file() || entry.path().filename() == "README.md") continue;
      INFO(entry.path().string());
      bool ok = false;
      CHECK_NOTHROW(ok = stiction::fuzz::load_fuzz_input(read_all(entry.path())));
      ++inputs;
      built += ok ? 1 : 0;
    }
  }
  CHECK(inputs > 0);
  CHECK(built >= 7);  // the bundled scenes all load
}

TEST_CASE("the fuzz input format carries --set lines after %%", "[fuzz]") {
  const std::string scene = read_all(fs::path(STICTION_SOURCE_DIR) / "scenes" / "sphere_roll.toml");
  CHECK(stiction::fuzz::load_fuzz_input(scene));
  CHECK(stiction::fuzz::load_fuzz_input(scene + "\n%%\nsimulation.dt=2e-4\n"));
  CHECK_FALSE(stiction::fuzz::load_fuzz_input(scene + "\n%%\nsimulation.dt=nan\n"));
  CHECK_FALSE(stiction::fuzz::load_fuzz_input(scene + "\n%%\nno.such.key=1\n"));
  CHECK_FALSE(stiction::fuzz::load_fuzz_input(scene + "\n%%\nsimulation.output_rate=1e300\n"));
}

TEST_CASE("the seeds of the new surfaces load and step to finite numbers or an instability",
          "[fuzz]") {
  // fuzz/seeds/pairs_* (coincident, nested, 780 pairs, nan-ish strings) and urdf_* (meshes
  // named outside the folder or with escapes, crossed limits, odd inertias, a 300-joint
  // limited chain), stepped as fuzz_pairs and fuzz_urdf step their inputs (issue 39 item 8).
  int stepped = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(STICTION_SOURCE_DIR) / "fuzz/seeds")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("pairs_", 0) != 0 && name.rfind("urdf_", 0) != 0) continue;
    INFO(name);
    std::optional<stiction::scene::Scene> scene;
    CHECK_NOTHROW(scene = stiction::fuzz::load_fuzz_scene(read_all(entry.path())));
    if (!scene) continue;
    CHECK_NOTHROW(stiction::fuzz::step_briefly(*scene));
    ++stepped;
  }
  CHECK(stepped >= 6);
}
