// The accuracy estimate of `run` (src/app/accuracy.hpp, docs/accuracy.md) against closed
// forms: a sphere started sliding on a floor sticks at 2 v0 / (7 mu g), a block sliding
// down a slope stops at v0 / (g (mu cos a - sin a)), an arm joint spinning down against
// Kikuuwe friction sticks at J w0 / F (with a joint spring as well: where its speed turns
// to zero). Generated scenes (random parameters, tilted slopes and joint axes), every
// fixed-step integrator at two steps: wherever the true error (run minus closed form) is
// above rounding, the estimate lies at or above it and within a factor 5. Then the bowling ball of
// issue 26 at dt = 0.003 s (above its chatter limit) is flagged inaccurate by `run`.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "services/accuracy.hpp"
#include "generated_scenes.hpp"
#include "run_stiction.hpp"
#include "scene_template.hpp"
#include "scene/scene.hpp"

namespace {

using namespace stiction;
constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.8;

// What the closed form says: the first event of a kind of an element, and final values.
struct Truth {
  std::string element, kind;
  double event_time = 0.0;
  std::map<std::string, double> finals;
};

struct Case {
  std::string name;
  std::string scene;  // TOML with INTEGRATOR and DT placeholders
  Truth truth;
  std::vector<double> dts;
};

std::string fill(const std::string& text, const std::string& integrator, double dt) {
  return testing::fill_template(text, integrator, dt);
}

// A duration past the event and a whole number of 2 ms: the last row then lies at the
// duration itself, a step end of every step tried (no interpolated final row).
double duration_after(double event_time) { return 0.002 * std::ceil(1.25 * event_time / 0.002); }

std::string header(const std::string& name, double duration, const std::string& gravity) {
  std::ostringstream s;
  s.precision(17);
  s << "name = \"" << name << "\"\ngravity = " << gravity
    << "\n[simulation]\nintegrator = \"INTEGRATOR\"\ndt = DT\nduration = " << duration
    << "\noutput_rate = 1000.0\n";
  return s.str();
}

// A solid sphere put sliding at v0 on a floor it rests on (settled: no bounce). The contact
// is stiff (its compliance, about mu g / omega^2 = 1e-7 m, is the model's departure from
// the closed form) and damped near critically so that every integrator is stable at these
// steps (Euler needs dt < 2 zeta / omega = 4.4e-4 s); the friction spring is lightly damped, as in
// the paper.
Case sliding_sphere(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double m = 0.5 + 2.0 * u(rng), r = 0.05 + 0.15 * u(rng), mu = 0.2 + 0.3 * u(rng);
  const double v0 = 1.0 + 2.0 * u(rng);
  const double k = 1e7 * m, b = 1.4 * std::sqrt(k * m);
  const double ts = 2.0 * v0 / (7.0 * mu * kG), duration = duration_after(ts);
  std::ostringstream s;
  s.precision(17);
  s << header("sliding_sphere", duration, "[0.0, 0.0, -9.8]")
    << "[bodies.ball]\ntype = \"rigid_body\"\nmass = " << m
    << "\nshape = \"sphere\"\nradius = " << r << "\nposition = [0.0, 0.0, " << r
    << "]\nvelocity = [" << v0 << ", 0.0, 0.0]\n[impedances.floor]\ntype = \"kikuuwe_contact\"\n"
    << "body = \"ball\"\nstiffness = " << k << "\ndamping = " << b << "\nmu = " << mu
    << "\nsettle = true\ntangential_damping = " << 0.6 * std::sqrt(k * m) << "\n";
  const double v = 5.0 / 7.0 * v0;
  const double x = v0 * ts - 0.5 * mu * kG * ts * ts + v * (duration - ts);
  return {"sliding sphere",
          s.str(),
          {"floor", "stick", ts, {{"ball.p.x", x}, {"ball.v.x", v}, {"ball.w.y", v / r}}},
          {2e-4, 1e-4}};
}

// A point mass launched down a slope of angle a with mu > tan a: it stops at
// v0 / (g (mu cos a - sin a)) after v0^2 / (2 g (mu cos a - sin a)).
Case block_on_slope(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double a = (10.0 + 15.0 * u(rng)) * kPi / 180.0;
  const double mu = std::tan(a) + 0.1 + 0.2 * u(rng), m = 0.5 + 2.0 * u(rng), v0 = 0.5 + u(rng);
  const double k = 1e7 * m, b = 1.4 * std::sqrt(k * m);
  const double decel = kG * (mu * std::cos(a) - std::sin(a));
  const double ts = v0 / decel, distance = v0 * v0 / (2.0 * decel), duration = duration_after(ts);
  const double x0 = 0.5, z0 = x0 * std::tan(a);  // on the plane through the origin
  std::ostringstream s;
  s.precision(17);
  s << header("block_on_slope", duration, "[0.0, 0.0, -9.8]")
    << "[bodies.block]\ntype = \"point_mass\"\nmass = " << m << "\nposition = [" << x0 << ", 0.0, "
    << z0 << "]\nvelocity = [" << -v0 * std::cos(a) << ", 0.0, " << -v0 * std::sin(a)
    << "]\n[impedances.slope]\ntype = \"kikuuwe_contact\"\n"
    << "body = \"block\"\nnormal = [" << -std::sin(a) << ", 0.0, " << std::cos(a)
    << "]\nstiffness = " << k << "\ndamping = " << b << "\nmu = " << mu
    << "\nsettle = true\ntangential_damping = " << 0.6 * std::sqrt(k * m) << "\n";
  return {
      "block on a slope",
      s.str(),
      {"slope",
       "stick",
       ts,
       {{"block.p.x", x0 - distance * std::cos(a)}, {"block.p.z", z0 - distance * std::sin(a)}}},
      {2e-4, 1e-4}};
}

// A one-link arm about a random axis (no gravity) spinning at w0 against Kikuuwe joint
// friction F; with `spring`, also a joint spring k that makes its speed turn to zero along
// a sine: J theta'' = -k theta - F from theta = 0, sticking where theta' = 0 if k theta < F.
Case arm_spin_down(std::mt19937& rng, bool spring) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double length = 0.2 + 0.3 * u(rng), width = 0.02, mass = 0.2 + u(rng);
  const double j = mass * (length * length + width * width) / 12.0 + mass * length * length / 4.0;
  const double f = 0.05 + 0.1 * u(rng);
  double w0 = 0.0, ts = 0.0, theta = 0.0, k = 0.0;
  if (!spring) {
    w0 = 1.0 + 2.0 * u(rng);
    ts = j * w0 / f;
    theta = j * w0 * w0 / (2.0 * f);
  } else {
    const double omega = 15.0 + 10.0 * u(rng);  // sqrt(k / J)
    k = omega * omega * j;
    w0 = std::sqrt(1.25) * f / k * omega;  // stops at k theta = F / 2: it sticks there
    ts = std::atan(w0 * k / (f * omega)) / omega;
    theta = -f / k + std::sqrt(f * f / (k * k) + w0 * w0 / (omega * omega));
  }
  const double duration = duration_after(ts);
  const double polar = kPi * u(rng), azimuth = 2.0 * kPi * u(rng);
  std::ostringstream s;
  s.precision(17);
  s << header(spring ? "arm_spring" : "arm_spin_down", duration, "[0.0, 0.0, 0.0]")
    << "[bodies.arm]\ntype = \"planar_arm\"\naxis = [" << std::sin(polar) * std::cos(azimuth)
    << ", " << std::sin(polar) * std::sin(azimuth) << ", " << std::cos(polar)
    << "]\nlinks = [{ length = " << length << ", width = " << width << ", mass = " << mass
    << " }]\nrates = [" << w0 << "]\n"
    << "[impedances.joint]\ntype = \"kikuuwe_friction\"\nbody = \"arm\"\njoint = 0\n"
    << "stiffness = 5000.0\ndamping = 1.0\nforce_limit = " << f << "\nstick_threshold = 1e-3\n";
  if (spring) {
    s << "[impedances.spring]\ntype = \"spring_damper\"\nbody = \"arm\"\njoint = 0\nstiffness = "
      << k << "\ndamping = 0.0\n";
  }
  return {spring ? "arm with a joint spring" : "arm spin-down",
          s.str(),
          {"joint", "stick", ts, {{"arm.theta.0", theta}, {"arm.omega.0", 0.0}}},
          {2e-3, 1e-3}};
}

