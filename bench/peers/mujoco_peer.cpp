// MuJoCo 2.2.2: its default solver (Newton, pyramidal cone, default solref/solimp soft
// contacts) with the Euler integrator (semi-implicit, the default) and with `implicit`
// (implicit in velocity; 2.2.2 has no implicitfast), each at MuJoCo's default step 2 ms and
// at 1/60 s. condim 3 and friction mu on both geoms (MuJoCo takes the larger of the two).
// The model is built from an XML text through a virtual file. The pendulum: a hinge joint with
// frictionloss F (MuJoCo's joint dry friction, a soft constraint like its contacts). The ramp
// grid is the slope box with the case's gravity and mu. The pinch: the block a free box,
// each finger a box on a slide joint along x pushed by qfrc_applied (set once: mj_step keeps
// it), condim 3 and friction mu on all three geoms.
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "peer.hpp"

namespace stiction::peers {
namespace {

// Room for contacts and constraint rows grows with N (2.2.2's defaults, 100 contacts and
// 500 rows, leave all but a tenth of 1000 spheres without contact; a sphere's contact takes
// 4 rows, a pyramid's edges). The N spheres collide
// with the plane only (contype 1 against the plane's conaffinity 1; sphere pairs match no
// bit), as in the other engines where the lanes keep them apart.
std::string model_xml(const Case& c, double dt, const char* integrator) {
  double g[3];
  gravity_of(c, g);
  const double mu = mu_of(c);
  char text[600];
  std::snprintf(text, sizeof text,
                "<mujoco><option timestep='%.17g' gravity='%.17g %.17g %.17g' integrator='%s'/>"
                "<size nconmax='%d' njmax='%d'/><worldbody>",
                dt, g[0], g[1], g[2], integrator, 100 + 2 * c.count, 500 + 4 * c.count);
  std::string xml = text;
  if (c.problem == Problem::pendulum) {
    // The hinge at the body's origin, the bar below it; frictionloss: MuJoCo's dry friction.
    const PendulumParams& k = kPendulum;
    std::snprintf(text, sizeof text,
                  "<body><joint type='hinge' axis='0 -1 0' frictionloss='%.17g'/>"
                  "<geom type='box' size='%.17g %.17g %.17g' pos='0 0 %.17g' mass='%.17g' "
                  "contype='0' conaffinity='0'/></body>",
                  k.friction, k.width / 2, k.width / 2, k.length / 2, -k.com(), k.mass);
    return xml + text + "</worldbody></mujoco>";
  }
  if (c.problem == Problem::pinch) {
    const PinchParams& k = kPinch;
    const double h = 0.5 * k.size;
    std::snprintf(text, sizeof text,
                  "<body pos='0 0 %.17g'><freejoint/><geom type='box' size='%.17g %.17g %.17g' "
                  "mass='%.17g' condim='3' friction='%.17g 0.005 0.0001'/></body>",
                  k.height, h, h, h, k.mass, mu);
    xml += text;
    for (int side : {-1, 1}) {
      std::snprintf(text, sizeof text,
                    "<body pos='%.17g 0 %.17g'><joint type='slide' axis='1 0 0'/><geom type='box' "
                    "size='%.17g %.17g %.17g' mass='%.17g' condim='3' "
                    "friction='%.17g 0.005 0.0001'/></body>",
                    side * (k.finger_x() - k.start_overlap), k.height, k.finger[0] / 2, k.finger[1] / 2,
                    k.finger[2] / 2, k.finger_mass, mu);
      xml += text;
    }
    return xml + "</worldbody></mujoco>";
  }
  std::snprintf(text, sizeof text,
                "<geom type='plane' size='0 0 1' condim='3' friction='%.17g 0.005 0.0001' "
                "contype='0' conaffinity='1'/>",
                mu);
  xml += text;
  for (int i = 0; i < c.count; ++i) {
    if (box_on_plane(c.problem)) {
      const double* s = kBox.size;
      std::snprintf(text, sizeof text,
                    "<body pos='0 0 %.17g'><freejoint/><geom type='box' size='%.17g %.17g %.17g' "
                    "mass='%.17g'",
                    s[2] / 2, s[0] / 2, s[1] / 2, s[2] / 2, kBox.mass);
    } else {
      std::snprintf(text, sizeof text,
                    "<body pos='0 %.17g %.17g'><freejoint/><geom type='sphere' size='%.17g' "
                    "mass='%.17g'",
                    spheres_lane(i), kSphere.radius, kSphere.radius, kSphere.mass);
    }
    xml += text;
    std::snprintf(text, sizeof text,
                  " condim='3' friction='%.17g 0.005 0.0001' contype='1' conaffinity='0'/></body>",
                  mu);
    xml += text;
  }
  return xml + "</worldbody></mujoco>";
}

class MujocoPeer final : public Peer {
 public:
  MujocoPeer(const char* integrator, double dt) : integrator_(integrator), dt_(dt) {}
  ~MujocoPeer() override { destroy(); }
  std::string engine() const override { return "MuJoCo 2.2.2"; }
  std::string settings() const override { return integrator_ + std::string(", default contact"); }
  double dt() const override { return dt_; }

