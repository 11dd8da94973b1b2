// Body-level events (core/body_events.hpp) on generated boxes against closed forms: pushed by
// a horizontal force ramp F = k t at height h on the middle of the back face, a box of mass m
// and half-length a along the push tips at t = m g a / (h k) where mu > a / h and slides at
// t = mu m g / k where mu < a / h (random mass, size, height, mu, ramp rate, yaw, and the face
// it rests on); a dropped box lands when its lowest corner has fallen its height; a launched
// box slides throughout, then sticks at v0 / (mu g); the unloaded back corners of a box about
// to slide creep below the stick threshold and are stuck. Issue 35 item 5: generated boxes
// pulled low by a ramp (random mass, mu, size, yaw, ramp rate from fast to slow, pull height),
// whose rear corners' law saturates 1.5 ms to 1.3 s before the box moves, slip with the box
// at mu m g / r, and below breakaway never slip. Also the state rule on generated point sets
// and the monitor's creep rule on speeds in closed form.
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
    // Touch-down is where the first corner's closure crosses zero within its step (core/
    // events.hpp): the fall time to a small part of a step (seen: 0.029 steps; the contact
    // force acts in the landing step's later stages).
    CHECK(std::abs(body.events[0].time - t_fall) <= 0.05 * kDt);
    CHECK(body.events[0].uncertainty == 0.0);
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

namespace {

// A box standing upright on the floor, turned by `yaw`, pulled along its length by a world
// force F = min(r t, f_max) through the middle of its front face at height h above the floor.
// The pull unloads the rear corners (their normal force falls by F h / (2 a) in all, a the
// half-length) without tipping the box when mu h < a, so their friction limit mu N is reached
// before the whole box's, mu m g: they are released by their law and creep while the front
// corners hold, until the box breaks loose at t* = mu m g / r.
std::string pulled(const Box& b, double h, double r, double f_max, double duration) {
  const Eigen::Vector3d at = b.body_point({0.5 * b.length, 0.0, h - 0.5 * b.height});
  const Eigen::Vector3d d = b.direction();
  const auto component = [&](double c) {
    return "\"" + num(c) + " * min(" + num(r) + " * t, " + num(f_max) + ")\"";
  };
  return "[simulation]\ndt = " + num(kDt) + "\nduration = " + num(duration) +
         "\noutput_rate = 1000.0\n" + b.table(0.5 * b.height) + "settle = true\n" +
         "[impedances.pull]\ntype = \"force_source\"\nbody = \"" + b.name +
         "\"\nframe = \"world\"\npoint = [" + num(at.x()) + ", " + num(at.y()) + ", " +
         num(at.z()) + "]\nforce = [" + component(d.x()) + ", " + component(d.y()) + ", 0.0]\n";
}

// A generated pulled box: mass, mu, size, yaw, the ramp's breakaway time t* in [t_min, t_max]
// (so the rate r = mu m g / t*) and the pull height h, with x = mu h / a in [x_min, x_max]
// (both log-uniform): the rear corners saturate at about F = mu m g / (1 + x) (equal
// tangential shares), x / (1 + x) of t* before the box moves: 1% (a short creep, shorter
// than the onset fit's reach on a slow ramp) to 46% of it.
struct Pull {
  Box box;
  double h = 0.0, r = 0.0, t_star = 0.0, x = 0.0;
};

Pull random_pull(std::mt19937& rng, double t_min, double t_max, double x_min, double x_max) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  Pull p;
  Box& b = p.box;
  b.m = 0.3 + 2.7 * uni(rng);
  b.mu = 0.2 + 0.6 * uni(rng);
  b.length = 0.1 + 0.3 * uni(rng);
  b.width = 0.1 + 0.3 * uni(rng);
  b.yaw = 2.0 * M_PI * uni(rng);
  b.name = "crate";
  p.x = x_min * std::pow(x_max / x_min, uni(rng));
  p.h = p.x * 0.5 * b.length / b.mu;
  b.height = std::max(p.h / (0.5 + 0.5 * uni(rng)), 0.05);  // the pull point on the face
  p.t_star = t_min * std::pow(t_max / t_min, uni(rng));     // slow to fast ramps
  p.r = b.mu * b.m * g / p.t_star;
  return p;
}

