// Islands (core/islands.hpp) and the implicit step per island (core/implicit_euler.hpp), on
// generated scenes:
// - find_islands puts bodies that an element joins (a contact between two bodies) in one
//   island, and every separate body with its own elements in its own;
// - a sphere stepped among many others moves exactly as the same sphere stepped alone, to
//   the bit: its island's Newton iteration, matrix, halvings and splits are its own, so the
//   others' regime switches cost it nothing and change nothing.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "core/implicit_euler.hpp"
#include "core/islands.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

struct Ball {
  double mass, radius, mu, vx, vy, wz, height_offset;
  double x0;
};

// A solid sphere on the floor (z = 0), launched sliding, spinning about z.
void write_ball(std::ostringstream& text, const std::string& name, const Ball& b) {
  text << "[bodies." << name << "]\ntype = \"rigid_body\"\nmass = " << b.mass
       << "\nshape = \"sphere\"\nradius = " << b.radius << "\nposition = [" << b.x0 << ", 0.0, "
       << b.radius + b.height_offset << "]\nvelocity = [" << b.vx << ", " << b.vy
       << ", 0.0]\nangular_velocity = [0.0, 0.0, " << b.wz << "]\n[impedances.floor_" << name
       << "]\ntype = \"kikuuwe_contact\"\nbody = \"" << name
       << "\"\nstiffness = 1e7\ndamping = 30.0\nmu = " << b.mu << "\n";
}

std::string header(double dt) {
  std::ostringstream text;
  text.precision(17);
  text << "name = \"balls\"\ngravity = [0.0, 0.0, -9.81]\n[simulation]\nintegrator = "
          "\"implicit\"\ndt = "
       << dt << "\nduration = 1.0\n";
  return text.str();
}

Ball random_ball(std::mt19937& rng, int k) {
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<>(lo, hi)(rng);
  };
  Ball b{};
  b.mass = uniform(0.1, 5.0);
  b.radius = uniform(0.02, 0.3);
  b.mu = uniform(0.1, 0.9);
  b.vx = uniform(-3.0, 3.0);
  b.vy = uniform(-3.0, 3.0);
  b.wz = uniform(-20.0, 20.0);
  b.height_offset = uniform(0.0, 0.05);  // some drop, bounce and land
  b.x0 = 2.0 * k;
  return b;
}

// GCC 12 warns (-Wrestrict, a false positive) on "b" + std::to_string(k) once inlined.
std::string ball_name(int k) {
  std::ostringstream name;
  name << "b" << k;
  return name.str();
}

