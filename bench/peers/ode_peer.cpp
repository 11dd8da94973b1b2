// ODE 0.16 (double precision): dWorldStep, the direct (Dantzig LCP) solver, with the world's
// default ERP and CFM, at 1/60 and 1/240 s. Contacts per the ODE manual: dContactApprox1 (mu
// is a coefficient on the normal force, not a force bound) and a soft contact whose
// dContactSoftERP/CFM are the manual's spring-damper equivalents ERP = h K / (h K + B),
// CFM = 1 / (h K + B) with each contact point's K and B of problems.hpp, so ODE's contacts
// have stiction's stiffness. Auto-disable (sleeping) is off, its default. The N spheres share
// a hash space (ODE's choice for many objects: the simple space would test all N^2 pairs).
// The pendulum: a box body on a hinge joint to the world whose motor has target velocity 0
// and maximum torque F, the ODE manual's way to model joint friction. The ramp grid is the
// slope box under the case's gravity and mu. The pinch: the block a free box, each finger a
// box body on a slider joint to the world along x, pushed by dBodyAddForce before every
// step; block-finger contacts as the box's (soft, K and B of kPinch per point).
#include <ode/ode.h>

#include <cmath>
#include <vector>

#include "peer.hpp"

namespace stiction::peers {
namespace {

class OdePeer final : public Peer {
 public:
  explicit OdePeer(double dt) : dt_(dt) {}
  ~OdePeer() override { destroy(); }
  std::string engine() const override { return "ODE 0.16"; }
  std::string settings() const override { return "dWorldStep, soft contact"; }
  double dt() const override { return dt_; }

  void reset(const Case& c) override {
    destroy();
    world_ = dWorldCreate();
    space_ = c.problem == Problem::spheres ? dHashSpaceCreate(nullptr) : dSimpleSpaceCreate(nullptr);
    contacts_ = dJointGroupCreate(0);
    double g[3];
    gravity_of(c, g);
    dWorldSetGravity(world_, g[0], g[1], g[2]);
    bodies_.clear();
    squeeze_ = 0.0;
    if (c.problem == Problem::pendulum) {
      add_pendulum();
      return;
    }
    mu_ = mu_of(c);
    if (c.problem == Problem::pinch) {
      add_pinch(c);
      return;
    }
    dCreatePlane(space_, 0, 0, 1, 0);
    dMass mass;
    if (c.problem == Problem::sphere || c.problem == Problem::spheres) {
      for (int i = 0; i < c.count; ++i) {
        dBodyID body = dBodyCreate(world_);
        dMassSetSphereTotal(&mass, kSphere.mass, kSphere.radius);
        dGeomSetBody(dCreateSphere(space_, kSphere.radius), body);
        dBodySetPosition(body, 0, spheres_lane(i), kSphere.radius);
        dBodySetLinearVel(body, spheres_v0(i, c.count), 0, 0);
        dBodySetMass(body, &mass);
        bodies_.push_back(body);
      }
      stiffness_ = kSphere.stiffness;
      damping_ = kSphere.damping;
    } else {
      dBodyID body = dBodyCreate(world_);
      const double* s = kBox.size;
      dMassSetBoxTotal(&mass, kBox.mass, s[0], s[1], s[2]);
      dGeomSetBody(dCreateBox(space_, s[0], s[1], s[2]), body);
      dBodySetPosition(body, 0, 0, s[2] / 2);
      dBodySetMass(body, &mass);
      bodies_.push_back(body);
      stiffness_ = kBox.stiffness;
      damping_ = kBox.damping;
    }
  }

  void step() override {
    if (squeeze_ != 0.0) {
      dBodyAddForce(bodies_[1], squeeze_, 0, 0);
      dBodyAddForce(bodies_[2], -squeeze_, 0, 0);
    }
    dSpaceCollide(space_, this, &OdePeer::near);
    dWorldStep(world_, dt_);
    dJointGroupEmpty(contacts_);
  }