// What a run gives for the case's closed-form quantities: its value and the estimate of its
// error, with a floor below which a true error is rounding.
struct Quantity {
  std::string what;
  double value = 0.0, estimate = 0.0, scale = 0.0;
};

std::vector<Quantity> measure(const Case& c, const std::string& integrator, double dt,
                              const std::filesystem::path& dir) {
  const auto path = testing::write_scene(dir, "case", fill(c.scene, integrator, dt));
  scene::Scene scene = scene::load_scene(path.string());
  const core::RunResult result = core::simulate(*scene.network, scene.run);
  REQUIRE_FALSE(result.instability);
  services::AccuracySettings on;
  on.mode = services::AccuracyMode::on;
  const services::AccuracyEstimate e = services::estimate_accuracy(scene, result, {}, on);
  REQUIRE(e.method == "richardson");
  std::vector<Quantity> out;
  for (const services::ElementEvents& element : e.events) {
    if (element.element != c.truth.element) continue;
    for (const services::EventAccuracy& a : element.events) {
      if (a.kind != c.truth.kind) continue;
      // Events that differ between the run and its companion have no error estimate: the
      // run is inaccurate for that reason alone (checked by the verdict below).
      if (!a.error) {
        CHECK(e.verdict == "inaccurate");
        std::printf("%-24s %-16s dt %-7g events differ from the companion's\n", c.name.c_str(),
                    integrator.c_str(), dt);
      } else {
        out.push_back({c.truth.element + " " + a.kind, a.time, *a.error, scene.run.duration});
      }
      break;
    }
  }
  for (const services::FinalAccuracy& f : e.finals) {
    if (c.truth.finals.count(f.column) > 0) out.push_back({f.column, f.value, f.error, f.scale});
  }
  REQUIRE(out.size() >= c.truth.finals.size());
  return out;
}

