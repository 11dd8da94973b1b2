// scenes/roll_to_slip*.toml: a sphere at rest on the floor under a torque ramp tau = k t
// rolls, then its contact slips at t* = mu M g R (1 + J / (M R^2)) / k (solid: 7 mu M g R /
// (5 k), hollow: 5 mu M g R / (3 k)). The slip onset must be within 0.5% of t*, for the
// bundled solid and hollow scenes and for other ramps and friction set with overrides.
#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

#include "core/simulation.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

void check_onset(const std::string& scene_name, double inertia_factor, double k, double mu,
                 const std::vector<std::string>& overrides) {
  scene::Scene s = scene::load_scene(scene_name, overrides);
  const core::RunResult r = core::simulate(*s.network, s.run);
  REQUIRE_FALSE(r.instability);
  const double M = 0.3, R = 0.2, g = 9.8;
  const double expected = mu * M * g * R * (1.0 + inertia_factor) / k;
  const core::SlipMonitor* ground = nullptr;
  for (const auto& h : r.slip_events) {
    if (h.component == "ground") ground = &h.monitor;
  }
  REQUIRE(ground != nullptr);
  std::printf("%s k %g mu %g: first slip %.6f s, t* %.6f s (%+.2e); events", scene_name.c_str(), k,
              mu, ground->first_slip(), expected, ground->first_slip() / expected - 1.0);
  for (const auto& e : ground->events()) std::printf(" %s %.6f", e.kind.c_str(), e.time);
  std::printf("\n");
  INFO(scene_name << " k " << k << " mu " << mu);
  CHECK(ground->initial_state() == "stick");
  REQUIRE(ground->events().size() >= 1);
  CHECK(ground->events().front().kind == "slip");
  CHECK(ground->first_slip() == Approx(expected).epsilon(5e-3));
}

}  // namespace

TEST_CASE("roll_to_slip: the contact slips at t* (solid and hollow)", "[events]") {
  check_onset("roll_to_slip", 0.4, 0.04116, 0.1, {});
  check_onset("roll_to_slip_hollow", 2.0 / 3.0, 0.04116, 0.1, {});
  // Another ramp and friction, through --set.
  check_onset("roll_to_slip", 0.4, 0.1, 0.2,
              {"impedances.motor.torque=\"0.1 * t\"", "impedances.ground.mu=0.2",
               "simulation.duration=2.0"});
  check_onset("roll_to_slip", 2.0 / 3.0, 0.03, 0.05,
              {"bodies.ball.shape=\"hollow_sphere\"", "impedances.motor.torque=\"0.03 * t\"",
               "impedances.ground.mu=0.05"});
}
