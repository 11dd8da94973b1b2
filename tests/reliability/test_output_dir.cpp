// The output directory as a transaction: an earlier run's outputs go before a run writes
// (the user's own files stay), summary.json lists exactly what this run wrote, a planted
// symlink is replaced or removed but its target never written, a second run into a locked
// directory fails at once, scene names cannot escape out/, and --out is a file name even
// when it looks like a URL.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "child.hpp"
#include "generated_scene.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

fs::path scratch(const std::string& name) { return scratch_dir("outdir", name); }

std::vector<std::string> listed(const fs::path& out) {
  const auto s = nlohmann::json::parse(read_text(out / "summary.json"));
  std::vector<std::string> files;
  for (const auto& f : s["files"]) files.push_back(f.get<std::string>());
  return files;
}

// Every regular file under `out`, relative, sorted.
std::vector<std::string> files_under(const fs::path& out) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    if (!e.is_regular_file()) continue;
    found.push_back(fs::relative(e.path(), out).generic_string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace

TEST_CASE("a run removes the earlier run's outputs and lists what it wrote", "[outdir]") {
  const fs::path dir = scratch("stale");
  SceneSpec spec;
  spec.name = "stale_" + std::string(150, 'n');  // long names are fine
  spec.bodies = 5;
  spec.seed = 7;
  const fs::path scene = write_scene(dir, spec);
  const fs::path out = dir / "o";
  fs::create_directories(out / "plots");
  fs::create_directories(out / "frames");
  for (const char* stale : {"video.mp4", "video.partial.mp4", "plots/old_plot.png", "plots/old.svg",
                            "frames/000000.png", "frames/000999.png", ".trajectory.csv.tmp-0123456789abcdef",
                            "video.mp4.tmp.4242", "plots/x.png.tmp.42-7"}) {
    std::ofstream(out / stale) << "stale";
  }
  std::ofstream(out / "notes.txt") << "the user's";
  std::ofstream(out / "plots" / "README") << "the user's too";
  // Not a stiction output directory (no manifest): written into only with --overwrite
  // (issue 25), which replaces the files of the names it writes and deletes nothing else;
  // the temporaries of a killed run go.
  const RunResult r = run_child({"run", scene.string(), "--no-video", "--out", "o", "--overwrite"}, dir);
  REQUIRE(r.code == 0);
  std::vector<std::string> files = listed(out);
  CHECK(files.front() == "trajectory.csv");
  // Exactly the listed files exist, plus the user's two and the stale-looking files that
  // this run did not write (not its own: they stay).
  for (const char* other : {"notes.txt", "plots/README", "video.mp4", "video.partial.mp4", "plots/old_plot.png",
                            "plots/old.svg", "frames/000000.png", "frames/000999.png", ".stiction-output"}) {
    files.push_back(other);
  }
  std::sort(files.begin(), files.end());
  CHECK(files_under(out) == files);
  CHECK(read_text(out / "notes.txt") == "the user's");
  CHECK(read_text(out / "video.mp4") == "stale");
  for (const char* stale : {"video.mp4", "video.partial.mp4", "plots/old_plot.png", "plots/old.svg",
                            "frames/000000.png", "frames/000999.png"}) {
    fs::remove(out / stale);  // the user moves them away: the rest is the run's own
  }

  // A second run with fewer outputs (no plots) leaves none of the first run's plots, even
  // those named only in the first summary.
  const RunResult again =
      run_child({"run", scene.string(), "--no-video", "--no-plots", "--out", "o"}, dir);
  REQUIRE(again.code == 0);
  CHECK(listed(out) == std::vector<std::string>{"trajectory.csv", "summary.json"});
  CHECK(files_under(out) == std::vector<std::string>{".stiction-output", "notes.txt", "plots/README", "summary.json",
                                                     "trajectory.csv"});
}

TEST_CASE("a planted symlink is never written through", "[outdir]") {
  const fs::path dir = scratch("symlink");
  const fs::path scene = write_scene(dir, {});
  const fs::path out = dir / "shared";
  fs::create_directories(out / "plots");
  for (const char* victim : {"victim_csv", "victim_json", "victim_video", "victim_plot"}) {
    std::ofstream(dir / victim) << "precious";
  }
  fs::create_symlink(dir / "victim_csv", out / "trajectory.csv");
  fs::create_symlink(dir / "victim_json", out / "summary.json");
  fs::create_symlink(dir / "victim_video", out / "video.mp4");
  fs::create_symlink(dir / "victim_plot", out / "plots" / "generated.png");
  const RunResult r = run_child({"run", scene.string(), "--no-video", "--out", "shared", "--overwrite"}, dir);
  REQUIRE(r.code == 0);
  for (const char* victim : {"victim_csv", "victim_json", "victim_video", "victim_plot"}) {
    INFO(victim);
    CHECK(read_text(dir / victim) == "precious");
  }
  CHECK(fs::is_regular_file(fs::symlink_status(out / "trajectory.csv")));
  CHECK(fs::is_regular_file(fs::symlink_status(out / "summary.json")));
  // Not written by this run (--no-video) and no manifest named it: left alone, as a link.
  CHECK(fs::is_symlink(fs::symlink_status(out / "video.mp4")));
}

TEST_CASE("a second run into a directory in use fails at once", "[outdir]") {
  const fs::path dir = scratch("concurrent");
  SceneSpec spec;
  spec.duration = 5000.0;
  spec.output_rate = 10.0;
  const fs::path scene = write_scene(dir, spec);
  Child first({"run", scene.string(), "--no-video", "--no-plots", "--out", "o"}, dir, "first");
  // Its trajectory temporary appears once it holds the lock and has cleaned the directory.
  REQUIRE(wait_until(first, [&] { return !temporaries_under(dir / "o").empty(); }));
  REQUIRE(first.running());
  const fs::path short_scene = write_scene(dir, {}, "short.toml");
  const RunResult second =
      run_child({"run", short_scene.string(), "--no-video", "--no-plots", "--out", "o"}, dir);
  CHECK(second.code == 1);
  CHECK_THAT(second.err, Contains("another stiction run is writing into this directory"));
  CHECK_FALSE(fs::exists(dir / "o" / "trajectory.csv"));  // the second wrote nothing
  first.signal(SIGINT);
  CHECK(first.wait(std::chrono::seconds(30)) == 130);
  // The lock went with the first run.
  const RunResult third =
      run_child({"run", short_scene.string(), "--no-video", "--no-plots", "--out", "o"}, dir);
  CHECK(third.code == 0);
}

TEST_CASE("scene names cannot name a path", "[outdir]") {
  const fs::path dir = scratch("names");
  for (const std::string name : {"../../x", "/tmp/abs", "a/b", "..", ".", ".hidden", "back\\\\slash", ""}) {
    SceneSpec spec;
    spec.name = name;
    const fs::path scene = write_scene(dir, spec);
    INFO("name = '" << name << "'");
    const RunResult r = run_child({"run", scene.string(), "--no-video"}, dir);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains(":1:8: error: name:"));
  }
  CHECK((!fs::exists(dir / "out") || fs::is_empty(dir / "out")));
}

TEST_CASE("an --out that looks like a URL is a directory name", "[outdir]") {
  const fs::path dir = scratch("url");
  SceneSpec spec;
  spec.bodies = 1;
  spec.duration = 0.2;
  spec.extra = "[render]\nsize = [32, 32]\nfps = 10\nmsaa = 1\nshadow_map_size = 0\n";
  const fs::path scene = write_scene(dir, spec);
  for (const std::string out : {"run:1", "tcp://127.0.0.1:9"}) {
    INFO(out);
    const RunResult r = run_child({"run", scene.string(), "--no-plots", "--out", out}, dir);
    CHECK(r.code == 0);
    CHECK(fs::file_size(dir / out / "video.mp4") > 0);
  }
}
