// planar_arm under gravity: the joint axis `axis` sets the plane of motion; gravity's part in
// that plane drives the arm, and its potential energy is part of the arm's energy.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include "components/admittance/planar_arm.hpp"
#include "sources_fixture.hpp"

using namespace stiction;
using testing::num;

namespace {

std::string vec(const core::Vec3& v) {
  std::string s = "[";  // appended piece by piece: GCC 12 warns (-Wrestrict) on "[" + string
  s += num(v.x());
  s += ", ";
  s += num(v.y());
  s += ", ";
  s += num(v.z());
  s += "]";
  return s;
}

}  // namespace

TEST_CASE("arm gravity: small swings have the compound pendulum's period, for any axis") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double g = 9.8;
  for (int trial = 0; trial < 4; ++trial) {
    // A random axis, tilted from horizontal by up to 60 degrees: gravity in the plane is
    // g cos(tilt).
    const double heading = 2 * std::numbers::pi * u(rng), tilt = (trial == 0 ? 0.0 : 1.0) * u(rng);
    const core::Vec3 axis(std::cos(heading) * std::cos(tilt), std::sin(heading) * std::cos(tilt),
                          std::sin(tilt));
    const double length = 0.2 + u(rng), mass = 0.1 + u(rng), width = 0.05 * u(rng);
    const double com = length * (0.3 + 0.6 * u(rng));
    core::Vec3 e1, e2;
    components::arm_plane(axis, e1, e2);
    const double g1 = -g * e1.z(), g2 = -g * e2.z();
    const double g_plane = std::hypot(g1, g2);
    REQUIRE(g_plane == Approx(g * std::cos(tilt)));
    const double hanging = std::atan2(g2, g1);
    const double inertia = mass * (length * length + width * width) / 12.0 +
                           mass * (com - length / 2) * (com - length / 2);
    const double joint_inertia = inertia + mass * com * com;
    const double period = 2 * std::numbers::pi * std::sqrt(joint_inertia / (mass * g_plane * com));
    const double amplitude = 0.005;
    const std::string arm = testing::long_name("pendulum", trial);
    const std::string text =
        "[simulation]\ndt = 2e-4\nduration = " + num(3.2 * period) +
        "\noutput_rate = 5000.0\n[bodies." + arm + "]\ntype = \"planar_arm\"\naxis = " + vec(axis) +
        "\nbase = [0.3, -0.2, 1.0]\nlinks = [{length = " + num(length) + ", mass = " + num(mass) +
        ", width = " + num(width) + ", com = " + num(com) + ", inertia = " + num(inertia) +
        "}]\nangles = [" + num(hanging + amplitude) + "]\n";
    const auto run = testing::run_text(text);
    REQUIRE_FALSE(run.result.instability);
    const auto t = run.times();
    const auto theta = run.values(arm + ".theta.0");
    // Upward zero crossings of theta - hanging, interpolated.
    std::vector<double> crossings;
    for (std::size_t i = 1; i < t.size(); ++i) {
      const double a = theta[i - 1] - hanging, b = theta[i] - hanging;
      if (a < 0.0 && b >= 0.0) crossings.push_back(t[i - 1] + (t[i] - t[i - 1]) * a / (a - b));
    }
    INFO("trial " << trial << ": axis " << vec(axis) << ", expected period " << period);
    REQUIRE(crossings.size() >= 2);
    CHECK((crossings.back() - crossings.front()) / double(crossings.size() - 1) ==
          Approx(period).epsilon(1e-4));
    // It swings about the hanging angle with the amplitude it was given.
    double top = -1e9;
    for (double v : theta) top = std::max(top, v - hanging);
    CHECK(top == Approx(amplitude).epsilon(1e-3));
  }
}

