// The event model on whole runs: every bundled scene over its full duration and generated
// scenes (random parameters, long names) whose slip speed dips under the threshold and rises
// again, or whose contacts open and close. For every element with a slip speed: events in
// time order, never two of one kind in a row, the first one differs from the initial state,
// intervals that tile the run; for contacts, no stick or slip event at a step where the
// normal force is zero, and every such step inside an `open` interval. The normal force is
// read from the contact's own `n_force` signal on a second pass that repeats the run's steps
// (fixed steps: the same states bit for bit), not from the monitor.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/integrator.hpp"
#include "core/simulation.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

struct NormalForceTrace {
  std::vector<double> t;
  std::vector<double> n;  // per step
};

// Repeats the steps simulate() takes (fixed step) and records each contact's n_force.
std::map<std::string, NormalForceTrace> normal_forces(scene::Scene& s) {
  std::map<std::string, NormalForceTrace> traces;
  core::Network& net = *s.network;
  const auto columns = net.signal_columns();
  std::map<std::string, int> column_of;
  for (const auto& imp : net.impedances()) {
    const auto it = std::find(columns.begin(), columns.end(), imp->name() + ".n_force");
    if (core::capabilities_of(*imp).slip != nullptr && it != columns.end())
      column_of[imp->name()] = static_cast<int>(it - columns.begin());
  }
  if (column_of.empty()) return traces;
  const double T = s.run.dt, end = s.run.duration;
  const long total = static_cast<long>(std::ceil(end / T - 1e-9));
  auto stepper = core::make_stepper(s.run.integrator, net.state_dim(), T, s.run.tolerance);
  core::Vec x = net.initial_state();
  core::Vec row(net.signal_count());
  auto record = [&](double t) {
    net.write_signals(t, x, T, row);
    for (const auto& [name, c] : column_of) {
      traces[name].t.push_back(t);
      traces[name].n.push_back(row[c]);
    }
  };
  record(0.0);
  double t = 0.0;
  for (long k = 0; t < end; ++k) {
    stepper->advance(net, t, end - t, x);
    t = (k + 1 >= total) ? end : (k + 1) * T;
    record(t);
  }
  return traces;
}

void check_history(const core::SlipHistory& h, double duration, const NormalForceTrace* trace) {
  INFO("element " << h.component);
  const auto& events = h.monitor.events();
  REQUIRE_FALSE(h.monitor.initial_state().empty());
  std::string previous = h.monitor.initial_state();
  double last = 0.0;
  for (const auto& e : events) {
    INFO("event " << e.kind << " at " << e.time << " after " << previous);
    CHECK((e.kind == "stick" || e.kind == "slip" || e.kind == "open"));
    CHECK(e.kind != previous);  // never two of one kind in a row
    CHECK(e.time >= last);      // time-ordered
    CHECK(e.time <= duration + 1e-12);
    if (trace == nullptr) CHECK(e.kind != "open");  // only contacts open
    previous = e.kind;
    last = e.time;
  }
  const auto intervals = h.monitor.intervals();
  REQUIRE(intervals.size() == events.size() + 1);
  double covered = 0.0;
  for (const auto& i : intervals) {
    CHECK(i.duration() >= 0.0);
    covered += i.duration();
  }
  CHECK(covered == Approx(duration).epsilon(1e-9));
  if (trace == nullptr) return;
  // No stick or slip event where the normal force is zero: the first step at or after
  // the event has N > 0 (the event's step ends closed).
  for (const auto& e : events) {
    if (e.kind == "open") continue;
    const auto it = std::lower_bound(trace->t.begin(), trace->t.end(), e.time - 1e-12);
    REQUIRE(it != trace->t.end());
    const double n = trace->n[it - trace->t.begin()];
    INFO(e.kind << " at " << e.time << ": N = " << n << " at the step " << *it);
    CHECK(n > 0.0);
  }
  // Every step with N = 0 lies in an open interval.
  std::size_t k = 0;
  int open_steps = 0;
  for (std::size_t j = 0; j < trace->t.size(); ++j) {
    if (trace->n[j] > 0.0) continue;
    ++open_steps;
    const double tj = trace->t[j];
    while (k + 1 < intervals.size() && intervals[k].end <= tj) ++k;
    INFO("N = 0 at " << tj << " in a " << intervals[k].kind << " interval [" << intervals[k].start
                     << ", " << intervals[k].end << ")");
    if (intervals[k].kind != "open") {
      CHECK(intervals[k].kind == "open");
      break;
    }
  }
  std::printf("  %s: %d open steps, %zu events\n", h.component.c_str(), open_steps, events.size());
}

