// `verify` and its golden sets (issue 25): --update writes only inside the golden directory
// (a golden.json naming "../x" or an absolute path is refused, exit 2, and nothing is
// deleted), replaces the set as one step (a failure part-way leaves the old set as it
// was), and special files in a set are never opened (exit 2 instead of a hang).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include "child.hpp"
#include "generated_scene.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

fs::path scratch(const std::string& name) { return scratch_dir("golden", name); }

// A small scene whose [verify] compares `frames` and `figures` as asked (tiny frames).
fs::path verify_scene(const fs::path& dir, bool frames, bool figures, unsigned seed = 1) {
  SceneSpec spec;
  spec.bodies = 2;
  spec.seed = seed;
  spec.duration = 0.3;
  spec.extra = "[render]\nsize = [32, 32]\nfps = 10\nmsaa = 1\nshadow_map_size = 0\n[verify]\nframes = " +
               std::string(frames ? "true" : "false") + "\nfigures = " + (figures ? "true" : "false") + "\n";
  return write_scene(dir, spec);
}

}  // namespace

TEST_CASE("verify --update deletes nothing outside its golden directory", "[golden]") {
  const fs::path dir = scratch("escape");
  const fs::path scene = verify_scene(dir, false, true);
  REQUIRE(run_child({"verify", scene.string(), "--golden", "g", "--update", "--quiet"}, dir).code == 0);
  const fs::path manifest_path = dir / "g" / "generated" / "golden.json";
  const nlohmann::json original = nlohmann::json::parse(read_text(manifest_path));
  const fs::path outside = dir / "outside";
  fs::create_directories(outside);
  const std::vector<std::string> escapes{"../../outside/victim.png", (outside / "absolute.toml").string(),
                                         "../sibling.json", "sub/../../outside/x.txt"};
  for (const std::string& escape : escapes) {
    INFO(escape);
    std::ofstream(outside / "victim.png") << "precious";
    std::ofstream(outside / "absolute.toml") << "precious";
    std::ofstream(outside / "x.txt") << "precious";
    std::ofstream(dir / "g" / "sibling.json") << "precious";
    nlohmann::json edited = original;
    edited["figures"].push_back({{"file", escape}, {"name", "x"}});
    std::ofstream(manifest_path) << edited.dump(2);
    const RunResult r = run_child({"verify", scene.string(), "--golden", "g", "--update", "--quiet"}, dir);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("golden.json"));
    CHECK_THAT(r.err, Contains(escape));
    for (const char* f : {"victim.png", "absolute.toml", "x.txt"}) CHECK(read_text(outside / f) == "precious");
    CHECK(read_text(dir / "g" / "sibling.json") == "precious");
  }
}

TEST_CASE("verify --update that fails part-way leaves the old golden set as it was", "[golden]") {
  const fs::path dir = scratch("partial");
  const fs::path scene = verify_scene(dir, true, true, 5);
  REQUIRE(run_child({"verify", scene.string(), "--golden", "g", "--update", "--quiet"}, dir).code == 0);
  std::ofstream(dir / "g" / "generated" / "README") << "the user's notes";
  const auto before = snapshot(dir / "g");
  REQUIRE(before.size() > 3);  // golden.json, frames, a figure, the README

  // Another scene's motion under the same name: every frame and figure changes. The
  // figures are larger than the file size limit the child inherits: the update fails
  // after the frames are written.
  const fs::path moved = verify_scene(dir, true, true, 6);
  rlimit old_limit{};
  ::getrlimit(RLIMIT_FSIZE, &old_limit);
  rlimit limit = old_limit;
  limit.rlim_cur = 6 * 1024;
  void (*old_handler)(int) = ::signal(SIGXFSZ, SIG_IGN);
  ::setrlimit(RLIMIT_FSIZE, &limit);
  Child child({"verify", moved.string(), "--golden", "g", "--update", "--quiet"}, dir, "update");
  ::setrlimit(RLIMIT_FSIZE, &old_limit);
  ::signal(SIGXFSZ, old_handler);
  CHECK(child.wait() == 1);
  CHECK(snapshot(dir / "g") == before);
  // Nothing of the failed update is left beside the set either.
  for (const auto& e : fs::directory_iterator(dir / "g")) CHECK(e.path().filename() == "generated");

  // Without the limit the update goes through as one set, the user's README kept.
  REQUIRE(run_child({"verify", moved.string(), "--golden", "g", "--update", "--quiet"}, dir).code == 0);
  const auto after = snapshot(dir / "g");
  CHECK(after.at("generated/README") == "the user's notes");
  CHECK(after.at("generated/golden.json") != before.at("generated/golden.json"));
  CHECK(run_child({"verify", moved.string(), "--golden", "g", "--quiet"}, dir).code == 0);
}

