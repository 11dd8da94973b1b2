// A sweep's directory is its own (issue 25): it records which sweep it belongs to (the plan
// with the scene's content and the settings, not only the varied keys), another sweep into it
// is refused (exit 2) unless --overwrite, a foreign non-empty directory too; a resume after
// SIGKILL removes the killed run's temporaries; SIGTERM stops the sweep without running the
// remaining points.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "child.hpp"
#include "generated_scene.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

fs::path scratch(const std::string& name) { return scratch_dir("sweepdir", name); }

// The table's rows (after the header) as point -> steps column.
std::map<std::string, std::string> steps_by_point(const fs::path& table) {
  std::map<std::string, std::string> rows;
  std::ifstream in(table);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = [&] {
    std::vector<std::string> h;
    std::size_t start = 0;
    for (std::size_t at; (at = line.find(',', start)) != std::string::npos; start = at + 1)
      h.push_back(line.substr(start, at - start));
    h.push_back(line.substr(start));
    return h;
  }();
  const auto steps = std::find(header.begin(), header.end(), "steps") - header.begin();
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::size_t start = 0;
    for (std::size_t at; (at = line.find(',', start)) != std::string::npos; start = at + 1)
      f.push_back(line.substr(start, at - start));
    f.push_back(line.substr(start));
    if (static_cast<std::size_t>(steps) < f.size()) rows[f[0]] = f[steps];
  }
  return rows;
}

}  // namespace

TEST_CASE("a different sweep into the same --out is refused, the first table kept", "[sweepdir]") {
  for (unsigned seed : {3u, 4u}) {
    INFO("seed " << seed);
    const fs::path dir = scratch("other_" + std::to_string(seed));
    SceneSpec spec;
    spec.seed = seed;
    spec.bodies = 1 + static_cast<int>(seed % 3);
    spec.duration = 0.1;
    const fs::path scene = write_scene(dir, spec);
    const std::vector<std::string> base{"sweep", scene.string(), "--vary", "simulation.duration=0.1,0.2",
                                        "-j", "1", "--quiet", "--out", "s"};
    REQUIRE(run_child(base, dir).code == 0);
    const auto first = steps_by_point(dir / "s" / "sweep.csv");
    REQUIRE(first.size() == 2);

    // The same points at another step (--set, --dt) or of an edited scene: another sweep.
    std::vector<std::vector<std::string>> others{{"--set", "simulation.dt=5e-5"}, {"--dt", "5e-5"}};
    for (const auto& extra : others) {
      std::vector<std::string> args = base;
      args.insert(args.end(), extra.begin(), extra.end());
      const RunResult r = run_child(args, dir);
      INFO(extra[0]);
      CHECK(r.code == 2);
      CHECK_THAT(r.err, Contains("another sweep"));
      CHECK(steps_by_point(dir / "s" / "sweep.csv") == first);
    }
    spec.dt = 5e-5;
    write_scene(dir, spec);  // edited in place
    CHECK(run_child(base, dir).code == 2);
    CHECK(steps_by_point(dir / "s" / "sweep.csv") == first);

    // --overwrite: the new sweep's table replaces the old one (twice the steps per point).
    std::vector<std::string> overwrite = base;
    overwrite.push_back("--overwrite");
    REQUIRE(run_child(overwrite, dir).code == 0);
    const auto second = steps_by_point(dir / "s" / "sweep.csv");
    REQUIRE(second.size() == 2);
    for (const auto& [point, steps] : first) CHECK(std::stol(second.at(point)) == 2 * std::stol(steps));
    // And the same sweep again resumes (nothing to run), exit 0.
    CHECK(run_child(base, dir).code == 0);
  }
}

TEST_CASE("a sweep into a directory of the user's files is refused", "[sweepdir]") {
  const fs::path dir = scratch("foreign");
  const fs::path scene = write_scene(dir, {});
  fs::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "sweep.csv") << "the user's table\n";
  std::ofstream(dir / "mine" / "notes.md") << "notes\n";
  const RunResult r =
      run_child({"sweep", scene.string(), "--vary", "simulation.duration=0.1", "--quiet", "--out", "mine"}, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("notes.md"));
  CHECK(read_text(dir / "mine" / "sweep.csv") == "the user's table\n");
  CHECK_FALSE(fs::exists(dir / "mine" / "sweep.plan.json"));
}

TEST_CASE("a sweep resumed after SIGKILL leaves no temporaries of the killed run", "[sweepdir]") {
  const fs::path dir = scratch("killed");
  SceneSpec spec;
  spec.bodies = 3;
  const fs::path scene = write_scene(dir, spec);
  const std::vector<std::string> args{"sweep", scene.string(), "--vary", "simulation.duration=10,11,12",
                                      "--keep", "all", "-j", "1", "--quiet", "--out", "s"};
  {
    Child child(args, dir, "killed");
    // A point's trajectory is being written: its temporary exists.
    REQUIRE(wait_until(child, [&] { return !temporaries_under(dir / "s" / "points").empty(); }));
    child.signal(SIGKILL);
    CHECK(child.wait() == 1000 + SIGKILL);
  }
  REQUIRE_FALSE(temporaries_under(dir / "s").empty());
  const RunResult resumed = run_child(args, dir);
  REQUIRE(resumed.code == 0);
  CHECK(steps_by_point(dir / "s" / "sweep.csv").size() == 3);
  const std::vector<std::string> left = temporaries_under(dir / "s");
  CHECK(left.empty());
  for (const std::string& t : left) UNSCOPED_INFO(t);
}

