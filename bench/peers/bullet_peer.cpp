// Bullet 3.24, its double-precision build (bullet-float64): btDiscreteDynamicsWorld with its
// defaults (sequential-impulse solver, 10 iterations, split impulse on, sleeping on) at
// 1/60 s (its default fixed step) and 1/240 s, one substep per call. Friction: Bullet
// multiplies the two bodies' coefficients, so the ground has 1 and the body mu; restitution
// 0. A third row at 1/60 s turns sleeping off, to show what holds the box when it is awake.
// Shapes: btStaticPlaneShape, btSphereShape, btBoxShape (its margin lies inside the box).
// The N spheres share one btSphereShape. The pendulum: a box body on a btHingeConstraint to
// the world whose angular motor has target velocity 0 and a largest impulse of F dt per step,
// Bullet's way to model joint friction (no ground: nothing touches the bar). The hold
// benchmark (ramp grid, pinch) keeps the row with sleeping off only: asleep, a body's zero
// creep would be sleep, not friction. The pinch: the block a free box, each finger a box whose
// motion is limited to x (linear factor (1, 0, 0), angular factor 0: Bullet's prismatic
// body), pushed by applyCentralForce before every step; finger friction 1, block mu.
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <memory>
#include <vector>

#include "peer.hpp"

namespace stiction::peers {
namespace {

struct BulletWorld {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  btStaticPlaneShape plane{btVector3(0, 0, 1), 0};
  std::unique_ptr<btCollisionShape> shape, finger_shape;
  std::unique_ptr<btRigidBody> ground;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::unique_ptr<btHingeConstraint> hinge;

  ~BulletWorld() {
    if (hinge) world.removeConstraint(hinge.get());
    for (auto& body : bodies) world.removeRigidBody(body.get());
    if (ground) world.removeRigidBody(ground.get());
  }
};

class BulletPeer final : public Peer {
 public:
  BulletPeer(double dt, bool sleeping) : dt_(dt), sleeping_(sleeping) {}
  std::string engine() const override { return "Bullet 3.24 (double)"; }
  std::string settings() const override {
    return sleeping_ ? "btDiscreteDynamicsWorld defaults" : "defaults, sleeping off";
  }
  double dt() const override { return dt_; }
  bool in_hold_benchmark() const override { return !sleeping_; }

  void reset(const Case& c) override {
    w_.reset();
    w_ = std::make_unique<BulletWorld>();
    double g[3];
    gravity_of(c, g);
    w_->world.setGravity(btVector3(g[0], g[1], g[2]));
    squeeze_ = 0.0;
    if (c.problem == Problem::pendulum) {
      add_pendulum();
      return;
    }
    if (c.problem == Problem::pinch) {
      add_pinch(c);
      return;
    }
    w_->ground = std::make_unique<btRigidBody>(0.0, nullptr, &w_->plane);
    w_->ground->setFriction(1.0);
    w_->ground->setRestitution(0.0);
    w_->world.addRigidBody(w_->ground.get());

    double mass = 0, z = 0;
    const bool spheres = c.problem == Problem::sphere || c.problem == Problem::spheres;
    if (spheres) {
      w_->shape = std::make_unique<btSphereShape>(kSphere.radius);
      mass = kSphere.mass;
      z = kSphere.radius;
    } else {
      const double* s = kBox.size;
      w_->shape = std::make_unique<btBoxShape>(btVector3(s[0] / 2, s[1] / 2, s[2] / 2));
      mass = kBox.mass;
      z = s[2] / 2;
    }
    btVector3 inertia;
    w_->shape->calculateLocalInertia(mass, inertia);
    for (int i = 0; i < c.count; ++i) {
      btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, w_->shape.get(), inertia);
      info.m_startWorldTransform.setOrigin(btVector3(0, spheres ? spheres_lane(i) : 0.0, z));
      info.m_friction = mu_of(c);
      info.m_restitution = 0.0;
      auto body = std::make_unique<btRigidBody>(info);
      if (spheres) body->setLinearVelocity(btVector3(spheres_v0(i, c.count), 0, 0));
      add_body(std::move(body));
    }
  }