double truth_of(const Case& c, const std::string& what) {
  const auto it = c.truth.finals.find(what);
  return it != c.truth.finals.end() ? it->second : c.truth.event_time;
}

}  // namespace

// The estimate is a bound with a safety factor 2 on final values (docs/accuracy.md,
// "Calibration") and order 1 on event times: on these smoothly converging cases it lies at or
// above the true error (within rounding of the closed form) and at most 5 times it.
TEST_CASE("accuracy: estimates bound the closed forms' errors within a factor 5", "[accuracy]") {
  const auto dir = testing::scratch_dir("stiction_accuracy_", "closed");
  std::mt19937 rng(26);
  std::vector<Case> cases{sliding_sphere(rng), block_on_slope(rng), arm_spin_down(rng, false),
                          arm_spin_down(rng, true)};
  int compared = 0, total = 0;
  for (const Case& c : cases) {
    // Rounding, per quantity: what the closed form cannot resolve. The deviation of a
    // reference run (rk4 at an eighth of the smallest step) from the closed form is the
    // model's own (a penalty contact's compliance, the friction spring's deflection) plus
    // rounding; a true error counts from 10 times that, and from 1e-10 of the quantity's
    // scale (duration for a time, the signal's largest magnitude for a final value).
    std::map<std::string, double> rounding;
    for (const Quantity& q : measure(c, "rk4", c.dts.back() / 8.0, dir)) {
      rounding[q.what] = std::max(10.0 * std::abs(q.value - truth_of(c, q.what)), 1e-10 * q.scale);
    }
    for (const std::string integrator : {"euler", "symplectic_euler", "heun", "rk4"}) {
      for (double dt : c.dts) {
        for (const Quantity& q : measure(c, integrator, dt, dir)) {
          const double truth_error = std::abs(q.value - truth_of(c, q.what));
          const bool counted = truth_error > rounding[q.what];
          ++total;
          std::printf("%-24s %-16s dt %-7g %-14s true %-10.3g estimate %-10.3g ratio %-8.3g%s\n",
                      c.name.c_str(), integrator.c_str(), dt, q.what.c_str(), truth_error,
                      q.estimate, q.estimate / truth_error, counted ? "" : " (rounding)");
          if (!counted) continue;
          ++compared;
          INFO(c.name << ", " << integrator << ", dt " << dt << ", " << q.what << ": true error "
                      << truth_error << ", estimate " << q.estimate << ", rounding "
                      << rounding[q.what]);
          CHECK(q.estimate <= 5.0 * truth_error);
          CHECK(q.estimate >= 0.9 * truth_error);
        }
      }
    }
  }
  std::printf("compared %d of %d estimates (the others at rounding)\n", compared, total);
  CHECK(compared > 20);  // the check is not vacuous: most errors are above rounding
  std::filesystem::remove_all(dir);
}

