// ODE 0.16 (double precision): dWorldStep, the direct (Dantzig LCP) solver, with the world's
// default ERP and CFM, at 1/60 and 1/240 s. Contacts per the ODE manual: dContactApprox1 (mu
// is a coefficient on the normal force, not a force bound) and a soft contact whose
// dContactSoftERP/CFM are the manual's spring-damper equivalents ERP = h K / (h K + B),
// CFM = 1 / (h K + B) with each contact point's K and B of problems.hpp, so ODE's contacts
// have stiction's stiffness. Auto-disable (sleeping) is off, its default.
#include <ode/ode.h>

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

  void reset(Problem problem) override {
    destroy();
    world_ = dWorldCreate();
    space_ = dSimpleSpaceCreate(nullptr);
    contacts_ = dJointGroupCreate(0);
    double g[3];
    gravity_of(problem, g);
    dWorldSetGravity(world_, g[0], g[1], g[2]);
    dCreatePlane(space_, 0, 0, 1, 0);
    body_ = dBodyCreate(world_);
    dMass mass;
    mu_ = mu_of(problem);
    if (problem == Problem::sphere) {
      dMassSetSphereTotal(&mass, kSphere.mass, kSphere.radius);
      dGeomSetBody(dCreateSphere(space_, kSphere.radius), body_);
      dBodySetPosition(body_, 0, 0, kSphere.radius);
      dBodySetLinearVel(body_, kSphere.v0, 0, 0);
      stiffness_ = kSphere.stiffness;
      damping_ = kSphere.damping;
    } else {
      const double* s = kBox.size;
      dMassSetBoxTotal(&mass, kBox.mass, s[0], s[1], s[2]);
      dGeomSetBody(dCreateBox(space_, s[0], s[1], s[2]), body_);
      dBodySetPosition(body_, 0, 0, s[2] / 2);
      stiffness_ = kBox.stiffness;
      damping_ = kBox.damping;
    }
    dBodySetMass(body_, &mass);
  }

  void step() override {
    dSpaceCollide(space_, this, &OdePeer::near);
    dWorldStep(world_, dt_);
    dJointGroupEmpty(contacts_);
  }

  void read(Sample& s) const override {
    const dReal* p = dBodyGetPosition(body_);
    const dReal* v = dBodyGetLinearVel(body_);
    const dReal* w = dBodyGetAngularVel(body_);
    fill_sample(s, p, v, w);
  }

 private:
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
  dBodyID body_ = nullptr;
  double mu_ = 0, stiffness_ = 0, damping_ = 0;
};

}  // namespace

void add_ode_peers(Peers& peers) {
  dInitODE2(0);
  for (double dt : {1.0 / 60, 1.0 / 240}) peers.push_back(std::make_unique<OdePeer>(dt));
}

}  // namespace stiction::peers