  void read(int i, Sample& s) const override {
    const dReal* p = dBodyGetPosition(bodies_[i]);
    const dReal* v = dBodyGetLinearVel(bodies_[i]);
    const dReal* w = dBodyGetAngularVel(bodies_[i]);
    fill_sample(s, p, v, w);
  }

 private:
  // The bar along its z axis, turned by angle0 about the hinge axis -y at the origin.
  void add_pendulum() {
    const PendulumParams& k = kPendulum;
    dBodyID body = dBodyCreate(world_);
    dMass mass;
    dMassSetBoxTotal(&mass, k.mass, k.width, k.width, k.length);
    dBodySetMass(body, &mass);
    dMatrix3 rotation;
    dRFromAxisAndAngle(rotation, 0, -1, 0, k.angle0);
    dBodySetRotation(body, rotation);
    dBodySetPosition(body, k.com() * std::sin(k.angle0), 0, -k.com() * std::cos(k.angle0));
    dJointID hinge = dJointCreateHinge(world_, nullptr);
    dJointAttach(hinge, body, nullptr);
    dJointSetHingeAnchor(hinge, 0, 0, 0);
    dJointSetHingeAxis(hinge, 0, -1, 0);
    dJointSetHingeParam(hinge, dParamVel, 0.0);
    dJointSetHingeParam(hinge, dParamFMax, k.friction);
    bodies_.push_back(body);
  }

  // The block (body 0) and the fingers at -x (1) and +x (2), each on a slider along x.
  void add_pinch(const Case& c) {
    const PinchParams& k = kPinch;
    dMass mass;
    dBodyID block = dBodyCreate(world_);
    dMassSetBoxTotal(&mass, k.mass, k.size, k.size, k.size);
    dBodySetMass(block, &mass);
    dGeomSetBody(dCreateBox(space_, k.size, k.size, k.size), block);
    dBodySetPosition(block, 0, 0, k.height);
    bodies_.push_back(block);
    for (int side : {-1, 1}) {
      dBodyID finger = dBodyCreate(world_);
      dMassSetBoxTotal(&mass, k.finger_mass, k.finger[0], k.finger[1], k.finger[2]);
      dBodySetMass(finger, &mass);
      dGeomSetBody(dCreateBox(space_, k.finger[0], k.finger[1], k.finger[2]), finger);
      dBodySetPosition(finger, side * (k.finger_x() - k.start_overlap), 0, k.height);
      dJointID slider = dJointCreateSlider(world_, nullptr);
      dJointAttach(slider, finger, nullptr);
      dJointSetSliderAxis(slider, 1, 0, 0);
      bodies_.push_back(finger);
    }
    squeeze_ = k.squeeze(c.margin);
    stiffness_ = k.stiffness;
    damping_ = k.damping;
  }

  static void near(void* data, dGeomID a, dGeomID b) {
    auto* self = static_cast<OdePeer*>(data);
    dContact contact[8];
    const int n = dCollide(a, b, 8, &contact[0].geom, sizeof(dContact));
    const double hk = self->dt_ * self->stiffness_;
    for (int i = 0; i < n; ++i) {
      contact[i].surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
      contact[i].surface.mu = self->mu_;
      contact[i].surface.soft_erp = hk / (hk + self->damping_);
      contact[i].surface.soft_cfm = 1.0 / (hk + self->damping_);
      dJointID joint = dJointCreateContact(self->world_, self->contacts_, &contact[i]);
      dJointAttach(joint, dGeomGetBody(a), dGeomGetBody(b));
    }
  }

  void destroy() {
    if (!world_) return;
    dJointGroupDestroy(contacts_);
    dSpaceDestroy(space_);  // destroys its geoms
    dWorldDestroy(world_);  // and its bodies
    world_ = nullptr;
  }

  double dt_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  std::vector<dBodyID> bodies_;
  double mu_ = 0, stiffness_ = 0, damping_ = 0;
  double squeeze_ = 0;  // the pinch's force on each finger (N)
};

}  // namespace

void add_ode_peers(Peers& peers) {
  dInitODE2(0);
  for (double dt : {1.0 / 60, 1.0 / 240}) peers.push_back(std::make_unique<OdePeer>(dt));
}

}  // namespace stiction::peers
