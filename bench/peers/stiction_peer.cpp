// stiction: the problems' scenes (bench/peers/scenes/*.toml; the N spheres' scene is written
// here, spheres_scene()) loaded with scene::load_scene and stepped by core::make_stepper's
// stepper, as bench/bench_step.cpp steps them. Rows: the paper's RK4 and symplectic Euler at
// 1e-4 s (explicit: the stiff contacts bound the step), and the implicit integrator at 1e-3,
// 1/240 and 1/60 s where this build has it.
#include <Eigen/Geometry>
#include <cmath>
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

class StictionPeer final : public Peer {
 public:
  StictionPeer(std::string integrator, double dt) : integrator_(std::move(integrator)), dt_(dt) {}
  std::string engine() const override { return "stiction"; }
  std::string settings() const override { return integrator_; }
  double dt() const override { return dt_; }

  void reset(const Case& c) override {
    problem_ = c.problem;
    scene_ = c.problem == Problem::spheres
                 ? scene::load_scene(scene::SceneSource::from_text(spheres_scene(c.count),
                                                                   "spheres.toml"))
                 : scene::load_scene(scene_file(c.problem));
    stepper_ = core::make_stepper(integrator_, scene_.network->state_dim(), dt_);
    x_ = scene_.network->initial_state();
    t_ = 0.0;
    steps_ = 0;
    // Each body's state offset, found by name (the loader's order is not the lanes' order).
    const core::Network& network = *scene_.network;
    bodies_.assign(static_cast<std::size_t>(c.count), 0);
    for (int a = 0; a < static_cast<int>(network.admittances().size()); ++a) {
      const std::string& name = network.admittances()[a]->name();
      for (int i = 0; i < c.count; ++i) {
        if (c.problem != Problem::spheres || name == sphere_name(i))
          bodies_[i] = network.admittance_slot(a).state_offset;
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
  scene::Scene scene_;
  std::unique_ptr<core::Stepper> stepper_;
  core::Vec x_;
  double t_ = 0.0;
  long steps_ = 0;
  Problem problem_ = Problem::sphere;
  std::vector<int> bodies_;                  // state offset of each body
  const core::JointSpace* arm_ = nullptr;  // the pendulum's arm
};

bool available(const std::string& integrator) {
  try {
    core::make_stepper(integrator, 13, 1e-3);
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
}

}  // namespace stiction::peers
