// Body-level events (core/body_events.hpp) on generated boxes against closed forms: pushed by
// a horizontal force ramp F = k t at height h on the middle of the back face, a box of mass m
// and half-length a along the push tips at t = m g a / (h k) where mu > a / h and slides at
// t = mu m g / k where mu < a / h (random mass, size, height, mu, ramp rate, yaw, and the face
// it rests on); a dropped box lands when its lowest corner has fallen its height; a launched
// box slides throughout, then sticks at v0 / (mu g); the unloaded back corners of a box about
// to slide creep below the stick threshold and are stuck. Also the state rule on generated
// point sets and the monitor's creep rule on speeds in closed form.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/body_events.hpp"
#include "core/simulation.hpp"
#include "scene/scene.hpp"
#include "toml_number.hpp"

using namespace stiction;
using stiction::testing::num;

namespace {

constexpr double g = 9.8;
constexpr double kDt = 1e-4;

core::RunResult run_text(const std::string& text) {
  scene::Scene s = scene::build_scene(toml::parse(text, std::string_view("gen.toml")), "gen.toml");
  return core::simulate(*s.network, s.run);
}

const core::BodyEventHistory& body_of(const core::RunResult& r, const std::string& name) {
  for (const auto& b : r.body_events) {
    if (b.body == name) return b;
  }
  FAIL("no body events for " << name);
  throw std::logic_error("unreachable");
}

const core::SlipMonitor& monitor_of(const core::RunResult& r, const std::string& element) {
  for (const auto& h : r.slip_events) {
    if (h.component == element) return h.monitor;
  }
  FAIL("no element " << element);
  throw std::logic_error("unreachable");
}

std::string kinds(const core::BodyEventHistory& b) {
  std::string s = b.initial + ":";
  for (const auto& e : b.events) s += " " + e.kind + "@" + num(e.time);
  return s;
}

// A box resting on one of its faces on a floor, turned by `yaw` about the vertical: `length`
// (2a) along `direction` (the push), `width` across, `height` up. on_side: it lies on a side
// face (its body y axis up), so other corners (body numbering) touch than standing upright.
struct Box {
  double m = 1.0, length = 0.2, width = 0.2, height = 0.2, mu = 0.5, yaw = 0.0;
  bool on_side = false;
  std::string name = "box";

  Eigen::Quaterniond orientation() const {
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    const Eigen::Quaterniond rest =
        on_side ? Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()))
                : Eigen::Quaterniond::Identity();
    return turn * rest;
  }
  // Body-frame size whose world extents are (length, width, height) with orientation().
  Eigen::Vector3d size() const {
    return on_side ? Eigen::Vector3d(length, height, width)
                   : Eigen::Vector3d(length, width, height);
  }
  // A body-frame point from coordinates along (push, across, up) about the centre.
  Eigen::Vector3d body_point(const Eigen::Vector3d& along) const {
    const Eigen::Quaterniond rest =
        on_side ? Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()))
                : Eigen::Quaterniond::Identity();
    return rest.conjugate() * along;
  }
  Eigen::Vector3d direction() const { return {std::cos(yaw), std::sin(yaw), 0.0}; }

  std::string table(double z, const std::string& extra = "") const {
    const Eigen::Quaterniond q = orientation();
    const Eigen::Vector3d s = size();
    const double k = 1e6, damping = 2.0 * std::sqrt(k * m / 4.0);  // critical per corner
    return "[bodies." + name + "]\ntype = \"rigid_body\"\nshape = \"box\"\nmass = " + num(m) +
           "\nsize = [" + num(s.x()) + ", " + num(s.y()) + ", " + num(s.z()) +
           "]\nposition = [0.0, 0.0, " + num(z) + "]\norientation = [" + num(q.w()) + ", " +
           num(q.x()) + ", " + num(q.y()) + ", " + num(q.z()) + "]\n" + extra +
           "[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"" + name +
           "\"\nstiffness = " + num(k) + "\ndamping = " + num(damping) + "\nmu = " + num(mu) + "\n";
  }
};

