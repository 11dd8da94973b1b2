// force_source on point masses and rigid bodies (world and body frame, at a body point),
// its power in the energy monitor, and a spring-damper between two bodies.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "sources_fixture.hpp"

using namespace stiction;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using testing::num;

TEST_CASE("force_source: a constant world force on point masses, with gravity") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 3; ++trial) {
    const double m = 0.2 + std::abs(u(rng));
    const core::Vec3 f(u(rng), u(rng), u(rng)), v0(u(rng), u(rng), u(rng)), g(0.0, 0.0, -9.8);
    const std::string name = testing::long_name("puck", trial);
    std::string text = "[simulation]\nduration = 0.5\n[bodies." + name +
                       "]\ntype = \"point_mass\"\nmass = " + num(m) + "\nvelocity = [" +
                       num(v0.x()) + ", " + num(v0.y()) + ", " + num(v0.z()) + "]\n";
    // Several sources on one body add up: the force split in two, one with expressions of t.
    text += "[impedances.push_a]\ntype = \"force_source\"\nbody = \"" + name + "\"\nforce = [" +
            num(0.5 * f.x()) + ", \"" + num(0.5 * f.y()) + " + 0*t\", " + num(0.5 * f.z()) + "]\n";
    text += "[impedances.push_b]\ntype = \"force_source\"\nbody = \"" + name +
            "\"\nframe = \"world\"\nforce = [" + num(0.5 * f.x()) + ", " + num(0.5 * f.y()) +
            ", \"" + num(0.5 * f.z()) + "\"]\n";
    const auto run = testing::run_text(text);
    REQUIRE_FALSE(run.result.instability);
    const double t = 0.5;
    const core::Vec3 expected = v0 * t + 0.5 * (f / m + g) * t * t;
    for (int k = 0; k < 3; ++k) {
      const std::string axis = std::string(1, "xyz"[k]);
      CHECK(run.values(name + ".p." + axis).back() == Approx(expected[k]).margin(1e-12));
      CHECK(run.values("push_a.f." + axis).back() == Approx(0.5 * f[k]));
    }
  }
}

TEST_CASE("force_source: its work feeds the energy monitor, which stays quiet") {
  // No gravity, a strong push: the energy grows by orders of magnitude over its start, all
  // of it the source's work F . dx.
  const std::string text =
      "gravity = [0.0, 0.0, 0.0]\n[simulation]\nduration = 2.0\nenergy_growth_limit = 1e-6\n"
      "[bodies.b]\ntype = \"point_mass\"\nmass = 0.5\nvelocity = [0.01, 0.0, 0.0]\n"
      "[impedances.push]\ntype = \"force_source\"\nbody = \"b\"\nforce = [\"3*(1 + sin(5*t))\", 0, "
      "0]\n";
  const auto run = testing::run_text(text);
  REQUIRE_FALSE(run.result.instability);
  const double v = run.values("b.v.x").back();
  CHECK(0.5 * 0.5 * v * v > 1e4 * 0.5 * 0.5 * 0.01 * 0.01);
  CHECK(run.scene.network->has_sources());
  // The power the network reports is F . v.
  core::Vec x = run.scene.network->initial_state();
  CHECK(run.scene.network->source_power(0.0, x) == Approx(3.0 * 0.01));
}

TEST_CASE("force_source: a body-frame force at the centre turns with a spinning body") {
  // Spin w0 about z, a body-frame force F along body x: the world force rotates,
  // v(t) = F / (m w0) (sin w0 t, 1 - cos w0 t, 0), and it puts no torque on the body.
  const double m = 2.0, w0 = 3.0, F = 1.5;
  const std::string text =
      "gravity = [0.0, 0.0, 0.0]\n[simulation]\nduration = 1.0\n"
      "[bodies.spinner]\ntype = \"rigid_body\"\nmass = 2.0\nshape = \"box\"\nsize = [0.3, 0.2, "
      "0.1]\n"
      "angular_velocity = [0.0, 0.0, 3.0]\n"
      "[impedances.thruster]\ntype = \"force_source\"\nbody = \"spinner\"\nframe = \"body\"\nforce "
      "= [1.5, 0, 0]\n";
  const auto run = testing::run_text(text);
  REQUIRE_FALSE(run.result.instability);
  const double t = 1.0;
  CHECK(run.values("spinner.v.x").back() == Approx(F / (m * w0) * std::sin(w0 * t)).margin(1e-9));
  CHECK(run.values("spinner.v.y").back() ==
        Approx(F / (m * w0) * (1 - std::cos(w0 * t))).margin(1e-9));
  CHECK(run.values("spinner.w.z").back() == Approx(w0).margin(1e-12));
  // The signal is the force as given (body frame).
  CHECK(run.values("thruster.f.x").back() == Approx(F));
}

