// libFuzzer target over sweep plans (issue 39 item 8): `stiction sweep`'s --vary, --zip and
// --shard and the Slurm array variables (services/sweep_plan.hpp), then the points' values
// applied to a bundled scene as the sweep applies them (`--set KEY=VALUE` per point).
//
// An input is text. Its first byte chooses: bit 0 --zip, bits 1-6 the bundled scene the
// points are applied to (in name order), bit 7 the plan's bound (the documented maximum of
// points, or 20000). Each further line is
//   `shard K/N`                  parsed as --shard,
//   `slurm ID COUNT [MIN]`       set as SLURM_ARRAY_TASK_ID/COUNT/MIN and read back,
//   anything else                a --vary argument (KEY=LIST).
// Invariants: every refusal is a scene::InputError whose message names the option or key
// (starts with "--vary ", "--shard ", "error: "); the plan has the product of the lists'
// lengths as points (or their common length with --zip), each with one value per key, never
// more than kMaxSweepPoints; no crash, sanitizer report, hang, or memory above the
// libFuzzer -rss_limit_mb (.ci/fuzz.sh: 2048 MB) for a plan at the documented maximum. The
// first, the last and one shard's first point are then built as scenes (load_fuzz_scene):
// a scene or an InputError.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz/load_fuzz_input.hpp"
#include "fuzz/step_fuzz_scene.hpp"
#include "services/sweep_plan.hpp"

namespace {

std::vector<std::string> base_scenes;

std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_sweep_plan: %s\n", what.c_str());
  std::abort();
}

void check_message(const stiction::scene::InputError& e) {
  const std::string m = e.what();
  if (m.rfind("--vary ", 0) != 0 && m.rfind("--shard ", 0) != 0 && m.rfind("error: ", 0) != 0) {
    finding("a refusal that names no option: " + m);
  }
}

// SLURM_ARRAY_TASK_* from "ID COUNT [MIN]", read as the sweep reads them, then unset.
void slurm(const std::string& text) {
  std::istringstream words(text);
  std::string id, count, min;
  words >> id >> count >> min;
  ::setenv("SLURM_ARRAY_TASK_ID", id.c_str(), 1);
  ::setenv("SLURM_ARRAY_TASK_COUNT", count.c_str(), 1);
  if (!min.empty()) ::setenv("SLURM_ARRAY_TASK_MIN", min.c_str(), 1);
  try {
    const std::optional<stiction::services::Shard> shard =
        stiction::services::shard_from_environment();
    if (!shard || shard->count < 1 || shard->index >= shard->count) {
      finding("SLURM variables '" + text + "' made no valid shard without an error");
    }
  } catch (const stiction::scene::InputError& e) {
    check_message(e);
  }
  ::unsetenv("SLURM_ARRAY_TASK_ID");
  ::unsetenv("SLURM_ARRAY_TASK_COUNT");
  ::unsetenv("SLURM_ARRAY_TASK_MIN");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(STICTION_SOURCE_DIR "/scenes")) {
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& f : files) base_scenes.push_back(read_all(f));
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stiction;
  fuzz::tally().target = "fuzz_sweep_plan";
  if (size == 0) return 0;
  const bool zip = (data[0] & 1) != 0;
  const std::string& base = base_scenes[((data[0] >> 1) & 63) % base_scenes.size()];
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  std::vector<services::VaryKey> keys;
  services::Shard shard;
  ++fuzz::tally().inputs;
  try {
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("shard ", 0) == 0) {
        shard = services::parse_shard(line.substr(6));
        if (shard.count < 1 || shard.index >= shard.count) finding("shard '" + line + "' accepted");
      } else if (line.rfind("slurm ", 0) == 0) {
        slurm(line.substr(6));
      } else {
        keys.push_back(services::parse_vary(line));
        if (keys.back().key.empty() || keys.back().values.empty()) {
          finding("--vary '" + line + "' gave an empty key or no values");
        }
      }
    }
    // The documented maximum of points when bit 7 of the first byte is set; otherwise
    // 20000, so that the fuzzer's time goes to many plans rather than to a few of a million
    // points (each about a second instrumented).
    const std::size_t limit = (data[0] & 0x80) != 0 ? services::kMaxSweepPoints : 20000;
    const std::vector<services::SweepPoint> points = services::make_points(keys, zip, limit);
    double expected = keys.empty() ? 0.0 : 1.0;
    for (const services::VaryKey& k : keys) {
      expected = zip ? static_cast<double>(k.values.size())
                     : expected * static_cast<double>(k.values.size());
    }
    if (static_cast<double>(points.size()) != expected || points.size() > limit) {
      finding("the plan has " + std::to_string(points.size()) + " points, expected " +
              std::to_string(expected));
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (points[i].index != i || points[i].values.size() != keys.size()) {
        finding("point " + std::to_string(i) + " has index " + std::to_string(points[i].index) +
                " and " + std::to_string(points[i].values.size()) + " values");
      }
    }
    // The first point, the last, and the shard's first, built as a sweep builds them.
    std::vector<std::size_t> chosen;
    if (!points.empty()) chosen = {0, points.size() - 1};
    if (shard.index < points.size()) chosen.push_back(shard.index);
    for (const std::size_t i : chosen) {
      std::string input = base + "\n%%\n";
      for (std::size_t k = 0; k < keys.size(); ++k) {
        input += keys[k].key + "=" + points[i].values[k] + "\n";
      }
      if (fuzz::load_fuzz_scene(input)) ++fuzz::tally().built;
    }
  } catch (const scene::InputError& e) {
    ++fuzz::tally().refused;
    check_message(e);
  }
  return 0;
}