// The box settled on the floor, pushed along its length by F = k t at height h on the middle
// of its back face (a world-frame force).
std::string pushed(const Box& b, double h, double k, double duration) {
  const Eigen::Vector3d at = b.body_point({-0.5 * b.length, 0.0, h - 0.5 * b.height});
  const Eigen::Vector3d d = b.direction();
  return "[simulation]\ndt = " + num(kDt) + "\nduration = " + num(duration) +
         "\noutput_rate = 100.0\n" + b.table(0.5 * b.height) + "settle = true\n" +
         "[impedances.push]\ntype = \"force_source\"\nbody = \"" + b.name +
         "\"\nframe = \"world\"\npoint = [" + num(at.x()) + ", " + num(at.y()) + ", " +
         num(at.z()) + "]\nforce = [\"" + num(k * d.x()) + " * t\", \"" + num(k * d.y()) +
         " * t\", 0.0]\n";
}

Box random_box(std::mt19937& rng) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  Box b;
  b.m = 0.3 + 2.7 * uni(rng);
  b.length = 0.1 + 0.3 * uni(rng);
  b.width = 0.1 + 0.3 * uni(rng);
  b.height = 0.1 + 0.3 * uni(rng);
  b.yaw = 2.0 * M_PI * uni(rng);
  b.on_side = uni(rng) < 0.5;
  b.name = "a_box_named_" + std::to_string(rng() % 1000);
  return b;
}

}  // namespace

TEST_CASE("body state: touching points spanning an area, an edge, a corner, none",
          "[events][body]") {
  std::mt19937 rng(2121);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    // A box's corners, turned and moved anywhere: the rule reads the body frame only, but
    // it must not depend on where the box or its points are.
    const Eigen::Vector3d half(0.05 + 0.5 * std::abs(uni(rng)), 0.05 + 0.5 * std::abs(uni(rng)),
                               0.05 + 0.5 * std::abs(uni(rng)));
    const Eigen::Quaterniond q =
        Eigen::Quaterniond(uni(rng), uni(rng), uni(rng), uni(rng)).normalized();
    const Eigen::Vector3d shift(uni(rng), uni(rng), uni(rng));
    std::vector<core::Vec3> corners;
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d c((i & 1 ? 1 : -1) * half.x(), (i & 2 ? 1 : -1) * half.y(),
                              (i & 4 ? 1 : -1) * half.z());
      corners.push_back(q * c + shift);
    }
    const double tol = 1e-6 * 2.0 * half.norm();
    std::vector<std::string> s(8, "open");
    CHECK(core::body_state(corners, s, tol) == core::BodyState::open);
    // Bottom face (bits 2 clear): an area.
    for (int i : {0, 1, 2, 3}) s[i] = "stick";
    CHECK(core::body_state(corners, s, tol) == core::BodyState::stick);
    s[1] = "slip";
    CHECK(core::body_state(corners, s, tol) == core::BodyState::partial_slip);
    for (int i : {0, 1, 2, 3}) s[i] = "slip";
    CHECK(core::body_state(corners, s, tol) == core::BodyState::slide);
    // Three corners of the face still span an area.
    s[0] = "open";
    CHECK(core::body_state(corners, s, tol) == core::BodyState::slide);
    // The front edge (1, 3): a tip, whatever its points do.
    s[2] = "open";
    s[1] = "stick";
    CHECK(core::body_state(corners, s, tol) == core::BodyState::tip);
    s[3] = "stick";
    CHECK(core::body_state(corners, s, tol) == core::BodyState::tip);
    // One corner.
    s[3] = "open";
    CHECK(core::body_state(corners, s, tol) == core::BodyState::tip);
    // A diagonal of the bottom face is a line too: the box on two opposite corners.
    s = std::vector<std::string>(8, "open");
    s[0] = s[3] = "slip";
    CHECK(core::body_state(corners, s, tol) == core::BodyState::tip);
    // Two diagonal corners of different faces (0 and 7) with 1 also touching: an area.
    s = std::vector<std::string>(8, "open");
    s[0] = s[7] = s[1] = "stick";
    CHECK(core::body_state(corners, s, tol) == core::BodyState::stick);
  }
  // A rod's points all on one line: with one end up it does not tip (nothing off the line),
  // with a point off the line open it does.
  std::vector<core::Vec3> rod{{-1, 0, 0}, {0, 0, 0}, {1, 0, 0}};
  CHECK(core::body_state(rod, {"stick", "stick", "open"}, 1e-6) == core::BodyState::stick);
  CHECK(core::body_state(rod, {"stick", "open", "open"}, 1e-6) == core::BodyState::tip);
  rod.push_back({0, 0.5, 0});
  CHECK(core::body_state(rod, {"stick", "stick", "stick", "open"}, 1e-6) == core::BodyState::tip);
  // A point mass on two surfaces: both points are the same point, so no tip.
  const std::vector<core::Vec3> same{{0, 0, 0}, {0, 0, 0}};
  CHECK(core::body_state(same, {"slip", "open"}, 1e-6) == core::BodyState::slide);
}

