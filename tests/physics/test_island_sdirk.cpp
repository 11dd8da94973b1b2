// sdirk2 and sdirk4 with a step of their own for every step group (core/island_sdirk.hpp),
// on generated scenes of separate spheres:
// - each sphere sticks at its closed-form time 2 |v0| / (7 mu g) and rolls at 5/7 |v0|;
// - a sphere among many takes the steps it takes alone, to the bit, so the work is the sum
//   of the spheres' own (linear in their number) and one sphere's switch costs the others
//   nothing;
// - parts of every kind (a box, a joint with friction, two spheres joined by their contact)
//   step among others as they step alone, and alone as SdirkStepper steps them, to the bit.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/integrator.hpp"
#include "core/island_sdirk.hpp"
#include "core/sdirk.hpp"
#include "core/simulation.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

struct Ball {
  double mass, radius, mu, vx, vy;
};

Ball random_ball(std::mt19937& rng) {
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<>(lo, hi)(rng);
  };
  Ball b{};
  b.mass = uniform(0.1, 5.0);
  b.radius = uniform(0.02, 0.3);
  b.mu = uniform(0.05, 0.6);
  const double speed = uniform(0.3, 3.0), heading = uniform(-3.14159, 3.14159);
  b.vx = speed * std::cos(heading);
  b.vy = speed * std::sin(heading);
  return b;
}

constexpr double kG = 9.81;

// prefix followed by the number k. (Built by appending: GCC 12 at -O3 reports a false
// -Wrestrict on "literal" + std::string, an error under the CI's -Werror.)
std::string named(const char* prefix, std::size_t k) {
  std::string name = prefix;
  name += std::to_string(k);
  return name;
}

// Solid spheres on the floor, launched sliding without spin, 1 m apart, resting at their
// static deflection (settle).
// first: the number of the first ball's name (b<first>, floor_b<first>).
std::string balls_scene(const std::vector<Ball>& balls, const std::string& integrator,
                        double duration, std::size_t first = 0) {
  std::ostringstream text;
  text.precision(17);
  text << "name = \"balls\"\ngravity = [0.0, 0.0, " << -kG << "]\n[simulation]\nintegrator = \""
       << integrator << "\"\ndt = 1e-4\ntolerance = 1e-6\nduration = " << duration
       << "\noutput_rate = 60.0\n";
  for (std::size_t k = 0; k < balls.size(); ++k) {
    const Ball& b = balls[k];
    const std::string name = named("b", first + k);
    text << "[bodies." << name << "]\ntype = \"rigid_body\"\nmass = " << b.mass
         << "\nshape = \"sphere\"\nradius = " << b.radius << "\nposition = ["
         << static_cast<double>(first + k) << ", 0.0, " << b.radius << "]\nvelocity = [" << b.vx
         << ", " << b.vy << ", 0.0]\n";
    text << "[impedances.floor_" << name << "]\ntype = \"kikuuwe_contact\"\nbody = \"" << name
         << "\"\nstiffness = 1e7\ndamping = " << 10.0 * b.mass / 0.3 << "\nmu = " << b.mu
         << "\nsettle = true\n";
  }
  return text.str();
}

scene::Scene load(const std::string& text) {
  return scene::load_scene(scene::SceneSource::from_text(text, "balls.toml"));
}

double stick_closed_form(const Ball& b) { return 2.0 * std::hypot(b.vx, b.vy) / (7.0 * b.mu * kG); }

}  // namespace

TEST_CASE("island sdirk: generated spheres each stick at 2 |v0| / (7 mu g) and roll at 5/7 |v0|",
          "[sdirk][islands]") {
  std::mt19937 rng(3636);
  std::vector<Ball> balls;
  for (int k = 0; k < 12; ++k) balls.push_back(random_ball(rng));
  double longest = 0.0;
  for (const Ball& b : balls) longest = std::max(longest, stick_closed_form(b));
  for (const std::string name : {"sdirk2", "sdirk4"}) {
    scene::Scene s = load(balls_scene(balls, name, longest + 0.3));
    core::RunResult r = core::simulate(*s.network, s.run);
    REQUIRE_FALSE(r.instability);
    const auto& tr = r.trajectory;
    for (std::size_t k = 0; k < balls.size(); ++k) {
      const Ball& b = balls[k];
      const std::string contact = named("floor_b", k);
      double stick = -1.0;
      for (const auto& h : r.slip_events) {
        if (h.component == contact) stick = h.monitor.stick_time();
      }
      const double t_stick = stick_closed_form(b);
      const std::string body = named("b", k);
      // At the run's end (every part's step ends there) and at the last row (interpolated
      // inside a part's own step).
      const auto end_value = [&](const std::string& column) {
        return r.end_row[static_cast<std::size_t>(*tr.find(column))];
      };
      const double speed = std::hypot(end_value(body + ".v.x"), end_value(body + ".v.y"));
      const std::size_t last = tr.row_count() - 1;
      const double row_speed =
          std::hypot(tr.at(last, *tr.find(body + ".v.x")), tr.at(last, *tr.find(body + ".v.y")));
      INFO(name << " ball " << k << ": mu " << b.mu << ", v0 " << std::hypot(b.vx, b.vy)
                << ": stick at " << stick << " (closed form " << t_stick << ", relative error "
                << (stick - t_stick) / t_stick << "), rolls at " << speed << " (closed form "
                << 5.0 / 7.0 * std::hypot(b.vx, b.vy) << ")");
      CHECK(stick == Approx(t_stick).epsilon(1e-10));
      CHECK(speed == Approx(5.0 / 7.0 * std::hypot(b.vx, b.vy)).epsilon(1e-9));
      // The rows between step ends: to the tolerance (sdirk4's rolling steps are up to the
      // bound of 4 rows long; measured 5e-8 at worst).
      CHECK(row_speed == Approx(5.0 / 7.0 * std::hypot(b.vx, b.vy)).epsilon(1e-6));
    }
  }
}