TEST_CASE("arm gravity: a three-link arm in a tilted plane keeps kinetic + potential energy") {
  const core::Vec3 axis = core::Vec3(0.3, -1.0, 0.4).normalized();
  const std::string text =
      "[simulation]\ndt = 1e-4\nduration = 2.0\noutput_rate = 100.0\n[bodies.chain]\ntype = "
      "\"planar_arm\"\n"
      "axis = " +
      vec(axis) +
      "\nbase = [0.0, 0.0, 2.0]\n"
      "links = [{length = 0.4, mass = 0.5}, {length = 0.3, mass = 0.4}, {length = 0.25, mass = "
      "0.3}]\n"
      "angles = [0.3, 0.8, -0.5]\nrates = [1.0, 0.0, -2.0]\n";
  const auto run = testing::run_text(text);
  REQUIRE_FALSE(run.result.instability);
  const auto& arm = *run.scene.network->admittances().front();
  core::Vec x(6);
  double e0 = 0.0, kinetic_min = 1e9, kinetic_max = 0.0, worst = 0.0;
  const auto* planar = dynamic_cast<const components::PlanarArm*>(&arm);
  REQUIRE(planar != nullptr);
  for (int row = 0; row < run.result.trajectory.row_count(); ++row) {
    for (int k = 0; k < 3; ++k) {
      x[k] = run.result.trajectory.at(
          row, *run.result.trajectory.find("chain.theta." + std::to_string(k)));
      x[3 + k] = run.result.trajectory.at(
          row, *run.result.trajectory.find("chain.omega." + std::to_string(k)));
    }
    const double e = arm.energy(x);
    core::Vec still = x;
    still.tail(3).setZero();
    const double kinetic = e - arm.energy(still);
    if (row == 0) e0 = e;
    worst = std::max(worst, std::abs(e - e0));
    kinetic_min = std::min(kinetic_min, kinetic);
    kinetic_max = std::max(kinetic_max, kinetic);
  }
  INFO("energy " << e0 << " J, kinetic " << kinetic_min << " .. " << kinetic_max << " J, drift "
                 << worst);
  CHECK(kinetic_max - kinetic_min > 1.0);             // gravity does real work on the arm...
  CHECK(worst < 1e-6 * (kinetic_max - kinetic_min));  // ...and the potential energy accounts for it
}

TEST_CASE("arm gravity: along the joint axis gravity does nothing, across it the arm falls") {
  // Default axis (vertical) and gravity along z: the arm stays where it is.
  const auto still = testing::run_text(
      "[simulation]\nduration = 0.5\n[bodies.arm]\ntype = \"planar_arm\"\n"
      "links = [{length = 0.2, mass = 0.2}, {length = 0.2, mass = 0.2}]\nangles = [0.4, 0.9]\n");
  CHECK(still.values("arm.theta.0").back() == 0.4);
  CHECK(still.values("arm.omega.1").back() == 0.0);
  // Gravity along -x with the vertical axis (formerly refused): from theta = pi/2 the link
  // starts to fall towards -x, i.e. theta grows at first.
  const auto falls = testing::run_text(
      "gravity = [-9.8, 0.0, 0.0]\n[simulation]\nduration = 0.05\n[bodies.arm]\ntype = "
      "\"planar_arm\"\n"
      "links = [{length = 0.2, mass = 0.2}]\nangles = [1.5707963267948966]\n");
  const double alpha = 9.8 * 0.1 * 0.2 / (0.2 * 0.04 / 12.0 + 0.2 * 0.01);  // m g l_c / I_joint
  CHECK(falls.values("arm.omega.0").back() == Approx(alpha * 0.05).epsilon(2e-3));
}

TEST_CASE("arm gravity: a bad axis is an error at its value") {
  const std::string head =
      "[bodies.arm]\ntype = \"planar_arm\"\nlinks = [{length = 0.2, mass = 0.2}]\n";
  using Catch::Matchers::StartsWith;
  CHECK_THAT(testing::load_error(head + "axis = [0, 0, 0]\n"),
             StartsWith("gen.toml:4:8: error: bodies.arm.axis: must be a non-zero vector"));
  CHECK_THAT(testing::load_error(head + "axis = [0, 1]\n"),
             StartsWith("gen.toml:4:8: error: bodies.arm.axis"));
  CHECK_THAT(testing::load_error(head + "axis = \"up\"\n"),
             StartsWith("gen.toml:4:8: error: bodies.arm.axis"));
}