TEST_CASE("SIGTERM stops a sweep without running the remaining points", "[sweepdir]") {
  const fs::path dir = scratch("term");
  SceneSpec spec;
  spec.bodies = 3;
  const fs::path scene = write_scene(dir, spec);
  Child child({"sweep", scene.string(), "--vary", "simulation.duration=5:6:40", "-j", "1", "--quiet", "--out", "s"},
              dir, "term");
  // Once the first point is in the table, the signal comes.
  REQUIRE(wait_until(child, [&] { return steps_by_point(dir / "s" / "sweep.csv").size() >= 1; }));
  child.signal(SIGTERM);
  CHECK(child.wait(std::chrono::seconds(30)) == 143);
  const auto rows = steps_by_point(dir / "s" / "sweep.csv");
  CHECK(rows.size() < 40);
  CHECK(temporaries_under(dir / "s").empty());
}

TEST_CASE("a sweep's progress in a log is plain lines, never carriage returns", "[sweepdir]") {
  // Issue 39: stderr that is no terminal (a batch job's log) got "\r  3 / 20 points" rewrites
  // piled into one line. Here stderr is a file.
  const fs::path dir = scratch("progress_log");
  SceneSpec spec;
  spec.bodies = 1;
  spec.duration = 0.05;
  const fs::path scene = write_scene(dir, spec);
  const RunResult r = run_child({"sweep", scene.string(), "--vary",
                                 "simulation.duration=0.01,0.02,0.03,0.04,0.05,0.06,0.07,0.08,0.09,0.1",
                                 "-j", "1", "--out", "s"},
                                dir);
  REQUIRE(r.code == 0);
  CHECK(r.err.find('\r') == std::string::npos);
  CHECK_THAT(r.err, Catch::Matchers::Contains("10 / 10 points after"));
}

// Issue 39: two sweeps started into one --out at the same moment both exited 0 with their
// points mixed. Now the directory is claimed under a lock: of two sweeps started together
// exactly one runs and the other is refused, and while a sweep runs, the same sweep again,
// a shard of it beside it, or --overwrite by another sweep are refused; its plan stays.
TEST_CASE("two sweeps into one --out: the second is refused, always", "[sweepdir]") {
  const fs::path dir = scratch("concurrent");
  SceneSpec spec;
  spec.bodies = 2;
  spec.duration = 0.05;
  const fs::path scene = write_scene(dir, spec);
  for (int round = 0; round < 5; ++round) {
    INFO("round " << round);
    const std::string out = "race_" + std::to_string(round);
    Child first({"sweep", scene.string(), "--vary", "simulation.duration=0.05,0.06", "-j", "1",
                 "--quiet", "--out", out},
                dir, "first");
    Child second({"sweep", scene.string(), "--vary", "simulation.duration=0.07,0.08", "-j", "1",
                  "--quiet", "--out", out},
                 dir, "second");
    const int a = first.wait(), b = second.wait();
    INFO("first " << a << ": " << first.err() << "\nsecond " << b << ": " << second.err());
    CHECK(((a == 0) != (b == 0)));
    const fs::path table = dir / out / "sweep.csv";
    const auto rows = steps_by_point(table);
    CHECK(rows.size() == 2);
    // The table holds the winner's points only (steps = duration / dt).
    std::vector<long> steps;
    for (const auto& [point, n] : rows) steps.push_back(std::stol(n));
    std::sort(steps.begin(), steps.end());
    CHECK(steps == (a == 0 ? std::vector<long>{500, 600} : std::vector<long>{700, 800}));
  }

  // A long sweep that is running: nothing else may write beside it.
  SceneSpec slow;
  slow.bodies = 3;
  const fs::path long_scene = write_scene(dir, slow, "slow.toml");
  const std::vector<std::string> args{"sweep", long_scene.string(), "--vary",
                                      "simulation.duration=10,11,12", "-j", "1", "--quiet",
                                      "--out", "s"};
  Child running(args, dir, "running");
  REQUIRE(wait_until(running, [&] { return fs::exists(dir / "s" / "sweep.plan.json"); }));
  const std::string plan = read_text(dir / "s" / "sweep.plan.json");
  RunResult r = run_child(args, dir);
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains("is writing into this directory"));
  std::vector<std::string> shard = args;
  shard.insert(shard.end(), {"--shard", "1/2"});
  r = run_child(shard, dir);
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains("an unsharded stiction sweep"));
  std::vector<std::string> other = args;
  other.insert(other.end(), {"--dt", "5e-5", "--overwrite"});
  r = run_child(other, dir);
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains("another stiction sweep"));
  CHECK(read_text(dir / "s" / "sweep.plan.json") == plan);
  running.signal(SIGTERM);
  CHECK(running.wait() == 143);
  // Once it has ended its locks are free: a shard of it (one that owns no point) runs there.
  std::vector<std::string> idle = args;
  idle.insert(idle.end(), {"--shard", "5/6"});
  r = run_child(idle, dir);
  CHECK(r.code == 0);
  INFO(r.err);
}
