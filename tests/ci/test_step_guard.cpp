// The step guard around the run (issue 26): its cache, a sweep point it refuses, compare
// refusing before anything runs, and the chatter warning located at the step's key. The
// refusal and suggestion of every bundled scene are in test_suggested_step.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "ci_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

nlohmann::json summary_of(const fs::path& out) {
  return nlohmann::json::parse(read_text(out / "summary.json"));
}

// A sphere sliding to a roll on a floor, written with its dt on a known line (10).
std::string rolling_ball(double dt) {
  return "name = \"guarded\"\n"
         "gravity = [0.0, 0.0, -9.8]\n"
         "\n"
         "[simulation]\n"
         "integrator = \"rk4\"\n"
         "duration = 0.6\n"
         "output_rate = 500.0\n"
         "# the step, on line 10\n"
         "\n"
         "dt = " +
         std::to_string(dt) +
         "\n"
         "\n"
         "[bodies.ball]\n"
         "type = \"rigid_body\"\n"
         "mass = 2.0\nshape = \"sphere\"\nradius = 0.1\nposition = [0.0, 0.0, 0.1]\n"
         "velocity = [1.5, 0.0, 0.0]\n"
         "\n"
         "[impedances.floor]\n"
         "type = \"kikuuwe_contact\"\nbody = \"ball\"\nnormal = [0.0, 0.0, 1.0]\n"
         "stiffness = 1e7\ndamping = 10.0\nmu = 0.3\nsettle = true\n";
}

// Sets an environment variable for the test's child processes, restored on exit.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_.empty()) {
      ::unsetenv(name_);
    } else {
      ::setenv(name_, old_.c_str(), 1);
    }
  }

 private:
  const char* name_;
  std::string old_;
};

}  // namespace

TEST_CASE("step guard: the check is cached by content, a corrupt entry is a miss, off is off") {
  const fs::path dir = scratch_dir("stiction_test_guard_", "cache");
  const fs::path cache = dir / "cache";
  write_text(dir / "ball.toml", rolling_ball(1e-4));
  const ScopedEnv env("STICTION_CACHE_DIR", cache.string());
  const std::vector<std::string> args{"run",     "ball.toml",  "--no-video", "--no-plots",
                                      "--quiet", "--accuracy", "off",        "--out"};
  auto run_to = [&](const std::string& out) {
    std::vector<std::string> a = args;
    a.push_back(out);
    const SplitOutcome o = run_split(a, dir);
    INFO(o.err);
    REQUIRE(o.code == 0);
    return summary_of(dir / out)["step_check"];
  };
  const nlohmann::json first = run_to("a");
  CHECK(first["cached"] == false);
  CHECK(first["verdict"] == "ok");
  const nlohmann::json second = run_to("b");
  CHECK(second["cached"] == true);
  CHECK(second["instability_limit"] == first["instability_limit"]);
  CHECK(second["chatter_limit"] == first["chatter_limit"]);
  // Another value of a key is another scene.
  write_text(dir / "ball.toml", rolling_ball(5e-5));
  CHECK(run_to("c")["cached"] == false);
  // A corrupt entry is a miss, and the analysis gives the same limits again.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(cache / "step_check")) {
    write_text(e.path(), "{not json");
    ++entries;
  }
  CHECK(entries == 2);
  const nlohmann::json again = run_to("d");
  CHECK(again["cached"] == false);
  CHECK(again["instability_limit"].get<double>() ==
        Approx(first["instability_limit"].get<double>()));
  {
    const ScopedEnv off("STICTION_CACHE_DIR", "off");
    fs::remove_all(cache);
    CHECK(run_to("e")["cached"] == false);
    CHECK(run_to("f")["cached"] == false);
    CHECK_FALSE(fs::exists(cache));
  }
  fs::remove_all(dir);
}

