// The shadow map is fitted to the casters and the visible ground each frame: the picture
// does not depend on the length of the run nor (within the golden tolerance) on the map size.
#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "image/compare.hpp"
#include "image/png.hpp"
#include "render/render_outputs.hpp"
#include "render/renderer.hpp"
#include "render/shadow_fit.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

// A sphere moving at 2 m/s along x for `length` metres, turning once a second.
core::Trajectory rolling(double length, double speed = 2.0) {
  core::Trajectory tr({"t", "sphere.p.x", "sphere.p.y", "sphere.p.z", "sphere.q.w", "sphere.q.x",
                       "sphere.q.y", "sphere.q.z", "contact.slip.x", "contact.slip.y",
                       "contact.slip.z"});
  const double R = 0.2, duration = length / speed;
  const int rows = static_cast<int>(duration * 200.0) + 1;
  for (int i = 0; i < rows; ++i) {
    const double t = duration * i / (rows - 1), x = speed * t, phi = 2.0 * std::numbers::pi * t;
    const double row[] = {t,   x,   0.0, R,  std::cos(0.5 * phi), 0.0, std::sin(0.5 * phi),
                          0.0, 0.0, 0.0, 0.0};
    tr.append(row);
  }
  return tr;
}

RenderSettings small(const scene::Scene& s, int shadow_map_size) {
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  settings.shadow_map_size = shadow_map_size;
  settings.overlay.enabled = false;
  settings.overlay.trail = false;
  return settings;
}

}  // namespace

TEST_CASE("shadows look the same on a 1 m and a 13 m run, and with a 4x smaller map",
          "[render][shadow]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const Drawing scene = s.drawing;
  // The sphere at x = 1 m and at x = 13 m (six checker periods of 2 m apart, six turns
  // apart), with the camera following it: the ground, the sphere and its shadow are the same.
  const core::Trajectory short_run = rolling(1.0), long_run = rolling(13.0);
  FrameRenderer a(scene, short_run, small(s, 2048));
  FrameRenderer b(scene, long_run, small(s, 2048));
  FrameRenderer c(scene, long_run, small(s, 512));
  const image::Image near_start = a.render(0.5);
  const image::Image far_out = b.render(6.5);
  const image::Image far_small_map = c.render(6.5);
  const image::CompareResult ab = image::compare_images(near_start, far_out);
  INFO("1 m run vs 13 m run: " << ab.message);
  CHECK(ab.matches);
  const image::CompareResult bc = image::compare_images(far_out, far_small_map);
  if (!bc.matches) {
    image::write_png(std::string(STICTION_TEST_OUTPUT_DIR) + "/failures/shadow_2048.png", far_out);
    image::write_png(std::string(STICTION_TEST_OUTPUT_DIR) + "/failures/shadow_512.png",
                     far_small_map);
  }
  INFO("2048 vs 512 map: " << bc.message);
  CHECK(bc.matches);
}

TEST_CASE("shadow fit: covers every caster, texels proportional to its size", "[render][shadow]") {
  DrawItem ball;
  ball.shape = Shape::sphere;
  ball.model =
      glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(100.0f, 3.0f, 0.2f)), glm::vec3(0.2f));
  DrawItem ground;
  ground.shape = Shape::plane;
  ground.casts_shadow = false;
  ground.model = glm::scale(glm::mat4(1.0f), glm::vec3(500.0f, 500.0f, 1.0f));
  Camera camera;
  camera.target = glm::vec3(100.0f, 3.0f, 0.2f);
  camera.eye = camera.target + glm::vec3(-0.5f, -2.0f, 1.0f);
  const glm::vec3 light = light_direction();
  const ShadowFit fit = fit_shadow({ball, ground}, camera, 16.0f / 9.0f, light, 1024);
  REQUIRE_FALSE(fit.empty);
  // The ball's surface lands inside the map (points in 26 directions from its centre);
  // the map is a small multiple of the ball.
  for (int i = 0; i < 27; ++i) {
    const glm::vec3 d(float(i % 3) - 1.0f, float(i / 3 % 3) - 1.0f, float(i / 9) - 1.0f);
    if (d == glm::vec3(0.0f)) continue;
    const glm::vec3 point = glm::vec3(100.0f, 3.0f, 0.2f) + 0.2f * glm::normalize(d);
    const glm::vec4 p = fit.light_view_proj * glm::vec4(point, 1.0f);
    CHECK(std::abs(p.x) < 1.0f);
    CHECK(std::abs(p.y) < 1.0f);
    CHECK(p.z > -1.0f);
    CHECK(p.z < 1.0f);
  }
  CHECK(fit.texel * 1024.0f < 4.0f * 0.4f);  // not the 1 km ground, nor the 100 m offset
  CHECK(fit.texel < 0.25f * fit.softness);   // the soft edge spans several texels
  // A caster behind the camera's view and far from it: nothing to shadow in view.
  DrawItem far = ball;
  far.model = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-400.0f, -400.0f, 0.2f)),
                         glm::vec3(0.2f));
  CHECK(fit_shadow({far, ground}, camera, 16.0f / 9.0f, light, 1024).empty);
}