core::Vec segment_of(const core::Network& network, const core::Vec& x, const std::string& body,
                     const std::string& contact) {
  std::vector<double> values;
  for (const auto& entry : network.layout()) {
    if (entry.component != body && entry.component != contact) continue;
    for (int k = 0; k < entry.size; ++k) values.push_back(x[entry.offset + k]);
  }
  return Eigen::Map<core::Vec>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace

TEST_CASE("islands: bodies a contact joins share an island, separate bodies have their own",
          "[implicit][islands]") {
  std::mt19937 rng(7);
  const int count = 9;
  std::ostringstream text;
  text.precision(17);
  text << header(1e-3);
  for (int k = 0; k < count; ++k) write_ball(text, ball_name(k), random_ball(rng, k));
  // b0-b1 and b1-b2 touch through pair contacts: one island of three; b5-b6 another of two.
  const auto pair = [&](int a, int b) {
    text << "[impedances.touch_" << a << "_" << b << "]\ntype = \"kikuuwe_contact\"\nbody = \"b"
         << a << "\"\nother = \"b" << b << "\"\nstiffness = 1e6\ndamping = 10.0\nmu = 0.3\n";
  };
  pair(0, 1);
  pair(1, 2);
  pair(6, 5);
  auto scene = scene::load_scene(scene::SceneSource::from_text(text.str(), "balls.toml"));
  const auto islands = core::find_islands(*scene.network);
  REQUIRE(islands.size() == static_cast<std::size_t>(count - 3));
  std::size_t states = 0;
  std::vector<std::size_t> sizes;
  for (const auto& island : islands) {
    states += island.states.size();
    sizes.push_back(island.admittances.size());
    for (int i : island.impedances) {
      // Every body an element moves is in the element's island.
      for (const auto* moved : scene.network->map_of(i).admittances()) {
        bool found = false;
        for (int j : island.admittances) {
          found = found || scene.network->admittances()[static_cast<std::size_t>(j)].get() == moved;
        }
        CHECK(found);
      }
    }
  }
  CHECK(states == static_cast<std::size_t>(scene.network->state_dim()));
  CHECK(sizes == std::vector<std::size_t>{3, 1, 1, 2, 1, 1});
}

TEST_CASE("islands: a ball stepped among many moves to the bit as the same ball stepped alone",
          "[implicit][islands]") {
  std::mt19937 rng(2026);
  const int count = 14;
  for (double dt : {1.0 / 60.0, 1e-3}) {
    std::vector<Ball> balls;
    std::ostringstream all;
    all.precision(17);
    all << header(dt);
    for (int k = 0; k < count; ++k) {
      balls.push_back(random_ball(rng, k));
      write_ball(all, ball_name(k), balls.back());
    }
    auto many = scene::load_scene(scene::SceneSource::from_text(all.str(), "many.toml"));
    core::ImplicitEulerStepper stepper(many.network->state_dim(), dt);
    core::Vec x = many.network->initial_state();
    const double duration = 1.0;
    double t = 0.0;
    while (t < duration - 1e-12) t += stepper.advance(*many.network, t, duration - t, x);
    CHECK(stepper.blocks() == static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) {
      const std::string name = ball_name(k);
      std::ostringstream one;
      one.precision(17);
      one << header(dt);
      write_ball(one, name, balls[static_cast<std::size_t>(k)]);
      auto alone = scene::load_scene(scene::SceneSource::from_text(one.str(), "one.toml"));
      core::ImplicitEulerStepper single(alone.network->state_dim(), dt);
      core::Vec y = alone.network->initial_state();
      double s = 0.0;
      while (s < duration - 1e-12) s += single.advance(*alone.network, s, duration - s, y);
      INFO("dt = " << dt << ", ball " << k);
      const core::Vec mine = segment_of(*many.network, x, name, std::string("floor_").append(name));
      const core::Vec own = segment_of(*alone.network, y, name, std::string("floor_").append(name));
      REQUIRE(mine.size() == own.size());
      CHECK(mine.allFinite());
      CHECK((mine - own).cwiseAbs().maxCoeff() == 0.0);
    }
  }
}

TEST_CASE(
    "islands: two spheres apart step as two islands, collide as one, and move as with "
    "the contact always attached",
    "[implicit][islands]") {
  // Generated glancing collisions without gravity: the contact between the spheres detaches
  // while they are apart (two islands and the contact's own) and attaches as they close.
  std::mt19937 rng(11);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<>(lo, hi)(rng);
  };
  for (int trial = 0; trial < 4; ++trial) {
    const double ra = uniform(0.05, 0.2), rb = uniform(0.05, 0.2), ma = uniform(0.5, 3.0),
                 mb = uniform(0.5, 3.0), v = uniform(1.0, 3.0), offset = uniform(0.0, 0.8);
    std::ostringstream text;
    text.precision(17);
    text << "name = \"glancing\"\ngravity = [0.0, 0.0, 0.0]\n[simulation]\nintegrator = "
            "\"implicit\"\ndt = 1e-4\nduration = 0.4\n[bodies.a]\ntype = \"rigid_body\"\nmass = "
         << ma << "\nshape = \"sphere\"\nradius = " << ra << "\nposition = [" << -(ra + rb + 0.2)
         << ", " << offset * (ra + rb) << ", 0.0]\nvelocity = [" << v
         << ", 0.0, 0.0]\n[bodies.b]\ntype = \"rigid_body\"\nmass = " << mb
         << "\nshape = \"sphere\"\nradius = " << rb
         << "\nposition = [0.0, 0.0, 0.0]\n[impedances.touch]\ntype = \"kikuuwe_contact\"\nbody = "
            "\"a\"\nother = \"b\"\nstiffness = 1e6\ndamping = 10.0\nmu = "
         << uniform(0.1, 0.6) << "\n";
    auto run = [&](bool detach, std::size_t& fewest, std::size_t& most) {
      auto scene = scene::load_scene(scene::SceneSource::from_text(text.str(), "glancing.toml"));
      core::ImplicitEulerStepper stepper(scene.network->state_dim(), 1e-4);
      stepper.set_detach_contacts(detach);
      core::Vec x = scene.network->initial_state();
      fewest = 1000;
      most = 0;
      for (double t = 0.0; t < 0.4 - 1e-12;) {
        t += stepper.advance(*scene.network, t, 0.4 - t, x);
        fewest = std::min(fewest, stepper.blocks());
        most = std::max(most, stepper.blocks());
      }
      return x;
    };
    std::size_t fewest = 0, most = 0, fewest_joined = 0, most_joined = 0;
    const core::Vec apart = run(true, fewest, most);
    const core::Vec joined = run(false, fewest_joined, most_joined);
    INFO("trial " << trial);
    CHECK(most == 3);    // a, b and the contact's own state while apart
    CHECK(fewest == 1);  // one island while they touch
    CHECK(most_joined == 1);
    CHECK(fewest_joined == 1);
    REQUIRE(apart.allFinite());
    // The same collision: Newton's tolerance (1e-12 relative) apart, over 4000 steps.
    const double scale = joined.cwiseAbs().maxCoeff();
    CHECK((apart - joined).cwiseAbs().maxCoeff() <= 1e-9 * scale);
  }
}