TEST_CASE("a special file in a golden set is refused, never opened", "[golden]") {
  for (const std::string fifo : {"golden.json", "figure_signals_1.png"}) {
    INFO(fifo);
    const fs::path dir = scratch("fifo_" + fs::path(fifo).stem().string());
    const fs::path scene = verify_scene(dir, false, true);
    REQUIRE(run_child({"verify", scene.string(), "--golden", "g", "--update", "--quiet"}, dir).code == 0);
    const fs::path path = dir / "g" / "generated" / fifo;
    REQUIRE(fs::exists(path));
    fs::remove(path);
    REQUIRE(::mkfifo(path.c_str(), 0644) == 0);
    Child child({"verify", scene.string(), "--golden", "g", "--quiet"}, dir, "fifo");
    const int code = child.wait(std::chrono::seconds(20));  // -1: it hung on the FIFO
    CHECK(code == 2);
    CHECK_THAT(child.err(), Contains(fifo));
    CHECK(fs::is_fifo(fs::symlink_status(path)));
  }
}

TEST_CASE("a link that leaves a golden set is refused, and nothing it points to is quoted",
          "[golden]") {
  // A golden set from a pull request must not have verify read a file elsewhere and copy
  // its first line into stderr, junit.xml or report.md (issue 39).
  for (const std::string name : {"golden.json", "figure_signals_1.png"}) {
    INFO(name);
    const fs::path dir = scratch("link_out_" + fs::path(name).stem().string());
    const fs::path scene = verify_scene(dir, false, true);
    REQUIRE(run_child({"verify", scene.string(), "--golden", "g", "--update", "--quiet"}, dir).code == 0);
    const fs::path secret = dir / "secret.txt";
    std::ofstream(secret) << "SECRET-TOKEN-1234\n";
    const fs::path path = dir / "g" / "generated" / name;
    fs::remove(path);
    fs::create_symlink(secret, path);
    const RunResult o = run_child({"verify", scene.string(), "--golden", "g", "--out", "report"}, dir);
    CHECK(o.code == 2);
    CHECK_THAT(o.err, Contains(name));
    CHECK_THAT(o.err, Contains("leaves the golden set"));
    CHECK_THAT(o.err, !Contains("SECRET-TOKEN"));
    for (const char* report : {"junit.xml", "report.md"}) {
      const fs::path file = dir / "report" / report;
      if (!fs::exists(file)) continue;
      std::ifstream in(file);
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      CHECK_THAT(text, !Contains("SECRET-TOKEN"));
    }
  }
  // A link within the set is still read.
  const fs::path dir = scratch("link_in");
  const fs::path scene = verify_scene(dir, false, true);
  REQUIRE(run_child({"verify", scene.string(), "--golden", "g", "--update", "--quiet"}, dir).code == 0);
  const fs::path set = dir / "g" / "generated";
  fs::rename(set / "golden.json", set / "manifest.json");
  fs::create_symlink("manifest.json", set / "golden.json");
  CHECK(run_child({"verify", scene.string(), "--golden", "g", "--quiet"}, dir).code == 0);
}
