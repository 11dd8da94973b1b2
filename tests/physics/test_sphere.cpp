// Simulation I against closed-form results: a sphere launched sliding at v0 on a surface of
// friction coefficient mu stops slipping at t = v0 / ((1 + M R^2 / J) mu g) and then rolls at
// v0 / (1 + J / (M R^2)) (angular momentum about the contact point is conserved).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "sphere_fixture.hpp"

using namespace stiction;
using testing::SphereCase;

namespace {

core::RunResult run(const SphereCase& c, double duration, double dt = 1e-4,
                    const std::string& integrator = "rk4") {
  auto net = testing::make_sphere(c);
  core::RunOptions options;
  options.integrator = integrator;
  options.dt = dt;
  options.duration = duration;
  return core::simulate(*net, options);
}

double closed_form_stick_time(const SphereCase& c) {
  const double k = c.inertia_factor;  // J = k M R^2
  return c.v0 / ((1.0 + 1.0 / k) * c.mu * c.g);
}

double final_speed(const core::RunResult& r) {
  const auto& tr = r.trajectory;
  return tr.at(tr.row_count() - 1, *tr.find("sphere.v.x"));
}

}  // namespace

TEST_CASE("paper start (1.01 R): rolling speed is 5/7 v0 and stick time near 0.58 s",
          "[sphere]") {
  SphereCase c;
  const auto r = run(c, 2.0);
  REQUIRE_FALSE(r.instability);
  const double v_end = final_speed(r);
  CHECK(v_end == Approx(5.0 / 7.0 * c.v0).epsilon(1e-3));
  const double t_stick = testing::first_stick_time(r);
  INFO("stick time at T = 1e-4: " << t_stick);
  CHECK(t_stick > 0.57);
  CHECK(t_stick < 0.63);
}

TEST_CASE("paper start: stick time converges as T is refined", "[sphere]") {
  SphereCase c;
  double previous = testing::first_stick_time(run(c, 0.8, 1e-4));
  double dt = 1e-4;
  double change = 1.0;
  for (int i = 0; i < 4 && change >= 1e-3; ++i) {
    dt /= 2;
    const double current = testing::first_stick_time(run(c, 0.8, dt));
    change = std::abs(current - previous) / current;
    std::printf("sphere_roll (1.01 R) stick time: T = %.3g s -> %.6f s (change %.2e)\n", dt,
                current, change);
    previous = current;
  }
  std::printf("sphere_roll (1.01 R) converged stick time: %.6f s\n", previous);
  CHECK(change < 1e-3);
  CHECK(previous > 0.57);
  CHECK(previous < 0.63);
}

TEST_CASE("resting start: stick time matches 2 v0 / (7 mu g) within 0.1%", "[sphere]") {
  struct Variant {
    double v0, mu, mass, radius;
  };
  const Variant variants[] = {
      {2.0, 0.1, 0.3, 0.2}, {1.0, 0.1, 0.3, 0.2}, {3.0, 0.3, 0.3, 0.2},
      {2.0, 0.2, 1.0, 0.2}, {2.0, 0.1, 0.3, 0.05}, {0.5, 0.5, 2.0, 0.5}};
  for (const auto& v : variants) {
    SphereCase c;
    c.v0 = v.v0;
    c.mu = v.mu;
    c.mass = v.mass;
    c.radius = v.radius;
    c.height = testing::resting_height(c);
    const double expected = closed_form_stick_time(c);
    const auto r = run(c, expected + 0.3);
    REQUIRE_FALSE(r.instability);
    const double t_stick = testing::first_stick_time(r);
    INFO("v0 " << v.v0 << " mu " << v.mu << " M " << v.mass << " R " << v.radius
               << ": stick " << t_stick << " expected " << expected);
    CHECK(t_stick == Approx(expected).epsilon(1e-3));
    CHECK(final_speed(r) == Approx(5.0 / 7.0 * c.v0).epsilon(1e-3));
  }
}

TEST_CASE("hollow sphere: stick at v0 / (2.5 mu g), rolls at 3/5 v0", "[sphere]") {
  SphereCase c;
  c.inertia_factor = 2.0 / 3.0;
  c.height = testing::resting_height(c);
  const double expected = c.v0 / (2.5 * c.mu * c.g);
  REQUIRE(closed_form_stick_time(c) == Approx(expected));
  const auto r = run(c, expected + 0.3);
  REQUIRE_FALSE(r.instability);
  CHECK(testing::first_stick_time(r) == Approx(expected).epsilon(1e-3));
  CHECK(final_speed(r) == Approx(0.6 * c.v0).epsilon(1e-3));
}

TEST_CASE("the sphere at rest on the surface stays there", "[sphere]") {
  SphereCase c;
  c.v0 = 0.0;
  c.height = testing::resting_height(c);
  const auto r = run(c, 1.0);
  const auto& tr = r.trajectory;
  const int last = tr.row_count() - 1;
  CHECK(std::abs(tr.at(last, *tr.find("sphere.p.x"))) < 1e-12);
  CHECK(tr.at(last, *tr.find("sphere.p.z")) == Approx(testing::resting_height(c)).epsilon(1e-9));
}
