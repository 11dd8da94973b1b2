// The step guard and the step it suggests, on every bundled scene and every fixed-step
// integrator (issue 26):
// - a run at 4x the largest stable step that `check` predicts (over the whole scene) exits 3
//   with a suggested step, refused before anything is simulated (no output directory, at
//   least once per scene) or stopped by the run's own monitors, or, over the shortened
//   duration of the test, runs clean;
// - that step lies below the step where stuck friction chatters, its message says a trial
//   confirmed it against a run at half the step, and a run at it exits 0 with the verdict ok;
// - with --force-step the refused step runs, and the run's own monitors still stop what
//   goes unstable (exit 3) or the summary's step_check says it was forced;
// - check's recommended step for the scene's integrator lies below both limits and was
//   confirmed.
// The scenes run for at most 1.5 s of simulated time (--duration) to keep the suite fast.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "ci_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

nlohmann::json read_json(const fs::path& path) { return nlohmann::json::parse(read_text(path)); }

// The smaller of the two predicted limits of an integrator in `check --json`.
double chatter_or_unstable(const nlohmann::json& limit) {
  const double unstable = limit["unstable_above"].get<double>();
  return limit["chatters_above"].is_null()
             ? unstable
             : std::min(unstable, limit["chatters_above"].get<double>());
}

void guarded_steps(const std::string& scene) {
  const fs::path dir = scratch_dir("stiction_test_ci_suggest_", scene);
  const SplitOutcome check = run_split({"check", scene, "--json"}, dir);
  REQUIRE(check.code == 0);
  const nlohmann::json report = nlohmann::json::parse(check.out);
  const nlohmann::json limits = report["step_limits"];
  const std::string own = report["simulation"]["integrator"];
  if (limits.contains(own) && !limits[own]["unstable_above"].is_null()) {
    INFO(scene << " check recommends for " << own << ": " << limits[own]["recommendation"]);
    CHECK(limits[own]["recommended_confirmed"].get<bool>());
    // Below the predicted limits, or above them only where trials at the larger step
    // confirmed it (the prediction is linear and its chatter limit conservative; issue 35):
    // then `run` at that step is not refused and is accurate.
    const double recommended = limits[own]["recommended_step"].get<double>();
    if (recommended >= chatter_or_unstable(limits[own])) {
      CHECK_THAT(limits[own]["recommendation"].get<std::string>(),
                 Contains("while trials at the larger step confirmed it"));
      // Over the scene's own duration, as check's trials judged it (final values at another
      // time are other quantities).
      char exact[32];  // the step as check gives it (std::to_string keeps 6 decimals)
      std::snprintf(exact, sizeof exact, "%.17g", recommended);
      const SplitOutcome at = run_split({"run", scene, "--dt", exact,
                                         "--no-video", "--no-plots", "--quiet", "--accuracy",
                                         "on", "--out", "rec"},
                                        dir);
      INFO(at.err);
      CHECK(at.code == 0);
      if (at.code == 0) {
        const nlohmann::json s = read_json(dir / "rec" / "summary.json");
        CHECK(s["step_check"]["verdict"] == "ok");
        CHECK(s["accuracy"]["verdict"] == "accurate");
      }
      fs::remove_all(dir / "rec");
    }
  }
  const double duration = std::min(1.5, report["simulation"]["duration"].get<double>());
  const std::string dur = std::to_string(duration);
  bool forced = false;
  int refusals = 0, limited = 0;
  for (const char* integrator : {"euler", "symplectic_euler", "heun", "rk4"}) {
    const nlohmann::json& l = limits[integrator];
    if (l["unstable_above"].is_null()) continue;  // no limit up to 1 s
    const double too_large = 4.0 * l["unstable_above"].get<double>();
    // A step longer than the run is refused as input (exit 2, issue 25): nothing to suggest.
    if (too_large > duration) continue;
    ++limited;
    const std::vector<std::string> at_too_large{
        "run",        scene, "--integrator", integrator,   "--dt",    std::to_string(too_large),
        "--duration", dur,   "--no-video",   "--no-plots", "--quiet", "--out",
        "bad"};
    const SplitOutcome bad = run_split(at_too_large, dir);
    INFO(scene << " " << integrator << " at dt " << too_large << ": " << bad.err);
    REQUIRE((bad.code == 3 || bad.code == 0));
    if (bad.code == 0) {  // over this shorter duration both the guard and the run are fine
      fs::remove_all(dir / "bad");
      continue;
    }
    // Refused before simulating, or (the prediction is a guard, not a proof: its pilot
    // samples at most 48 states) stopped by the run's own monitors.
    const bool refused = bad.err.find("nothing was simulated") != std::string::npos;
    if (refused) {
      ++refusals;
      CHECK_THAT(bad.err, Contains("predicted instability limit"));
      CHECK_FALSE(fs::exists(dir / "bad"));
    } else {
      CHECK_THAT(bad.err, Contains("numerical instability at t = "));
      fs::remove_all(dir / "bad");
    }
    std::smatch m;
    REQUIRE(std::regex_search(bad.err, m, std::regex("--dt ([0-9.eE+-]+)")));
    const std::string suggested = m[1].str();
    // rk4 and the scene's own integrator must find a confirmed step, judged as `run` judges
    // a run (docs/accuracy.md), unless what fails does not converge with the step at all
    // (sphere_roll's bounce: its first stick and final vertical speed follow the bounce
    // phase at every step), which the message says; a first-order method may need more
    // halvings than the trials' budget allows, and then says so.
    const bool confirmed =
        bad.err.find("was accurate against a run at half the step") != std::string::npos;
    const bool not_converging =
        bad.err.find("error does not shrink with the step") != std::string::npos;
    if ((std::string(integrator) == "rk4" || integrator == own) && !not_converging) {
      CHECK(confirmed);
    } else if (!confirmed) {
      CHECK_THAT(bad.err, Contains("not confirmed"));
      CHECK_THAT(bad.err, Contains("a smaller step to try: --dt"));
      continue;
    }
    const SplitOutcome good =
        run_split({"run", scene, "--integrator", integrator, "--dt", suggested, "--duration", dur,
                   "--no-video", "--no-plots", "--quiet", "--out", "good"},
                  dir);
    INFO("suggested --dt " << suggested << ": " << good.err);
    CHECK(good.code == 0);
    // Below the chatter limit of the run's own check (its duration, its pilot).
    const nlohmann::json summary = read_json(dir / "good" / "summary.json");
    CHECK(summary["step_check"]["verdict"] == "ok");
    CHECK(std::stod(suggested) < summary["step_check"]["chatter_limit"].get<double>());
    if (!forced && refused) {  // once per scene: the refused step, forced
      forced = true;
      std::vector<std::string> force = at_too_large;
      force.push_back("--force-step");
      const SplitOutcome f = run_split(force, dir);
      INFO("forced: " << f.err);
      REQUIRE((f.code == 3 || f.code == 0));
      const nlohmann::json s = read_json(dir / "bad" / "summary.json");
      CHECK(s["step_check"]["verdict"] == "unstable");
      CHECK(s["step_check"]["forced"] == true);
      CHECK((f.code == 3) == (s["status"] == "unstable"));
      fs::remove_all(dir / "bad");
    }
  }
  WARN(scene << ": " << refusals << " of " << limited << " steps at 4x the limit refused");
  CHECK(refusals >= 1);
}

}  // namespace