TEST_CASE("island sdirk: a sphere among many takes the steps it takes alone, to the bit",
          "[sdirk][islands]") {
  std::mt19937 rng(1036);
  std::vector<Ball> balls;
  for (int k = 0; k < 8; ++k) balls.push_back(random_ball(rng));
  const double duration = 1.2;
  scene::Scene all = load(balls_scene(balls, "sdirk2", duration));
  core::IslandSdirkStepper together(core::sdirk2_tableau(), core::step_groups(*all.network),
                                    all.network->state_dim(), 1e-4, 1e-6, 4.0 / 60.0);
  REQUIRE(together.groups() == balls.size());
  core::Vec x = all.network->initial_state();
  double t = 0.0;
  long macro_steps = 0;
  while (t < duration) {
    t += together.advance(*all.network, t, duration - t, x);
    ++macro_steps;
  }
  long alone_steps = 0;
  for (std::size_t k = 0; k < balls.size(); ++k) {
    scene::Scene one = load(balls_scene({balls[k]}, "sdirk2", duration, k));
    core::IslandSdirkStepper alone(core::sdirk2_tableau(), core::step_groups(*one.network),
                                   one.network->state_dim(), 1e-4, 1e-6, 4.0 / 60.0);
    core::Vec y = one.network->initial_state();
    double s = 0.0;
    while (s < duration) s += alone.advance(*one.network, s, duration - s, y);
    alone_steps += alone.group_steps();
    // Ball k's entries in both, by component name.
    INFO("ball " << k);
    bool same = true;
    for (const core::LayoutEntry& e : one.network->layout()) {
      for (const core::LayoutEntry& f : all.network->layout()) {
        if (f.component != e.component) continue;
        REQUIRE(f.size == e.size);
        for (int i = 0; i < e.size; ++i) same = same && y[e.offset + i] == x[f.offset + i];
      }
    }
    CHECK(same);
  }
  INFO(macro_steps << " steps of the run loop, " << together.group_steps()
                   << " steps of single spheres; alone " << alone_steps);
  CHECK(together.group_steps() == alone_steps);
}