  void step() override {
    if (squeeze_ != 0.0) {
      w_->bodies[1]->applyCentralForce(btVector3(squeeze_, 0, 0));
      w_->bodies[2]->applyCentralForce(btVector3(-squeeze_, 0, 0));
    }
    w_->world.stepSimulation(dt_, 1, dt_);
  }

  void read(int i, Sample& s) const override {
    const btRigidBody& body = *w_->bodies[i];
    const btVector3& p = body.getCenterOfMassPosition();
    const btVector3& v = body.getLinearVelocity();
    const btVector3& w = body.getAngularVelocity();
    fill_sample(s, p, v, w);
  }

 private:
  void add_body(std::unique_ptr<btRigidBody> body) {
    if (!sleeping_) body->setActivationState(DISABLE_DEACTIVATION);
    w_->world.addRigidBody(body.get());
    w_->bodies.push_back(std::move(body));
  }

  // The block (body 0) and the fingers at -x (1) and +x (2).
  void add_pinch(const Case& c) {
    const PinchParams& k = kPinch;
    const double h = 0.5 * k.size;
    w_->shape = std::make_unique<btBoxShape>(btVector3(h, h, h));
    w_->finger_shape = std::make_unique<btBoxShape>(
        btVector3(k.finger[0] / 2, k.finger[1] / 2, k.finger[2] / 2));
    btVector3 inertia;
    w_->shape->calculateLocalInertia(k.mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(k.mass, nullptr, w_->shape.get(), inertia);
    info.m_startWorldTransform.setOrigin(btVector3(0, 0, k.height));
    info.m_friction = c.mu;
    info.m_restitution = 0.0;
    add_body(std::make_unique<btRigidBody>(info));
    w_->finger_shape->calculateLocalInertia(k.finger_mass, inertia);
    for (int side : {-1, 1}) {
      btRigidBody::btRigidBodyConstructionInfo finger(k.finger_mass, nullptr,
                                                      w_->finger_shape.get(), inertia);
      finger.m_startWorldTransform.setOrigin(btVector3(side * (k.finger_x() - k.start_overlap), 0, k.height));
      finger.m_friction = 1.0;
      finger.m_restitution = 0.0;
      auto body = std::make_unique<btRigidBody>(finger);
      body->setLinearFactor(btVector3(1, 0, 0));
      body->setAngularFactor(btVector3(0, 0, 0));
      add_body(std::move(body));
    }
    squeeze_ = k.squeeze(c.margin);
  }

  // The bar along its z axis, turned by angle0 about the hinge axis -y at the origin; the
  // hinge at the bar's top end (local z = +l_c).
  void add_pendulum() {
    const PendulumParams& k = kPendulum;
    w_->shape = std::make_unique<btBoxShape>(btVector3(k.width / 2, k.width / 2, k.length / 2));
    btVector3 inertia;
    w_->shape->calculateLocalInertia(k.mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(k.mass, nullptr, w_->shape.get(), inertia);
    info.m_startWorldTransform.setRotation(btQuaternion(btVector3(0, -1, 0), k.angle0));
    info.m_startWorldTransform.setOrigin(
        btVector3(k.com() * std::sin(k.angle0), 0, -k.com() * std::cos(k.angle0)));
    add_body(std::make_unique<btRigidBody>(info));
    w_->hinge = std::make_unique<btHingeConstraint>(*w_->bodies[0], btVector3(0, 0, k.com()),
                                                    btVector3(0, -1, 0));
    w_->hinge->enableAngularMotor(true, 0.0, k.friction * dt_);
    w_->world.addConstraint(w_->hinge.get());
  }

  double dt_;
  bool sleeping_;
  double squeeze_ = 0.0;  // the pinch's force on each finger (N)
  std::unique_ptr<BulletWorld> w_;
};

}  // namespace

void add_bullet_peers(Peers& peers) {
  for (double dt : {1.0 / 60, 1.0 / 240}) peers.push_back(std::make_unique<BulletPeer>(dt, true));
  peers.push_back(std::make_unique<BulletPeer>(1.0 / 60, false));
}

}  // namespace stiction::peers
