// A point mass on a 20 degree slope: it slides at g (sin - mu cos) with mu = 0.2, and with
// mu = 0.5 it holds without drift (Kikuuwe friction keeps its anchor exactly).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "scenario.hpp"

using stiction::testing::run_scenario;

namespace {
const double kAngle = 20.0 * M_PI / 180.0;
// Position along the slope, downhill positive. The scenes' surface normal is
// (-sin 20, 0, cos 20), so gravity's tangential part points along -(cos 20, 0, sin 20).
double along(const stiction::testing::ScenarioRun& run, const std::string& body, double t) {
  return -(std::cos(kAngle) * run.at(body + ".p.x", t) + std::sin(kAngle) * run.at(body + ".p.z", t));
}
}  // namespace

TEST_CASE("slope_slide: accelerates at g (sin 20 - mu cos 20)", "[scenario][slope]") {
  const auto run = run_scenario("slope_slide", {"simulation.duration=2.0"});
  REQUIRE_FALSE(run.result.instability);
  const double g = 9.8, mu = 0.2;
  const double expected = g * (std::sin(kAngle) - mu * std::cos(kAngle));
  // Second difference of the position over [0.5, 1.5] s: a = 2 (s(t2) - 2 s(tm) + s(t1)) / dt^2.
  const double s1 = along(run, "block", 0.5), sm = along(run, "block", 1.0), s2 = along(run, "block", 1.5);
  const double a = (s2 - 2 * sm + s1) / (0.5 * 0.5);
  std::printf("slope_slide acceleration %.6f m/s^2 (expected %.6f)\n", a, expected);
  CHECK(a == Approx(expected).epsilon(5e-3));
}

TEST_CASE("slope_hold: no drift between 1 s and 100 s", "[scenario][slope]") {
  const auto run = run_scenario("slope_hold");
  REQUIRE_FALSE(run.result.instability);
  const double drift = std::abs(along(run, "block", 100.0) - along(run, "block", 1.0));
  std::printf("slope_hold drift between 1 s and 100 s: %.3e m\n", drift);
  CHECK(drift < 1e-9);
}
