// Figure options of `run` and `compare` (DESIGN section 3): --plot-format, a [[plots]] name
// with an extension, and compare's per-run overrides, labels, --signals and --duration.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "generated_scenes.hpp"
#include "run_stiction.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

std::string head(const fs::path& file, std::size_t n) {
  std::ifstream in(file, std::ios::binary);
  std::string s(n, '\0');
  in.read(s.data(), static_cast<std::streamsize>(n));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}

}  // namespace

TEST_CASE("run writes plots as SVG or PDF by --plot-format or by the plot's name",
          "[app][figures]") {
  const fs::path dir = stiction::testing::scratch_dir("stiction_test_figures_", "formats");
  std::string scene = stiction::testing::slope_to_floor_scene(0.2);
  scene += "[[plots]]\nname = \"block.svg\"\n  [[plots.panels]]\n  signals = [\"block.v.x\"]\n";
  scene += "[[plots]]\nname = \"force\"\nformat = \"pdf\"\n  [[plots.panels]]\n";
  scene += "  signals = [\"floor.f.z\"]\n";
  const fs::path path = stiction::testing::write_scene(dir, "s", scene);
  auto o = stiction::testing::run_stiction({"run", path.string(), "--no-video", "--out", "a"}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK(head(dir / "a/plots/block.svg", 5) == "<?xml");
  CHECK(head(dir / "a/plots/force.pdf", 5) == "%PDF-");
  CHECK_THAT(o.out, Contains("a/plots/block.svg") && Contains("a/plots/force.pdf"));
  o = stiction::testing::run_stiction(
      {"run", path.string(), "--no-video", "--plot-format", "png", "--out", "b"}, dir);
  REQUIRE(o.code == 0);
  CHECK(head(dir / "b/plots/block.png", 4) == "\x89PNG");
  CHECK(head(dir / "b/plots/force.png", 4) == "\x89PNG");
  o = stiction::testing::run_stiction({"run", path.string(), "--plot-format", "gif"}, dir);
  CHECK(o.code == 2);
}

TEST_CASE("run reads the print size and labels keys of [[plots]], errors at file:line:key",
          "[app][figures]") {
  const fs::path dir = stiction::testing::scratch_dir("stiction_test_figures_", "print");
  const std::string base = stiction::testing::slope_to_floor_scene(0.2);
  const auto with = [&](const std::string& keys) {
    return base + "[[plots]]\nname = \"p.pdf\"\n" + keys +
           "  [[plots.panels]]\n  signals = [\"block.v.x\"]\n";
  };
  auto path = stiction::testing::write_scene(
      dir, "good",
      with("width = \"3.5 in\"\nheight = \"6 cm\"\nfont_size = 9\n"
           "labels = [\"floor.first_stick\", \"floor.touch_down\"]\n"));
  auto o = stiction::testing::run_stiction({"run", path.string(), "--no-video", "--out", "a"}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK(head(dir / "a/plots/p.pdf", 5) == "%PDF-");
  // The line of the bad key in the scene file: the base scene's lines, then name, then it.
  const int line = static_cast<int>(std::count(base.begin(), base.end(), '\n')) + 3;
  const struct {
    std::string keys, key, what;
  } bad[] = {{"width = \"88 px\"\n", "plots[0].width", "mm, cm or in"},
             {"font_size = 100\n", "plots[0].font_size", "4 .. 72 pt"},
             {"size = [800, 600]\nwidth = 88\n", "plots[0].size", "excludes width"},
             {"labels = \"most\"\n", "plots[0].labels", "\"important\""},
             {"labels = [\"floor.stop\"]\n", "plots[0].labels[0]", "unknown event 'stop'"},
             {"events = [\"ceiling\"]\n", "plots[0].events[0]", "'ceiling' is not a component"}};
  for (const auto& b : bad) {
    path = stiction::testing::write_scene(dir, "bad", with(b.keys));
    o = stiction::testing::run_stiction({"run", path.string(), "--no-video", "--out", "b"}, dir);
    INFO(o.out);
    CHECK(o.code == 2);
    CHECK_THAT(o.out, Contains("bad.toml:" + std::to_string(line) + ":") && Contains(b.key) &&
                          Contains(b.what));
    CHECK_FALSE(fs::exists(dir / "b/summary.json"));
  }
}

TEST_CASE("compare labels runs of one scene by their overrides, with --signals and --duration",
          "[app][figures]") {
  const fs::path dir = stiction::testing::scratch_dir("stiction_test_figures_", "compare");
  const fs::path path =
      stiction::testing::write_scene(dir, "floor", stiction::testing::slope_to_floor_scene(5.0));
  auto o = stiction::testing::run_stiction(
      {"compare", path.string(), path.string() + "@impedances.slope.mu=0.3", "--duration", "0.3",
       "--signals", "block.v,floor.n_force", "--plot-format", "svg", "--out", "c"},
      dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, Contains("slope_to_floor: rk4") &&
                        Contains("slope_to_floor (impedances.slope.mu=0.3): rk4") &&
                        Contains("0.3 s simulated"));
  const fs::path svg = dir / "c/compare.svg";
  REQUIRE(fs::exists(svg));
  std::ifstream in(svg);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("<svg") != std::string::npos);

  // The same scene twice: still two labels.
  o = stiction::testing::run_stiction(
      {"compare", path.string(), path.string(), "--duration", "0.1", "--out", "d"}, dir);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, Contains("slope_to_floor (run 1)") && Contains("slope_to_floor (run 2)"));

  // An unknown signal fails before any simulation.
  o = stiction::testing::run_stiction(
      {"compare", path.string(), path.string(), "--signals", "block.nothing", "--out", "e"}, dir);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("block.nothing"));
  CHECK_FALSE(fs::exists(dir / "e/compare.png"));
  CHECK(o.out.find("simulated") == std::string::npos);
}

TEST_CASE("compare --signals of runs with no signal in common says so", "[app][figures]") {
  // Issue 39: the message ended "they have: " with nothing after it.
  const fs::path dir = stiction::testing::scratch_dir("stiction_test_figures_", "nothing_common");
  const auto o = stiction::testing::run_stiction(
      {"compare", "sphere_roll", "two_link", "--duration", "0.05", "--signals", "sphere.v", "--out", "c"},
      dir);
  INFO(o.out);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("'sphere.v' is not a signal of every run") &&
                        Contains("the runs have no signal in common"));
}
