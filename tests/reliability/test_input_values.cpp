// Values that used to give exit 0 with wrong results, and hostile TOML that crashed the
// reader (issue 25, "Every number checked, every expression one expression"): each case runs
// the binary in a child process and checks the exit code, the located message and, where the
// run goes ahead, the numbers it wrote against their closed form.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "child.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

fs::path scratch(const std::string& name) { return scratch_dir("input_values", name); }

void write(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

// One point mass or rigid body in free fall (no contact): closed forms are exact for rk4.
std::string falling_body(const std::string& body_lines, double duration = 0.01,
                         double output_rate = 1000.0, double dt = 1e-3) {
  return "name = \"v\"\n[simulation]\ndt = " + number(dt) + "\nduration = " + number(duration) +
         "\noutput_rate = " + number(output_rate) + "\n" + body_lines;
}

nlohmann::json summary_of(const fs::path& out) {
  return nlohmann::json::parse(read_text(out / "summary.json"));
}

RunResult run_scene(const fs::path& dir, const std::string& file, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"run", file, "--out", "out", "--no-plots", "--no-video", "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_child(args, dir);
}

}  // namespace

TEST_CASE("orientations of huge or tiny components normalize to their unit quaternion", "[input_values]") {
  const fs::path dir = scratch("quaternion");
  std::mt19937 rng(25);
  std::normal_distribution<double> component(0.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 307);
  for (int trial = 0; trial < 6; ++trial) {
    double q[4];
    double norm = 0.0;
    for (double& c : q) {
      c = component(rng);
      norm += c * c;
    }
    norm = std::sqrt(norm);
    // The first trials at the extremes the issue found: every component 1e308 in magnitude.
    const double scale = trial < 2 ? 1e308 / std::abs(*std::max_element(q, q + 4, [](double a, double b) {
                                       return std::abs(a) < std::abs(b);
                                     }))
                                   : std::pow(10.0, exponent(rng));
    std::string orientation;
    for (double c : q) orientation += (orientation.empty() ? "" : ", ") + number(c * scale);
    INFO("orientation = [" << orientation << "]");
    write(dir / "q.toml", falling_body("[bodies.b]\ntype = \"rigid_body\"\nmass = 0.3\nshape = \"sphere\"\n"
                                       "radius = 0.2\norientation = [" + orientation + "]\n"));
    const RunResult r = run_scene(dir, "q.toml");
    REQUIRE(r.code == 0);
    const auto final_row = summary_of(dir / "out")["final"];
    double unit = 0.0;
    const char* names[] = {"b.q.w", "b.q.x", "b.q.y", "b.q.z"};
    for (int i = 0; i < 4; ++i) {
      const double got = final_row[names[i]].get<double>();
      unit += got * got;
      CHECK(got == Approx(q[i] / norm).margin(1e-12));  // no spin: the orientation stays
    }
    CHECK(unit == Approx(1.0).epsilon(1e-12));
  }
  // Zero and mixed non-finite are refused at the key.
  write(dir / "z.toml", falling_body("[bodies.b]\ntype = \"rigid_body\"\nmass = 0.3\nshape = \"sphere\"\n"
                                     "radius = 0.2\norientation = [0.0, 0.0, 0.0, 0.0]\n"));
  const RunResult zero = run_scene(dir, "z.toml");
  CHECK(zero.code == 2);
  CHECK_THAT(zero.err, Contains("z.toml:11:") && Contains("bodies.b.orientation") && Contains("non-zero"));
}

TEST_CASE("component names with a dot or other column-breaking characters are refused at the key", "[input_values]") {
  const fs::path dir = scratch("names");
  struct Case {
    std::string section, name;
  };
  for (const Case& c : {Case{"bodies", "a.b"}, Case{"bodies", "x.y.z"}, Case{"bodies", "a b"},
                        Case{"bodies", "a,b"}, Case{"impedances", "s.1"}}) {
    INFO(c.section << " '" << c.name << "'");
    std::string text = falling_body("");
    const std::string body = c.section == "bodies" ? c.name : "m";
    text += "[bodies.\"" + body + "\"]\ntype = \"point_mass\"\nmass = 1.0\n";
    if (c.section == "impedances") {
      text += "[impedances.\"" + c.name + "\"]\ntype = \"spring_damper\"\nbody = \"m\"\nstiffness = 10.0\n";
    }
    write(dir / "n.toml", text);
    for (const char* command : {"run", "check"}) {
      const RunResult r = std::string(command) == "run" ? run_scene(dir, "n.toml")
                                                       : run_child({"check", "n.toml"}, dir);
      CHECK(r.code == 2);
      CHECK_THAT(r.err, Contains("n.toml:") && Contains(c.section + ".\"" + c.name + "\""));
    }
  }
}

