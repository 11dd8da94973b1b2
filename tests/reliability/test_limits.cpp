// Values that used to crash, hang or lie (issue 14): each is refused up front with exit 2
// and a message that names the key (and, for scene values, FILE:LINE:COL), before any
// output is written. Bounds are documented in docs/limits.md.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>

#include <catch2/catch.hpp>

#include "child.hpp"
#include "core/run_limits.hpp"
#include "generated_scene.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

fs::path scratch(const std::string& name) { return scratch_dir("limits", name); }

}  // namespace

TEST_CASE("run options beyond the limits are found in floating point", "[limits]") {
  stiction::core::RunOptions o;
  CHECK_FALSE(stiction::core::check_run_limits(o));
  o.duration = 1e20;  // 1e24 steps: would overflow a long step counter
  REQUIRE(stiction::core::check_run_limits(o));
  CHECK(stiction::core::check_run_limits(o)->key == "dt");
  o = {};
  o.dt = 1e-300;
  CHECK(stiction::core::check_run_limits(o)->key == "dt");
  o = {};
  o.output_rate = 1e300;
  CHECK(stiction::core::check_run_limits(o)->key == "output_rate");
  o = {};
  o.dt = std::nan("");
  CHECK(stiction::core::check_run_limits(o)->key == "dt");
  o = {};
  o.duration = std::numeric_limits<double>::infinity();
  CHECK(stiction::core::check_run_limits(o)->key == "duration");
  // Exactly at the limits is allowed; just past them is not.
  o = {};
  o.duration = 1.0;
  o.dt = 1.0 / stiction::core::RunLimits::kMaxSteps;
  CHECK_FALSE(stiction::core::check_run_limits(o));
  o.dt /= 1.01;
  CHECK(stiction::core::check_run_limits(o));
  o = {};
  o.output_rate = stiction::core::RunLimits::kMaxRows - 1.0;
  CHECK_FALSE(stiction::core::check_run_limits(o));
  o.output_rate = stiction::core::RunLimits::kMaxRows;
  CHECK(stiction::core::check_run_limits(o));
  // rk4_adaptive: a tolerance below a double's rounding is no step at all (issue 39).
  o = {};
  o.integrator = "rk4_adaptive";
  o.tolerance = stiction::core::RunLimits::kMinTolerance;
  CHECK_FALSE(stiction::core::check_run_limits(o));
  o.tolerance = 1e-300;
  REQUIRE(stiction::core::check_run_limits(o));
  CHECK(stiction::core::check_run_limits(o)->key == "tolerance");
  CHECK_THAT(stiction::core::check_run_limits(o)->message, Contains("double precision"));
}

TEST_CASE("command-line numbers must be finite and positive", "[limits]") {
  const fs::path dir = scratch("cli");
  const fs::path scene = write_scene(dir, {});
  for (const std::string value : {"nan", "NaN", "inf", "-inf", "0", "-1", "1e400"}) {
    INFO("--dt " << value);
    const RunResult r = run_child(
        {"run", scene.string(), "--dt", value, "--no-video", "--no-plots", "--out", "o"}, dir);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("--dt"));
    CHECK_FALSE(fs::exists(dir / "o" / "trajectory.csv"));
  }
  const RunResult r =
      run_child({"run", scene.string(), "--duration", "nan", "--no-video", "--out", "o"}, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--duration"));
}

