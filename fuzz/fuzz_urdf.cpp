// libFuzzer target over URDF robots (issue 39 item 8): the bytes are a recipe
// (fuzz/urdf_recipe.hpp) for a URDF with meshes (package:// paths, traversals, devices,
// control characters), <limit>, <dynamics> and odd inertias, and the scene that loads it as
// `fuzz.urdf`. Both are written into the process's scratch directory and loaded as `run`
// loads them (fuzz/load_fuzz_input.hpp), then stepped briefly (fuzz/step_fuzz_scene.hpp).
//
// Invariants: an InputError or a scene that steps to an instability, a model fault or finite
// numbers (never a crash, a sanitizer report, a hang or a finished run with a non-finite
// number), and no file opened outside the scratch directory while the scene is built and run
// (fuzz/open_watch.cpp sees every open, fopen and openat of the process): a mesh named
// ../../etc/passwd or /dev/zero must not be read. A path outside aborts with the path.
//
// A finding is bytes; its input in the fuzz_scene format (the scene, "%%urdf", the URDF),
// which test_fuzz_regressions replays:
//   STICTION_FUZZ_WRITE=fuzz/regressions/NAME.fuzz build-fuzz/fuzz/fuzz_urdf CRASH
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz/load_fuzz_input.hpp"
#include "fuzz/open_watch.hpp"
#include "fuzz/step_fuzz_scene.hpp"
#include "fuzz/urdf_recipe.hpp"

namespace {

bool watching = false;
std::vector<std::string> opened;  // paths opened while watching, made absolute

}  // namespace

void stiction::fuzz::note_open(const char* path, int dir) {
  if (!watching || path == nullptr) return;
  watching = false;  // what follows may open nothing itself, but allocates: no re-entry
  std::string p(path);
  if (dir != kCurrentDirectory && !p.empty() && p.front() != '/') {
    p = "<directory descriptor " + std::to_string(dir) + ">/" + p;
  } else {
    std::error_code ignored;
    p = std::filesystem::absolute(p, ignored).lexically_normal().string();
  }
  opened.push_back(p);
  watching = true;
}

namespace {

// Aborts (a finding) when a path opened is not inside the scratch directory.
void check_opened() {
  const std::string inside = stiction::fuzz::scratch_directory().lexically_normal().string() + "/";
  for (const std::string& p : opened) {
    if (p.compare(0, inside.size(), inside) != 0) {
      std::fprintf(stderr, "fuzz_urdf: the input opened '%s', outside %s\n", p.c_str(),
                   inside.c_str());
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // The watch must see the library's own reads: check it once on the scratch directory.
  const std::filesystem::path probe = stiction::fuzz::scratch_directory() / "probe";
  std::ofstream(probe) << "probe";
  watching = true;
  { std::ifstream in(probe); }
  watching = false;
  if (opened.size() != 1) {
    std::fprintf(stderr, "fuzz_urdf: the open watch saw %zu opens of a probe file, not 1\n",
                 opened.size());
    std::abort();
  }
  opened.clear();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stiction::fuzz;
  tally().target = "fuzz_urdf";
  ByteReader in(data, size);
  const std::string scene_text = urdf_scene(in);
  const std::string robot = urdf_robot(in);
  const std::string input = scene_text + "\n%%urdf\n" + robot;
  if (const char* path = std::getenv("STICTION_FUZZ_WRITE")) {
    std::ofstream(path, std::ios::binary) << input;
  }
  ++tally().inputs;
  opened.clear();
  // load_fuzz_scene writes fuzz.toml and fuzz.urdf into the scratch directory (inside), then
  // builds the scene; the watch covers the build and the steps.
  watching = true;
  std::optional<stiction::scene::Scene> scene = load_fuzz_scene(input);
  if (scene) {
    ++tally().built;
    step_briefly(*scene);
  } else {
    ++tally().refused;
  }
  watching = false;
  check_opened();
  return 0;
}