void check_scene(scene::Scene s) {
  const core::RunResult r = core::simulate(*s.network, s.run);
  INFO("scene " << s.name);
  REQUIRE_FALSE(r.instability);
  const auto traces = normal_forces(s);
  std::printf("%s (%g s):\n", s.name.c_str(), s.run.duration);
  for (const auto& h : r.slip_events) {
    const auto it = traces.find(h.component);
    check_history(h, s.run.duration, it == traces.end() ? nullptr : &it->second);
    for (const auto& e : h.monitor.events()) {
      if (h.monitor.events().size() <= 12) std::printf("    %s %.9g\n", e.kind.c_str(), e.time);
    }
  }
}

std::filesystem::path write_scene(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "stiction_test_events";
  std::filesystem::create_directories(dir);
  const auto path = dir / (name + ".toml");
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("events: every bundled scene over its full duration", "[events]") {
  for (const auto& [name, description] : scene::bundled_scenes())
    check_scene(scene::load_scene(name));
}

TEST_CASE("events: a one-joint arm whose speed dips under the threshold and rises again",
          "[events]") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::string element = "a_rather_long_joint_friction_element_name_for_the_only_joint";
  for (int trial = 0; trial < 6; ++trial) {
    const double length = 0.1 + 0.3 * u(rng), mass = 0.1 + 0.5 * u(rng);
    const double inertia = mass * length * length / 3.0;
    const double friction = 0.2 + 0.5 * u(rng), omega0 = 1.0 + 3.0 * u(rng);
    const double stop = omega0 * inertia / friction;  // sliding would end here
    // The step comes a little before or after the stop, forward or backward.
    const double t_step = stop * (0.97 + 0.06 * u(rng));
    const double torque = (trial % 2 == 0 ? 1.0 : -1.0) * friction * (1.05 + 0.5 * u(rng));
    char text[2048];
    std::snprintf(text, sizeof text, R"(name = "dip_%d"
gravity = [0.0, 0.0, 0.0]
[simulation]
dt = 1e-4
duration = %.17g
[bodies.arm]
type = "planar_arm"
links = [{ length = %.17g, mass = %.17g }]
rates = [%.17g]
[impedances.%s]
type = "kikuuwe_friction"
body = "arm"
joint = 0
stiffness = 5000.0
damping = 1.0
force_limit = %.17g
stick_threshold = 0.02
[impedances.motor]
type = "torque_source"
body = "arm"
joint = 0
torque = "t < %.17g ? 0 : %.17g"
)",
                  trial, stop + 1.0, length, mass, omega0, element.c_str(), friction, t_step,
                  torque);
    INFO(text);
    check_scene(scene::load_scene(write_scene("dip_" + std::to_string(trial), text).string()));
  }
}

TEST_CASE("events: a block sliding down a slope onto a floor", "[events]") {
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    const double deg = 20.0 + 15.0 * u(rng), theta = deg * 3.14159265358979 / 180.0;
    const double height = 0.3 + 0.7 * u(rng);
    const double mu_slope = 0.3 * std::tan(theta) * u(rng), mu_floor = 0.3 + 0.4 * u(rng);
    const double mass = 0.5 + 2.0 * u(rng), K = 1e6;
    // On the slope at rest, pressed in by its static deflection (no bounce).
    const double sink = mass * 9.8 * std::cos(theta) / K;
    const double nx = std::sin(theta), nz = std::cos(theta);
    const double offset = nz * height;  // the slope passes through (0, 0, height)
    char text[2048];
    std::snprintf(text, sizeof text, R"(name = "slope_to_floor_%d"
[simulation]
dt = 1e-4
duration = 4.0
[bodies.the_block_that_slides_down_onto_the_floor]
type = "point_mass"
mass = %.17g
position = [%.17g, 0.0, %.17g]
[impedances.slope]
type = "kikuuwe_contact"
body = "the_block_that_slides_down_onto_the_floor"
normal = [%.17g, 0.0, %.17g]
offset = %.17g
stiffness = %.17g
damping = %.17g
mu = %.17g
[impedances.floor]
type = "kikuuwe_contact"
body = "the_block_that_slides_down_onto_the_floor"
offset = 0.0
stiffness = %.17g
damping = %.17g
mu = %.17g
)",
                  trial, mass, -sink * nx, height - sink * nz, nx, nz, offset, K,
                  2.0 * std::sqrt(K * mass), mu_slope, K, 2.0 * std::sqrt(K * mass), mu_floor);
    INFO(text);
    scene::Scene s =
        scene::load_scene(write_scene("slope_to_floor_" + std::to_string(trial), text).string());
    const core::RunResult r = core::simulate(*s.network, s.run);
    // The floor starts open, the slope ends open: both report it.
    for (const auto& h : r.slip_events) {
      if (h.component == "floor") CHECK(h.monitor.initial_state() == "open");
      if (h.component == "slope") {
        REQUIRE_FALSE(h.monitor.events().empty());
        CHECK(h.monitor.events().back().kind == "open");
      }
    }
    check_scene(std::move(s));
  }
}
