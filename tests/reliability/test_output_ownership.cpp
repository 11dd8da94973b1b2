// The output directory is the program's own (issue 25): a run deletes or replaces only the
// files a manifest says stiction wrote, refuses a foreign non-empty directory (exit 2,
// naming files) unless --overwrite, refuses the home directory, never writes through a
// `plots` link, and keeps the previous run's files intact and consistent when it fails.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include <signal.h>
#include <sys/resource.h>

#include "child.hpp"
#include "generated_scene.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

fs::path scratch(const std::string& name) { return scratch_dir("ownership", name); }

std::vector<std::string> listed(const fs::path& out) {
  const auto s = nlohmann::json::parse(read_text(out / "summary.json"));
  std::vector<std::string> files;
  for (const auto& f : s["files"]) files.push_back(f.get<std::string>());
  return files;
}

// A user's project: figures, frames, a video, a summary and a table of their own, with
// random names and contents (seeded).
std::map<std::string, std::string> plant_user_files(const fs::path& dir, unsigned seed) {
  std::mt19937 random(seed);
  std::map<std::string, std::string> planted;
  const std::vector<std::string> names{"plots/figure_" + std::to_string(random() % 1000) + ".png",
                                       "plots/signals_1.png", "plots/draft.svg", "plots/paper.pdf",
                                       "frames/" + std::string(6 - 1, '0') + std::to_string(random() % 10) + ".png",
                                       "video.mp4", "summary.json", "trajectory.csv", "notes.md"};
  for (const std::string& n : names) {
    fs::create_directories((dir / n).parent_path());
    const std::string content = "the user's " + n + " " + std::to_string(random());
    std::ofstream(dir / n) << content;
    planted[n] = content;
  }
  return planted;
}

// Sets an environment variable for the children spawned while it lives.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_) ::setenv(name_, old_->c_str(), 1);
    else ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace

TEST_CASE("a run into a directory of the user's files deletes none of them", "[ownership]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    INFO("seed " << seed);
    const fs::path dir = scratch("user_" + std::to_string(seed));
    SceneSpec spec;
    spec.bodies = 1 + static_cast<int>(seed);
    spec.seed = seed;
    spec.duration = 0.2;
    const fs::path scene = write_scene(dir, spec);
    const fs::path project = dir / "project";
    const auto planted = plant_user_files(project, seed);
    // `--out .` in the user's project: refused, naming what it found, nothing touched.
    const RunResult r = run_child({"run", scene.string(), "--no-video", "--out", "."}, project);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("--overwrite"));
    CHECK_THAT(r.err, Contains("notes.md"));
    auto now = snapshot(project);
    now.erase("child.stdout");
    now.erase("child.stderr");
    CHECK(now == planted);
  }
}

TEST_CASE("an overwrite run replaces only the files of the names a run writes", "[ownership]") {
  const fs::path dir = scratch("overwrite");
  SceneSpec spec;
  spec.duration = 0.2;
  const fs::path scene = write_scene(dir, spec);
  const fs::path out = dir / "o";
  const auto planted = plant_user_files(out, 11);
  const RunResult r = run_child({"run", scene.string(), "--no-video", "--out", "o", "--overwrite"}, dir);
  REQUIRE(r.code == 0);
  const std::vector<std::string> files = listed(out);
  for (const auto& [name, content] : planted) {
    INFO(name);
    const bool written = std::find(files.begin(), files.end(), name) != files.end();
    if (written) CHECK(read_text(out / name) != content);
    else CHECK(read_text(out / name) == content);  // not this run's: still the user's
  }
  // The manifest now says which files are the program's: a user's figure added later is
  // not its own, and a second run says so instead of replacing or deleting it.
  std::ofstream(out / "plots" / "mine.png") << "mine";
  const RunResult again = run_child({"run", scene.string(), "--no-video", "--out", "o"}, dir);
  CHECK(again.code == 2);
  CHECK_THAT(again.err, Contains("plots/mine.png"));
  CHECK(read_text(out / "plots" / "mine.png") == "mine");
}

TEST_CASE("the home directory is never an output directory", "[ownership]") {
  const fs::path home = scratch("home");
  const fs::path dir = scratch("home_scene");
  const fs::path scene = write_scene(dir, {});
  const ScopedEnv env("HOME", home.string());
  const RunResult r = run_child({"run", scene.string(), "--no-video", "--out", home.string(), "--overwrite"}, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("home directory"));
  CHECK(fs::is_empty(home));
}

TEST_CASE("a plots link in the output directory is never written through", "[ownership]") {
  const fs::path dir = scratch("plots_link");
  SceneSpec spec;
  spec.duration = 0.2;
  const fs::path scene = write_scene(dir, spec);
  REQUIRE(run_child({"run", scene.string(), "--no-video", "--out", "o"}, dir).code == 0);
  // Someone replaces plots/ by a link to a directory of theirs holding a file of the name
  // the run writes.
  const fs::path elsewhere = dir / "elsewhere";
  fs::create_directories(elsewhere);
  std::string plot;  // a name the run writes into plots/
  for (const auto& e : fs::directory_iterator(dir / "o" / "plots")) plot = e.path().filename().string();
  REQUIRE_FALSE(plot.empty());
  std::ofstream(elsewhere / plot) << "precious";
  fs::remove_all(dir / "o" / "plots");
  fs::create_directory_symlink(elsewhere, dir / "o" / "plots");
  const RunResult r = run_child({"run", scene.string(), "--no-video", "--out", "o"}, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("plots"));
  CHECK(read_text(elsewhere / plot) == "precious");
  CHECK(snapshot(elsewhere).size() == 1);
}

TEST_CASE("a run that fails keeps the previous run's files intact and consistent", "[ownership]") {
  const fs::path dir = scratch("failing");
  SceneSpec spec;
  spec.duration = 0.2;
  spec.bodies = 3;
  const fs::path scene = write_scene(dir, spec);
  REQUIRE(run_child({"run", scene.string(), "--no-video", "--out", "o"}, dir).code == 0);
  const auto before = snapshot(dir / "o");
  REQUIRE(std::any_of(before.begin(), before.end(), [](const auto& f) { return f.first.starts_with("plots/"); }));

  // The second run's trajectory outgrows what the disk (RLIMIT_FSIZE, inherited by the
  // child) lets it write: it fails with exit 1 part-way.
  spec.duration = 20.0;
  const fs::path long_scene = write_scene(dir, spec, "long.toml");
  rlimit old_limit{};
  ::getrlimit(RLIMIT_FSIZE, &old_limit);
  rlimit limit = old_limit;
  limit.rlim_cur = 256 * 1024;
  void (*old_handler)(int) = ::signal(SIGXFSZ, SIG_IGN);  // a write fails instead of killing
  ::setrlimit(RLIMIT_FSIZE, &limit);
  Child child({"run", long_scene.string(), "--no-video", "--out", "o"}, dir, "failing");
  ::setrlimit(RLIMIT_FSIZE, &old_limit);
  ::signal(SIGXFSZ, old_handler);
  CHECK(child.wait() == 1);

  // The previous run's files are all there, unchanged, and its summary lists exactly them.
  CHECK(snapshot(dir / "o") == before);
  for (const std::string& f : listed(dir / "o")) {
    INFO(f);
    CHECK(fs::is_regular_file(dir / "o" / f));
  }
  CHECK(temporaries_under(dir / "o").empty());
}