TEST_CASE("step and row counts beyond the limits exit 2 before writing anything", "[limits]") {
  const fs::path dir = scratch("counts");
  const fs::path scene = write_scene(dir, {});
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Case> cases{
      {{"--duration", "1e20"}, "steps"},
      {{"--dt", "1e-300"}, "steps"},
      {{"--dt", "1e-19"}, "steps"},  // 1e19 steps: past 2^63, the counter used to wrap
      {{"--set", "simulation.output_rate=1e300"}, "rows"},
      {{"--set", "simulation.output_rate=1e9"}, "rows"},  // used to ask for 367 GB
      {{"--set", "simulation.duration=1e300"}, "steps"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args{"run", scene.string(), "--no-video", "--no-plots", "--out", "o"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    INFO(c.args[0] << " " << c.args[1]);
    const RunResult r = run_child(args, dir);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains(c.says));
    CHECK_THAT(r.err, Contains("error:"));
    CHECK_FALSE(fs::exists(dir / "o" / "trajectory.csv"));
  }
}

TEST_CASE("a scene value past a limit is reported at its FILE:LINE:COL", "[limits]") {
  const fs::path dir = scratch("scene_limits");
  SceneSpec spec;
  spec.output_rate = 1e12;  // line 7 of the generated scene: output_rate = ...
  const fs::path scene = write_scene(dir, spec);
  const RunResult r = run_child({"run", scene.string(), "--no-video", "--out", "o"}, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains(scene.string() + ":7:15: error: simulation.output_rate:"));
}

TEST_CASE("integers beyond 2^53 are located errors, not crashes", "[limits]") {
  const fs::path dir = scratch("bigint");
  SceneSpec spec;
  spec.bodies = 1;
  std::string text = generated_scene(spec);
  // The mass line of the only body: replace its value by an integer past 2^53.
  const std::size_t at = text.find("mass = ");
  const std::size_t end = text.find('\n', at);
  text.replace(at, end - at, "mass = 9007199254740993");
  std::ofstream(dir / "big.toml") << text;
  int line = 1;
  for (std::size_t i = 0; i < at; ++i) line += text[i] == '\n';
  const RunResult r =
      run_child({"run", (dir / "big.toml").string(), "--no-video", "--out", "o"}, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains((dir / "big.toml").string() + ":" + std::to_string(line) + ":8: error: bodies.mass_0.mass:"));
  CHECK_THAT(r.err, Contains("2^53"));

  // 2^53 itself is exact, and accepted.
  text.replace(at, std::string("mass = 9007199254740993").size(), "mass = 9007199254740992");
  std::ofstream(dir / "exact.toml") << text;
  const RunResult ok = run_child({"check", (dir / "exact.toml").string()}, dir);
  CHECK(ok.code == 0);

  // The same through --set, and in an array.
  const fs::path scene = write_scene(dir, spec);
  RunResult s = run_child({"run", scene.string(), "--no-video", "--out", "o", "--set",
                           "bodies.mass_0.mass=-9223372036854775808"},
                          dir);
  CHECK(s.code == 2);
  CHECK_THAT(s.err, Contains("--set bodies.mass_0.mass:1:"));
  CHECK_THAT(s.err, Contains("2^53"));
  s = run_child({"run", scene.string(), "--no-video", "--out", "o", "--set",
                 "bodies.mass_0.velocity=[1, 0, 18014398509481984]"},
                dir);
  CHECK(s.code == 2);
  CHECK_THAT(s.err, Contains("bodies.mass_0.velocity"));
  CHECK_THAT(s.err, Contains("2^53"));
  // A non-finite value through --set.
  s = run_child({"run", scene.string(), "--no-video", "--out", "o", "--set", "simulation.dt=nan"},
                dir);
  CHECK(s.code == 2);
  CHECK_THAT(s.err, Contains("simulation.dt: expected a finite number"));
}

TEST_CASE("a --set array index past the limit does not wrap to element 0", "[limits]") {
  const fs::path dir = scratch("index");
  const fs::path scene = write_scene(dir, {});
  for (const std::string index : {"18446744073709551616", "18446744073709551617", "99999999999999999999999", "3"}) {
    INFO(index);
    const RunResult r = run_child({"run", scene.string(), "--no-video", "--out", "o", "--set",
                                   "bodies.mass_0.velocity[" + index + "]=5.0"},
                                  dir);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("out of range"));
    CHECK_FALSE(fs::exists(dir / "o" / "trajectory.csv"));
  }
}

