// Golden images of the issue-22 overlay layers (640x360, hand-written trajectories so they do
// not change with the physics): force arrows, legend and badges on a box tipping over its
// front edge; several values with a title and a caption on the rolling sphere.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "image/compare.hpp"
#include "render/contact_sites.hpp"
#include "render/render_outputs.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;
namespace fs = std::filesystem;

namespace {

const fs::path kGoldenDir = fs::path(STICTION_SOURCE_DIR) / "tests" / "golden";
const fs::path kFailureDir = fs::path(STICTION_TEST_OUTPUT_DIR) / "failures";

void check_golden(const std::string& name, const image::Image& frame) {
  const image::CompareResult r =
      image::compare_to_golden(kGoldenDir / (name + ".png"), frame, kFailureDir);
  INFO(r.message);
  CHECK(r.matches);
}

const char* box_tip_toml() {
  return R"(
name = "box_push_tip"
description = "A box pushed high by a force ramp tips at t = 1.633 s"
gravity = [0.0, 0.0, -9.8]
[bodies.box]
type = "rigid_body"
mass = 1.0
shape = "box"
size = [0.2, 0.2, 0.4]
position = [0.0, 0.0, 0.2]
[impedances.floor]
type = "kikuuwe_contact"
body = "box"
stiffness = 1e6
mu = 0.5
[camera]
follow = "box"
[overlay]
signal = "floor.0.n_force"
label = "back corner"
unit = "N"
forces = true
velocities = true
badges = true
)";
}

// The box pivots about its front bottom edge (x = 0.1) from t = 1.2 s, theta = 0.6 (t - 1.2)^2;
// before that the four bottom corners share m g and the friction that holds the push 2 t,
// after it the front corners carry it all and the back ones are open.
core::Trajectory box_tip_trajectory() {
  std::vector<std::string> columns{"t",       "box.p.x", "box.p.y", "box.p.z", "box.q.w", "box.q.x",
                                   "box.q.y", "box.q.z", "box.v.x", "box.v.y", "box.v.z"};
  for (int i = 0; i < 8; ++i) {
    for (const char* a : {".f.x", ".f.y", ".f.z", ".slip.x", ".slip.y", ".slip.z", ".n_force"}) {
      columns.push_back("floor." + std::to_string(i) + a);
    }
  }
  core::Trajectory tr(columns);
  auto theta = [](double t) { return t < 1.2 ? 0.0 : 0.6 * (t - 1.2) * (t - 1.2); };
  auto centre = [&](double t) {
    const double a = theta(t);
    return core::Vec3(0.1 - 0.1 * std::cos(a) + 0.2 * std::sin(a), 0.0,
                      0.1 * std::sin(a) + 0.2 * std::cos(a));
  };
  for (int k = 0; k <= 2000; ++k) {
    const double t = 1e-3 * k;
    const double a = theta(t);
    const core::Vec3 c = centre(t);
    const core::Vec3 v =
        (centre(t + 1e-4) - centre(std::max(0.0, t - 1e-4))) / (t < 1e-4 ? 1e-4 : 2e-4);
    std::vector<double> row{t,   c.x(), c.y(), c.z(), std::cos(0.5 * a), 0.0, std::sin(0.5 * a),
                            0.0, v.x(), v.y(), v.z()};
    const bool tipped = a > 0.0;
    for (int i = 0; i < 8; ++i) {
      const bool bottom = (i & 4) == 0, front = (i & 1) != 0;
      const int sharing = tipped ? 2 : 4;
      const bool loaded = bottom && (front || !tipped);
      const double n = loaded ? 9.8 / sharing : 0.0;
      const double friction = loaded ? -2.0 * t / sharing : 0.0;
      row.insert(row.end(), {friction, 0.0, n, 0.0, 0.0, 0.0, n});
    }
    tr.append(row.data());
  }
  return tr;
}

}  // namespace

TEST_CASE("golden: force arrows, legend and stick/open badges on a tipping box",
          "[render][golden][forces][badges]") {
  const scene::Scene s = testing::make_scene(box_tip_toml(), "box_push_tip");
  const core::Trajectory tr = box_tip_trajectory();
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  FrameRenderer renderer(s.drawing, tr, settings);
  check_golden("render_box_tip_forces_badges", renderer.render(1.7));
}

TEST_CASE("golden: several overlay values with a title and a caption",
          "[render][golden][overlay_values]") {
  const scene::Scene s = testing::make_scene(
      std::string(testing::sphere_roll_toml()) +
          "values = [{signal = \"sphere.p.x\", label = \"distance\", unit = \"m\"},"
          " {signal = \"sphere.q.w\", label = \"q.w\"}]\n"
          "title = \"Rolling to slip\"\ncaption = \"Simulation I: R = 0.2 m, v0 = 2 m/s, mu = "
          "0.1\"\n",
      "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory();
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  FrameRenderer renderer(s.drawing, tr, settings);
  check_golden("render_sphere_roll_values", renderer.render(0.35));
}