  void reset(const Case& c) override {
    destroy();
    problem_ = c.problem;
    const std::string xml = model_xml(c, dt_, integrator_);
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    mj_makeEmptyFileVFS(vfs.get(), "peer.xml", static_cast<int>(xml.size()));
    std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), "peer.xml")], xml.data(), xml.size());
    char error[500] = "";
    model_ = mj_loadXML("peer.xml", vfs.get(), error, sizeof error);
    mj_deleteVFS(vfs.get());
    if (!model_) throw std::runtime_error(std::string("MuJoCo: ") + error);
    data_ = mj_makeData(model_);
    if (c.problem == Problem::pendulum) {
      data_->qpos[0] = kPendulum.angle0;
    } else if (c.problem == Problem::sphere || c.problem == Problem::spheres) {
      for (int i = 0; i < c.count; ++i) data_->qvel[6 * i] = spheres_v0(i, c.count);
    } else if (c.problem == Problem::pinch) {
      // dofs: the block's free joint (6), then each finger's slide joint.
      const double force = kPinch.squeeze(c.margin);
      data_->qfrc_applied[6] = force;
      data_->qfrc_applied[7] = -force;
    }
  }

  void step() override { mj_step(model_, data_); }

  void read(int i, Sample& s) const override {
    if (problem_ == Problem::pendulum) {
      // From the joint (mj_step leaves the body positions one step behind qpos).
      const double phi = data_->qpos[0], rate = data_->qvel[0], l = kPendulum.com();
      const double p[3] = {l * std::sin(phi), 0.0, -l * std::cos(phi)};
      const double v[3] = {l * rate * std::cos(phi), 0.0, l * rate * std::sin(phi)};
      const double w[3] = {0.0, -rate, 0.0};
      fill_sample(s, p, v, w);
      return;
    }
    if (problem_ == Problem::pinch && i > 0) {
      // Finger i: its slide joint's displacement from its starting x.
      const double side = i == 1 ? -1.0 : 1.0;
      const double p[3] = {side * (kPinch.finger_x() - kPinch.start_overlap) + data_->qpos[6 + i], 0.0, kPinch.height};
      const double v[3] = {data_->qvel[5 + i], 0.0, 0.0}, w[3] = {0.0, 0.0, 0.0};
      fill_sample(s, p, v, w);
      return;
    }
    // Free joint i: qpos = position, quaternion; qvel = world linear velocity, local angular.
    const mjtNum* q = data_->qpos + 7 * i;
    const mjtNum* v = data_->qvel + 6 * i;
    mjtNum w[3];
    mju_rotVecQuat(w, v + 3, q + 3);
    fill_sample(s, q, v, w);
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
  Problem problem_ = Problem::sphere;
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
