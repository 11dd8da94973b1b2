// Simulation II (constraint-based arm with Kikuuwe joint friction) holds without drift once
// stopped; LuGre under the same torques drifts; Simulation III (penalty joints) follows II.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scenario.hpp"

using stiction::testing::run_scenario;
using stiction::testing::ScenarioRun;

namespace {

double max_change(const ScenarioRun& run, const std::string& column, double from, double to) {
  const auto& tr = run.result.trajectory;
  const int c = run.column(column);
  const double ref = run.at(column, from);
  double worst = 0.0;
  for (int r = 0; r < tr.row_count(); ++r) {
    const double t = tr.at(r, 0);
    if (t >= from && t <= to) worst = std::max(worst, std::abs(tr.at(r, c) - ref));
  }
  return worst;
}

}  // namespace

TEST_CASE("two_link: at rest by 5 s, anchors hold to 1e-11 rad until 20 s", "[scenario][arm]") {
  const auto run = run_scenario("two_link");
  REQUIRE_FALSE(run.result.instability);
  for (int j = 0; j < 2; ++j) {
    const std::string theta = "arm.theta." + std::to_string(j);
    const std::string e = "joint" + std::to_string(j) + "_friction.e";
    // Anchor theta - e over [5, 20] s.
    const auto& tr = run.result.trajectory;
    const int ct = run.column(theta), ce = run.column(e);
    const double anchor5 = run.at(theta, 5.0) - run.at(e, 5.0);
    double anchor_drift = 0.0;
    for (int r = 0; r < tr.row_count(); ++r) {
      if (tr.at(r, 0) < 5.0) continue;
      anchor_drift = std::max(anchor_drift, std::abs(tr.at(r, ct) - tr.at(r, ce) - anchor5));
    }
    const double band = max_change(run, theta, 5.0, 20.0);
    std::printf("two_link joint %d: anchor drift %.3e rad, angle band %.3e rad (5-20 s)\n", j,
                anchor_drift, band);
    CHECK(anchor_drift < 1e-11);
    CHECK(band < 1e-4);
    CHECK(std::abs(run.at("arm.omega." + std::to_string(j), 5.0)) < 0.05);
  }
  // It did move first: about two revolutions of joint 0.
  CHECK(std::abs(run.at("arm.theta.0", 5.0)) > 2.0 * M_PI);
}

TEST_CASE("two_link_lugre drifts under the same torques", "[scenario][arm]") {
  const auto run = run_scenario("two_link_lugre");
  REQUIRE_FALSE(run.result.instability);
  double worst = 0.0;
  for (int j = 0; j < 2; ++j) {
    const std::string theta = "arm.theta." + std::to_string(j);
    const double drift = std::abs(run.at(theta, 20.0) - run.at(theta, 5.0));
    std::printf("two_link_lugre joint %d drift between 5 s and 20 s: %.4f rad\n", j, drift);
    worst = std::max(worst, drift);
  }
  CHECK(worst > 1e-2);
}

TEST_CASE("two_link_penalty follows two_link within 5e-3 rad over 0-10 s", "[scenario][arm]") {
  const auto constraint = run_scenario("two_link", {"simulation.duration=10.0"});
  const auto penalty = run_scenario("two_link_penalty", {"simulation.duration=10.0"});
  REQUIRE_FALSE(penalty.result.instability);
  double worst = 0.0;
  for (int j = 0; j < 2; ++j) {
    const auto a = constraint.values("arm.theta." + std::to_string(j));
    const auto b = penalty.values("joint" + std::to_string(j) + ".theta");
    REQUIRE(a.size() == b.size());
    for (std::size_t r = 0; r < a.size(); ++r) worst = std::max(worst, std::abs(a[r] - b[r]));
  }
  std::printf("two_link_penalty vs two_link: largest joint angle difference %.3e rad\n", worst);
  CHECK(worst < 5e-3);
}
