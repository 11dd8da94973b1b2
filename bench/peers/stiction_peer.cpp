// stiction: the problems' scenes (bench/peers/scenes/*.toml; the N spheres' scene is written
// here, spheres_scene()) loaded with scene::load_scene and stepped by core::make_stepper's
// stepper, as bench/bench_step.cpp steps them. Rows: the paper's RK4 and symplectic Euler at
// 1e-4 s (explicit: the stiff contacts bound the step), and the implicit integrator at 1e-3,
// 1/240 and 1/60 s where this build has it. The hold benchmark (ramp_grid, pinch) keeps rk4
// at 1e-4 s and implicit at 1/60 s; its scenes are written here (ramp_scene, pinch_scene).
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "core/body.hpp"
#include "core/integrator.hpp"
#include "core/network.hpp"
#include "peer.hpp"
#include "scene/scene.hpp"

namespace stiction::peers {
namespace {

std::string scene_file(Problem problem) {
  return std::string(STICTION_PEERS_SCENE_DIR) + "/" + problem_name(problem) + ".toml";
}

std::string sphere_name(int i) {
  char name[16];
  std::snprintf(name, sizeof name, "s%04d", i);
  return name;
}

// Problem 4's scene: scenes/sphere.toml's sphere and contact n times, one per lane.
std::string spheres_scene(int n) {
  std::string text =
      "name = \"peers_spheres\"\n"
      "description = \"bench_peers: N spheres on a plane, stick times spread\"\n"
      "gravity = [0.0, 0.0, -9.81]\n"
      "[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = 1.0\n";
  char block[600];
  for (int i = 0; i < n; ++i) {
    const std::string name = sphere_name(i);
    std::snprintf(block, sizeof block,
                  "[bodies.%s]\ntype = \"rigid_body\"\nmass = %.17g\nshape = \"sphere\"\n"
                  "radius = %.17g\nposition = [0.0, %.17g, %.17g]\nvelocity = [%.17g, 0.0, 0.0]\n"
                  "[impedances.%s_ground]\ntype = \"kikuuwe_contact\"\nbody = \"%s\"\n"
                  "stiffness = %.17g\ndamping = %.17g\nmu = %.17g\nsettle = true\n",
                  name.c_str(), kSphere.mass, kSphere.radius, spheres_lane(i), kSphere.radius,
                  spheres_v0(i, n), name.c_str(), name.c_str(), kSphere.stiffness, kSphere.damping,
                  kSphere.mu);
    text += block;
  }
  return text;
}

std::string vec(double x, double y, double z) {
  char text[96];
  std::snprintf(text, sizeof text, "[%.17g, %.17g, %.17g]", x, y, z);
  return text;
}

// Problem 6's scene at one grid point: scenes/slope_hold.toml's box and contact with the
// case's mu, under gravity tilted by the case's angle.
std::string ramp_scene(const Case& c) {
  double g[3];
  gravity_of(c, g);
  char text[900];
  std::snprintf(text, sizeof text,
                "name = \"peers_ramp\"\ndescription = \"bench_peers: a box on a ramp\"\n"
                "gravity = %s\n[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = 1.0\n"
                "[bodies.box]\ntype = \"rigid_body\"\nmass = %.17g\nshape = \"box\"\n"
                "size = %s\nposition = [0.0, 0.0, %.17g]\n"
                "[impedances.plane]\ntype = \"kikuuwe_contact\"\nbody = \"box\"\n"
                "stiffness = %.17g\ndamping = %.17g\nmu = %.17g\nsettle = true\n",
                vec(g[0], g[1], g[2]).c_str(), kBox.mass,
                vec(kBox.size[0], kBox.size[1], kBox.size[2]).c_str(), 0.5 * kBox.size[2],
                kBox.stiffness, kBox.damping, c.mu);
  return text;
}

// Problem 7's scene: the block between two finger boxes (box-box pair contacts, 16 points
// each, K and B of kPinch per point). Each finger runs in a frictionless channel, its gripper's
// prismatic guide: a floor (mu 0, settled: it carries the finger and the block's weight) under
// its four bottom corners and two walls (mu 0) touching its faces at -y and +y at four
// corners each, so it slides along x alone (without the walls the pair yaws: forces along
// world x on fingers turned about z have a moment that turns them further). A force source
// presses each finger towards the block.
std::string pinch_scene(const Case& c) {
  const PinchParams& k = kPinch;
  const double force = k.squeeze(c.margin);
  const double hx = 0.5 * k.finger[0], hy = 0.5 * k.finger[1], hz = 0.5 * k.finger[2];
  auto corners = [&](int axis, double side) {
    std::string list = "[";
    for (int i = 0; i < 4; ++i) {
      double p[3];
      const double u = i & 1 ? 1.0 : -1.0, v = i & 2 ? 1.0 : -1.0;
      p[axis] = side * (axis == 1 ? hy : hz);
      p[0] = u * hx;
      p[axis == 1 ? 2 : 1] = v * (axis == 1 ? hz : hy);
      list += (i ? ", " : "") + vec(p[0], p[1], p[2]);
    }
    return list + "]";
  };
  std::string text =
      "name = \"peers_pinch\"\ndescription = \"bench_peers: a block pinched between two "
      "fingers\"\ngravity = [0.0, 0.0, -9.81]\n[simulation]\nintegrator = \"rk4\"\n"
      "dt = 1e-4\nduration = 1.0\n";
  char block[1600];
  std::snprintf(block, sizeof block,
                "[bodies.block]\ntype = \"rigid_body\"\nmass = %.17g\nshape = \"box\"\n"
                "size = %s\nposition = [0.0, 0.0, %.17g]\n",
                k.mass, vec(k.size, k.size, k.size).c_str(), k.height);
  text += block;
  for (int side : {-1, 1}) {
    const char* name = side < 0 ? "left" : "right";
    std::snprintf(block, sizeof block,
                  "[bodies.%s]\ntype = \"rigid_body\"\nmass = %.17g\nshape = \"box\"\n"
                  "size = %s\nposition = %s\n"
                  "[impedances.%s_floor]\ntype = \"kikuuwe_contact\"\nbody = \"%s\"\n"
                  "stiffness = %.17g\ndamping = %.17g\nmu = 0.0\nsettle = true\npoints = %s\n"
                  "[impedances.%s_wall_a]\ntype = \"kikuuwe_contact\"\nbody = \"%s\"\n"
                  "normal = [0.0, 1.0, 0.0]\noffset = %.17g\n"
                  "stiffness = %.17g\ndamping = %.17g\nmu = 0.0\npoints = %s\n"
                  "[impedances.%s_wall_b]\ntype = \"kikuuwe_contact\"\nbody = \"%s\"\n"
                  "normal = [0.0, -1.0, 0.0]\noffset = %.17g\n"
                  "stiffness = %.17g\ndamping = %.17g\nmu = 0.0\npoints = %s\n",
                  name, k.finger_mass, vec(k.finger[0], k.finger[1], k.finger[2]).c_str(),
                  vec(side * (k.finger_x() - 0.25 * force / k.stiffness), 0.0, k.height).c_str(),
                  name, name, k.stiffness, k.damping, corners(2, -1.0).c_str(), name, name, -hy,
                  k.stiffness, k.damping, corners(1, -1.0).c_str(), name, name, -hy, k.stiffness,
                  k.damping, corners(1, 1.0).c_str());
    text += block;
    std::snprintf(block, sizeof block,
                  "[impedances.%s_pinch]\ntype = \"kikuuwe_contact\"\nbody = \"block\"\n"
                  "other = \"%s\"\nstiffness = %.17g\ndamping = %.17g\nmu = %.17g\n"
                  "[impedances.%s_squeeze]\ntype = \"force_source\"\nbody = \"%s\"\n"
                  "force = [%.17g, 0.0, 0.0]\n",
                  name, name, k.stiffness, k.damping, c.mu, name, name, -side * force);
    text += block;
  }
  return text;
}

class StictionPeer final : public Peer {
 public:
  // tolerance > 0: an error-controlled integrator (sdirk2, sdirk4), dt its first step and the
  // interval at which the bench reads it.
  StictionPeer(std::string integrator, double dt, double tolerance = 0.0)
      : integrator_(std::move(integrator)), dt_(dt), tolerance_(tolerance) {}
  std::string engine() const override { return "stiction"; }
  std::string settings() const override {
    if (!(tolerance_ > 0.0)) return integrator_;
    char text[64];
    std::snprintf(text, sizeof text, "%s tol %.0e", integrator_.c_str(), tolerance_);
    return text;
  }
  double dt() const override { return dt_; }
  bool in_hold_benchmark() const override {
    return (integrator_ == "rk4" && dt_ == 1e-4) ||
           (integrator_ == "implicit" && std::abs(dt_ - 1.0 / 60) < 1e-12);
  }