namespace {

nlohmann::json read_summary(const std::filesystem::path& dir) {
  std::ifstream in(dir / "summary.json");
  return nlohmann::json::parse(in);
}

const std::string kBowling = std::string(STICTION_ACCURACY_TEST_DIR) + "/accuracy_bowling.toml";

// `run` with --force-step: the step guard refuses dt = 0.003 s for the bowling ball.
testing::Outcome run_forced(std::vector<std::string> args, const std::filesystem::path& dir) {
  args.push_back("--force-step");  // the step guard refuses dt = 0.003 s (above 2.38e-3 s)
  return testing::run_stiction(args, dir);
}

}  // namespace

// Issue 26: the bowling ball at dt = 0.003 s (above the chatter limit 1.03e-3 s that `check`
// predicts) never sticks and lifts off again and again. Over its first 2 s (its energy
// monitor stops the full 3 s run as unstable at 2.06 s on this build) the run ends with exit
// 0 and status ok, and must say it is inaccurate. First the estimate itself, with the energy
// monitor relaxed so that the run finishes whatever the monitor's rule, then `run`.
TEST_CASE("accuracy: the bowling ball at dt = 0.003 s is flagged inaccurate", "[accuracy]") {
  scene::Scene scene = scene::load_scene(kBowling);
  scene.run.dt = 0.003;
  scene.run.energy_tolerance = 1e6;
  const core::RunResult result = core::simulate(*scene.network, scene.run);
  REQUIRE_FALSE(result.instability);
  services::AccuracySettings on;
  on.mode = services::AccuracyMode::on;
  const services::AccuracyEstimate e = services::estimate_accuracy(scene, result, {}, on);
  CHECK(e.method == "richardson");
  CHECK(e.order == 4);
  CHECK(e.companion_dt == Approx(0.0015));
  CHECK(e.verdict == "inaccurate");
  CHECK_FALSE(e.reasons.empty());

  const auto dir = testing::scratch_dir("stiction_accuracy_", "bowling");
  const auto o = run_forced({"run", kBowling, "--dt", "0.003", "--duration", "2", "--no-video",
                             "--no-plots", "--out", (dir / "out").string()},
                            dir);
  INFO(o.out);
  const nlohmann::json s = read_summary(dir / "out");
  if (o.code == 3) {
    // A stricter energy monitor (issue 26 item 2) may stop it first: no estimate then.
    CHECK(s["status"] == "unstable");
    CHECK(s["accuracy"]["method"] == "off");
  } else {
    REQUIRE(o.code == 0);
    CHECK(s["status"] == "ok");
    const nlohmann::json& a = s["accuracy"];
    CHECK(a["method"] == "richardson");
    CHECK(a["companion"]["dt"].get<double>() == Approx(0.0015));
    CHECK(a["verdict"] == "inaccurate");
    CHECK_FALSE(a["reasons"].empty());
    CHECK(o.out.find("warning: bowling: the run is inaccurate") != std::string::npos);
  }
  std::filesystem::remove_all(dir);
}

