// The command line as a user meets it: exit codes, messages, output files (DESIGN
// sections 3 and 4). Each test runs the built binary in a scratch directory.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "run_stiction.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

using stiction::testing::Outcome;

fs::path scratch(const std::string& name) {
  return stiction::testing::scratch_dir("stiction_test_app_", name);
}

Outcome run_cli(const std::vector<std::string>& args, const fs::path& cwd) {
  return stiction::testing::run_stiction(args, cwd);
}

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) if (header[i] == name) return static_cast<int>(i);
    FAIL("no column " << name);
    return -1;
  }
};

Csv read_csv(const fs::path& p) {
  std::ifstream in(p);
  Csv csv;
  std::string line, cell;
  std::getline(in, line);
  std::stringstream h(line);
  while (std::getline(h, cell, ',')) csv.header.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream r(line);
    std::vector<double> row;
    while (std::getline(r, cell, ',')) row.push_back(std::stod(cell));
    csv.rows.push_back(row);
  }
  return csv;
}

const char* kGoodScene = R"(name = "tiny"
description = "a point mass on a spring"
gravity = [0.0, 0.0, 0.0]

[simulation]
dt = 1e-3
duration = 0.2

[bodies.ball]
type = "point_mass"
mass = 1.0
position = [0.1, 0.0, 0.0]

[impedances.spring]
type = "spring_damper"
body = "ball"
stiffness = 100.0
damping = 1.0
)";

// A scene with an arm (for the torque expression), minimal and valid.
const char* kArmScene = R"(gravity = [0.0, 0.0, 0.0]
[simulation]
dt = 1e-4
duration = 0.1
[bodies.arm]
type = "planar_arm"
links = [{ length = 0.2, width = 0.02, mass = 0.2 }]
[impedances.motor]
type = "torque_source"
body = "arm"
joint = 0
torque = "t < 4 ? min(0.52, 0.3*t) : 0.3"
)";

void expect_input_error(const fs::path& dir, const std::string& text, const std::string& key,
                        int line) {
  write(dir / "bad.toml", text);
  const Outcome o = run_cli({"run", "bad.toml", "--out", "bad_out"}, dir);
  INFO(o.out);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("bad.toml:" + std::to_string(line) + ":"));
  CHECK_THAT(o.out, Contains(": error: "));
  CHECK_THAT(o.out, Contains(key));
  CHECK_FALSE(fs::exists(dir / "bad_out" / "summary.json"));
}

}  // namespace

TEST_CASE("cli: --help, --version, no subcommand, unknown option") {
  const fs::path dir = scratch("help");
  Outcome o = run_cli({"--help"}, dir);
  CHECK(o.code == 0);
  CHECK_THAT(o.out, Contains("run"));
  CHECK_THAT(o.out, Contains("check"));
  CHECK_THAT(o.out, Contains("scenes"));
  o = run_cli({"--version"}, dir);
  CHECK(o.code == 0);
  CHECK_THAT(o.out, Contains("stiction "));
  CHECK(run_cli({}, dir).code == 2);
  CHECK(run_cli({"run", "sphere_roll", "--bogus"}, dir).code == 2);
  CHECK(run_cli({"run", "sphere_roll", "--dt", "-1"}, dir).code == 2);
  CHECK(run_cli({"run", "sphere_roll", "--integrator", "rk5"}, dir).code == 2);
  o = run_cli({"run", "no_such_scene"}, dir);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("no_such_scene"));
}

TEST_CASE("cli: a mistyped command gets a suggestion, exit 2") {
  const fs::path dir = scratch("typo");
  const std::pair<const char*, const char*> typos[] = {
      {"rn", "run"},         {"chek", "check"},   {"comapre", "compare"}, {"sweap", "sweep"},
      {"verfy", "verify"},   {"studdy", "study"}, {"scnees", "scenes"},   {"sw", "sweep"}};
  for (const auto& [typo, meant] : typos) {
    const Outcome o = run_cli({typo, "sphere_roll"}, dir);
    INFO(o.out);
    CHECK(o.code == 2);
    CHECK_THAT(o.out, Contains(std::string("unknown command '") + typo + "'; did you mean '" +
                               meant + "'?"));
  }
  // Nothing near: the list of commands.
  const Outcome o = run_cli({"simulate"}, dir);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("unknown command 'simulate'; the commands are: run, check"));
}

TEST_CASE("cli: scenes lists the bundled scenes with descriptions") {
  const Outcome o = run_cli({"scenes"}, scratch("scenes"));
  CHECK(o.code == 0);
  for (const char* name : {"sphere_roll", "two_link", "two_link_lugre", "two_link_dahl",
                           "two_link_penalty", "slope_hold", "slope_slide"}) {
    CHECK_THAT(o.out, Contains(name));
  }
  CHECK_THAT(o.out, Contains("slips, then rolls"));
}

