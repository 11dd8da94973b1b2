#include <catch2/catch.hpp>

#include "scene/overrides.hpp"
#include "scene/scene.hpp"

using namespace stiction::scene;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {
toml::table doc() {
  return toml::parse(R"(
[simulation]
dt = 1e-4
[bodies.ball]
type = "point_mass"
mass = 1.0
velocity = [0, 0, 0]
[bodies.arm]
links = [{length = 0.2}, {length = 0.3}]
)", std::string_view("s.toml"));
}
}  // namespace

TEST_CASE("overrides: replace a number, an array, an array element") {
  toml::table d = doc();
  apply_override(d, "simulation.dt=3e-4");
  apply_override(d, "bodies.ball.velocity=[3, 0, 0.5]");
  apply_override(d, "bodies.arm.links[1].length=0.25");
  CHECK(d["simulation"]["dt"].value<double>() == 3e-4);
  CHECK(d["bodies"]["ball"]["velocity"][2].value<double>() == 0.5);
  CHECK(d["bodies"]["arm"]["links"][1]["length"].value<double>() == 0.25);
  // The new value carries the override as its position, for later messages.
  const auto* dt = d["simulation"]["dt"].node();
  REQUIRE(dt->source().path);
  CHECK(*dt->source().path == "--set simulation.dt");
  CHECK(dt->source().begin.column == 15);  // column of the value in "simulation.dt=3e-4"
}

TEST_CASE("overrides: a new key is added for the schema to judge") {
  toml::table d = doc();
  apply_override(d, "simulation.output_rate=500");
  CHECK(d["simulation"]["output_rate"].value<double>() == 500.0);
}

TEST_CASE("overrides: malformed arguments and paths are input errors") {
  toml::table d = doc();
  CHECK_THROWS_WITH(apply_override(d, "simulation.dt"), Contains("expected KEY=VALUE"));
  CHECK_THROWS_WITH(apply_override(d, "simulation.dt=[1,"), StartsWith("--set simulation.dt:1:"));
  CHECK_THROWS_WITH(apply_override(d, "bodies.nosuch.mass=1"),
                    StartsWith("--set bodies.nosuch.mass:1:8: error: unknown key 'bodies.nosuch'"));
  CHECK_THROWS_WITH(apply_override(d, "bodies.arm.links[5].length=1"), Contains("index out of range"));
  CHECK_THROWS_WITH(apply_override(d, "simulation.dt.x=1"), Contains("not a table"));
}

TEST_CASE("overrides: a key unknown to the schema fails in the loader at the override") {
  toml::table d = toml::parse(R"(
[bodies.ball]
type = "point_mass"
mass = 1.0
)", std::string_view("s.toml"));
  apply_override(d, "bodies.ball.mas=2");
  CHECK_THROWS_WITH(build_scene(std::move(d), "s.toml"),
                    StartsWith("--set bodies.ball.mas:1:1: error: unknown key 'bodies.ball.mas'"));
}

TEST_CASE("overrides: a missing table of defaults is created, a missing component or inset is not") {
  toml::table d = doc();  // no [render], [camera], [verify] or [inset]
  apply_override(d, "render.fps=10");
  apply_override(d, "render.size=[320, 240]");
  apply_override(d, "camera.fov=40");
  apply_override(d, "verify.frames=false");
  CHECK(d["render"]["fps"].value<int64_t>() == 10);
  CHECK(d["render"]["size"][1].value<int64_t>() == 240);
  CHECK(d["camera"]["fov"].value<int64_t>() == 40);
  CHECK(d["verify"]["frames"].value<bool>() == false);
  CHECK_THROWS_WITH(apply_override(d, "inset.signals=[\"t\"]"),
                    StartsWith("--set inset.signals:1:1: error: unknown key 'inset'"));
  CHECK_THROWS_WITH(apply_override(d, "bodies.nosuch.mass=1"), Contains("unknown key 'bodies.nosuch'"));
  // Only at the top: a table of the same name further down is not created.
  CHECK_THROWS_WITH(apply_override(d, "bodies.render.mass=1"), Contains("unknown key 'bodies.render'"));
}
