// libFuzzer target over the STRUCTURE of scene files (issue 25): the bytes are not TOML but
// a recipe (fuzz/toml_structure.hpp) for deep tables, long dotted keys, deep and huge arrays
// and many tables appended to a bundled scene, which then goes through the same loader as
// fuzz_scene (fuzz/load_fuzz_input.hpp). Findings must end in a built scene or an
// InputError, as there.
//
// A crash input is bytes; to keep it as a regression (fuzz/regressions/, plain TOML that
// test_fuzz_regressions replays), write the document it makes:
//   STICTION_FUZZ_WRITE=fuzz/regressions/NAME.toml build-fuzz/fuzz/fuzz_toml_structure CRASH
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/load_fuzz_input.hpp"
#include "fuzz/toml_structure.hpp"

namespace {

std::vector<std::string> base_scenes;

std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(STICTION_SOURCE_DIR "/scenes")) {
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());  // the same byte picks the same scene everywhere
  base_scenes.push_back("name = \"fuzz\"\n");
  for (const auto& f : files) base_scenes.push_back(read_all(f));
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  stiction::fuzz::ByteReader in(data, size);
  const std::string& base = base_scenes[in.byte() % base_scenes.size()];
  const std::string document = stiction::fuzz::toml_structure(in, base);
  if (const char* path = std::getenv("STICTION_FUZZ_WRITE")) {
    std::ofstream(path, std::ios::binary) << document;
  }
  stiction::fuzz::load_fuzz_input(document);
  return 0;
}
