// Goldens of the mechanism's drawing (640x360, hand-written trajectories): a damped spring to
// a post, force and torque source arrows, a belt between its rollers, a tilting board on its
// axle. Regenerate after an intended change with
//   STICTION_UPDATE_GOLDEN=1 ./build/tests/render/test_render "[golden]"
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "image/compare.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render_fixtures.hpp"

namespace fs = std::filesystem;
using namespace stiction;
using namespace stiction::render;

namespace {

void check_mechanism_golden(const std::string& toml, const std::string& name,
                            const core::Trajectory& tr, double t) {
  const scene::Scene s = testing::make_scene(toml, name);
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  FrameRenderer renderer(s.drawing, tr, settings);
  const image::CompareResult r =
      image::compare_to_golden(fs::path(STICTION_SOURCE_DIR) / "tests" / "golden" / (name + ".png"),
                               renderer.render(t), fs::path(STICTION_TEST_OUTPUT_DIR) / "failures");
  INFO(r.message);
  CHECK(r.matches);
}

// A block on a floor held by a damped spring to a world point, oscillating along x.
const char* kSpringPost = R"(
name = "render_spring_post"
gravity = [0.0, 0.0, -9.8]
[bodies.mass]
type = "point_mass"
mass = 1.0
[impedances.floor]
type = "kikuuwe_contact"
body = "mass"
[impedances.spring]
type = "spring_damper"
body = "mass"
other_point = [-0.4, 0.0, 0.0]
stiffness = 100.0
damping = 2.0
length = 0.3
[overlay]
enabled = false
)";

// A box pushed at its back face and a ball driven about y, both by ramps.
const char* kSources = R"(
name = "render_sources"
gravity = [0.0, 0.0, -9.8]
[bodies.box]
type = "rigid_body"
shape = "box"
size = [0.2, 0.2, 0.4]
mass = 1.0
position = [0.0, 0.0, 0.2]
[bodies.ball]
type = "rigid_body"
shape = "sphere"
radius = 0.1
mass = 1.0
position = [0.5, 0.0, 0.1]
[impedances.floor]
type = "kikuuwe_contact"
body = "box"
[impedances.push]
type = "force_source"
body = "box"
point = [-0.1, 0.0, 0.1]
force = ["2.0 * t", 0.0, 0.0]
[impedances.motor]
type = "torque_source"
body = "ball"
axis = [0.0, 1.0, 0.0]
torque = "0.04 * t"
[camera]
position = [-0.2, -2.0, 0.85]
target = [-0.1, 0.0, 0.15]
[overlay]
enabled = false
)";

// A block riding a 0.3 m wide belt over a floor.
const char* kBelt = R"(
name = "render_belt"
gravity = [0.0, 0.0, -9.8]
[bodies.mass]
type = "point_mass"
mass = 1.0
[impedances.belt]
type = "kikuuwe_contact"
body = "mass"
belt_speed = 0.2
extent = { axis = [1.0, 0.0, 0.0], min = [-0.6, -0.15], max = [0.6, 0.15] }
[impedances.floor]
type = "kikuuwe_contact"
body = "mass"
offset = -0.12
[overlay]
enabled = false
)";

// A ball on a 2 m x 1.2 m board tilting about y through its left third, over a floor.
const char* kTilt = R"(
name = "render_tilt"
gravity = [0.0, 0.0, -9.8]
[bodies.ball]
type = "rigid_body"
shape = "sphere"
radius = 0.1
mass = 1.0
position = [0.3, 0.0, 0.1]
[impedances.board]
type = "kikuuwe_contact"
body = "ball"
tilt = "0.1*t"
tilt_axis = [0.0, 1.0, 0.0]
extent = { centre = [0.4, 0.0, 0.0], axis = [1.0, 0.0, 0.0], min = [-1.0, -0.6], max = [1.0, 0.6] }
[impedances.floor]
type = "kikuuwe_contact"
body = "ball"
offset = -0.4
[overlay]
enabled = false
)";

}  // namespace

TEST_CASE("golden: a damped spring from a block to its post", "[render][golden][mechanism]") {
  core::Trajectory tr({"t", "mass.p.x", "mass.p.y", "mass.p.z"});
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.01 * i, row[] = {t, 0.05 * std::sin(6.0 * t), 0.0, 0.0};
    tr.append(row);
  }
  check_mechanism_golden(kSpringPost, "render_spring_post", tr, 0.3);
}

TEST_CASE("golden: force and torque sources as arrows", "[render][golden][mechanism]") {
  core::Trajectory tr({"t", "box.p.x", "box.p.y", "box.p.z", "box.q.w", "box.q.x", "box.q.y",
                       "box.q.z", "ball.p.x", "ball.p.y", "ball.p.z", "ball.q.w", "ball.q.x",
                       "ball.q.y", "ball.q.z", "push.f.x", "push.f.y", "push.f.z", "motor.tau"});
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.02 * i;
    const double row[] = {t,   0.0, 0.0, 0.2, 1.0, 0.0,     0.0, 0.0, 0.5,     0.0,
                          0.1, 1.0, 0.0, 0.0, 0.0, 2.0 * t, 0.0, 0.0, 0.04 * t};
    tr.append(row);
  }
  check_mechanism_golden(kSources, "render_sources", tr, 1.5);
}

TEST_CASE("golden: a belt between its rollers", "[render][golden][mechanism]") {
  core::Trajectory tr({"t", "mass.p.x", "mass.p.y", "mass.p.z"});
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.01 * i, row[] = {t, 0.2 * t - 0.1, 0.0, 0.0};
    tr.append(row);
  }
  check_mechanism_golden(kBelt, "render_belt_rollers", tr, 0.37);
}

TEST_CASE("golden: a tilting board on its pivot axle", "[render][golden][mechanism]") {
  core::Trajectory tr(
      {"t", "ball.p.x", "ball.p.y", "ball.p.z", "ball.q.w", "ball.q.x", "ball.q.y", "ball.q.z"});
  for (int i = 0; i <= 200; ++i) {
    // The ball carried by the board, 0.3 m from the pivot, as the board tilts.
    const double t = 0.01 * i, a = 0.1 * t;
    const double row[] = {t,   0.3 * std::cos(a) + 0.1 * std::sin(a),
                          0.0, -0.3 * std::sin(a) + 0.1 * std::cos(a),
                          1.0, 0.0,
                          0.0, 0.0};
    tr.append(row);
  }
  check_mechanism_golden(kTilt, "render_tilting_pivot", tr, 2.0);
}