TEST_CASE("an energy that overflows while the state is finite is an instability, never ok", "[input_values]") {
  const fs::path dir = scratch("overflow");
  // sphere_roll at contact stiffnesses whose bounce overflows the kinetic energy but not the
  // speed (1e191 m/s): exit 3, never 0 with status ok.
  for (const std::string set : {"impedances.ground.stiffness=1e200", "impedances.ground.stiffness=1e250",
                                "bodies.sphere.mass=1e-200"}) {
    INFO(set);
    const RunResult r = run_scene(dir, "sphere_roll",
                                  {"--force-step", "--set", set, "--set", "simulation.duration=0.1"});
    CHECK(r.code == 3);
    if (fs::exists(dir / "out" / "summary.json")) {
      CHECK(summary_of(dir / "out")["status"] == "unstable");
    }
  }
}

TEST_CASE("a step longer than the run, or fewer than two rows, is refused naming the keys", "[input_values]") {
  const fs::path dir = scratch("step_rows");
  const std::string body = "[bodies.m]\ntype = \"point_mass\"\nmass = 1.0\n";
  const RunResult cli = run_scene(dir, "sphere_roll", {"--dt", "1e308", "--duration", "0.05"});
  CHECK(cli.code == 2);
  CHECK_THAT(cli.err, Contains("--dt") && Contains("dt"));
  write(dir / "dt.toml", falling_body(body, 0.05, 1000.0, 0.1));
  const RunResult scene_dt = run_scene(dir, "dt.toml");
  CHECK(scene_dt.code == 2);
  CHECK_THAT(scene_dt.err, Contains("dt.toml:3:") && Contains("simulation.dt"));
  CHECK(run_child({"check", "dt.toml"}, dir).code == 2);
  write(dir / "rows.toml", falling_body(body, 2.0, 0.1));
  const RunResult rows = run_scene(dir, "rows.toml");
  CHECK(rows.code == 2);
  CHECK_THAT(rows.err, Contains("rows.toml:5:") && Contains("output_rate") && Contains("duration"));
}

TEST_CASE("summary final is the state at the end of the run even between output rows", "[input_values]") {
  const fs::path dir = scratch("final");
  std::mt19937 rng(2025);
  std::uniform_real_distribution<double> height(-5.0, 5.0), speed(-3.0, 3.0), rate(1.1, 9.0);
  for (int trial = 0; trial < 4; ++trial) {
    const double z0 = height(rng), v0 = speed(rng), output_rate = rate(rng);
    const double duration = 1.0 + 0.0005 * std::floor(1000.0 * std::uniform_real_distribution<double>(0, 1)(rng));
    INFO("z0 " << z0 << " v0 " << v0 << " output_rate " << output_rate << " duration " << duration);
    write(dir / "f.toml", falling_body("[bodies.m]\ntype = \"point_mass\"\nmass = 2.0\nposition = [0.0, 0.0, " +
                                           number(z0) + "]\nvelocity = [0.0, 0.0, " + number(v0) + "]\n",
                                       duration, output_rate, 5e-4));
    const RunResult r = run_scene(dir, "f.toml");
    REQUIRE(r.code == 0);
    const auto final_row = summary_of(dir / "out")["final"];
    // rk4 integrates a constant acceleration exactly: z = z0 + v0 t - g t^2 / 2.
    CHECK(final_row["t"].get<double>() == Approx(duration).margin(1e-12));
    CHECK(final_row["m.p.z"].get<double>() ==
          Approx(z0 + v0 * duration - 4.9 * duration * duration).margin(1e-9));
    CHECK(final_row["m.v.z"].get<double>() == Approx(v0 - 9.8 * duration).margin(1e-9));
  }
}

TEST_CASE("expressions are one expression without assignment, and a non-finite value is their fault", "[input_values]") {
  const fs::path dir = scratch("expressions");
  auto scene = [](const std::string& expression) {
    return falling_body("[bodies.m]\ntype = \"point_mass\"\nmass = 1.0\nposition = [0.0, 0.0, 1.0]\n"
                        "[impedances.push]\ntype = \"force_source\"\nbody = \"m\"\nforce = [\"" +
                            expression + "\", \"0\", \"0\"]\n",
                        1.0, 100.0);
  };
  struct Case {
    std::string expression, says;
  };
  for (const Case& c : {Case{"t=5", "assignment"}, Case{"t+=1", "assignment"}, Case{"1,2", "list"},
                        Case{"sin(t), 3", "list"}, Case{"1/0", "t = 0 s"}, Case{"log(0)", "t = 0 s"},
                        Case{"log(t - 0.5)", "t = 0 s"}, Case{"1/(t - 0.75)", "t = 0.75 s"}}) {
    INFO(c.expression);
    write(dir / "e.toml", scene(c.expression));
    for (const char* command : {"run", "check"}) {
      INFO(command);
      const RunResult r = std::string(command) == "run" ? run_scene(dir, "e.toml")
                                                       : run_child({"check", "e.toml"}, dir);
      CHECK(r.code == 2);
      CHECK_THAT(r.err, Contains("e.toml:13:") && Contains("impedances.push.force[0]") && Contains(c.says));
    }
  }
  // An expression of the state that is not finite at the start (the scene's own initial
  // state) is the expression's fault, named with the values it saw, by run as by check.
  write(dir / "e.toml", scene("1/(m.p.z - 1)"));
  for (const char* command : {"run", "check"}) {
    INFO(command);
    const RunResult r = std::string(command) == "run" ? run_scene(dir, "e.toml")
                                                     : run_child({"check", "e.toml"}, dir);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("e.toml:13:") && Contains("impedances.push.force[0]") &&
                          Contains("is inf at t = 0 s with m.p.z = 1"));
  }
  // One that becomes non-finite later, as the body is pulled to x = 0.5, is the run's
  // instability (exit 3), never `ok`: it is not blamed on the expression, since a runaway's or
  // a Newton trial's finite state can overflow a sound one.
  write(dir / "e.toml", scene("1/(0.5 - m.p.x)"));
  CHECK(run_scene(dir, "e.toml").code == 3);
  // Comparisons, function argument lists and the conditional stay expressions.
  for (const std::string ok : {"t >= 0.5 ? 1 : 0", "min(1, t) + (t == 0) + (t != 1) + (t <= 2)"}) {
    INFO(ok);
    write(dir / "e.toml", scene(ok));
    CHECK(run_scene(dir, "e.toml").code == 0);
  }
}

