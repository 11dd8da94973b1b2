// The pendulum with joint friction (amplitude falls by 2F/(m g l_c) per half swing, then it
// sticks inside the friction band) and the PD-controlled arm (overshoot of its closed-loop
// second-order system), on the bundled scenes and on generated ones.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include "sources_fixture.hpp"

using namespace stiction;
using testing::num;

namespace {

struct Swing {
  std::vector<double> amplitudes;  // |theta - hanging| at each turning point
  double final_offset = 0.0;       // theta - hanging at the end
  double final_rate = 0.0;
};

// Turning points: where omega changes sign (interpolated), while the joint still moves.
Swing swings(const testing::TextRun& run, const std::string& arm, double hanging) {
  Swing s;
  const auto theta = run.values(arm + ".theta.0"), omega = run.values(arm + ".omega.0");
  for (std::size_t i = 1; i < theta.size(); ++i) {
    if ((omega[i - 1] > 0.0) != (omega[i] > 0.0) &&
        std::abs(omega[i - 1]) + std::abs(omega[i]) > 1e-3) {
      const double f = omega[i - 1] / (omega[i - 1] - omega[i]);
      s.amplitudes.push_back(std::abs(theta[i - 1] + f * (theta[i] - theta[i - 1]) - hanging));
    }
  }
  s.final_offset = theta.back() - hanging;
  s.final_rate = omega.back();
  return s;
}

struct Pendulum {
  double mass, length, width, friction, start;
};

std::string pendulum_text(const Pendulum& p, const std::string& arm, double duration) {
  return "[simulation]\ndt = 1e-4\nduration = " + num(duration) + "\n[bodies." + arm +
         "]\ntype = \"planar_arm\"\naxis = [0.0, -1.0, 0.0]\nlinks = [{length = " + num(p.length) +
         ", mass = " + num(p.mass) + ", width = " + num(p.width) + "}]\nangles = [" +
         num(-std::numbers::pi / 2 + p.start) + "]\n[impedances." + arm +
         "_friction]\ntype = \"kikuuwe_friction\"\nbody = \"" + arm +
         "\"\njoint = 0\nstiffness = 5000.0\n"
         "damping = 1.0\nforce_limit = " +
         num(p.friction) + "\n";
}

void check_pendulum(const testing::TextRun& run, const std::string& arm, const Pendulum& p) {
  const double k = p.mass * 9.8 * p.length / 2;  // m g l_c
  const double step = 2 * p.friction / k;        // closed form, small angles
  const Swing s = swings(run, arm, -std::numbers::pi / 2);
  INFO("predicted loss per half swing " << step << " rad; turning points " << s.amplitudes.size());
  REQUIRE(s.amplitudes.size() >= 4);
  int checked = 0;
  for (std::size_t i = 1; i < s.amplitudes.size(); ++i) {
    const double a0 = s.amplitudes[i - 1], a1 = s.amplitudes[i];
    if (a0 > 0.25 || a1 < 1.5 * step) continue;  // small angles; not the last, partial swing
    INFO("half swing " << i << ": " << a0 << " -> " << a1);
    CHECK(a0 - a1 == Approx(step).epsilon(0.02));
    ++checked;
  }
  CHECK(checked >= 3);
  // At rest, inside the band where friction holds the weight: |m g l_c sin(offset)| <= F.
  INFO("final offset " << s.final_offset << " rad: m g l_c sin = " << k * std::sin(s.final_offset)
                       << " N m, F = " << p.friction << " N m");
  CHECK(std::abs(s.final_rate) < 1e-6);
  CHECK(std::abs(k * std::sin(s.final_offset)) <= p.friction);
}

// Step response of I theta'' + Kd theta' + Kp (theta - r) = 0 from rest at 0.
double overshoot_formula(double kp, double kd, double inertia) {
  const double zeta = kd / (2 * std::sqrt(kp * inertia));
  return std::exp(-std::numbers::pi * zeta / std::sqrt(1 - zeta * zeta));
}

double measured_overshoot(const testing::TextRun& run, const std::string& column, double start,
                          double target) {
  double peak = -1e9;
  for (double v : run.values(column)) peak = std::max(peak, v);
  return (peak - target) / (target - start);
}

}  // namespace

