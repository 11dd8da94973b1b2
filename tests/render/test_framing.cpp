// The automatic camera on generated planar arms: whatever the plane the arm swings in (a
// horizontal arm, a pendulum in any vertical plane), every joint and the tip stay in the
// picture at every time, and an arm in a vertical plane is seen face on, not edge on.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>

#include "render/camera.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

struct GeneratedArm {
  std::string toml;
  core::Trajectory trajectory;
};

// An arm of 1-4 random links about a random axis (vertical, or horizontal in any direction)
// whose joints sweep random ranges over two seconds.
GeneratedArm generated_arm(std::mt19937& rng, bool vertical_axis) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int links = 1 + static_cast<int>(unit(rng) * 4.0) % 4;
  const double heading = 2.0 * std::numbers::pi * unit(rng);
  const std::string name = "arm_generated_with_a_long_name_" + std::to_string(links);
  std::string toml = "name = \"framing\"\n[bodies." + name + "]\ntype = \"planar_arm\"\n";
  if (!vertical_axis) {
    toml += "axis = [" + std::to_string(std::cos(heading)) + ", " +
            std::to_string(std::sin(heading)) + ", 0.0]\n";
  }
  toml += "base = [" + std::to_string(unit(rng) - 0.5) + ", " + std::to_string(unit(rng) - 0.5) +
          ", " + std::to_string(0.5 + unit(rng)) + "]\nlinks = [";
  for (int k = 0; k < links; ++k) {
    toml += std::string(k ? ", " : "") + "{ length = " + std::to_string(0.1 + 0.5 * unit(rng)) +
            ", mass = 1.0, width = " + std::to_string(0.01 + 0.03 * unit(rng)) + " }";
  }
  toml += "]\n";
  std::vector<std::string> columns{"t"};
  for (int k = 0; k < links; ++k) columns.push_back(name + ".theta." + std::to_string(k));
  core::Trajectory trajectory(columns);
  std::vector<double> start, rate;
  for (int k = 0; k < links; ++k) {
    start.push_back(2.0 * std::numbers::pi * unit(rng));
    rate.push_back(4.0 * (unit(rng) - 0.5));
  }
  for (int i = 0; i <= 200; ++i) {
    std::vector<double> row{i * 0.01};
    for (int k = 0; k < links; ++k) row.push_back(start[k] + rate[k] * row[0]);
    trajectory.append(row.data());
  }
  return {toml, std::move(trajectory)};
}

}  // namespace

TEST_CASE("automatic framing keeps every joint of a generated arm in view, in any plane",
          "[render][framing]") {
  std::mt19937 rng(20261130);
  for (int trial = 0; trial < 12; ++trial) {
    const bool vertical_axis = trial % 3 == 0;
    const GeneratedArm arm = generated_arm(rng, vertical_axis);
    const scene::Scene s = testing::make_scene(arm.toml, "framing");
    const Drawing scene = s.drawing;
    const PoseTrack poses(arm.trajectory, scene);
    const float aspect = 16.0f / 9.0f;
    const CameraRig rig(CameraSettings{}, scene, poses, aspect);
    INFO("trial " << trial << ":\n" << arm.toml);
    for (int i = 0; i <= 40; ++i) {
      const double t = 0.05 * i;
      const Camera c = rig.at(t);
      for (const core::Vec3& joint : arm_joints(scene.bodies[0], poses, 0, t)) {
        const glm::vec4 clip = c.projection(aspect) * c.view() * glm::vec4(to_glm(joint), 1.0f);
        CHECK(std::abs(clip.x / clip.w) < 1.0f);
        CHECK(std::abs(clip.y / clip.w) < 1.0f);
      }
    }
    // Face on: the view's horizontal direction lies along a horizontal joint axis.
    const glm::vec3 direction = default_view_direction(scene);
    const glm::vec3 axis = to_glm(scene.bodies[0].axis);
    if (!vertical_axis) {
      CHECK(std::abs(glm::dot(glm::normalize(glm::vec3(direction.x, direction.y, 0.0f)),
                              glm::normalize(glm::vec3(axis.x, axis.y, 0.0f)))) > 0.95f);
    }
  }
}