  void reset(const Case& c) override {
    problem_ = c.problem;
    switch (c.problem) {
      case Problem::spheres:
        scene_ = scene::load_scene(
            scene::SceneSource::from_text(spheres_scene(c.count), "spheres.toml"));
        break;
      case Problem::ramp_grid:
        scene_ = scene::load_scene(scene::SceneSource::from_text(ramp_scene(c), "ramp.toml"));
        break;
      case Problem::pinch:
        scene_ = scene::load_scene(scene::SceneSource::from_text(pinch_scene(c), "pinch.toml"));
        break;
      default:
        scene_ = scene::load_scene(scene_file(c.problem));
    }
    // With the network: sdirk on several islands steps each on its own (core/island_sdirk.hpp).
    stepper_ = core::make_stepper(integrator_, scene_.network->state_dim(), dt_, tolerance_,
                                  std::numeric_limits<double>::infinity(), scene_.network.get());
    x_ = scene_.network->initial_state();
    t_ = 0.0;
    steps_ = 0;
    // Each body's state offset, found by name (the loader's order is not the lanes' order).
    const core::Network& network = *scene_.network;
    bodies_.assign(static_cast<std::size_t>(c.count), 0);
    for (int a = 0; a < static_cast<int>(network.admittances().size()); ++a) {
      const std::string& name = network.admittances()[a]->name();
      for (int i = 0; i < c.count; ++i) {
        const bool match = c.problem == Problem::spheres ? name == sphere_name(i)
                           : c.problem == Problem::pinch ? name == (i == 0   ? "block"
                                                                    : i == 1 ? "left"
                                                                             : "right")
                                                         : true;
        if (match) bodies_[i] = network.admittance_slot(a).state_offset;
      }
    }
    arm_ = dynamic_cast<const core::JointSpace*>(network.admittances()[0].get());
  }
  // One step of dt_; a stepper that takes shorter steps is advanced until it gets there.
  void step() override {
    const double target = static_cast<double>(++steps_) * dt_;
    while (t_ < target - 1e-9 * dt_) t_ += stepper_->advance(*scene_.network, t_, target - t_, x_);
  }
  void read(int i, Sample& s) const override {
    if (problem_ == Problem::pendulum) {
      // planar_arm about -y: theta from +x towards +z, hanging at -pi/2.
      const double phi = arm_->joint_angle(x_, 0) + 0.5 * std::numbers::pi;
      const double rate = arm_->joint_rate(x_, 0), l = kPendulum.com();
      const double p[3] = {l * std::sin(phi), 0.0, -l * std::cos(phi)};
      const double v[3] = {l * rate * std::cos(phi), 0.0, l * rate * std::sin(phi)};
      const double w[3] = {0.0, -rate, 0.0};
      fill_sample(s, p, v, w);
      return;
    }
    // rigid_body state: p, v, q (w x y z), angular velocity in the body frame.
    const int b = bodies_[i];
    const Eigen::Quaterniond q(x_[b + 6], x_[b + 7], x_[b + 8], x_[b + 9]);
    const Eigen::Vector3d w = q * Eigen::Vector3d(x_.segment<3>(b + 10));
    fill_sample(s, x_.segment<3>(b), x_.segment<3>(b + 3), w);
  }