TEST_CASE("force_source: a force at a body point puts its moment on the body") {
  // A world force F z at the body point (a, 0, 0) of a box at rest: w_dot_y = -a F / Jyy at
  // the start, and the centre accelerates at F / m. Short run: the angle stays small.
  const double m = 1.2, a = 0.15, F = 0.8;
  const double lx = 0.4, ly = 0.1, lz = 0.05;
  const double jyy = m * (lx * lx + lz * lz) / 12.0;
  const std::string text =
      "gravity = [0.0, 0.0, 0.0]\n[simulation]\nduration = 0.01\n"
      "[bodies.plank]\ntype = \"rigid_body\"\nmass = " +
      num(m) + "\nshape = \"box\"\nsize = [" + num(lx) + ", " + num(ly) + ", " + num(lz) +
      "]\n"
      "[impedances.lift]\ntype = \"force_source\"\nbody = \"plank\"\npoint = [" +
      num(a) + ", 0.0, 0.0]\nforce = [0, 0, " + num(F) + "]\n";
  const auto run = testing::run_text(text);
  const double t = 0.01;
  CHECK(run.values("plank.w.y").back() == Approx(-a * F / jyy * t).epsilon(1e-3));
  CHECK(run.values("plank.v.z").back() == Approx(F / m * t).epsilon(1e-3));
}

TEST_CASE("spring_damper between two bodies: reduced-mass oscillation, momentum kept") {
  // Point wiring with `other`: two masses joined by a spring k (with damping c) along x.
  // The separation obeys mu s'' + c s' + k s = 0 with mu = m1 m2 / (m1 + m2); the centre of
  // mass does not move.
  const double m1 = 0.4, m2 = 1.1, k = 90.0, c = 0.3, s0 = 0.05;
  const double mu = m1 * m2 / (m1 + m2);
  const double wn = std::sqrt(k / mu), zeta = c / (2 * std::sqrt(k * mu)),
               wd = wn * std::sqrt(1 - zeta * zeta);
  const std::string text =
      "gravity = [0.0, 0.0, 0.0]\n[simulation]\nduration = 1.0\n"
      "[bodies.left_body]\ntype = \"point_mass\"\nmass = " +
      num(m1) + "\nposition = [" + num(s0) +
      ", 0.0, 0.0]\n"
      "[bodies.right_body]\ntype = \"rigid_body\"\nmass = " +
      num(m2) +
      "\nshape = \"sphere\"\nradius = 0.05\n"
      "position = [0.0, 0.0, 0.0]\n"
      "[impedances.link]\ntype = \"spring_damper\"\nbody = \"left_body\"\nother = \"right_body\"\n"
      "stiffness = " +
      num(k) + "\ndamping = " + num(c) + "\n";
  const auto run = testing::run_text(text);
  REQUIRE_FALSE(run.result.instability);
  const auto t = run.times();
  const auto x1 = run.values("left_body.p.x"), x2 = run.values("right_body.p.x");
  double worst = 0.0, drift = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double s =
        s0 * std::exp(-zeta * wn * t[i]) *
        (std::cos(wd * t[i]) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t[i]));
    worst = std::max(worst, std::abs((x1[i] - x2[i]) - s));
    drift = std::max(drift, std::abs((m1 * x1[i] + m2 * x2[i]) / (m1 + m2) - m1 * s0 / (m1 + m2)));
  }
  CHECK(worst < 1e-9);
  CHECK(drift < 1e-12);
}

TEST_CASE("force_source: bad values are errors at FILE:LINE:COL") {
  const std::string head =
      "[bodies.b]\ntype = \"rigid_body\"\nmass = 1\nshape = \"sphere\"\nradius = 0.1\n"
      "[impedances.push]\ntype = \"force_source\"\nbody = \"b\"\n";
  CHECK_THAT(
      testing::load_error(head + "force = [1, 2, 3]\nframe = \"sideways\"\n"),
      StartsWith("gen.toml:10:9: error: impedances.push.frame: expected \"world\" or \"body\""));
  CHECK_THAT(testing::load_error(head + "force = [1, 2]\n"),
             StartsWith("gen.toml:9:9: error: impedances.push.force: expected an array of 3"));
  CHECK_THAT(testing::load_error(head + "force = 3\n"),
             StartsWith("gen.toml:9:9: error: impedances.push.force: expected an array of 3"));
  CHECK_THAT(
      testing::load_error(head + "force = [1, true, 3]\n"),
      StartsWith("gen.toml:9:9: error: impedances.push.force: expected a number or an expression"));
  CHECK_THAT(testing::load_error(head + "force = [1, 2, \"3 *\"]\n"), StartsWith("gen.toml:9:"));
  CHECK_THAT(testing::load_error(head),
             StartsWith("gen.toml:6:1: error: impedances.push.force: missing"));
  CHECK_THAT(testing::load_error(head + "force = [1, 2, 3]\npoint = [1, 2]\n"),
             StartsWith("gen.toml:10:9: error: impedances.push.point"));
  CHECK_THAT(testing::load_error(head + "force = [1, 2, 3]\njoint = 0\n"),
             StartsWith("gen.toml:10:1: error: unknown key 'impedances.push.joint'"));
  // A force acts on a point mass or rigid body, not on an arm.
  CHECK_THAT(
      testing::load_error(
          "[bodies.arm]\ntype = \"planar_arm\"\nlinks = [{length = 0.2, mass = 0.2}]\n"
          "[impedances.push]\ntype = \"force_source\"\nbody = \"arm\"\nforce = [1, 2, 3]\n"),
      Contains("impedances.push.body: 'arm' is a planar_arm, not a point_mass or rigid_body"));
}