TEST_CASE("hostile TOML structure is refused with exit 2, never a crash", "[input_values]") {
  const fs::path dir = scratch("hostile");
  const int n = 40000;  // about 80 kB: 30700 parts of a dotted key crashed the old reader
  std::string dotted = "a";
  for (int i = 1; i < n; ++i) dotted += ".a";
  struct Case {
    std::string name, text;
  };
  const std::vector<Case> cases{
      {"dotted_key", "name = \"h\"\n" + dotted + " = 1\n"},
      {"table_header", "name = \"h\"\n[" + dotted + "]\n"},
      {"array_header", "name = \"h\"\n[[" + dotted + "]]\n"},
      {"under_bodies", "name = \"h\"\n[bodies." + dotted + "]\n"},
      {"under_render", "name = \"h\"\n[render." + dotted + "]\n"},
      {"inline_dotted", "name = \"h\"\nx = {" + dotted + " = 1}\n"},
      {"arrays", "name = \"h\"\nx = " + std::string(n, '[') + std::string(n, ']') + "\n"},
      {"inline_tables", "name = \"h\"\nx = " + [&] {
         std::string s;
         for (int i = 0; i < n / 4; ++i) s += "{a=";
         s += "1";
         return s + std::string(n / 4, '}');
       }() + "\n"},
      {"huge_array", "name = \"h\"\nx = [" + [&] {
         std::string s = "1";
         for (int i = 1; i < n; ++i) s += ",1";
         return s;
       }() + "]\n"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    write(dir / (c.name + ".toml"), c.text);
    for (const char* command : {"run", "check"}) {
      INFO(command);
      const RunResult r = std::string(command) == "run" ? run_scene(dir, c.name + ".toml")
                                                       : run_child({"check", c.name + ".toml"}, dir);
      CHECK(r.code == 2);  // a signal death is 1000 + the signal
      CHECK_THAT(r.err, Contains(c.name + ".toml:2:"));
    }
  }
  // The same through --set: a value with a deep dotted key.
  const RunResult set = run_scene(dir, "sphere_roll", {"--set", "simulation.dt={" + dotted + " = 1}"});
  CHECK(set.code == 2);
}

// Issue 39: a key or table defined twice was reported with toml++'s garbled name ('"mamass" ',
// 'bodies."a.a.b"'); now as written, at its line, exit 2.
TEST_CASE("a key or table defined twice is named as the user wrote it", "[input_values]") {
  const fs::path dir = scratch("defined_twice");
  struct Case {
    std::string text, says;
    int line;
  };
  const std::vector<Case> cases{
      {"[bodies.ball]\ntype = \"point_mass\"\n\"mass\" = 1.0\n\"mass\" = 2.0\n",
       "key \"mass\" is defined twice", 4},
      {"[bodies.ball]\ntype = \"point_mass\"\n'ma = ss' = 1.0\n'ma = ss'   =   2.0\n",
       "key 'ma = ss' is defined twice", 4},
      {"[bodies.\"a.b\"]\ntype = \"point_mass\"\n\n[bodies.\"a.b\"]\n",
       "table [bodies.\"a.b\"] is defined twice", 4},
      {"[bodies.ball]\nmass = 1.0\nmass = 2.0\n", "key mass is defined twice", 3},
  };
  for (const Case& c : cases) {
    INFO(c.text);
    write(dir / "twice.toml", c.text);
    const RunResult r = run_child({"check", "twice.toml"}, dir);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("twice.toml:" + std::to_string(c.line) + ":") && Contains(c.says));
  }
}
