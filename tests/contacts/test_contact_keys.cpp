// Every contact key with a bad value is an InputError "FILE:LINE:COL: error: KEY: ...";
// points, box corners, initial_e and settle build what they say.
#include <catch2/catch.hpp>

#include "common.hpp"
#include "components/impedance/kikuuwe_contact.hpp"

using namespace stiction;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

scene::Scene from_text(const std::string& text) {
  return scene::build_scene(toml::parse(text, std::string_view("x.toml")), "x.toml");
}

const char* kBox = R"(
[bodies.b]
type = "rigid_body"
shape = "box"
mass = 1.0
size = [0.2, 0.2, 0.1]
position = [0.0, 0.0, 0.05]
[impedances.c]
type = "kikuuwe_contact"
body = "b"
)";

void expect_error(const std::string& extra, const std::string& where, const std::string& what) {
  INFO(extra);
  try {
    from_text(std::string(kBox) + extra + "\n");
    FAIL("no error");
  } catch (const scene::InputError& e) {
    CHECK_THAT(e.what(), StartsWith(where));
    CHECK_THAT(e.what(), Contains(": error: ") && Contains(what));
  }
}

}  // namespace

TEST_CASE("contact keys: bad values are errors at their line and column", "[contacts][keys]") {
  // kBox's [impedances.c] table ends at line 10; the extra key is on line 11.
  expect_error("points = [[0.0, 0.0]]", "x.toml:11:", "impedances.c.points");
  expect_error("points = []", "x.toml:11:", "impedances.c.points");
  expect_error("points = 3", "x.toml:11:", "impedances.c.points");
  expect_error("extent = { min = [0.0] }", "x.toml:11:", "impedances.c.extent.min");
  expect_error("extent = { min = [nan, 0.0] }", "x.toml:11:", "impedances.c.extent.min");
  expect_error("extent = { min = [1.0, 0.0], max = [0.0, 1.0] }",
               "x.toml:11:", "impedances.c.extent.max");
  expect_error("extent = { axis = [0.0, 0.0, 1.0], max = [0.0, inf] }",
               "x.toml:11:", "impedances.c.extent.axis");
  expect_error("extent = { }", "x.toml:11:", "impedances.c.extent");
  expect_error("extent = { size = 1.0 }", "x.toml:11:", "unknown key 'impedances.c.extent.size'");
  expect_error("initial_e = [1.0, 2.0, 3.0]", "x.toml:11:", "impedances.c.initial_e");
  expect_error("initial_e = [[1.0, 2.0]]", "x.toml:11:", "impedances.c.initial_e");
  expect_error("belt_speed = \"2*(t\"", "x.toml:11:", "impedances.c.belt_speed");
  expect_error("belt_speed = true", "x.toml:11:", "impedances.c.belt_speed");
  expect_error("belt_speed = 1.0\nbelt_direction = [0.0, 0.0, 2.0]",
               "x.toml:12:", "impedances.c.belt_direction");
  expect_error("belt_direction = [1.0, 0.0, 0.0]", "x.toml:11:", "needs `belt_speed`");
  expect_error("tilt = \"sin(\"", "x.toml:11:", "impedances.c.tilt");
  expect_error("tilt = 0.1\ntilt_axis = [0.0, 0.0, 0.0]", "x.toml:12:", "impedances.c.tilt_axis");
  expect_error("tilt_pivot = [0.0, 0.0, 0.0]", "x.toml:11:", "needs `tilt`");
  expect_error("settle = 1", "x.toml:11:", "impedances.c.settle");
  expect_error("mu = -1.0", "x.toml:11:", "impedances.c.mu");
}

TEST_CASE("contact keys: kikuuwe_friction initial_e needs one number per axis",
          "[contacts][keys]") {
  const std::string base = R"(
[bodies.m]
type = "point_mass"
mass = 1.0
[impedances.f]
type = "kikuuwe_friction"
body = "m"
)";
  CHECK_THROWS_WITH(from_text(base + "initial_e = [1.0, 2.0]\n"),
                    StartsWith("x.toml:8:") && Contains("impedances.f.initial_e"));
  CHECK_THROWS_WITH(from_text(base + "initial_e = \"x\"\n"), StartsWith("x.toml:8:"));
  // A preloaded 3-D friction spring starts at its state.
  const scene::Scene s = from_text(base + "initial_e = [1e-4, -2e-4, 0.0]\n");
  const core::Vec x = s.network->initial_state();
  CHECK(x.tail(3).isApprox(core::Vec3(1e-4, -2e-4, 0.0)));
}

TEST_CASE("contact points: a box gets its eight corners, `points` its own list",
          "[contacts][keys]") {
  const scene::Scene box = from_text(kBox);
  std::vector<std::string> names;
  for (const auto& imp : box.network->impedances()) names.push_back(imp->name());
  CHECK(names == std::vector<std::string>{"c.0", "c.1", "c.2", "c.3", "c.4", "c.5", "c.6", "c.7"});
  CHECK(box.run.stick_thresholds.size() == 8);
  const scene::Scene listed =
      from_text(std::string(kBox) +
                "points = [[0.1, 0.0, -0.05], [-0.1, 0.0, -0.05], [0.0, 0.1, -0.05]]\n"
                "initial_e = [[1e-6, 0.0], [0.0, 1e-6], [2e-6, 0.0]]\n");
  REQUIRE(listed.network->impedances().size() == 3);
  const core::Vec x = listed.network->initial_state();
  // Body (13) then three 2-D friction states, as given.
  CHECK(x.segment<2>(13) == Eigen::Vector2d(1e-6, 0.0));
  CHECK(x.segment<2>(15) == Eigen::Vector2d(0.0, 1e-6));
  CHECK(x.segment<2>(17) == Eigen::Vector2d(2e-6, 0.0));
  // A name taken by a contact's points is taken for every other component too.
  CHECK_THROWS_WITH(
      from_text(std::string(kBox) + "[impedances.c2]\ntype = \"spring_damper\"\nbody = "
                                    "\"b\"\n[bodies.c]\ntype = \"point_mass\"\nmass = 1.0\n"),
      Contains("already used"));
}

TEST_CASE(
    "settle: a box on a floor starts at its static deflection, each corner carrying a quarter",
    "[contacts][keys]") {
  const scene::Scene s = from_text(std::string(kBox) + "stiffness = 1e6\nsettle = true\n");
  const core::Vec x = s.network->initial_state();
  CHECK(x[2] == Approx(0.05 - 9.8 / 4e6).epsilon(1e-12));
  // Without settle it starts where the file put it.
  CHECK(from_text(kBox).network->initial_state()[2] == 0.05);
}
