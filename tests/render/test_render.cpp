#include <catch2/catch.hpp>
#include <filesystem>

#include "image/compare.hpp"
#include "image/png.hpp"
#include "render/camera.hpp"
#include "render/gl_context.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render_fixtures.hpp"

namespace fs = std::filesystem;
using namespace stiction;
using namespace stiction::render;

namespace {

const fs::path kGoldenDir = fs::path(STICTION_SOURCE_DIR) / "tests" / "golden";
const fs::path kFailureDir = fs::path(STICTION_TEST_OUTPUT_DIR) / "failures";

// Goldens are small (640x360) so the repository stays small; everything else is as in a
// default video (4x MSAA, shadows, overlay).
RenderSettings golden_settings(const scene::Scene& s) {
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  return settings;
}

void check_golden(const std::string& name, const image::Image& frame) {
  const image::CompareResult r =
      image::compare_to_golden(kGoldenDir / (name + ".png"), frame, kFailureDir);
  INFO(r.message);
  CHECK(r.matches);
}

}  // namespace

TEST_CASE("the OSMesa context gives OpenGL 3.3 core or later with 4x MSAA", "[render]") {
  auto context = create_offscreen_context();
  INFO(context->renderer() << " / " << context->version());
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  CHECK(major * 10 + minor >= 33);
  CHECK(context->max_samples() >= 4);
  CHECK(context->backend() == "OSMesa");
}

TEST_CASE("golden: sphere_roll while slipping and after it rolls", "[render][golden]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory();
  FrameRenderer renderer(s.drawing, tr, golden_settings(s));
  check_golden("render_sphere_roll_slip", renderer.render(0.35));
  check_golden("render_sphere_roll_roll", renderer.render(1.5));
}

TEST_CASE("golden: two_link arm", "[render][golden]") {
  const scene::Scene s = testing::make_scene(testing::two_link_toml(), "two_link");
  const core::Trajectory tr = testing::two_link_trajectory();
  FrameRenderer renderer(s.drawing, tr, golden_settings(s));
  check_golden("render_two_link", renderer.render(0.5));
}

TEST_CASE("golden: two_link_penalty arm of rigid bodies and penalty joints", "[render][golden]") {
  const scene::Scene s = testing::make_scene(testing::two_link_penalty_toml(), "two_link_penalty");
  const core::Trajectory tr = testing::two_link_penalty_trajectory();
  const Drawing scene = s.drawing;
  // Both joints, with their articulation points and axes from the scene.
  REQUIRE(scene.joints.size() == 2);
  CHECK(scene.joints[0].parent == -1);
  CHECK(scene.joints[1].parent == 0);
  CHECK(scene.joints[1].child == 1);
  CHECK(scene.joints[1].parent_point.x() == 0.1);
  CHECK(scene.joints[1].point.x() == -0.1);
  CHECK(scene.joints[0].axis.z() == 1.0);
  CHECK(scene.joints[0].width == 0.02);
  FrameRenderer renderer(scene, tr, golden_settings(s));
  check_golden("render_two_link_penalty", renderer.render(0.5));
}

TEST_CASE("golden: slope_hold block on its slope", "[render][golden]") {
  const scene::Scene s = testing::make_scene(testing::slope_hold_toml(), "slope_hold");
  const core::Trajectory tr = testing::slope_hold_trajectory();
  FrameRenderer renderer(s.drawing, tr, golden_settings(s));
  check_golden("render_slope_hold", renderer.render(0.5));
}

TEST_CASE(
    "follow camera: horizontal with a vertical dead zone, all three axes with follow_vertical",
    "[render]") {
  // A block sliding down the 20 degree slope of slope_hold's scene: it moves along x and z.
  const scene::Scene s = testing::make_scene(testing::slope_hold_toml(), "slope_hold");
  core::Trajectory tr({"t", "block.p.x", "block.p.y", "block.p.z"});
  const double a = 20.0 * std::numbers::pi / 180.0;
  for (int i = 0; i <= 100; ++i) {
    const double t = i * 0.1, d = 0.5 * 1.5 * t * t;  // 75 m along the slope at t = 10 s
    const double row[] = {t, d * std::cos(a), 0.0, -d * std::sin(a)};
    tr.append(row);
  }
  const Drawing scene = s.drawing;
  const PoseTrack poses(tr, scene);
  CameraSettings settings;
  settings.follow = "block";
  const glm::vec3 moved = to_glm(poses.position(0, 10.0) - poses.position(0, 0.0));
  {
    const CameraRig rig(settings, scene, poses, 16.0f / 9.0f);
    const glm::vec3 shift = rig.at(10.0).target - rig.at(0.0).target;
    CHECK(shift.x == Approx(moved.x).margin(1e-3));
    // A small height change (a bounce) does not move the camera ...
    const glm::vec3 early = rig.at(0.2).target - rig.at(0.0).target;
    CHECK(early.z == 0.0f);
    CHECK(early.x > 0.0f);
    // ... but the block dropping 25 m is followed, beyond a dead zone: it stays in view.
    CHECK(shift.z < 0.0f);
    CHECK(shift.z > moved.z);
    CHECK_FALSE(rig.follows_vertically());
    const Camera c = rig.at(10.0);
    const glm::vec4 clip = c.projection(16.0f / 9.0f) * c.view() *
                           glm::vec4(moved + to_glm(poses.position(0, 0.0)), 1.0f);
    CHECK(std::abs(clip.x / clip.w) < 1.0f);
    CHECK(std::abs(clip.y / clip.w) < 1.0f);
  }
  settings.follow_vertical = true;
  const CameraRig rig(settings, scene, poses, 16.0f / 9.0f);
  CHECK(rig.follows_vertically());
  const Camera c0 = rig.at(0.0), c1 = rig.at(10.0);
  CHECK(c1.target.x - c0.target.x == Approx(moved.x).margin(1e-3));
  CHECK(c1.target.z - c0.target.z == Approx(moved.z).margin(1e-3));
  CHECK(c1.eye.z - c0.eye.z == Approx(moved.z).margin(1e-3));
  // The framed region (ground square and shadow map) moves with the block.
  const Bounds b = rig.follow_bounds(10.0);
  const glm::vec3 p = to_glm(poses.position(0, 10.0));
  CHECK(glm::all(glm::lessThan(b.min, p)));
  CHECK(glm::all(glm::greaterThan(b.max, p)));
}

TEST_CASE("rendering is repeatable frame to frame", "[render]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory(1.0);
  RenderSettings settings = golden_settings(s);
  settings.width = 320;
  settings.height = 180;
  FrameRenderer renderer(s.drawing, tr, settings);
  const image::Image a = renderer.render(0.2);
  const image::Image other = renderer.render(0.8);
  const image::Image b = renderer.render(0.2);
  CHECK(image::compare_images(a, b, {0, 0.0}).matches);
  // ... and the sphere does move between 0.2 s and 0.8 s.
  CHECK_FALSE(image::compare_images(a, other).matches);
}