TEST_CASE("body events from point histories: order, short states, land at the first touch",
          "[events][body]") {
  // Four points of a square, fed through their monitors at a 1 ms step: they touch down one
  // after the other, stick, then break loose one after the other (0.5 ms apart, below the
  // resolution of one step, and 5 ms apart, above it).
  const double dt = 1e-3;
  const std::vector<core::Vec3> square{{-1, -1, 0}, {1, -1, 0}, {-1, 1, 0}, {1, 1, 0}};
  for (const double spacing : {0.5e-3, 5e-3}) {
    std::vector<core::SlipHistory> histories;
    for (int i = 0; i < 4; ++i) {
      histories.push_back({"c." + std::to_string(i), core::SlipMonitor(1e-3, dt)});
      histories.back().body = "plate";
      histories.back().point = square[i];
    }
    const double touch[4] = {0.100, 0.101, 0.103, 0.103};  // the first one alone: on a corner
    for (int k = 0; k <= 1000; ++k) {
      const double t = k * dt;
      for (int i = 0; i < 4; ++i) {
        const double onset = 0.5 + spacing * i;
        const double speed = t > onset ? 0.5 * (t - onset) : 0.0;  // constant acceleration
        histories[i].monitor.observe(t, core::Vec3(speed, 0.0, 0.0), t < touch[i]);
      }
    }
    for (auto& h : histories) h.monitor.finish();
    const auto bodies = core::body_events(histories);
    REQUIRE(bodies.size() == 1);
    const auto& b = bodies[0];
    INFO(kinds(b));
    CHECK(b.initial == "open");
    REQUIRE(b.events.size() >= 3);
    CHECK(b.events[0].kind == "land");
    CHECK(b.events[0].time == Approx(0.100));  // the first touch, on a corner
    CHECK(b.events[0].state == "tip");
    CHECK(b.events[1].kind == "stick");  // all four down: the face
    CHECK(b.events[1].time == Approx(0.103));
    if (spacing < dt) {
      // Breaking loose within one step: one slide when the last point slips.
      REQUIRE(b.events.size() == 3);
      CHECK(b.events[2].kind == "slide");
      CHECK(b.events[2].time == Approx(0.5 + 3 * spacing).margin(1e-6));
    } else {
      REQUIRE(b.events.size() == 4);
      CHECK(b.events[2].kind == "partial_slip");
      CHECK(b.events[2].time == Approx(0.5).margin(1e-6));
      CHECK(b.events[3].kind == "slide");
      CHECK(b.events[3].time == Approx(0.5 + 3 * spacing).margin(1e-6));
    }
    // Intervals tile the run.
    REQUIRE(b.intervals.size() == b.events.size() + 1);
    CHECK(b.intervals.front().start == 0.0);
    CHECK(b.intervals.back().end == Approx(1.0));
    for (std::size_t i = 0; i + 1 < b.intervals.size(); ++i)
      CHECK(b.intervals[i].end == b.intervals[i + 1].start);
  }
}

