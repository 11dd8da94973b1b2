// One verdict across commands (issue 35 items 3 and 4), on generated scenes of every kind:
// a sphere, a pushed box, a wheel under a torque ramp, two spheres colliding, a planar arm
// with joint friction, a URDF arm, a mass on a belt, a sphere under a torque source, each
// with random parameters. For each:
//   - the instability limit `check` predicts, against the largest step that runs stable,
//     found by bisecting whole runs; where the prediction is more than 1.25x below it (a
//     linear prediction cannot be tight on contacts that open and close) the guard confirms by
//     a trial: it refuses a step between the two only when a whole run at that step is
//     unstable or inaccurate;
//   - the step `check` recommends and the step `study` recommends both run stable and
//     `accurate` by `run`'s own verdict, each at least 0.6x the largest step `study` finds
//     within its target, and study's at most 0.8x the bisected stable step.
// `ctest -R consistency -V` prints the table of docs/study.md.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/integrator_traits.hpp"
#include "scene/scene.hpp"
#include "services/accuracy.hpp"
#include "services/step_check.hpp"
#include "services/step_guard.hpp"
#include "services/study.hpp"
#include "services/suggest_step.hpp"

using namespace stiction;

namespace {

struct Kind {
  std::string kind;
  scene::SceneSource source;
  std::vector<std::string> overrides;
};

std::string number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  std::string text = s.str();
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string wheel(double k, double mu, double mass) {
  std::ostringstream s;
  s.precision(17);
  s << "name = \"wheel\"\ngravity = [0.0, 0.0, -9.8]\n[simulation]\nintegrator = \"rk4\"\n"
    << "dt = 1e-4\nduration = " << 1.5 * 0.2 * mu * mass * 9.8 / k + 0.3 << "\n"
    << "[bodies.wheel]\ntype = \"rigid_body\"\nshape = \"cylinder\"\nmass = " << mass
    // On its two lowest rim points (one per end cap), at their static deflection.
    << "\nradius = 0.2\nlength = 0.1\naxis = [0.0, 1.0, 0.0]\nposition = [0.0, 0.0, "
    << 0.2 - mass * 9.8 / 2e7 << "]\n"
    << "[impedances.ground]\ntype = \"kikuuwe_contact\"\nbody = \"wheel\"\nstiffness = 1e7\n"
    << "damping = 2000.0\nmu = " << mu << "\n"
    << "[impedances.drive]\ntype = \"torque_source\"\nbody = \"wheel\"\naxis = [0.0, 1.0, 0.0]\n"
    << "torque = \"" << k << " * t\"\n";
  return s.str();
}

std::vector<Kind> generated_kinds(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto set = [](const std::string& key, double v) { return key + "=" + number(v); };
  std::vector<Kind> kinds;
  // sphere_roll bounces for the whole run (no step is accurate for its first stick, which
  // moves with the bounce phase): the sphere here starts settled on the floor.
  kinds.push_back({"sphere", scene::SceneSource("sphere_roll"),
                   {set("impedances.ground.mu", 0.1 + 0.2 * u(rng)),
                    "bodies.sphere.velocity=[" + number(1.0 + 2.0 * u(rng)) + ", 0.0, 0.0]",
                    "bodies.sphere.position=[0.0, 0.0, 0.2]", "impedances.ground.settle=true",
                    "impedances.ground.damping=2000.0", "simulation.duration=1.2"}});
  kinds.push_back({"box", scene::SceneSource("box_push_slide"),
                   {set("impedances.floor.mu", 0.3 + 0.3 * u(rng)), "simulation.duration=2.0"}});
  kinds.push_back({"cylinder",
                   scene::SceneSource::from_text(wheel(0.3 + 0.3 * u(rng), 0.2 + 0.2 * u(rng),
                                                       0.5 + u(rng)),
                                                 "wheel.toml"),
                   {}});
  kinds.push_back({"pair", scene::SceneSource("glancing_spheres"),
                   {set("impedances.touch.mu", 0.2 + 0.2 * u(rng)), "simulation.duration=0.05"}});
  kinds.push_back({"planar arm", scene::SceneSource("two_link"),
                   {set("impedances.joint0_friction.force_limit", 0.2 + 0.3 * u(rng)),
                    "simulation.duration=2.0"}});
  kinds.push_back({"URDF arm", scene::SceneSource("two_link_urdf"), {"simulation.duration=2.0"}});
  kinds.push_back({"belt", scene::SceneSource("belt_oscillator"),
                   {set("impedances.belt.mu", 0.2 + 0.2 * u(rng)),
                    set("impedances.belt.belt_speed", 0.1 + 0.2 * u(rng)),
                    "simulation.duration=1.5"}});
  kinds.push_back({"source", scene::SceneSource("roll_to_slip"),
                   {"impedances.motor.torque=\"" + number(0.03 + 0.03 * u(rng)) + " * t\"",
                    "simulation.duration=2.5"}});
  return kinds;
}

// The run at h: stable, and `run`'s verdict on it.
struct Verdict {
  bool stable = false;
  std::string accuracy;
};

Verdict run_at(scene::Scene& scene, double h) {
  const core::RunOptions kept = scene.run;
  scene.run.dt = h;
  Verdict v;
  const core::RunResult r = core::simulate(*scene.network, scene.run);
  v.stable = !r.instability;
  if (v.stable) {
    services::AccuracySettings on;
    on.mode = services::AccuracyMode::on;
    v.accuracy = services::estimate_accuracy(scene, r, {}, on).verdict;
  }
  scene.run = kept;
  return v;
}

bool stable_at(scene::Scene& scene, double h) {
  const core::RunOptions kept = scene.run;
  scene.run.dt = h;
  const bool stable = !core::simulate(*scene.network, scene.run).instability;
  scene.run = kept;
  return stable;
}

// The largest step whose whole run is stable, to 5% (0: none found).
double bisect_stable(scene::Scene& scene, double start) {
  double lo = 0.0, hi = 0.0, h = start;
  const double longest = scene.run.duration / 8.0;
  if (stable_at(scene, h)) {
    lo = h;
    while (hi == 0.0 && h < longest) {
      h *= 2.0;
      if (stable_at(scene, h)) lo = h; else hi = h;
    }
    if (hi == 0.0) return lo;
  } else {
    hi = h;
    for (int i = 0; i < 12 && lo == 0.0; ++i) {
      h /= 2.0;
      if (stable_at(scene, h)) lo = h; else hi = h;
    }
    if (lo == 0.0) return 0.0;
  }
  while (hi / lo > 1.05) {
    const double mid = std::sqrt(lo * hi);
    if (stable_at(scene, mid)) lo = mid; else hi = mid;
  }
  return lo;
}

}  // namespace

