// stiction: the problems' scenes (bench/peers/scenes/*.toml) loaded with scene::load_scene and
// stepped by core::make_stepper's stepper, as bench/bench_step.cpp steps them. Rows: the
// paper's RK4 and symplectic Euler at 1e-4 s (explicit: the stiff contacts bound the step),
// and the implicit integrator at 1e-3, 1/240 and 1/60 s where this build has it.
#include <Eigen/Geometry>
#include <cstdio>
#include <stdexcept>

#include "core/integrator.hpp"
#include "peer.hpp"
#include "scene/scene.hpp"

namespace stiction::peers {
namespace {

std::string scene_file(Problem problem) {
  return std::string(STICTION_PEERS_SCENE_DIR) + "/" + problem_name(problem) + ".toml";
}

class StictionPeer final : public Peer {
 public:
  StictionPeer(std::string integrator, double dt) : integrator_(std::move(integrator)), dt_(dt) {}
  std::string engine() const override { return "stiction"; }
  std::string settings() const override { return integrator_; }
  double dt() const override { return dt_; }

  void reset(Problem problem) override {
    scene_ = scene::load_scene(scene_file(problem));
    stepper_ = core::make_stepper(integrator_, scene_.network->state_dim(), dt_);
    x_ = scene_.network->initial_state();
    t_ = 0.0;
    steps_ = 0;
    body_ = scene_.network->admittance_slot(0).state_offset;
  }
  // One step of dt_; a stepper that takes shorter steps is advanced until it gets there.
  void step() override {
    const double target = static_cast<double>(++steps_) * dt_;
    while (t_ < target - 1e-9 * dt_) t_ += stepper_->advance(*scene_.network, t_, target - t_, x_);
  }
  void read(Sample& s) const override {
    // rigid_body state: p, v, q (w x y z), angular velocity in the body frame.
    const Eigen::Quaterniond q(x_[body_ + 6], x_[body_ + 7], x_[body_ + 8], x_[body_ + 9]);
    const Eigen::Vector3d w = q * Eigen::Vector3d(x_.segment<3>(body_ + 10));
    fill_sample(s, x_.segment<3>(body_), x_.segment<3>(body_ + 3), w);
  }

 private:
  std::string integrator_;
  double dt_;
  scene::Scene scene_;
  std::unique_ptr<core::Stepper> stepper_;
  core::Vec x_;
  double t_ = 0.0;
  long steps_ = 0;
  int body_ = 0;
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