TEST_CASE("step guard: a chatter warning names the step's key and line, or --dt") {
  const fs::path dir = scratch_dir("stiction_test_guard_", "chatter");
  const ScopedEnv env("STICTION_CACHE_DIR", (dir / "cache").string());
  // Between the chatter and the instability limit the guard first runs a trial of the step
  // (issue 35); this ball's trial would pass, so the scene asks for a tolerance no step
  // meets, and the trial fails: the warning stands, and its location is what is tested.
  const std::string strict = "\n[accuracy]\ntolerance = 1e-12\n";
  write_text(dir / "ball.toml", rolling_ball(1e-4) + strict);
  const SplitOutcome check = run_split({"check", "ball.toml", "--json"}, dir);
  REQUIRE(check.code == 0);
  const nlohmann::json rk4 = nlohmann::json::parse(check.out)["step_limits"]["rk4"];
  REQUIRE_FALSE(rk4["chatters_above"].is_null());
  const double chatter = rk4["chatters_above"].get<double>();
  const double unstable = rk4["unstable_above"].get<double>();
  REQUIRE(chatter < unstable);
  const double between = std::sqrt(chatter * unstable);
  // In the scene file: located at [simulation] dt, line 10.
  write_text(dir / "between.toml", rolling_ball(between) + strict);
  SplitOutcome o = run_split(
      {"run", "between.toml", "--no-video", "--no-plots", "--accuracy", "off", "--out", "file"},
      dir);
  INFO(o.err);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.err, Contains("between.toml:10:6: warning: simulation.dt: "));
  nlohmann::json s = summary_of(dir / "file");
  CHECK(s["step_check"]["verdict"] == "chatter");
  REQUIRE(s["warnings"].size() == 1);
  CHECK(s["warnings"][0]["key"] == "simulation.dt");
  CHECK(s["warnings"][0]["line"] == 10);
  // From the command line: key --dt; --quiet silences stderr, not the summary.
  o = run_split({"run", "ball.toml", "--dt", std::to_string(between), "--no-video", "--no-plots",
                 "--accuracy", "off", "--quiet", "--out", "cli"},
                dir);
  REQUIRE(o.code == 0);
  CHECK(o.err.empty());
  s = summary_of(dir / "cli");
  REQUIRE(s["warnings"].size() == 1);
  CHECK(s["warnings"][0]["key"] == "--dt");
  CHECK(s["warnings"][0]["file"] == "(command line)");
  fs::remove_all(dir);
}

TEST_CASE("step guard: a sweep point above the limit is refused, --force-step simulates it") {
  const fs::path dir = scratch_dir("stiction_test_guard_", "sweep");
  const ScopedEnv env("STICTION_CACHE_DIR", (dir / "cache").string());
  write_text(dir / "ball.toml", rolling_ball(1e-4));
  for (const bool force : {false, true}) {
    std::vector<std::string> args{
        "sweep", "ball.toml", "--vary", "simulation.dt=1e-4,4e-3",   "--quiet", "--keep", "none",
        "-j",    "1",         "--out",  force ? "forced" : "guarded"};
    if (force) args.push_back("--force-step");
    const SplitOutcome o = run_split(args, dir);
    INFO(o.err);
    REQUIRE(o.code == 0);
    const std::string table = read_text(dir / (force ? "forced" : "guarded") / "sweep.csv");
    INFO(table);
    CHECK_THAT(table, Contains(",ok,"));
    if (force) {
      CHECK_THAT(table, Contains(",unstable,"));
    } else {
      CHECK_THAT(table, Contains(",refused,"));
      CHECK_THAT(table, Contains("not simulated: dt = 0.004 s is above rk4's predicted"));
    }
  }
  // Resuming the guarded sweep with --force-step runs the refused point, as its note says.
  const SplitOutcome resumed =
      run_split({"sweep", "ball.toml", "--vary", "simulation.dt=1e-4,4e-3", "--quiet", "--keep",
                 "none", "-j", "1", "--out", "guarded", "--force-step"},
                dir);
  INFO(resumed.err);
  REQUIRE(resumed.code == 0);
  const std::string table = read_text(dir / "guarded" / "sweep.csv");
  CHECK_THAT(table, Contains(",unstable,"));
  CHECK_THAT(table, !Contains(",refused,"));
  fs::remove_all(dir);
}

TEST_CASE("step guard: compare refuses before anything runs or is written") {
  const fs::path dir = scratch_dir("stiction_test_guard_", "compare");
  const ScopedEnv env("STICTION_CACHE_DIR", (dir / "cache").string());
  write_text(dir / "ball.toml", rolling_ball(1e-4));
  const SplitOutcome o =
      run_split({"compare", "ball.toml", "ball.toml@simulation.dt=4e-3", "--out", "cmp"}, dir);
  INFO(o.err);
  CHECK(o.code == 3);
  CHECK_THAT(o.err, Contains("nothing was simulated"));
  CHECK_THAT(o.out, !Contains("simulated in"));
  CHECK_FALSE(fs::exists(dir / "cmp"));
  fs::remove_all(dir);
}