TEST_CASE("suggested step: sphere_roll") { guarded_steps("sphere_roll"); }
TEST_CASE("suggested step: slope_hold") { guarded_steps("slope_hold"); }
TEST_CASE("suggested step: slope_slide") { guarded_steps("slope_slide"); }
TEST_CASE("suggested step: two_link") { guarded_steps("two_link"); }
TEST_CASE("suggested step: two_link_dahl") { guarded_steps("two_link_dahl"); }
TEST_CASE("suggested step: two_link_lugre") { guarded_steps("two_link_lugre"); }
TEST_CASE("suggested step: two_link_penalty") { guarded_steps("two_link_penalty"); }
TEST_CASE("suggested step: roll_to_slip") { guarded_steps("roll_to_slip"); }
TEST_CASE("suggested step: roll_to_slip_hollow") { guarded_steps("roll_to_slip_hollow"); }
TEST_CASE("suggested step: box_slope") { guarded_steps("box_slope"); }
TEST_CASE("suggested step: box_slope_hold") { guarded_steps("box_slope_hold"); }
TEST_CASE("suggested step: belt_oscillator") { guarded_steps("belt_oscillator"); }
TEST_CASE("suggested step: tilting_plane") { guarded_steps("tilting_plane"); }
TEST_CASE("suggested step: pendulum_friction") { guarded_steps("pendulum_friction"); }
TEST_CASE("suggested step: pd_arm") { guarded_steps("pd_arm"); }