TEST_CASE("consistency: check, the guard, study and run agree on generated scenes of every kind",
          "[study][consistency]") {
  std::mt19937 rng(3535);
  std::printf(
      "| kind | predicted limit (s) | bisected limit (s) | ratio | guard between | check's step | "
      "run there | study's step | run there | largest accurate (s) |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Kind& k : generated_kinds(rng)) {
    INFO(k.kind);
    scene::Scene scene = scene::load_scene(k.source, k.overrides);
    const services::StepCheck check = services::check_step(scene);
    REQUIRE(check.applies);
    REQUIRE_FALSE(check.skipped);
    const double predicted = check.unbounded ? 1.0 : check.instability_limit;
    const double bisected = bisect_stable(scene, std::max(predicted, scene.run.dt));
    REQUIRE(bisected > 0.0);
    const double ratio = predicted / bisected;
    // Where the prediction is not tight, the guard must not refuse a step that works.
    std::string between = "-";
    if (ratio < 0.8) {
      const double h = std::sqrt(predicted * bisected);
      scene.run.dt = h;
      const services::StepGuard guard = services::guard_step(scene, false, services::kTrialWork);
      scene.run.dt = scene.authored_dt;
      const Verdict whole = run_at(scene, h);
      between = (guard.refusal ? "refused " : "runs ") + number(h) + " (" +
                (whole.stable ? whole.accuracy : "unstable") + ")";
      if (guard.refusal) {
        CHECK_FALSE((whole.stable && whole.accuracy == "accurate"));
        CHECK(guard.refusal->verified);
      }
    }
    CHECK(ratio <= 1.25);  // never refuses a step that the whole run shows stable

    const services::StepSuggestion rec = services::recommend_step(scene, check, 2.0 * services::kTrialWork);
    const Verdict at_rec = run_at(scene, rec.dt);

    services::StudyOptions options;
    options.scene = k.source;
    options.overrides = k.overrides;
    options.integrators = {scene.run.integrator};
    options.repeats = 1;
    options.bisection_precision = 0.03;
    const services::StudyResult study = services::run_study(options);
    CHECK_FALSE(study.recommendation.integrator.empty());
    REQUIRE(study.limits.size() == 1);
    const double largest_accurate = study.limits[0].accurate;
    const bool recommended = !study.recommendation.integrator.empty();
    const Verdict at_study = recommended ? run_at(scene, study.recommendation.dt) : Verdict{};

    std::printf("| %s | %.3g | %.3g | %.2f | %s | %.3g | %s | %.3g | %s | %.3g |\n",
                k.kind.c_str(), predicted, bisected, ratio, between.c_str(), rec.dt,
                at_rec.stable ? at_rec.accuracy.c_str() : "unstable", study.recommendation.dt,
                at_study.stable ? at_study.accuracy.c_str() : "unstable", largest_accurate);
    std::fflush(stdout);
    CHECK(at_rec.stable);
    CHECK(at_rec.accuracy == "accurate");
    CHECK(at_study.stable);
    CHECK(at_study.accuracy == "accurate");
    CHECK(study.recommendation.run_verdict == "accurate");
    if (largest_accurate > 0.0) {
      CHECK(rec.dt >= 0.6 * largest_accurate);
      CHECK(study.recommendation.dt >= 0.6 * largest_accurate);
    }
    CHECK(study.recommendation.dt <= 0.8 * bisected * 1.05);
  }
}
