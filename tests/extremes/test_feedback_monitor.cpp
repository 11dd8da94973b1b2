// The run's monitor on feedback sources (core/feedback_monitor.hpp): a PD controller written as
// an expression of the arm's state is a spring and a damper in disguise, and its work must not
// pay for a numerical instability. One-link arms under gravity with random gains, damping
// ratios, sizes, masses and set points (scenes generated here), for every fixed-step
// integrator: at 4x the largest stable step that `check` predicts the run must be stopped as
// unstable, at 0.8x it must run to its end, and at the scene's own step it must settle at the
// set point.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "core/stability.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

std::string num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

struct PdArm {
  std::string text;
  double set_point, omega_n, zeta;
};

// tau = Kp (set - theta) - Kd omega + m g l_c cos(theta), in a vertical plane.
PdArm pd_arm(std::mt19937& rng, int index) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double length = 0.2 + 0.6 * u(rng), mass = 0.3 + 2.7 * u(rng), width = 0.02;
  const double inertia = mass * (length * length + width * width) / 12.0 +
                         mass * length * length / 4.0;  // about the joint
  const double kp = 5.0 + 195.0 * u(rng);
  const double zeta = 0.02 + 1.5 * u(rng);
  const double kd = 2.0 * zeta * std::sqrt(kp * inertia);
  const double set_point = -0.5 + 2.0 * u(rng);
  const std::string arm = "arm_of_generated_pd_controller_" + std::to_string(index);
  const std::string text =
      "name = \"pd_" + std::to_string(index) + "\"\n[simulation]\nintegrator = \"rk4\"\n" +
      "dt = 1e-4\nduration = 2.0\noutput_rate = 200.0\n[bodies." + arm +
      "]\ntype = \"planar_arm\"\naxis = [0.0, -1.0, 0.0]\nlinks = [{ length = " + num(length) +
      ", width = " + num(width) + ", mass = " + num(mass) + " }]\n[impedances.controller]\n" +
      "type = \"torque_source\"\nbody = \"" + arm + "\"\njoint = 0\ntorque = \"" + num(kp) + "*(" +
      num(set_point) + " - " + arm + ".theta.0) - " + num(kd) + "*" + arm + ".omega.0 + " +
      num(mass * 9.8 * length / 2.0) + "*cos(" + arm + ".theta.0)\"\n";
  return {text, set_point, std::sqrt(kp / inertia), zeta};
}

scene::Scene build(const std::string& text) {
  return scene::build_scene(toml::parse(text, std::string_view("generated_pd_arm.toml")),
                            "generated_pd_arm.toml");
}

}  // namespace

TEST_CASE("feedback monitor: PD arms with random gains, unstable at 4x the predicted step only") {
  std::mt19937 rng(20261130);
  int flagged = 0, runs = 0;
  for (int index = 0; index < 8; ++index) {
    const PdArm arm = pd_arm(rng, index);
    INFO(arm.text);
    scene::Scene scene = build(arm.text);
    core::Network& network = *scene.network;
    const core::RunResult own = core::simulate(network, scene.run);
    REQUIRE_FALSE(own.instability);
    // Gravity is compensated exactly: I theta'' + Kd theta' + Kp (theta - set) = 0 from rest
    // at 0, whose distance to the set point stays within |set| exp(-zeta omega_n t) /
    // sqrt(1 - zeta^2) (within |set| when overdamped).
    const auto theta = own.trajectory.column(1);
    const double t_end = own.trajectory.column(0).back();
    const double envelope = arm.zeta < 1.0 ? std::exp(-arm.zeta * arm.omega_n * t_end) /
                                                 std::sqrt(1.0 - arm.zeta * arm.zeta)
                                           : 1.0;
    CHECK(std::abs(theta.back() - arm.set_point) <= std::abs(arm.set_point) * envelope + 1e-6);

    const auto states = core::sample_states(network, scene.run, 10);
    for (const char* integrator : {"euler", "symplectic_euler", "heun", "rk4"}) {
      const core::StepLimit limit = core::predict_step_limit(network, integrator, states);
      if (limit.unbounded || !(limit.max_step > 0.0)) continue;
      core::RunOptions options = scene.run;
      options.integrator = integrator;
      // At least a few checks of the monitor (every 8 steps) at the large step.
      options.duration = std::max(scene.run.duration, 40.0 * limit.max_step);
      options.dt = 4.0 * limit.max_step;
      const core::RunResult bad = core::simulate(network, options);
      INFO(integrator << ": predicted limit " << limit.max_step << " s");
      CHECK(bad.instability);
      if (bad.instability) {
        ++flagged;
        CHECK_THAT(bad.instability->reason, Catch::Matchers::Contains("step map"));
      }
      options.dt = 0.8 * limit.max_step;
      const core::RunResult good = core::simulate(network, options);
      const std::string why =
          good.instability
              ? good.instability->reason + " at t = " + std::to_string(good.instability->time)
              : "";
      INFO("at 0.8x: " << why);
      CHECK_FALSE(good.instability);
      ++runs;
    }
  }
  WARN(flagged << " of " << runs << " runs at 4x the predicted step flagged unstable");
  CHECK(runs >= 28);
}