TEST_CASE("pendulum_friction: linear amplitude decay, then stuck inside the friction band") {
  testing::TextRun run{scene::load_scene("pendulum_friction"), {}};
  run.result = core::simulate(*run.scene.network, run.scene.run);
  REQUIRE_FALSE(run.result.instability);
  check_pendulum(run, "arm", {1.0, 0.5, 0.03, 0.02, 0.2});
  // The joint's events: a stick and a slip at every reversal, then the final stick, after
  // the last turning point (about 6.95 s) and for good.
  bool found = false;
  for (const auto& h : run.result.slip_events) {
    if (h.component != "joint_friction") continue;
    found = true;
    const auto& events = h.monitor.events();
    REQUIRE(events.size() >= 10);
    CHECK(events.back().kind == "stick");
    CHECK(events.back().time > 6.0);
    CHECK(events.back().time < 8.0);
  }
  CHECK(found);
}

TEST_CASE("pendulum_friction: generated pendulums, random mass, length and friction") {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    Pendulum p{0.3 + 2 * u(rng), 0.2 + 0.6 * u(rng), 0.02, 0.0, 0.2};
    // A loss of 0.01 .. 0.025 rad per half swing.
    p.friction = (0.005 + 0.0075 * u(rng)) * p.mass * 9.8 * p.length / 2;
    p.width = 0.05 * p.length;
    const double period =
        2 * std::numbers::pi * std::sqrt((p.length * p.length / 3) / (9.8 * p.length / 2));
    const std::string arm = testing::long_name("swing", trial);
    const auto run = testing::run_text(pendulum_text(p, arm, 12 * period));
    REQUIRE_FALSE(run.result.instability);
    check_pendulum(run, arm, p);
  }
}

TEST_CASE("pd_arm: the bundled PD arm overshoots as its closed loop predicts") {
  testing::TextRun run{scene::load_scene("pd_arm"), {}};
  run.result = core::simulate(*run.scene.network, run.scene.run);
  REQUIRE_FALSE(run.result.instability);
  const double inertia = 1.0 * (0.25 + 0.0004) / 12 + 1.0 * 0.0625;
  const double expected = overshoot_formula(20.0, 0.5, inertia);
  const double measured = measured_overshoot(run, "arm.theta.0", 0.0, 1.0);
  INFO("overshoot " << measured << ", formula " << expected);
  CHECK(measured == Approx(expected).epsilon(0.05));
  CHECK(measured ==
        Approx(expected).epsilon(1e-4));  // the exact gravity compensation makes it linear
  CHECK(run.values("arm.theta.0").back() == Approx(1.0).margin(1e-3));
}

TEST_CASE("pd_arm: generated PD arms, random gains, inertia and set point, among other bodies") {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    const double length = 0.2 + 0.5 * u(rng), mass = 0.2 + u(rng);
    const double inertia = mass * length * length / 3;
    const double kp = 5 + 40 * u(rng), zeta = 0.1 + 0.5 * u(rng);
    const double kd = 2 * zeta * std::sqrt(kp * inertia);
    const double target = 0.3 + u(rng), start = -0.2 * u(rng);
    const std::string arm = testing::long_name("robot", trial);
    // Distractors: other bodies before and after the arm, so the observed slice is not the first.
    std::string text = "gravity = [0.0, 0.0, 0.0]\n[simulation]\nduration = " +
                       num(8 / (zeta * std::sqrt(kp / inertia))) + "\n";
    for (int j = 0; j < 3; ++j) {
      text += "[bodies.ball" + std::to_string(j) +
              "]\ntype = \"point_mass\"\nmass = 1.0\nvelocity = [1.0, " + num(j) + ", 0.0]\n";
    }
    text += "[bodies." + arm + "]\ntype = \"planar_arm\"\nlinks = [{length = " + num(length) +
            ", mass = " + num(mass) + "}]\nangles = [" + num(start) + "]\n";
    text += "[bodies.tail]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"sphere\"\nradius = 0.1\n";
    text += "[impedances.pd]\ntype = \"torque_source\"\nbody = \"" + arm +
            "\"\njoint = 0\ntorque = \"" + num(kp) + "*(" + num(target) + " - " + arm +
            ".theta.0) - " + num(kd) + "*" + arm + ".omega.0\"\n";
    const auto run = testing::run_text(text);
    REQUIRE_FALSE(run.result.instability);
    const double expected = overshoot_formula(kp, kd, inertia);
    const double measured = measured_overshoot(run, arm + ".theta.0", start, target);
    INFO("trial " << trial << ": zeta " << zeta << ", overshoot " << measured << ", formula "
                  << expected);
    CHECK(measured == Approx(expected).epsilon(0.05));
    CHECK(run.values(arm + ".theta.0").back() == Approx(target).margin(2e-3 * (target - start)));
    CHECK(run.values("pd.tau").back() == Approx(0.0).margin(1e-2));
  }
}
