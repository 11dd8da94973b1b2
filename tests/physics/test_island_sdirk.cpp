// sdirk2 and sdirk4 with a step of their own for every step group (core/island_sdirk.hpp),
// on generated scenes of separate spheres:
// - each sphere sticks at its closed-form time 2 |v0| / (7 mu g) and rolls at 5/7 |v0|;
// - a sphere among many takes the steps it takes alone, to the bit, so the work is the sum
//   of the spheres' own (linear in their number) and one sphere's switch costs the others
//   nothing;
// - the rows between the run loop's steps come from each sphere's own steps.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/integrator.hpp"
#include "core/island_sdirk.hpp"
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
    const std::string name = "b" + std::to_string(first + k);
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
      const std::string contact = "floor_b" + std::to_string(k);
      double stick = -1.0;
      for (const auto& h : r.slip_events) {
        if (h.component == contact) stick = h.monitor.stick_time();
      }
      const double t_stick = stick_closed_form(b);
      const std::string body = "b" + std::to_string(k);
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
