#include <cmath>

#include <catch2/catch.hpp>

#include "core/simulation.hpp"
#include "scene/scene.hpp"

using namespace stiction;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {
scene::Scene from_text(const char* text) { return scene::build_scene(toml::parse(std::string_view(text), std::string_view("x.toml")), "x.toml"); }
}  // namespace

TEST_CASE("loader: every bundled scene loads and builds a network") {
  const auto bundled = scene::bundled_scenes();
  std::vector<std::string> names;
  for (const auto& [name, description] : bundled) {
    names.push_back(name);
    CHECK_FALSE(description.empty());
  }
  for (const char* expected : {"sphere_roll", "two_link", "two_link_lugre", "two_link_dahl",
                               "two_link_penalty", "slope_hold", "slope_slide"}) {
    INFO(expected);
    CHECK(std::find(names.begin(), names.end(), expected) != names.end());
  }
  for (const auto& name : names) {
    INFO(name);
    const scene::Scene s = scene::load_scene(name);
    CHECK(s.name == name);
    CHECK(s.network->state_dim() > 0);
  }
}

TEST_CASE("loader: sphere_roll has the paper's parameters") {
  const scene::Scene s = scene::load_scene("sphere_roll");
  CHECK(s.run.integrator == "rk4");
  CHECK(s.run.dt == 1e-4);
  CHECK(s.run.output_rate == 1000.0);
  CHECK(s.run.stick_thresholds.size() == 1);
  CHECK(s.run.stick_thresholds.at("ground") == 1e-3);
  const auto layout = s.network->layout();
  REQUIRE(layout.size() == 2);
  CHECK(layout[0].component == "sphere");
  CHECK(layout[0].size == 13);
  CHECK(layout[1].component == "ground");
  CHECK(layout[1].size == 2);
  CHECK(s.document["bodies"]["sphere"]["radius"].value<double>() == 0.2);
}

TEST_CASE("loader: components keep the order of the file, not of the keys") {
  const scene::Scene s = from_text(R"(
[bodies.zeta]
type = "point_mass"
mass = 1
[bodies.alpha]
type = "point_mass"
mass = 2
)");
  const auto layout = s.network->layout();
  REQUIRE(layout.size() == 2);
  CHECK(layout[0].component == "zeta");
  CHECK(layout[1].component == "alpha");
}

TEST_CASE("loader: a sphere contact defaults to the sphere's radius") {
  // Resting on the ground at its static penetration, the sphere must stay put: with a
  // contact point at the centre (radius 0) it would fall 0.1 m.
  const scene::Scene base = from_text(R"(
[simulation]
duration = 0.05
[bodies.ball]
type = "rigid_body"
mass = 1.0
shape = "hollow_sphere"
radius = 0.1
position = [0, 0, 0.09999902]
[impedances.ground]
type = "kikuuwe_contact"
body = "ball"
stiffness = 1e7
damping = 100
)");
  core::RunResult r = core::simulate(*base.network, base.run);
  const int z = *r.trajectory.find("ball.p.z");
  CHECK(std::abs(r.trajectory.at(r.trajectory.row_count() - 1, z) - 0.09999902) < 1e-6);
}

TEST_CASE("loader: render, camera, overlay and plots are kept, not validated") {
  const scene::Scene s = from_text(R"(
[bodies.b]
type = "point_mass"
mass = 1
[render]
anything = 1
[camera]
eye = [1, 2, 3]
[[plots]]
y = ["b.p.z"]
)");
  CHECK(s.document["render"]["anything"].value<int>() == 1);
  CHECK(s.document["plots"][0]["y"][0].value<std::string>() == "b.p.z");
}

TEST_CASE("loader: schema errors name the key and its position") {
  CHECK_THROWS_WITH(from_text("[bodies.b]\ntype = \"point_mass\"\nmass = -2\n"),
                    StartsWith("x.toml:3:8: error: bodies.b.mass: must be > 0"));
  CHECK_THROWS_WITH(from_text("[bodies.b]\ntype = \"blob\"\nmass = 2\n"),
                    StartsWith("x.toml:2:8: error: bodies.b.type: unknown component type 'blob'"));
  CHECK_THROWS_WITH(from_text("[simulation]\ndt = 0\n[bodies.b]\ntype = \"point_mass\"\nmass = 1\n"),
                    StartsWith("x.toml:2:6: error: simulation.dt: must be > 0"));
  CHECK_THROWS_WITH(from_text("[simulation]\nintegrator = \"rk5\"\n[bodies.b]\ntype = \"point_mass\"\nmass = 1\n"),
                    Contains("simulation.integrator: unknown integrator 'rk5'"));
  CHECK_THROWS_WITH(from_text("[bodies.b]\ntype = \"point_mass\"\nmass = 1\ncolour = 2\n"),
                    StartsWith("x.toml:4:1: error: unknown key 'bodies.b.colour'"));
  CHECK_THROWS_WITH(from_text("[bodies.b]\ntype = \"point_mass\"\nmass = 1\n"
                              "[impedances.c]\ntype = \"kikuuwe_contact\"\nbody = \"nobody\"\n"),
                    Contains("impedances.c.body: no body named 'nobody'"));
  CHECK_THROWS_WITH(from_text("[bodies.b]\ntype = \"rigid_body\"\nmass = 1\nshape = \"sphere\"\nradius = 0.1\n"
                              "[impedances.m]\ntype = \"torque_source\"\nbody = \"b\"\ntorque = \"1 +\"\n"),
                    StartsWith("x.toml:9:"));
  CHECK_THROWS_WITH(from_text("[bodies.b]\ntype = \"point_mass\"\nmass = 1\n"
                              "[impedances.m]\ntype = \"torque_source\"\nbody = \"b\"\ntorque = 1\n"),
                    Contains("impedances.m.body: a torque needs bodies that rotate"));
  // An arm's joint axis: a zero vector is an error at the value.
  CHECK_THROWS_WITH(from_text("[bodies.arm]\ntype = \"planar_arm\"\n"
                              "links = [{length = 0.2, mass = 0.2}]\naxis = [0, 0, 0]\n"),
                    StartsWith("x.toml:4:8: error: bodies.arm.axis: must be a non-zero vector"));
  CHECK_THROWS_WITH(from_text("[bodies.arm]\ntype = \"planar_arm\"\nlinks = [{length = 0.2, mass = 0.2}]\n"
                              "[impedances.f]\ntype = \"kikuuwe_friction\"\nbody = \"arm\"\njoint = 1\n"),
                    Contains("impedances.f.joint: must be in 0..0"));
}

TEST_CASE("loader: find_scene reports what it searched") {
  CHECK_THROWS_WITH(scene::find_scene("no_such_scene"), Contains("sphere_roll"));
  CHECK_THROWS_AS(scene::find_scene("/nonexistent/file.toml"), scene::InputError);
}