// The rear bottom corners, away from the pull: body x < 0, z < 0 (box corner numbering:
// bit 0 is +x, bit 2 is +z).
bool rear_bottom(int corner) { return (corner & 1) == 0 && (corner & 4) == 0; }
bool bottom(int corner) { return (corner & 4) == 0; }

// From the rows: the first time a corner's tangential force reaches mu N (its law released
// it), or a negative value; and its largest slip speed over [t0, t1].
double release_time(const core::RunResult& r, const std::string& element, double mu) {
  const core::Trajectory& tr = r.trajectory;
  const int fx = *tr.find(element + ".f.x"), fy = *tr.find(element + ".f.y"),
            n = *tr.find(element + ".n_force");
  for (int row = 0; row < tr.row_count(); ++row) {
    const double ft = std::hypot(tr.at(row, fx), tr.at(row, fy));
    if (tr.at(row, n) > 0.0 && ft >= (1.0 - 1e-6) * mu * tr.at(row, n)) return tr.at(row, 0);
  }
  return -1.0;
}

double max_slip(const core::RunResult& r, const std::string& element, double t0, double t1) {
  const core::Trajectory& tr = r.trajectory;
  const int sx = *tr.find(element + ".slip.x"), sy = *tr.find(element + ".slip.y");
  double worst = 0.0;
  for (int row = 0; row < tr.row_count(); ++row) {
    if (tr.at(row, 0) < t0 || tr.at(row, 0) > t1) continue;
    worst = std::max(worst, std::hypot(tr.at(row, sx), tr.at(row, sy)));
  }
  return worst;
}

}  // namespace

TEST_CASE("generated pulled boxes: corners that creep after their release slip with the box",
          "[events][body][creep]") {
  // Issue 35 item 5: the rear corners' law saturates before the box moves, and they creep
  // below the threshold; they are stuck until the box breaks loose at t* = mu m g / r, and
  // then every bottom corner slips and the box slides, all at t*.
  //
  // Tolerance 2 steps. The front corners' onset is placed in their law's bracket, the
  // creeping corners' in the step after their last calm step: each one step wide, the fit
  // placing it inside. The real onset is the quasi-static t* up to the contacts' compliance:
  // the box creeps at a steady speed, so the friction force sums to F and saturates at
  // mu m g, but the law's release can come a fraction of a step early (as on a block:
  // test_event_uncertainty.cpp), and on the fastest ramps (t* a few tens of ms, a
  // few periods of the contacts' mode) the box accelerates as the rear corners let go
  // (friction F - m a): there it broke loose about a step late. Seen: at most 0.94 steps;
  // the second step is margin.
  std::mt19937 rng(3505);
  const double threshold = 1e-3;  // the contacts' default stick threshold
  const double tolerance = 2.0 * kDt;
  double worst_front = 0.0, worst_rear = 0.0, worst_body = 0.0;
  int short_creeps = 0;
  for (int i = 0; i < 16; ++i) {
    const Pull p = random_pull(rng, 0.02, 3.0, 0.01, 0.85);
    const Box& b = p.box;
    // The onset fit's reach: the speed r (t - t*)^2 / (2 m) passes the threshold after it.
    const double reach = std::sqrt(2.0 * b.m * threshold / p.r);
    const double duration = p.t_star + 3.0 * reach + 0.01;
    const core::RunResult r = run_text(pulled(b, p.h, p.r, 1e300, duration));
    REQUIRE_FALSE(r.instability);
    const core::BodyEventHistory& body = body_of(r, b.name);
    INFO("m " << b.m << " mu " << b.mu << " 2a " << b.length << " H " << b.height << " h " << p.h
              << " r " << p.r << " yaw " << b.yaw << " t* " << p.t_star << ": " << kinds(body));
    CHECK(body.initial == "stick");
    CHECK(body.events.size() == 1);  // no partial_slip before: the creeping corners stuck
    REQUIRE_FALSE(body.events.empty());
    const core::BodyEvent& slide = body.events.front();
    CHECK(slide.kind == "slide");
    CHECK(std::abs(slide.time - p.t_star) < tolerance);
    worst_body = std::max(worst_body, std::abs(slide.time - p.t_star));
    double release = 1e300, creep = 0.0, front = 0.0, rear = 0.0, u_at_slide = 0.0;
    for (int c = 0; c < 8; ++c) {
      if (!bottom(c)) continue;
      const std::string element = "floor." + std::to_string(c);
      const core::SlipMonitor& m = monitor_of(r, element);
      INFO(element << " first slip " << num(m.first_slip()));
      CHECK(m.initial_state() == "stick");
      REQUIRE(m.events().size() == 1);
      const core::SlipEvent& e = m.events()[0];
      CHECK(e.kind == "slip");
      CHECK(std::abs(e.time - p.t_star) < tolerance);
      // Located within a step (the bracket, or the step after the last calm one).
      CHECK(e.uncertainty > 0.5 * kDt);
      CHECK(e.uncertainty < 1.0 * kDt + 1e-12);
      if (e.time == slide.time) u_at_slide = std::max(u_at_slide, e.uncertainty);
      double& worst = rear_bottom(c) ? rear : front;
      worst = std::max(worst, std::abs(e.time - p.t_star));
      if (rear_bottom(c)) {
        const double t_r = release_time(r, element, b.mu);
        release = std::min(release, t_r);
        creep = std::max(creep, max_slip(r, element, t_r, p.t_star - 1e-3));
        CHECK(t_r > 0.0);
        CHECK(t_r < p.t_star - 10.0 * kDt);  // the case this is about: a creep
      }
    }
    // The body's slide carries the uncertainty of the corner events that made it.
    CHECK(slide.uncertainty == u_at_slide);
    short_creeps += p.t_star - release < reach;
    worst_front = std::max(worst_front, front);
    worst_rear = std::max(worst_rear, rear);
    std::printf(
        "pulled box t* %.6f s: slide %+.2f steps, corners within %.2f (front) %.2f (rear) steps; "
        "rear corners released %.1f ms before (fit reach %.1f ms), creeping at most at %.2g "
        "of the threshold\n",
        p.t_star, (slide.time - p.t_star) / kDt, front / kDt, rear / kDt,
        1e3 * (p.t_star - release), 1e3 * reach, creep / threshold);
  }
  std::printf(
      "pulled boxes: worst onset error %.2f steps (front corners), %.2f (rear, creeping), %.2f "
      "(body slide); %d of 16 creeps shorter than the fit's reach\n",
      worst_front / kDt, worst_rear / kDt, worst_body / kDt, short_creeps);
  CHECK(short_creeps >= 3);  // the cases the reach alone took for onsets at the release
}