TEST_CASE("creep below the threshold after the law released the element is a stick",
          "[events][body]") {
  // The law releases the element at 1.0 s; it creeps at 1 um/s until 2.0 s, then breaks loose
  // with s = (t - 2)^2 (a force ramped through the limit). The onset is 2.0 s, not 1.0 s.
  // Then a second element whose speed grows from its release at once: the law's bracket
  // still places that onset within the step of the release.
  const double dt = 1e-4;
  core::SlipMonitor creep(1e-3, dt), ramp(1e-3, dt);
  for (long k = 0; k <= 25000; ++k) {
    const double t = k * dt;
    const double s_creep = t < 1.0 ? 0.0 : 1e-6 + (t > 2.0 ? (t - 2.0) * (t - 2.0) : 0.0);
    const auto law_creep =
        creep.sticking() || s_creep > 1e-3
            ? (t < 1.0 ? core::SlipMonitor::Law::held : core::SlipMonitor::Law::released)
            : core::SlipMonitor::Law::unknown;
    creep.observe(t, core::Vec3(s_creep, 0.0, 0.0), false, law_creep);
    const double onset = 1.23456;
    const double s_ramp = t > onset ? (t - onset) * (t - onset) : 0.0;
    const auto law_ramp =
        ramp.sticking() || s_ramp > 1e-3
            ? (t <= onset ? core::SlipMonitor::Law::held : core::SlipMonitor::Law::released)
            : core::SlipMonitor::Law::unknown;
    ramp.observe(t, core::Vec3(s_ramp, 0.0, 0.0), false, law_ramp);
  }
  creep.finish();
  ramp.finish();
  std::printf("creep: first slip %.7f s (speed onset 2.0); ramp: %.7f s (release 1.23456)\n",
              creep.first_slip(), ramp.first_slip());
  CHECK(creep.initial_state() == "stick");
  REQUIRE(creep.events().size() == 1);
  CHECK(creep.first_slip() == Approx(2.0).margin(2e-4));
  REQUIRE(ramp.events().size() == 1);
  CHECK(ramp.first_slip() >= 1.2345);
  CHECK(ramp.first_slip() <= 1.2346);
}

TEST_CASE("generated pushed boxes tip at m g a / (h k) or slide at mu m g / k", "[events][body]") {
  std::mt19937 rng(2103);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 20; ++i) {
    Box b = random_box(rng);
    const bool tips = i % 2 == 0;
    if (tips) b.height = b.length * (1.0 + uni(rng));  // tall: mu > a / h stays below 2
    const double a = 0.5 * b.length;
    const double h = b.height * (0.6 + 0.4 * uni(rng));  // above the centre, at most the top
    // Well inside either side of mu = a / h, so the other outcome is far off.
    b.mu = tips ? (a / h) * (1.3 + 0.7 * uni(rng)) : (a / h) * (0.2 + 0.5 * uni(rng));
    const double t_expected = 0.3 + 0.7 * uni(rng);  // so the runs stay short
    const double k = tips ? b.m * g * a / (h * t_expected) : b.mu * b.m * g / t_expected;
    // Past the event: a slide is seen once the speed k (t - t*)^2 / (2 m) passes the 1 mm/s
    // threshold; well before the other outcome (tipping while sliding needs 1.4 t* at least).
    const double reach = tips ? 0.0 : std::sqrt(2.0 * b.m * 1e-3 / k);
    const double duration = 1.03 * t_expected + 3.0 * reach + 0.01;
    const core::RunResult r = run_text(pushed(b, h, k, duration));
    REQUIRE_FALSE(r.instability);
    const core::BodyEventHistory& body = body_of(r, b.name);
    INFO("box " << b.name << " m " << b.m << " 2a " << b.length << " w " << b.width << " H "
                << b.height << " h " << h << " mu " << b.mu << " k " << k << " yaw " << b.yaw
                << (b.on_side ? " on its side" : " upright") << ": " << kinds(body));
    CHECK(body.initial == "stick");
    REQUIRE(body.events.size() == 1);
    const core::BodyEvent& e = body.events[0];
    CHECK(e.kind == (tips ? "tip" : "slide"));
    std::printf("%s at %.6f s, closed form %.6f s (%+.2e s = %+.1f steps; mu %.3f, a/h %.3f)\n",
                e.kind.c_str(), e.time, t_expected, e.time - t_expected,
                (e.time - t_expected) / kDt, b.mu, a / h);
    // The tip is the end of the step in which the back corners' normal force reaches zero;
    // the compliant contact lags the quasi-static balance by its rocking mode's damping time
    // (a few steps here). The slide is the fitted onset of the speed (s ~ (t - t*)^2).
    CHECK(std::abs(e.time - t_expected) < 5.0 * kDt + 1e-4 * t_expected);
    // Every corner that touched stuck until then, the creeping back corners included.
    for (const std::string& p : body.points) {
      const core::SlipMonitor& m = monitor_of(r, p);
      if (m.initial_state() == "open") continue;
      CHECK(m.initial_state() == "stick");
      if (m.first_slip() >= 0.0) CHECK(m.first_slip() >= e.time - 5.0 * kDt);
    }
  }
}

