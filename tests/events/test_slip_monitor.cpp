// The event model of core::SlipMonitor on speeds given in closed form: where the times fall,
// which events are dropped, and what an open contact reports.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "core/events.hpp"

using namespace stiction;
using core::SlipMonitor;
using core::Vec3;

namespace {

// Observes speed(t) along x at every step dt from 0 to end; open(t) says when the contact is
// open.
void feed(SlipMonitor& m, double dt, double end, const std::function<double(double)>& speed,
          const std::function<bool(double)>& open = {}) {
  const long steps = std::lround(end / dt);
  for (long k = 0; k <= steps; ++k) {
    const double t = k * dt;
    m.observe(t, Vec3(speed(t), 0.0, 0.0), open ? open(t) : false);
  }
  m.finish();
}

}  // namespace

TEST_CASE("slip monitor: a linear slow-down sticks at its zero, past the step of the crossing") {
  // 3.43 m/s^2 with the threshold 1e-3: the zero lies ~3 steps after the crossing step.
  for (double t0 : {0.58312345, 0.2000001, 1.23456789}) {
    SlipMonitor m(1e-3, 1e-4);
    feed(m, 1e-4, t0 + 0.2, [&](double t) { return std::max(0.0, 3.43 * (t0 - t)); });
    REQUIRE(m.events().size() == 1);
    CHECK(m.events()[0].kind == "stick");
    CHECK(m.events()[0].time == Approx(t0).margin(1e-9));
    CHECK(m.initial_state() == "slip");
    CHECK(m.stick_time() == m.events()[0].time);
    CHECK(m.first_slip() < 0.0);
  }
}

TEST_CASE("slip monitor: slip onset of a ramped force (speed ~ (t - t*)^2) at t*") {
  // The threshold alone would put it sqrt(thr / c) = 35 ms late.
  for (double c : {0.83, 0.2, 5.0}) {
    const double t_star = 2.0812345;
    SlipMonitor m(1e-3, 1e-4);
    feed(m, 1e-4, t_star + 0.5,
         [&](double t) { return t > t_star ? c * (t - t_star) * (t - t_star) : 0.0; });
    REQUIRE(m.events().size() == 1);
    CHECK(m.events()[0].kind == "slip");
    INFO("c = " << c);
    CHECK(m.events()[0].time == Approx(t_star).margin(2e-4));
    CHECK(m.initial_state() == "stick");
    CHECK(m.first_slip() == m.events()[0].time);
  }
}

TEST_CASE("slip monitor: a step force breaks loose at its start (linear onset)") {
  const double t_star = 0.73456;
  SlipMonitor m(1e-3, 1e-4);
  feed(m, 1e-4, 1.0, [&](double t) { return t > t_star ? 0.4 * (t - t_star) : 0.0; });
  REQUIRE(m.events().size() == 1);
  CHECK(m.events()[0].time == Approx(t_star).margin(1e-8));
}

TEST_CASE("slip monitor: a stick shorter than the resolution is not reported") {
  // Slows down to zero at 0.5 s, stays stuck 0.5 ms, then breaks loose again.
  auto pause = [](double t) {
    return t < 0.5 ? 2.0 * (0.5 - t) : (t > 0.5005 ? 2.0 * (t - 0.5005) : 0.0);
  };
  SlipMonitor coarse(1e-3, 1e-3);
  feed(coarse, 1e-4, 1.0, pause);
  CHECK(coarse.events().empty());
  CHECK(coarse.initial_state() == "slip");
  // With a finer resolution it is a stick, then a slip, each at its moment.
  SlipMonitor fine(1e-3, 1e-5);
  feed(fine, 1e-4, 1.0, pause);
  REQUIRE(fine.events().size() == 2);
  CHECK(fine.events()[0].kind == "stick");
  CHECK(fine.events()[0].time == Approx(0.5).margin(1e-9));
  CHECK(fine.events()[1].kind == "slip");
  CHECK(fine.events()[1].time == Approx(0.5005).margin(1e-9));
}

TEST_CASE("slip monitor: a dip under the threshold that does not reach zero is no stick") {
  // V-shaped speed with its minimum at half the threshold: the fits on both sides meet
  // before the threshold crossings, so there is no stick of positive length to report.
  auto dip = [](double t) { return 0.5e-3 + 2.0 * std::abs(t - 0.5); };
  SlipMonitor m(1e-3, 0.0);
  feed(m, 1e-4, 1.0, dip);
  CHECK(m.events().empty());
}

TEST_CASE("slip monitor: passing through zero between two sliding steps is not a stick") {
  SlipMonitor m(1e-3, 1e-4);
  for (int k = 0; k <= 1000; ++k) {
    const double t = k * 1e-4;
    m.observe(t, Vec3(5.0 * (0.05005 - t), 0.0, 0.0));  // crosses zero between two steps
  }
  m.finish();
  CHECK(m.events().empty());
}

TEST_CASE("slip monitor: no stick or slip while open, lift-off and touch-down") {
  SlipMonitor m(1e-3, 1e-4);
  // Open until 0.1 s (sliding in the air at 2 m/s: no slip reported), touch-down sliding,
  // slows down linearly, sticks at 0.6 s, lifts off at 0.8 s, lands stuck at 0.9 s.
  feed(
      m, 1e-4, 1.0,
      [](double t) { return t < 0.6 ? 2.0 - 2.0 / 0.5 * std::max(0.0, t - 0.1) : 0.0; },
      [](double t) { return t < 0.1 - 1e-12 || (t > 0.8 - 1e-12 && t < 0.9 - 1e-12); });
  CHECK(m.initial_state() == "open");
  REQUIRE(m.events().size() == 4);
  CHECK(m.events()[0].kind == "slip");
  CHECK(m.events()[0].time == Approx(0.1));
  CHECK(m.events()[1].kind == "stick");
  CHECK(m.events()[1].time == Approx(0.6).margin(1e-9));
  CHECK(m.events()[2].kind == "open");
  CHECK(m.events()[2].time == Approx(0.8));
  CHECK(m.events()[3].kind == "stick");
  CHECK(m.events()[3].time == Approx(0.9));
  const auto intervals = m.intervals();
  REQUIRE(intervals.size() == 5);
  CHECK(intervals[0].kind == "open");
  CHECK(intervals[1].duration() == Approx(0.5).margin(1e-9));
  CHECK(intervals[4].end == Approx(1.0));
  CHECK(m.last_stick() == Approx(0.9));
}

TEST_CASE("slip monitor: a touch-down stuck for less than the resolution, then slipping") {
  SlipMonitor m(1e-3, 1e-3);
  // Lands at 0.1 s with no slip, starts sliding (step force) 0.2 ms later.
  feed(
      m, 1e-4, 0.3, [](double t) { return t > 0.1002 ? 3.0 * (t - 0.1002) : 0.0; },
      [](double t) { return t < 0.1 - 1e-12; });
  REQUIRE(m.events().size() == 1);
  CHECK(m.events()[0].kind == "slip");  // the touch-down, sliding
  CHECK(m.events()[0].time == Approx(0.1));
}