// At 1e-4 s the same ball matches the closed form (rolls from 1.4840 s at 5.0914 m/s): the
// run is accurate, the stick gets an error bar, and the estimate is small.
TEST_CASE("accuracy: the bowling ball at the scene's step is accurate, with error bars",
          "[accuracy]") {
  const auto dir = testing::scratch_dir("stiction_accuracy_", "bowling_fine");
  // --accuracy on: the default leaves the companion off when it would cost more than its wall
  // time budget, which an instrumented build's run does (its summary then has no events).
  const auto o = testing::run_stiction({"run", kBowling, "--no-video", "--no-plots", "--accuracy",
                                        "on", "--out", (dir / "out").string()},
                                       dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  const nlohmann::json s = read_summary(dir / "out");
  const nlohmann::json& a = s.at("accuracy");
  CHECK(a.at("verdict") == "accurate");
  REQUIRE(a.at("events").at("lane").size() == s.at("events").at("lane").at("events").size());
  const nlohmann::json& stick = a.at("events").at("lane").at(0);
  CHECK(stick["kind"] == "stick");
  CHECK(stick["time"].get<double>() == Approx(10.18 / (3.5 * 0.2 * 9.8)).epsilon(1e-4));
  CHECK(stick["error"].get<double>() < 1e-4);
  CHECK(a["final"]["ball.v.x"]["value"].get<double>() == Approx(5.0914).epsilon(1e-4));
  CHECK(a["final"]["ball.v.x"]["error"].get<double>() < 1e-4);
  CHECK(o.out.find("first stick at t = 1.48") != std::string::npos);
  CHECK(o.out.find("s (+- ") != std::string::npos);
  CHECK(o.out.find("inaccurate") == std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("accuracy: --accuracy off, --quiet, and on by default for a short run", "[accuracy]") {
  const auto dir = testing::scratch_dir("stiction_accuracy_", "switch");
  auto o = testing::run_stiction(
      {"run", "sphere_roll", "--no-video", "--no-plots", "--out", (dir / "a").string()}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  const nlohmann::json on = read_summary(dir / "a")["accuracy"];
  CHECK(on["method"] == "richardson");
  CHECK(on["cpu_seconds"].get<double>() >= 0.0);
  CHECK(on["final"].contains("sphere.v.x"));
  o = testing::run_stiction({"run", "sphere_roll", "--accuracy", "off", "--no-video", "--no-plots",
                             "--out", (dir / "b").string()},
                            dir);
  REQUIRE(o.code == 0);
  const nlohmann::json off = read_summary(dir / "b")["accuracy"];
  CHECK(off["method"] == "off");
  CHECK(off["reason"] == "--accuracy off");
  CHECK(o.out.find("(+- ") == std::string::npos);
  o = testing::run_stiction(
      {"run", "sphere_roll", "--accuracy", "maybe", "--out", (dir / "c").string()}, dir);
  CHECK(o.code == 2);
  // sphere_roll at its own step is inaccurate too: its lightly damped contact keeps
  // bouncing, and the number of micro-bounces depends on the step (docs/accuracy.md).
  o = testing::run_stiction(
      {"run", "sphere_roll", "--quiet", "--no-video", "--no-plots", "--out", (dir / "d").string()},
      dir);
  CHECK(o.code == 0);
  CHECK(o.out.empty());
  CHECK(read_summary(dir / "d")["accuracy"]["verdict"] == "inaccurate");
  std::filesystem::remove_all(dir);
}

// The default's rule: off when the companion is expected to cost more than the budget (2x
// the run's time for half the step), and abandoned when it passes the budget anyway.
TEST_CASE("accuracy: the default stays within its budget", "[accuracy]") {
  scene::Scene scene = scene::load_scene(kBowling);
  scene.run.duration = 0.5;
  core::RunResult result = core::simulate(*scene.network, scene.run);
  REQUIRE_FALSE(result.instability);
  services::AccuracySettings automatic;
  CHECK(services::estimate_accuracy(scene, result, {}, automatic).method == "richardson");
  automatic.budget_seconds = 1.9 * result.wall_seconds;
  const services::AccuracyEstimate skipped = services::estimate_accuracy(scene, result, {}, automatic);
  CHECK(skipped.method == "off");
  CHECK(skipped.cpu_seconds == 0.0);
  CHECK(skipped.reason.find("budget") != std::string::npos);
  // A run that claims to have cost nothing passes the prediction; the companion is then
  // stopped at its first progress report, past a budget of 1 ns.
  result.wall_seconds = 0.0;
  automatic.budget_seconds = 1e-9;
  const services::AccuracyEstimate abandoned = services::estimate_accuracy(scene, result, {}, automatic);
  CHECK(abandoned.method == "off");
  CHECK(abandoned.reason.find("passed the 1e-09 s budget") != std::string::npos);
  CHECK(abandoned.cpu_seconds > 0.0);
  services::AccuracySettings forced;
  forced.mode = services::AccuracyMode::on;
  forced.budget_seconds = 1e-9;
  CHECK(services::estimate_accuracy(scene, result, {}, forced).method == "richardson");
}

// rk4_adaptive: the companion at a tolerance 100 times tighter; the JSON of the estimate
// carries the predicted limits when the caller has them.
TEST_CASE("accuracy: rk4_adaptive against a tighter tolerance", "[accuracy]") {
  scene::Scene scene = scene::load_scene(kBowling);
  scene.run.integrator = "rk4_adaptive";
  scene.run.tolerance = 1e-8;
  scene.run.duration = 2.0;
  const core::RunResult result = core::simulate(*scene.network, scene.run);
  REQUIRE_FALSE(result.instability);
  services::AccuracySettings on;
  on.mode = services::AccuracyMode::on;
  const services::AccuracyEstimate e = services::estimate_accuracy(scene, result, {1.03e-3, 2.49e-3}, on);
  CHECK(e.method == "tighter_tolerance");
  REQUIRE(e.companion_tolerance);
  CHECK(*e.companion_tolerance == Approx(1e-10));
  CHECK(e.verdict == "accurate");
  REQUIRE(e.events.size() == 1);
  REQUIRE(e.events[0].events.size() == 1);
  const services::EventAccuracy& stick = e.events[0].events[0];
  CHECK(stick.kind == "stick");
  REQUIRE(stick.error);
  // The closed form's stick, 10.18 / (3.5 mu g): the estimate bounds the run's distance to
  // it within the factor 3 (or both are below 1e-9 s).
  const double truth = std::abs(stick.time - 10.18 / (3.5 * 0.2 * 9.8));
  INFO("stick " << stick.time << ", true error " << truth << ", estimate " << *stick.error);
  if (truth > 1e-9 || *stick.error > 1e-9) {
    CHECK(*stick.error <= 3.0 * truth);
    CHECK(*stick.error >= truth / 3.0);
  }
  const nlohmann::ordered_json j = services::accuracy_json(e);
  CHECK(j["companion"]["tolerance"].get<double>() == Approx(1e-10));
  CHECK(j["step_limits"]["chatter"].get<double>() == Approx(1.03e-3));
  CHECK(j["events"]["lane"][0]["kind"] == "stick");
  CHECK(j["final"]["ball.v.x"]["judged"] == true);
  CHECK(j["final"]["lane.f.x"]["judged"] == false);
}