TEST_CASE("cli: check prints the state layout and dt advice") {
  const Outcome o = run_cli({"check", "sphere_roll"}, scratch("check"));
  INFO(o.out);
  CHECK(o.code == 0);
  CHECK_THAT(o.out, Contains("[0..12]"));
  CHECK_THAT(o.out, Contains("sphere (rigid_body): p.x p.y p.z"));
  CHECK_THAT(o.out, Contains("ground (kikuuwe_contact): e.0 e.1"));
  CHECK_THAT(o.out, Contains("predicted step limits of the whole network"));
  CHECK_THAT(o.out, Contains("rk4               unstable above "));
  const Outcome e = run_cli({"check", "two_link", "--dt", "1"}, scratch("check2"));
  CHECK(e.code == 2);  // check takes no run options
  const fs::path dot = scratch("check3") / "net.dot";
  const Outcome g = run_cli({"check", "two_link", "--graph", dot.string()}, scratch("check3"));
  CHECK(g.code == 0);
  std::ifstream in(dot);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK_THAT(text, Contains("\"arm\" -> \"joint0_friction\""));
  CHECK_THAT(text, Contains("\"motor1\" -> \"arm\""));
}

TEST_CASE("cli: bad input gives exit 2 and FILE:LINE:COL: error: naming the key") {
  const fs::path dir = scratch("bad");
  const std::string base = kGoodScene;
  write(dir / "good.toml", base);
  {
    const Outcome o = run_cli({"run", "good.toml", "--out", "o", "--quiet"}, dir);
    INFO(o.out);
    REQUIRE(o.code == 0);
    CHECK(o.out.empty());  // --quiet: nothing but errors
  }
  const int base_lines = static_cast<int>(std::count(base.begin(), base.end(), '\n'));
  SECTION("unknown key") {
    expect_input_error(dir, base + "[impedances.spring2]\ntype = \"spring_damper\"\nbody = \"ball\"\nstifness = 3\n",
                       "unknown key 'impedances.spring2.stifness'", base_lines + 4);
  }
  SECTION("unknown component type") {
    std::string s = base;
    s.replace(s.find("\"spring_damper\""), 15, "\"springdamper\"");
    expect_input_error(dir, s, "impedances.spring.type", 15);
  }
  SECTION("negative mass") {
    std::string s = base;
    s.replace(s.find("mass = 1.0"), 10, "mass = -1.0");
    expect_input_error(dir, s, "bodies.ball.mass", 11);
  }
  SECTION("dt = 0 and dt < 0") {
    std::string s = base;
    s.replace(s.find("dt = 1e-3"), 9, "dt = 0");
    expect_input_error(dir, s, "simulation.dt", 6);
    s = base;
    s.replace(s.find("dt = 1e-3"), 9, "dt = -1e-3");
    expect_input_error(dir, s, "simulation.dt", 6);
  }
  SECTION("malformed expression") {
    std::string s = kArmScene;
    s.replace(s.find("0.3*t) : 0.3"), 12, "0.3*t) : 0.3 +");
    write(dir / "bad.toml", s);
    const Outcome o = run_cli({"run", "bad.toml", "--out", "bad_out"}, dir);
    INFO(o.out);
    CHECK(o.code == 2);
    CHECK_THAT(o.out, Contains("bad.toml:12:"));
    CHECK_THAT(o.out, Contains(": error: impedances.motor.torque"));
    CHECK_THAT(o.out, Contains("of the expression"));
  }
  SECTION("TOML syntax error") {
    expect_input_error(dir, base + "[bodies\n", "expected ']'", base_lines + 1);
  }
}

TEST_CASE("cli: --set overrides scene values, unknown keys are errors") {
  const fs::path dir = scratch("set");
  Outcome o = run_cli({"run", "sphere_roll", "--out", "o", "--quiet", "--set", "simulation.duration=0.05",
                        "--set", "bodies.sphere.velocity=[3.0, 0.0, 0.0]"},
                       dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  const nlohmann::json s = read_json(dir / "o" / "summary.json");
  CHECK(s["duration"] == 0.05);
  const Csv csv = read_csv(dir / "o" / "trajectory.csv");
  CHECK(csv.rows.size() == 51);
  CHECK(csv.rows[0][csv.column("sphere.v.x")] == 3.0);

  o = run_cli({"run", "sphere_roll", "--out", "o2", "--set", "bodies.sphere.masss=1"}, dir);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("--set bodies.sphere.masss:1:1: error: unknown key 'bodies.sphere.masss'"));
  o = run_cli({"run", "sphere_roll", "--out", "o2", "--set", "bodies.sphere.mass=-3"}, dir);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("--set bodies.sphere.mass:1:20: error: bodies.sphere.mass: must be > 0"));
  o = run_cli({"run", "sphere_roll", "--out", "o2", "--set", "nosuch.key=1"}, dir);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("error: unknown key 'nosuch'"));
  CHECK_FALSE(fs::exists(dir / "o2" / "summary.json"));
}