namespace {

// A generated scene of separate parts of every kind, 2 m apart: a sphere launched sliding, a
// box launched sliding at a random yaw, a pendulum with Coulomb joint friction, and two
// spheres on the floor rolling into each other (one part: their contact joins them).
// only: the number of the one part to write (-1: all).
std::string mixed_scene(std::uint32_t seed, int parts, int only, double duration) {
  std::mt19937 rng(seed);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<>(lo, hi)(rng);
  };
  std::ostringstream text;
  text.precision(17);
  text << "name = \"mixed\"\ngravity = [0.0, 0.0, " << -kG << "]\n[simulation]\nintegrator = "
       << "\"sdirk2\"\ndt = 1e-4\ntolerance = 1e-6\nduration = " << duration
       << "\noutput_rate = 60.0\n";
  for (int k = 0; k < parts; ++k) {
    // Every part draws its numbers whether written or not: the same part in either scene.
    const int kind = k % 4;
    const double x0 = 2.0 * k, mass = uniform(0.2, 3.0), mu = uniform(0.1, 0.6);
    const double a = uniform(-1.0, 1.0), b = uniform(-1.0, 1.0), c = uniform(0.05, 0.3);
    if (only >= 0 && only != k) continue;
    const std::string n = std::to_string(k);
    const auto floor = [&](const std::string& body) {
      text << "[impedances.floor_" << body << "]\ntype = \"kikuuwe_contact\"\nbody = \"" << body
           << "\"\nstiffness = 1e6\ndamping = " << 30.0 * mass << "\nmu = " << mu
           << "\nsettle = true\n";
    };
    if (kind == 0 || kind == 1) {
      const std::string body = named(kind == 0 ? "ball" : "box", static_cast<std::size_t>(k));
      text << "[bodies." << body << "]\ntype = \"rigid_body\"\nmass = " << mass;
      if (kind == 0) {
        text << "\nshape = \"sphere\"\nradius = " << c << "\nposition = [" << x0 << ", 0.0, " << c;
      } else {
        text << "\nshape = \"box\"\nsize = [" << 2.0 * c << ", " << c + 0.05 << ", " << c
             << "]\nposition = [" << x0 << ", 0.0, " << 0.5 * c << "]\norientation = ["
             << std::cos(a) << ", 0.0, 0.0, " << std::sin(a);
      }
      text << "]\nvelocity = [" << 2.0 * a << ", " << 2.0 * b << ", 0.0]\n";
      floor(body);
    } else if (kind == 2) {
      text << "[bodies.arm" << n << "]\ntype = \"planar_arm\"\naxis = [0.0, -1.0, 0.0]\nbase = ["
           << x0 << ", 0.0, 0.6]\nlinks = [{ length = 0.5, width = 0.03, mass = " << mass
           << " }]\nangles = [" << -1.5707963267948966 + 0.3 * a << "]\n"
           << "[impedances.joint" << n << "]\ntype = \"kikuuwe_friction\"\nbody = \"arm" << n
           << "\"\njoint = 0\nstiffness = 5000.0\ndamping = 1.0\nforce_limit = " << 0.05 * c
           << "\n";
    } else {
      const double r = 0.1;
      for (int side = 0; side < 2; ++side) {
        std::string body = named("pair", static_cast<std::size_t>(k));
        body += side == 0 ? "a" : "b";
        text << "[bodies." << body << "]\ntype = \"rigid_body\"\nmass = " << mass
             << "\nshape = \"sphere\"\nradius = " << r << "\nposition = ["
             << x0 + (side == 0 ? -0.3 : 0.3) << ", " << (side == 0 ? 0.05 * b : 0.0) << ", " << r
             << "]\nvelocity = [" << (side == 0 ? 1.0 + a : -0.5) << ", 0.0, 0.0]\n";
        floor(body);
      }
      text << "[impedances.touch" << n << "]\ntype = \"kikuuwe_contact\"\nbody = \"pair" << n
           << "a\"\nother = \"pair" << n << "b\"\nstiffness = 1e6\ndamping = 10.0\nmu = " << mu
           << "\n";
    }
  }
  return text.str();
}

// Steps a scene's network from its initial state to `duration` with the given stepper.
core::Vec run_to(core::Network& network, core::Stepper& stepper, double duration) {
  core::Vec x = network.initial_state();
  double t = 0.0;
  while (t < duration) t += stepper.advance(network, t, duration - t, x);
  return x;
}

}  // namespace

TEST_CASE(
    "island sdirk: parts of every kind (spheres, boxes, a joint with friction, a colliding "
    "pair) step among others as they step alone, and alone as one step for all",
    "[sdirk][islands]") {
  const double duration = 1.0;
  for (const std::uint32_t seed : {11u, 12u}) {
    const int parts = 8;
    scene::Scene all = load(mixed_scene(seed, parts, -1, duration));
    const std::vector<core::Island> groups = core::step_groups(*all.network);
    REQUIRE(groups.size() == static_cast<std::size_t>(parts));  // the pair is one part
    core::IslandSdirkStepper together(core::sdirk2_tableau(), groups, all.network->state_dim(),
                                      1e-4, 1e-6, 4.0 / 60.0);
    const core::Vec x = run_to(*all.network, together, duration);
    REQUIRE(x.allFinite());
    long alone_steps = 0;
    for (int k = 0; k < parts; ++k) {
      scene::Scene one = load(mixed_scene(seed, parts, k, duration));
      core::IslandSdirkStepper alone(core::sdirk2_tableau(), core::step_groups(*one.network),
                                     one.network->state_dim(), 1e-4, 1e-6, 4.0 / 60.0);
      const core::Vec y = run_to(*one.network, alone, duration);
      alone_steps += alone.group_steps();
      // One step for all (SdirkStepper) on the part alone: the same method, so the same
      // steps and the same state, to the bit.
      scene::Scene again = load(mixed_scene(seed, parts, k, duration));
      core::SdirkStepper whole(core::sdirk2_tableau(), again.network->state_dim(), 1e-4, 1e-6,
                               4.0 / 60.0);
      const core::Vec z = run_to(*again.network, whole, duration);
      double worst_whole = 0.0;
      bool same = true;
      for (const core::LayoutEntry& e : one.network->layout()) {
        for (const core::LayoutEntry& f : all.network->layout()) {
          if (f.component != e.component) continue;
          REQUIRE(f.size == e.size);
          for (int i = 0; i < e.size; ++i) {
            same = same && y[e.offset + i] == x[f.offset + i];
            worst_whole = std::max(worst_whole, std::abs(y[e.offset + i] - z[e.offset + i]) /
                                                    (1.0 + std::abs(z[e.offset + i])));
          }
        }
      }
      INFO("seed " << seed << ", part " << k << " (kind " << k % 4 << "): alone and one step "
                   << "for all differ by " << worst_whole << " at most");
      CHECK(same);
      CHECK(worst_whole == 0.0);
    }
    CHECK(together.group_steps() == alone_steps);
  }
}
