// Scenes and hand-made trajectories for the renderer's tests and benchmark: the renderer only
// reads poses from signals, so a trajectory written from closed forms is all it needs.
#pragma once

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/trajectory.hpp"
#include "scene/scene.hpp"

namespace stiction::render::testing {

inline scene::Scene make_scene(const std::string& toml_text, const std::string& name) {
  return scene::build_scene(toml::parse(std::string_view(toml_text), std::string_view(name + ".toml")),
                           name + ".toml");
}

// The paper's Simulation I: R = 0.2 m, v0 = 2 m/s, mu = 0.1.
inline const char* sphere_roll_toml() {
  return R"(
name = "sphere_roll"
[bodies.sphere]
type = "rigid_body"
shape = "sphere"
radius = 0.2
mass = 0.3
position = [0.0, 0.0, 0.2]
velocity = [2.0, 0.0, 0.0]
[impedances.contact]
type = "kikuuwe_contact"
body = "sphere"
mu = 0.1
[camera]
follow = "sphere"
[overlay]
signal = "contact.slip"
label = "slip speed"
unit = "m/s"
trail = true
)";
}

// Closed-form rolling-to-slip motion of Simulation I (no bounce), sampled at 1 kHz: the
// centre decelerates at mu g and the spin (about +y) accelerates at 5 mu g / (2 R) until the
// contact point stops slipping at t = 2 v0 / (7 mu g); then it rolls at 5/7 v0.
inline core::Trajectory sphere_roll_trajectory(double duration = 2.0) {
  core::Trajectory tr({"t", "sphere.p.x", "sphere.p.y", "sphere.p.z", "sphere.q.w", "sphere.q.x",
                       "sphere.q.y", "sphere.q.z", "contact.slip.x", "contact.slip.y",
                       "contact.slip.z"});
  const double R = 0.2, v0 = 2.0, mug = 0.1 * 9.8;
  const double ts = 2.0 * v0 / (7.0 * mug);
  const double alpha = 5.0 * mug / (2.0 * R);
  const int rows = static_cast<int>(duration * 1000.0) + 1;
  for (int i = 0; i < rows; ++i) {
    const double t = i * 1e-3;
    double x, v, phi, w;
    if (t < ts) {
      x = v0 * t - 0.5 * mug * t * t;
      v = v0 - mug * t;
      phi = 0.5 * alpha * t * t;
      w = alpha * t;
    } else {
      const double xs = v0 * ts - 0.5 * mug * ts * ts, vs = v0 - mug * ts;
      const double ps = 0.5 * alpha * ts * ts;
      x = xs + vs * (t - ts);
      v = vs;
      phi = ps + vs / R * (t - ts);
      w = vs / R;
    }
    const double slip = v - w * R;
    const double row[] = {t, x, 0.0, R, std::cos(0.5 * phi), 0.0, std::sin(0.5 * phi), 0.0,
                          slip, 0.0, 0.0};
    tr.append(row);
  }
  return tr;
}

// Simulation II's arm: two 0.2 m x 0.02 m links in the horizontal plane.
inline const char* two_link_toml() {
  return R"(
name = "two_link"
gravity = [0.0, 0.0, 0.0]
[bodies.arm]
type = "planar_arm"
links = [ { length = 0.2, mass = 0.2, width = 0.02 }, { length = 0.2, mass = 0.2, width = 0.02 } ]
[overlay]
signal = "arm.theta.1"
label = "joint 1"
unit = "rad"
)";
}

inline core::Trajectory two_link_trajectory() {
  core::Trajectory tr({"t", "arm.theta.0", "arm.theta.1", "arm.omega.0", "arm.omega.1"});
  for (int i = 0; i <= 1000; ++i) {
    const double t = i * 1e-3;
    const double row[] = {t, 0.3 + 1.2 * t, 0.4 + 0.9 * t, 1.2, 0.9};
    tr.append(row);
  }
  return tr;
}

// Simulation III's arm: the links of two_link as two rigid boxes held by penalty joints (the
// first to the ground at the origin), drawn like the planar arm.
inline const char* two_link_penalty_toml() {
  return R"(
name = "two_link_penalty"
gravity = [0.0, 0.0, 0.0]
[bodies.link0]
type = "rigid_body"
mass = 0.2
shape = "box"
size = [0.2, 0.02, 0.02]
position = [0.1, 0.0, 0.0]
[bodies.link1]
type = "rigid_body"
mass = 0.2
shape = "box"
size = [0.2, 0.02, 0.02]
position = [0.3, 0.0, 0.0]
[impedances.joint0]
type = "penalty_joint"
body = "link0"
point = [-0.1, 0.0, 0.0]
[impedances.joint1]
type = "penalty_joint"
body = "link1"
parent = "link0"
point = [-0.1, 0.0, 0.0]
parent_point = [0.1, 0.0, 0.0]
[overlay]
signal = "joint1.theta"
label = "joint 1"
unit = "rad"
)";
}

// The joint angles of two_link_trajectory, as the two links' poses (centres and rotations
// about z), so the golden shows the same arm as render_two_link.
inline core::Trajectory two_link_penalty_trajectory() {
  core::Trajectory tr({"t", "link0.p.x", "link0.p.y", "link0.p.z", "link0.q.w", "link0.q.x",
                       "link0.q.y", "link0.q.z", "link1.p.x", "link1.p.y", "link1.p.z", "link1.q.w",
                       "link1.q.x", "link1.q.y", "link1.q.z", "joint0.theta", "joint1.theta"});
  for (int i = 0; i <= 1000; ++i) {
    const double t = i * 1e-3;
    const double theta0 = 0.3 + 1.2 * t, theta1 = 0.4 + 0.9 * t;
    const double phi0 = theta0, phi1 = theta0 + theta1;
    const double ex = 0.2 * std::cos(phi0), ey = 0.2 * std::sin(phi0);  // the elbow
    const double row[] = {t,
                          0.5 * ex, 0.5 * ey, 0.0,
                          std::cos(0.5 * phi0), 0.0, 0.0, std::sin(0.5 * phi0),
                          ex + 0.1 * std::cos(phi1), ey + 0.1 * std::sin(phi1), 0.0,
                          std::cos(0.5 * phi1), 0.0, 0.0, std::sin(0.5 * phi1),
                          theta0, theta1};
    tr.append(row);
  }
  return tr;
}

// A point mass at rest on a 20 degree slope (normal tilted towards +x: downhill is +x).
inline std::string slope_hold_toml() {
  const double a = 20.0 * std::numbers::pi / 180.0;
  return "name = \"slope_hold\"\n"
         "[bodies.block]\ntype = \"point_mass\"\nmass = 1.0\nposition = [0.0, 0.0, 0.0]\n"
         "[impedances.contact]\ntype = \"kikuuwe_contact\"\nbody = \"block\"\nmu = 0.5\n"
         "normal = [" + std::to_string(std::sin(a)) + ", 0.0, " + std::to_string(std::cos(a)) + "]\n"
         "[overlay]\nsignal = \"contact.slip\"\nlabel = \"slip speed\"\nunit = \"m/s\"\n";
}

inline core::Trajectory slope_hold_trajectory() {
  core::Trajectory tr({"t", "block.p.x", "block.p.y", "block.p.z", "contact.slip.x",
                       "contact.slip.y", "contact.slip.z"});
  for (int i = 0; i <= 100; ++i) {
    const double row[] = {i * 0.01, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    tr.append(row);
  }
  return tr;
}

}  // namespace stiction::render::testing
