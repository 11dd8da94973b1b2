// MuJoCo 2.2.2: its default solver (Newton, pyramidal cone, default solref/solimp soft
// contacts) with the Euler integrator (semi-implicit, the default) and with `implicit`
// (implicit in velocity; 2.2.2 has no implicitfast), each at MuJoCo's default step 2 ms and
// at 1/60 s. condim 3 and friction mu on both geoms (MuJoCo takes the larger of the two).
// The model is built from an XML text through a virtual file.
#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "peer.hpp"

namespace stiction::peers {
namespace {

std::string model_xml(Problem problem, double dt, const char* integrator) {
  double g[3];
  gravity_of(problem, g);
  const double mu = mu_of(problem);
  char geom[200];
  if (problem == Problem::sphere) {
    std::snprintf(geom, sizeof geom,
                  "pos='0 0 %.17g'><freejoint/><geom type='sphere' size='%.17g' mass='%.17g'",
                  kSphere.radius, kSphere.radius, kSphere.mass);
  } else {
    const double* s = kBox.size;
    std::snprintf(
        geom, sizeof geom,
        "pos='0 0 %.17g'><freejoint/><geom type='box' size='%.17g %.17g %.17g' mass='%.17g'",
        s[2] / 2, s[0] / 2, s[1] / 2, s[2] / 2, kBox.mass);
  }
  char xml[1000];
  std::snprintf(
      xml, sizeof xml,
      "<mujoco><option timestep='%.17g' gravity='%.17g %.17g %.17g' integrator='%s'/>"
      "<worldbody><geom type='plane' size='0 0 1' condim='3' friction='%.17g 0.005 0.0001'/>"
      "<body %s condim='3' friction='%.17g 0.005 0.0001'/></body></worldbody></mujoco>",
      dt, g[0], g[1], g[2], integrator, mu, geom, mu);
  return xml;
}

class MujocoPeer final : public Peer {
 public:
  MujocoPeer(const char* integrator, double dt) : integrator_(integrator), dt_(dt) {}
  ~MujocoPeer() override { destroy(); }
  std::string engine() const override { return "MuJoCo 2.2.2"; }
  std::string settings() const override { return integrator_ + std::string(", default contact"); }
  double dt() const override { return dt_; }

  void reset(Problem problem) override {
    destroy();
    const std::string xml = model_xml(problem, dt_, integrator_);
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    mj_makeEmptyFileVFS(vfs.get(), "peer.xml", static_cast<int>(xml.size()));
    std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), "peer.xml")], xml.data(), xml.size());
    char error[500] = "";
    model_ = mj_loadXML("peer.xml", vfs.get(), error, sizeof error);
    mj_deleteVFS(vfs.get());
    if (!model_) throw std::runtime_error(std::string("MuJoCo: ") + error);
    data_ = mj_makeData(model_);
    if (problem == Problem::sphere) data_->qvel[0] = kSphere.v0;
  }

  void step() override { mj_step(model_, data_); }

  void read(Sample& s) const override {
    // Free joint: qpos = position, quaternion; qvel = world linear velocity, local angular.
    mjtNum w[3];
    mju_rotVecQuat(w, data_->qvel + 3, data_->qpos + 3);
    fill_sample(s, data_->qpos, data_->qvel, w);
  }

 private:
  void destroy() {
    if (data_) mj_deleteData(data_);
    if (model_) mj_deleteModel(model_);
    data_ = nullptr;
    model_ = nullptr;
  }

  const char* integrator_;
  double dt_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
};

}  // namespace

void add_mujoco_peers(Peers& peers) {
  for (const char* integrator : {"Euler", "implicit"}) {
    for (double dt : {0.002, 1.0 / 60})
      peers.push_back(std::make_unique<MujocoPeer>(integrator, dt));
  }
}

}  // namespace stiction::peers