TEST_CASE("fps and slow_motion are bounded, and so is the frame count", "[limits]") {
  const fs::path dir = scratch("render");
  struct Case {
    std::string render;
    std::string key;
  };
  for (const Case& c : {Case{"fps = 1e-300", "render.fps"}, Case{"fps = 0.5", "render.fps"},
                        Case{"slow_motion = 1e300", "render.slow_motion"},
                        Case{"slow_motion = 1e-9", "render.slow_motion"},
                        Case{"fps = nan", "render.fps"}}) {
    SceneSpec spec;
    spec.extra = "[render]\n" + c.render + "\n";
    const fs::path scene = write_scene(dir, spec);
    INFO(c.render);
    const RunResult r = run_child({"run", scene.string(), "--out", "o"}, dir);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains(c.key));
    CHECK_FALSE(fs::exists(dir / "o" / "trajectory.csv"));  // refused before simulating
  }
  // 1e5 s at 60 fps: 6e6 frames, past the limit; fine without a video.
  SceneSpec spec;
  spec.duration = 1e5;
  spec.output_rate = 1.0;
  spec.dt = 1.0;
  spec.extra = "[render]\nfps = 60\n";
  const fs::path scene = write_scene(dir, spec);
  const RunResult r = run_child({"run", scene.string(), "--out", "o"}, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("render.fps"));
  CHECK_THAT(r.err, Contains("frames"));
}

TEST_CASE("check bounds its pilot run whatever the duration", "[limits]") {
  const fs::path dir = scratch("check");
  SceneSpec spec;
  spec.duration = 3e6;  // 3e10 steps: a pilot over all of it would run for days
  spec.output_rate = 1.0;
  const fs::path scene = write_scene(dir, spec);
  Child child({"check", scene.string()}, dir);
  const int code = child.wait(std::chrono::seconds(120));  // a hang bound, not a timing test
  CHECK(code == 0);
  CHECK_THAT(child.out(), Contains("the part that fits its step budget"));
  CHECK_THAT(child.out(), Contains("rk4"));
}

TEST_CASE("a write error on standard output is a failure", "[limits]") {
  const fs::path dir = scratch("stdout");
  const fs::path scene = write_scene(dir, {});
  // /dev/full accepts the open and fails every write with ENOSPC.
  const std::string command = "cd '" + dir.string() + "' && '" + STICTION_BINARY + "' scenes > /dev/full 2> err.txt";
  const int status = std::system(command.c_str());
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 1);
  CHECK_THAT(read_text(dir / "err.txt"), Contains("standard output"));
  const std::string run_command = "cd '" + dir.string() + "' && '" + STICTION_BINARY + "' run '" +
                                  scene.string() + "' --no-video --no-plots --out o > /dev/full 2> err.txt";
  const int run_status = std::system(run_command.c_str());
  REQUIRE(WIFEXITED(run_status));
  CHECK(WEXITSTATUS(run_status) == 1);
}

// Issue 39: 500 spheres with a contact for every pair (124750 elements) ended in
// std::bad_alloc after loading. The scene's contact elements are bounded together: 201
// spheres make 20100 pairs, and the pair that passes 20000 is the located error, exit 2,
// before anything is written.
TEST_CASE("contact elements are bounded over the whole scene", "[limits]") {
  const fs::path dir = scratch("pairs");
  std::ostringstream s;
  s << "gravity = [0.0, 0.0, 0.0]\n[simulation]\ndt = 1e-4\nduration = 0.01\n";
  const int spheres = 201;
  for (int i = 0; i < spheres; ++i) {
    s << "[bodies.s" << i << "]\ntype = \"rigid_body\"\nshape = \"sphere\"\nmass = 1.0\n"
      << "radius = 0.1\nposition = [" << 0.3 * i << ", 0.0, 0.0]\n";
  }
  int pair = 0;
  std::string crossing;
  for (int i = 0; i < spheres; ++i) {
    for (int j = i + 1; j < spheres; ++j, ++pair) {
      const std::string name = "p_" + std::to_string(pair);
      if (pair == 20000) crossing = name;  // the 20001st element
      s << "[impedances." << name << "]\ntype = \"kikuuwe_contact\"\nbody = \"s" << i
        << "\"\nother = \"s" << j << "\"\n";
    }
  }
  std::ofstream(dir / "pairs.toml") << s.str();
  const RunResult r =
      run_child({"run", "pairs.toml", "--no-video", "--no-plots", "--out", "o"}, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("impedances." + crossing + ": the scene's contacts reach 20001"));
  CHECK_THAT(r.err, Contains("the limit is 20000 in a scene"));
  CHECK_FALSE(fs::exists(dir / "o" / "trajectory.csv"));
}

