// The outputs of `stiction run` and `stiction compare` beyond the CSV and the summary: the
// video, the plots, the frames, Ctrl-C during the render, and the checks that run before the
// simulation (DESIGN sections 3 and 4). Each test runs the built binary in a scratch
// directory, at small frame sizes and short durations so that it takes a few seconds.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "run_stiction.hpp"

extern char** environ;

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

using stiction::testing::Outcome;

fs::path scratch(const std::string& name) {
  return stiction::testing::scratch_dir("stiction_test_outputs_", name);
}

Outcome run_cli(const std::vector<std::string>& args, const fs::path& cwd) {
  return stiction::testing::run_stiction(args, cwd);
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Width and height from a PNG's IHDR; {0, 0} if the file is not a PNG.
std::pair<int, int> png_size(const fs::path& p) {
  const std::string b = read_bytes(p);
  if (b.size() < 24 || b.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || b.compare(12, 4, "IHDR") != 0) {
    return {0, 0};
  }
  auto be32 = [&](std::size_t at) {
    int v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
    return v;
  };
  return {be32(16), be32(20)};
}

// An MP4 that a player can open: an "ftyp" box first and the "moov" index written, which
// happens only when the muxer finalized the file.
bool finalized_mp4(const fs::path& p) {
  const std::string b = read_bytes(p);
  return b.size() > 1000 && b.compare(4, 4, "ftyp") == 0 && b.find("moov") != std::string::npos;
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("run writes video.mp4 and the scene's plots", "[app][outputs]") {
  const fs::path dir = scratch("video");
  const Outcome o = run_cli(
      {"run", "sphere_roll", "--duration", "0.2", "--set", "render.size=[320,180]", "--out", "out"},
      dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK(finalized_mp4(dir / "out" / "video.mp4"));
  // sphere_roll has no [[plots]]: it gets the paper's Fig. 4.
  // The paper figure, then every signal in figures of a few panels each.
  CHECK(names_in(dir / "out" / "plots") ==
        std::vector<std::string>{"fig4_sphere.png", "signals_1.png", "signals_2.png"});
  // A one-column figure, 88 x 80 mm at 300 dpi (docs/plots.md).
  CHECK(png_size(dir / "out" / "plots" / "fig4_sphere.png") == std::pair{1039, 945});
  // Only the finished files: no temporary names, no partial video, no frames unasked.
  CHECK(names_in(dir / "out") ==
        std::vector<std::string>{".stiction-output", "plots", "summary.json", "trajectory.csv", "video.mp4"});
  // Every output is named on stdout; 0.2 s at 60 fps is 13 frames.
  CHECK_THAT(o.out, Contains("out/video.mp4 (13 frames, 320x180"));
  CHECK_THAT(o.out, Contains("out/plots/fig4_sphere.png"));
}

TEST_CASE("run --frames writes one PNG per video frame", "[app][outputs]") {
  const fs::path dir = scratch("frames");
  fs::create_directories(dir / "out" / "frames");
  std::ofstream(dir / "out" / "frames" / "000099.png") << "from an older, longer run";
  // ... which its manifest names (issue 25: only files a manifest names are removed).
  std::ofstream(dir / "out" / ".stiction-output") << R"({"files": ["frames/000099.png"]})";
  const Outcome o =
      run_cli({"run", "sphere_roll", "--duration", "0.05", "--set", "render.size=[320,180]",
               "--no-video", "--no-plots", "--frames", "--out", "out"},
              dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  // 0.05 s at 60 fps: frames at 0, 1/60, 2/60, 3/60 s. The stale frame 99 is gone.
  CHECK(names_in(dir / "out" / "frames") ==
        std::vector<std::string>{"000000.png", "000001.png", "000002.png", "000003.png"});
  CHECK(png_size(dir / "out" / "frames" / "000003.png") == std::pair{320, 180});
  CHECK_FALSE(fs::exists(dir / "out" / "video.mp4"));
}

TEST_CASE("run --no-video --no-plots writes neither", "[app][outputs]") {
  const fs::path dir = scratch("none");
  const Outcome o = run_cli(
      {"run", "sphere_roll", "--duration", "0.2", "--no-video", "--no-plots", "--out", "out"}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK(names_in(dir / "out") == std::vector<std::string>{".stiction-output", "summary.json", "trajectory.csv"});
}

TEST_CASE("a plot naming an unknown signal fails before the simulation", "[app][outputs]") {
  const fs::path dir = scratch("bad_plot");
  std::ofstream(dir / "scene.toml") << R"(name = "bad_plot"
[simulation]
duration = 0.1
[bodies.block]
type = "point_mass"
mass = 1.0
[[plots]]
name = "speed"
  [[plots.panels]]
  signals = ["block.p.z", "block.vel.x"]
)";
  const Outcome o = run_cli({"run", "scene.toml", "--out", "out"}, dir);
  INFO(o.out);
  CHECK(o.code == 2);
  // Line 10, column 27: the second string of the array.
  CHECK_THAT(o.out, Contains("scene.toml:10:27: error:"));
  CHECK_THAT(o.out, Contains("'block.vel.x'"));
  CHECK_THAT(o.out, Contains("block.v.x"));  // the signals that exist are listed
  CHECK_FALSE(fs::exists(dir / "out" / "trajectory.csv"));
}

TEST_CASE("bad render settings fail before the simulation", "[app][outputs]") {
  const fs::path dir = scratch("bad_render");
  const Outcome o =
      run_cli({"run", "sphere_roll", "--set", "render.size=[321,180]", "--out", "out"}, dir);
  INFO(o.out);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("render.size"));
  CHECK_FALSE(fs::exists(dir / "out" / "trajectory.csv"));
}

TEST_CASE("an unstable run writes no plots and no video", "[app][outputs]") {
  const fs::path dir = scratch("unstable");
  // RK4 with a step far beyond the contact's limit (about 1.7e-4 s for sphere_roll).
  const Outcome o = run_cli({"run", "sphere_roll", "--dt", "2e-3", "--duration", "0.5", "--set",
                             "render.size=[320,180]", "--out", "out", "--force-step"},
                            dir);
  INFO(o.out);
  REQUIRE(o.code == 3);
  CHECK(names_in(dir / "out") == std::vector<std::string>{".stiction-output", "summary.json", "trajectory.csv"});
}

TEST_CASE("Ctrl-C during the render keeps a playable video.partial.mp4", "[app][outputs]") {
  const fs::path dir = scratch("interrupt");
  const fs::path out = dir / "out";
  // Four times slow motion: 481 frames, far more than are rendered before the signal lands.
  std::vector<std::string> args{STICTION_BINARY,
                                "run",
                                "sphere_roll",
                                "--set",
                                "render.size=[320,180]",
                                "--set",
                                "render.slow_motion=4",
                                "--no-plots",
                                "--frames",
                                "--quiet",
                                "--out",
                                out.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  REQUIRE(::posix_spawn(&pid, STICTION_BINARY, &actions, nullptr, argv.data(), environ) == 0);
  posix_spawn_file_actions_destroy(&actions);

  // The third frame on disk means the renderer is running (and the SIGINT handler is set).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  // (While it renders, the run writes into its staging directory: output_dir.hpp.)
  const auto staged_frame = [&] {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(out, ec)) {
      if (fs::exists(e.path() / "frames" / "000002.png", ec)) return true;
    }
    return fs::exists(out / "frames" / "000002.png", ec);
  };
  while (!staged_frame() &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGINT);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(finalized_mp4(out / "video.partial.mp4"));
  CHECK_FALSE(fs::exists(out / "video.mp4"));
  for (const std::string& name : names_in(out)) CHECK(name.find(".tmp") == std::string::npos);
}

TEST_CASE("the tolerance option selects rk4_adaptive", "[app][outputs]") {
  const fs::path dir = scratch("tolerance");
  const Outcome ok = run_cli({"run", "sphere_roll", "--tolerance", "1e-7", "--duration", "0.1",
                              "--no-video", "--no-plots", "--out", "out"},
                             dir);
  INFO(ok.out);
  REQUIRE(ok.code == 0);
  CHECK(read_json(dir / "out" / "summary.json")["integrator"] == "rk4_adaptive");

  const Outcome clash = run_cli({"run", "sphere_roll", "--tolerance", "1e-7", "--integrator", "rk4",
                                 "--no-video", "--no-plots", "--out", "out2"},
                                dir);
  CHECK(clash.code == 2);
  CHECK_THAT(clash.out, Contains("--tolerance"));

  const Outcome missing = run_cli({"run", "sphere_roll", "--integrator", "rk4_adaptive",
                                   "--no-video", "--no-plots", "--out", "out3"},
                                  dir);
  CHECK(missing.code == 2);
  CHECK_THAT(missing.out, Contains("tolerance"));
}

TEST_CASE("the tolerance option runs the adaptive integrator that --integrator names (sdirk2)",
          "[app][outputs]") {
  const fs::path dir = scratch("tolerance_sdirk");
  const Outcome ok = run_cli({"run", "sphere_roll", "--integrator", "sdirk2", "--tolerance", "1e-6",
                              "--duration", "0.1", "--no-video", "--no-plots", "--out", "out"},
                             dir);
  INFO(ok.out);
  REQUIRE(ok.code == 0);
  const auto summary = read_json(dir / "out" / "summary.json");
  CHECK(summary["integrator"] == "sdirk2");
  CHECK(summary["tolerance"] == 1e-6);

  const Outcome missing = run_cli({"run", "sphere_roll", "--integrator", "sdirk4", "--no-video",
                                   "--no-plots", "--out", "out2"},
                                  dir);
  CHECK(missing.code == 2);
  CHECK_THAT(missing.out, Contains("sdirk4 needs a tolerance"));
}

TEST_CASE("[simulation] tolerance selects rk4_adaptive and is checked", "[app][outputs]") {
  const fs::path dir = scratch("tolerance_key");
  const std::string body = "[bodies.block]\ntype = \"point_mass\"\nmass = 1.0\n";
  std::ofstream(dir / "adaptive.toml") << "[simulation]\nduration = 0.1\ntolerance = 1e-8\n"
                                       << body;
  std::ofstream(dir / "clash.toml") << "[simulation]\nintegrator = \"rk4\"\ntolerance = 1e-8\n"
                                    << body;
  std::ofstream(dir / "missing.toml") << "[simulation]\nintegrator = \"rk4_adaptive\"\n" << body;

  const Outcome ok =
      run_cli({"run", "adaptive.toml", "--no-video", "--no-plots", "--out", "out"}, dir);
  INFO(ok.out);
  REQUIRE(ok.code == 0);
  CHECK(read_json(dir / "out" / "summary.json")["integrator"] == "rk4_adaptive");

  const Outcome clash = run_cli({"check", "clash.toml"}, dir);
  CHECK(clash.code == 2);
  CHECK_THAT(clash.out, Contains("clash.toml:3:13: error:"));
  const Outcome missing = run_cli({"check", "missing.toml"}, dir);
  CHECK(missing.code == 2);
  CHECK_THAT(missing.out, Contains("missing.toml:2:14: error:"));
}

TEST_CASE("compare overlays two runs in compare.png", "[app][outputs]") {
  const fs::path dir = scratch("compare");
  const Outcome o = run_cli(
      {"compare", "two_link", "two_link_lugre", "--set", "simulation.duration=6", "--out", "cmp"},
      dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK(names_in(dir / "cmp") == std::vector<std::string>{"compare.png"});
  // Two runs: a one-column figure, 88 mm wide at 300 dpi, 106 mm high for its three panels.
  CHECK(png_size(dir / "cmp" / "compare.png") == std::pair{1039, 1252});
  CHECK_THAT(o.out, Contains("cmp/compare.png"));

  const Outcome one = run_cli({"compare", "two_link", "--out", "cmp1"}, dir);
  CHECK(one.code == 2);
  CHECK_FALSE(fs::exists(dir / "cmp1" / "compare.png"));
}