TEST_CASE("generated pulled boxes below breakaway: creeping corners never slip",
          "[events][body][creep]") {
  std::mt19937 rng(3506);
  for (int i = 0; i < 4; ++i) {
    const Pull p = random_pull(rng, 0.05, 0.5, 0.1, 0.85);
    const Box& b = p.box;
    // Halfway between the rear corners' release, at about 1 / (1 + x) of the breakaway force,
    // and the breakaway (at least 4.5% below it): the pull either stops rising there and holds
    // for long, or the run ends when the ramp reaches it.
    const double fraction = (1.0 + 0.5 * p.x) / (1.0 + p.x);
    const bool hold = i % 2 == 0;
    const double f_max = hold ? fraction * b.mu * b.m * g : 1e300;
    const double duration = hold ? 2.0 * p.t_star + 0.1 : fraction * p.t_star;
    const core::RunResult r = run_text(pulled(b, p.h, p.r, f_max, duration));
    REQUIRE_FALSE(r.instability);
    const core::BodyEventHistory& body = body_of(r, b.name);
    INFO("m " << b.m << " mu " << b.mu << " h " << p.h << " r " << p.r << ": " << kinds(body));
    CHECK(body.initial == "stick");
    CHECK(body.events.empty());
    for (int c = 0; c < 8; ++c) {
      if (!bottom(c)) continue;
      const std::string element = "floor." + std::to_string(c);
      const core::SlipMonitor& m = monitor_of(r, element);
      INFO(element);
      CHECK(m.initial_state() == "stick");
      CHECK(m.total() == 0);
      if (rear_bottom(c)) CHECK(release_time(r, element, b.mu) > 0.0);  // it did creep
    }
  }
}