TEST_CASE("torque_source: a feedback torque on a rigid body (viscous spin-down)") {
  // torque = -c w_z about the body's z axis: w_z(t) = w0 exp(-c t / J), J = 2/5 m r^2.
  const double m = 1.0, r = 0.1, c = 0.004, w0 = 5.0;
  const double j = 0.4 * m * r * r;
  const std::string text =
      "gravity = [0.0, 0.0, 0.0]\n[simulation]\nduration = 1.0\n"
      "[bodies.top]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"sphere\"\nradius = 0.1\n"
      "angular_velocity = [0.0, 0.0, 5.0]\n"
      "[impedances.brake]\ntype = \"torque_source\"\nbody = \"top\"\ntorque = \"-" +
      num(c) + "*top.w.z\"\n";
  const auto run = testing::run_text(text);
  REQUIRE_FALSE(run.result.instability);
  CHECK(run.values("top.w.z").back() == Approx(w0 * std::exp(-c / j)).epsilon(1e-9));
  CHECK(run.values("brake.tau").back() == Approx(-c * w0 * std::exp(-c / j)).epsilon(1e-9));
}

TEST_CASE("spring_damper with a free length: acts along the line, any direction") {
  // Two bodies on a line of random direction, a spring of free length L stretched by s0:
  // the distance oscillates about L as mu s'' + c s' + k s = 0, and stays on the line.
  std::mt19937 rng(4);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const core::Vec3 n = core::Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
  const double m1 = 0.6, m2 = 0.9, k = 50.0, c = 0.2, length = 0.4, s0 = 0.03;
  const double mu = m1 * m2 / (m1 + m2);
  const double wn = std::sqrt(k / mu), zeta = c / (2 * std::sqrt(k * mu)),
               wd = wn * std::sqrt(1 - zeta * zeta);
  const core::Vec3 p1 = (length + s0) * n;
  std::string text =
      "gravity = [0.0, 0.0, 0.0]\n[simulation]\nduration = 1.0\n[bodies.a]\ntype = "
      "\"point_mass\"\nmass = ";
  text +=
      num(m1) + "\nposition = [" + num(p1.x()) + ", " + num(p1.y()) + ", " + num(p1.z()) + "]\n";
  text += "[bodies.b]\ntype = \"point_mass\"\nmass = " + num(m2) + "\n";
  text += "[impedances.coil]\ntype = \"spring_damper\"\nbody = \"a\"\nother = \"b\"\nstiffness = " +
          num(k) + "\ndamping = " + num(c) + "\nlength = " + num(length) + "\n";
  const auto run = testing::run_text(text);
  REQUIRE_FALSE(run.result.instability);
  const auto t = run.times();
  const auto distance = run.values("coil.length");
  double worst = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double s =
        s0 * std::exp(-zeta * wn * t[i]) *
        (std::cos(wd * t[i]) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t[i]));
    worst = std::max(worst, std::abs(distance[i] - (length + s)));
  }
  CHECK(worst < 1e-9);
  // The separation stays along n.
  const core::Vec3 d(run.values("a.p.x").back() - run.values("b.p.x").back(),
                     run.values("a.p.y").back() - run.values("b.p.y").back(),
                     run.values("a.p.z").back() - run.values("b.p.z").back());
  CHECK(d.cross(n).norm() < 1e-12);
  // The force on a (the moving side) pulls it back while stretched: at t = 0, -k s0 n.
  CHECK(run.values("coil.f.x").front() == Approx(-k * s0 * n.x()));

  const std::string head =
      "[bodies.a]\ntype = \"point_mass\"\nmass = 1\n[impedances.s]\ntype = \"spring_damper\"\n"
      "body = \"a\"\n";
  CHECK_THAT(testing::load_error(head + "length = -1\n"),
             StartsWith("gen.toml:7:10: error: impedances.s.length: must be >= 0"));
  CHECK_THAT(testing::load_error(head + "length = 1\nrest = [0, 0, 0]\n"),
             StartsWith("gen.toml:7:10: error: impedances.s.length: give either"));
  CHECK_THAT(
      testing::load_error(
          "[bodies.arm]\ntype = \"planar_arm\"\nlinks = [{length = 0.2, mass = 0.2}]\n"
          "[impedances.s]\ntype = \"spring_damper\"\nbody = \"arm\"\njoint = 0\nlength = 1\n"),
      StartsWith("gen.toml:8:10: error: impedances.s.length: a free length needs point wiring"));
}