TEST_CASE("cli: run writes trajectory.csv and summary.json per the output contract") {
  const fs::path dir = scratch("run");
  const Outcome o = run_cli({"run", "sphere_roll", "--no-video", "--no-plots", "--quiet"}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  const fs::path out = dir / "out" / "sphere_roll";  // the default --out
  const nlohmann::json s = read_json(out / "summary.json");
  for (const char* key : {"scene", "integrator", "dt", "duration", "steps", "state_dim", "wall_seconds",
                          "status", "final", "events"}) {
    CHECK(s.contains(key));
  }
  CHECK(s["scene"] == "sphere_roll");
  CHECK(s["status"] == "ok");
  CHECK(s["steps"] == 20000);
  CHECK(s["state_dim"] == 15);
  CHECK(s["events"]["ground"]["threshold"] == 1e-3);
  const double stick = s["events"]["ground"]["stick_time"].get<double>();
  CHECK(stick > 0.57);
  CHECK(stick < 0.63);
  const Csv csv = read_csv(out / "trajectory.csv");
  CHECK(csv.header[0] == "t");
  for (const char* column : {"sphere.p.x", "sphere.v.z", "sphere.q.w", "sphere.w.y", "ground.f.x",
                             "ground.slip.x", "ground.e.0"}) {
    CHECK(std::find(csv.header.begin(), csv.header.end(), column) != csv.header.end());
  }
  CHECK(csv.rows.size() == 2001);
  // "final" is the last row, by column name, exactly (both are shortest round-trip text).
  CHECK(s["final"]["sphere.v.x"].get<double>() == csv.rows.back()[csv.column("sphere.v.x")]);
  CHECK(std::abs(s["final"]["sphere.v.x"].get<double>() - 2.0 * 5.0 / 7.0) < 1e-3 * 2.0 * 5.0 / 7.0);
  // No temporary files left next to the outputs (the third is the manifest .stiction-output).
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(out)) ++files;
  CHECK(files == 3);
}

TEST_CASE("cli: rows come at the output rate whatever dt") {
  const fs::path dir = scratch("rate");
  for (const char* dt : {"1e-4", "3e-4"}) {
    const Outcome o = run_cli({"run", "sphere_roll", "--out", dt, "--quiet", "--dt", dt, "--duration", "0.05"}, dir);
    INFO(o.out);
    REQUIRE(o.code == 0);
    const Csv csv = read_csv(dir / dt / "trajectory.csv");
    REQUIRE(csv.rows.size() == 51);
    for (std::size_t k = 0; k < csv.rows.size(); ++k) CHECK(csv.rows[k][0] == Approx(k * 1e-3).margin(1e-12));
    CHECK(read_json(dir / dt / "summary.json")["dt"] == std::stod(dt));
  }
}

TEST_CASE("cli: a step above the predicted limit is refused before anything is simulated") {
  const fs::path dir = scratch("refused");
  const Outcome o = run_cli({"run", "sphere_roll", "--out", "o", "--dt", "2e-3"}, dir);
  INFO(o.out);
  CHECK(o.code == 3);
  CHECK_THAT(o.out, Contains("above rk4's predicted instability limit"));
  CHECK_THAT(o.out, Contains("a trial at dt = 0.002 s: it failed: unstable at t = "));
  // sphere_roll's touch-downs are located within their steps (docs/events.md), so halving
  // from the chatter limit reaches a step whose 2 s trial is accurate (2.66e-6 s; the
  // bounce's phase at the end decides, docs/accuracy.md).
  CHECK_THAT(o.out, Contains("a step that works: --dt "));
  CHECK_THAT(o.out, Contains("halved"));
  CHECK_THAT(o.out, Contains("--force-step"));
  CHECK_FALSE(fs::exists(dir / "o"));
}

TEST_CASE("cli: an unstable run exits 3, keeps its rows and says what to do") {
  const fs::path dir = scratch("unstable");
  // The contact's normal mode limits RK4 to ~4.6e-4 s; 2e-3 s diverges within a few steps.
  // The guard refuses that step; --force-step runs it, and the run's monitor stops it.
  const Outcome o =
      run_cli({"run", "sphere_roll", "--out", "o", "--dt", "2e-3", "--force-step"}, dir);
  INFO(o.out);
  CHECK(o.code == 3);
  CHECK_THAT(o.out, Contains("instability at t = "));
  const nlohmann::json s = read_json(dir / "o" / "summary.json");
  CHECK(s["status"] == "unstable");
  const double suggested = s["instability"]["suggested_dt"];
  char shown[64];
  std::snprintf(shown, sizeof shown, "--dt %g", suggested);
  CHECK_THAT(o.out, Contains(shown));
  CHECK_THAT(o.out, Contains(std::string("'") + s["instability"]["component"].get<std::string>() + "'"));
  const Csv csv = read_csv(dir / "o" / "trajectory.csv");
  CHECK(csv.rows.size() >= 1);
  CHECK(csv.rows.size() < 2001);
  // The advice works: the suggested step runs clean.
  REQUIRE(suggested < 2e-3);
  const Outcome again = run_cli({"run", "sphere_roll", "--out", "again", "--dt",
                                 std::to_string(suggested), "--no-video", "--no-plots"}, dir);
  INFO(again.out);
  CHECK(again.code == 0);
}
