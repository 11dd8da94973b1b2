// The renderer draws a planar arm in its own plane: a pendulum (horizontal joint axis) hangs
// below its base, a default arm stays in its horizontal plane. Geometry only, no GL.
#include <catch2/catch.hpp>
#include <numbers>

#include "render/scene_view.hpp"
#include "sources_fixture.hpp"

using namespace stiction;

namespace {

// Bounds of the arm drawn at joint angle theta (one sample of a synthetic run).
render::Bounds arm_bounds(const std::string& axis, double theta) {
  const auto s = testing::scene_from_text(
      "[bodies.arm]\ntype = \"planar_arm\"\naxis = " + axis +
      "\nbase = [0.0, 0.0, 1.0]\nlinks = [{length = 0.5, mass = 1.0, width = 0.02}]\n");
  core::Trajectory trajectory({"t", "arm.theta.0", "arm.omega.0"});
  for (double t : {0.0, 1.0}) {
    const double row[] = {t, theta, 0.0};
    trajectory.append(row);
  }
  const render::Drawing scene = s.drawing;
  const render::PoseTrack poses(trajectory, scene);
  return render::body_bounds(scene, poses, 0.5);
}

}  // namespace

TEST_CASE("arm view: a pendulum hangs below its base, in the x-z plane") {
  // axis -y: theta from +x towards +z, so -pi/2 hangs straight down.
  const render::Bounds b = arm_bounds("[0.0, -1.0, 0.0]", -std::numbers::pi / 2);
  INFO("x " << b.min.x << " .. " << b.max.x << ", z " << b.min.z << " .. " << b.max.z);
  CHECK(b.min.z == Approx(0.5).margin(0.03));  // the tip, 0.5 m below the base
  CHECK(b.max.z == Approx(1.0).margin(0.03));
  CHECK(b.max.x - b.min.x < 0.06);  // no horizontal extent beyond the link's width
  // Turned to theta = 0 it points along +x at the height of the base.
  const render::Bounds h = arm_bounds("[0.0, -1.0, 0.0]", 0.0);
  CHECK(h.max.x == Approx(0.5).margin(0.03));
  CHECK(h.max.z - h.min.z < 0.06);
}

TEST_CASE("arm view: the default (vertical) axis keeps the arm horizontal") {
  const render::Bounds b = arm_bounds("[0.0, 0.0, 1.0]", std::numbers::pi / 2);
  CHECK(b.max.y == Approx(0.5).margin(0.03));  // along +y
  CHECK(b.max.z - b.min.z < 0.06);
}