 private:
  std::string integrator_;
  double dt_;
  double tolerance_;
  scene::Scene scene_;
  std::unique_ptr<core::Stepper> stepper_;
  core::Vec x_;
  double t_ = 0.0;
  long steps_ = 0;
  Problem problem_ = Problem::sphere;
  std::vector<int> bodies_;                // state offset of each body
  const core::JointSpace* arm_ = nullptr;  // the pendulum's arm
};

bool available(const std::string& integrator) {
  try {
    core::make_stepper(integrator, 13, 1e-3, 1e-6);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

}  // namespace

void add_stiction_peers(Peers& peers) {
  peers.push_back(std::make_unique<StictionPeer>("rk4", 1e-4));
  peers.push_back(std::make_unique<StictionPeer>("symplectic_euler", 1e-4));
  if (!available("implicit")) {
    std::printf("implicit: not available in this build\n");
    return;
  }
  for (double dt : {1e-3, 1.0 / 240, 1.0 / 60}) {
    peers.push_back(std::make_unique<StictionPeer>("implicit", dt));
  }
  // The error-controlled implicit methods (issue 36 item 2), read every 1/60 s.
  if (available("sdirk2")) {
    for (const char* name : {"sdirk2", "sdirk4"}) {
      peers.push_back(std::make_unique<StictionPeer>(name, 1.0 / 60, 1e-6));
    }
  }
}

}  // namespace stiction::peers