TEST_CASE(
    "generated dropped boxes land after falling their height, launched boxes slide "
    "throughout and stop at v0 / (mu g)",
    "[events][body]") {
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 4; ++i) {
    Box b = random_box(rng);
    const double drop = 0.005 + 0.03 * uni(rng);
    const std::string text = "[simulation]\ndt = " + num(kDt) + "\nduration = 0.3\n" +
                             "output_rate = 100.0\n" + b.table(0.5 * b.height + drop);
    const core::RunResult r = run_text(text);
    REQUIRE_FALSE(r.instability);
    const core::BodyEventHistory& body = body_of(r, b.name);
    INFO(kinds(body));
    const double t_fall = std::sqrt(2.0 * drop / g);
    CHECK(body.initial == "open");
    REQUIRE_FALSE(body.events.empty());
    CHECK(body.events[0].kind == "land");
    // Touch-down is the end of the first step in contact.
    CHECK(body.events[0].time >= t_fall);
    CHECK(body.events[0].time <= t_fall + kDt + 1e-9);
    // It may hop: the contact's damping clamps the normal force to zero on the rebound
    // (a restitution of about e^-2 at critical damping), so a lift-off and a second landing
    // can follow, each lift-off after a landing; it ends at rest on its face.
    for (std::size_t k = 1; k < body.events.size(); ++k) {
      if (body.events[k].kind == "lift_off") CHECK(body.events[k - 1].kind != "lift_off");
      if (body.events[k].kind == "land") CHECK(body.events[k - 1].kind == "lift_off");
    }
    CHECK(body.intervals.back().kind == "stick");
  }
  for (int i = 0; i < 4; ++i) {
    Box b = random_box(rng);
    b.mu = 0.2 + 0.4 * uni(rng);
    b.height = std::min(b.height, 0.8 * b.length / b.mu);  // friction does not tip it forward
    const double v0 = 0.2 + 0.5 * uni(rng);
    const double t_stop = v0 / (b.mu * g);
    const Eigen::Vector3d v = v0 * b.direction();
    const std::string velocity = "velocity = [" + num(v.x()) + ", " + num(v.y()) + ", 0.0]\n";
    for (const double duration : {0.8 * t_stop, 1.2 * t_stop}) {
      const std::string text = "[simulation]\ndt = " + num(kDt) + "\nduration = " + num(duration) +
                               "\noutput_rate = 100.0\n" + b.table(0.5 * b.height, velocity) +
                               "settle = true\n";
      const core::RunResult r = run_text(text);
      REQUIRE_FALSE(r.instability);
      const core::BodyEventHistory& body = body_of(r, b.name);
      INFO("mu " << b.mu << " v0 " << v0 << " H " << b.height << ": " << kinds(body));
      CHECK(body.initial == "slide");
      if (duration < t_stop) {
        CHECK(body.events.empty());  // slides throughout
      } else {
        REQUIRE(body.events.size() == 1);
        CHECK(body.events[0].kind == "stick");
        std::printf("launched box stops at %.6f s, closed form %.6f s (%+.2e s)\n",
                    body.events[0].time, t_stop, body.events[0].time - t_stop);
        CHECK(body.events[0].time == Approx(t_stop).epsilon(2e-3));
      }
    }
  }
}