// Issue 39: a sweep at the documented maximum of 1e7 points held about 4.9 GB before its first
// point ran. The bound is 1e6 points, for a range and for a grid, exit 2 naming --vary.
TEST_CASE("a sweep plans at most 1e6 points", "[limits]") {
  const fs::path dir = scratch("sweep_points");
  const fs::path scene = write_scene(dir, {});
  RunResult r = run_child({"sweep", scene.string(), "--vary", "simulation.duration=0.1:0.2:1000001",
                           "--quiet", "--out", "s"},
                          dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("range count must be an integer in 1..1000000"));
  r = run_child({"sweep", scene.string(), "--vary", "simulation.duration=0.1:0.2:1001", "--vary",
                 "simulation.dt=1e-4:2e-4:1000", "--quiet", "--out", "s"},
                dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--vary: the grid has") && Contains("more than 1000000"));
  CHECK_FALSE(fs::exists(dir / "s" / "sweep.csv"));
}

// Issue 39: 10000 contact points under a memory limit ended in a bare "error: std::bad_alloc".
// Under a 300 MB address-space limit (inherited by the child; the test process restores its
// own) the run says it ran out of memory, what costs memory and what to reduce; exit 1 and no
// trajectory left behind. Not under AddressSanitizer, which reserves terabytes of address
// space at start.
TEST_CASE("running out of memory is said in words, exit 1, nothing half-written", "[limits]") {
#if defined(__SANITIZE_ADDRESS__)
  WARN("not run: AddressSanitizer cannot start under an address-space limit");
#else
  const fs::path dir = scratch("out_of_memory");
  std::ostringstream s;
  s << "[simulation]\ndt = 1e-4\nduration = 0.2\noutput_rate = 500.0\n"
    << "[bodies.box]\ntype = \"rigid_body\"\nshape = \"box\"\nmass = 1.0\n"
    << "size = [0.2, 0.2, 0.1]\nposition = [0.0, 0.0, 0.05]\n"
    << "[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"box\"\npoints = [";
  for (int i = 0; i < 10000; ++i) {
    s << (i ? ", " : "") << "[" << -0.1 + 0.2 * (i % 100) / 99.0 << ", "
      << -0.1 + 0.2 * (i / 100) / 99.0 << ", -0.05]";
  }
  s << "]\n";
  std::ofstream(dir / "box.toml") << s.str();
  rlimit before{};
  REQUIRE(::getrlimit(RLIMIT_AS, &before) == 0);
  rlimit limited = before;
  limited.rlim_cur = 300ul << 20;
  REQUIRE(::setrlimit(RLIMIT_AS, &limited) == 0);
  Child child({"run", "box.toml", "--no-video", "--no-plots", "--force-step", "--out", "o"}, dir,
              "oom");
  REQUIRE(::setrlimit(RLIMIT_AS, &before) == 0);
  CHECK(child.wait() == 1);
  const std::string err = child.err();
  CHECK_THAT(err, Contains("error: out of memory") && Contains("reduce contacts"));
  CHECK_THAT(err, !Contains("std::bad_alloc"));
  CHECK_FALSE(fs::exists(dir / "o" / "trajectory.csv"));
#endif
}
