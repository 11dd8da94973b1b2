// The bundled Simulation I scene, as the paper runs it (start at 1.01 R, T = 1e-4).
#include <catch2/catch.hpp>
#include <cstdio>

#include "scenario.hpp"

using stiction::testing::run_scenario;

TEST_CASE("sphere_roll: rolls at 5/7 v0 and stops slipping between 0.57 and 0.63 s",
          "[scenario][sphere]") {
  const auto run = run_scenario("sphere_roll");
  REQUIRE_FALSE(run.result.instability);
  CHECK(run.at("sphere.v.x", 2.0) == Approx(5.0 / 7.0 * 2.0).epsilon(1e-3));
  const double stick = run.stick_time("ground");
  std::printf("sphere_roll stick time at T = 1e-4 s: %.6f s\n", stick);
  CHECK(stick > 0.57);
  CHECK(stick < 0.63);
}

TEST_CASE("sphere_roll with mu = 0: the sphere never spins up", "[scenario][sphere]") {
  const auto run = run_scenario("sphere_roll", {"impedances.ground.mu=0.0", "simulation.duration=0.5"});
  REQUIRE_FALSE(run.result.instability);
  CHECK(std::abs(run.at("sphere.w.y", 0.5)) < 1e-12);
  CHECK(run.at("sphere.v.x", 0.5) == Approx(2.0).epsilon(1e-12));
  CHECK(run.stick_time("ground") < 0.0);
}
