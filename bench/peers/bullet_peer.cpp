// Bullet 3.24, its double-precision build (bullet-float64): btDiscreteDynamicsWorld with its
// defaults (sequential-impulse solver, 10 iterations, split impulse on, sleeping on) at
// 1/60 s (its default fixed step) and 1/240 s, one substep per call. Friction: Bullet
// multiplies the two bodies' coefficients, so the ground has 1 and the body mu; restitution
// 0. A third row at 1/60 s turns sleeping off, to show what holds the box when it is awake.
// Shapes: btStaticPlaneShape, btSphereShape, btBoxShape (its margin lies inside the box).
#include <btBulletDynamicsCommon.h>

#include <memory>

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
  std::unique_ptr<btCollisionShape> shape;
  std::unique_ptr<btRigidBody> ground, body;

  ~BulletWorld() {
    if (body) world.removeRigidBody(body.get());
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

  void reset(Problem problem) override {
    w_.reset();
    w_ = std::make_unique<BulletWorld>();
    double g[3];
    gravity_of(problem, g);
    w_->world.setGravity(btVector3(g[0], g[1], g[2]));
    w_->ground = std::make_unique<btRigidBody>(0.0, nullptr, &w_->plane);
    w_->ground->setFriction(1.0);
    w_->ground->setRestitution(0.0);
    w_->world.addRigidBody(w_->ground.get());

    double mass = 0, z = 0;
    if (problem == Problem::sphere) {
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
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, w_->shape.get(), inertia);
    info.m_startWorldTransform.setOrigin(btVector3(0, 0, z));
    info.m_friction = mu_of(problem);
    info.m_restitution = 0.0;
    w_->body = std::make_unique<btRigidBody>(info);
    if (problem == Problem::sphere) w_->body->setLinearVelocity(btVector3(kSphere.v0, 0, 0));
    if (!sleeping_) w_->body->setActivationState(DISABLE_DEACTIVATION);
    w_->world.addRigidBody(w_->body.get());
  }

  void step() override { w_->world.stepSimulation(dt_, 1, dt_); }

  void read(Sample& s) const override {
    const btVector3& p = w_->body->getCenterOfMassPosition();
    const btVector3& v = w_->body->getLinearVelocity();
    const btVector3& w = w_->body->getAngularVelocity();
    fill_sample(s, p, v, w);
  }

 private:
  double dt_;
  bool sleeping_;
  std::unique_ptr<BulletWorld> w_;
};

}  // namespace

void add_bullet_peers(Peers& peers) {
  for (double dt : {1.0 / 60, 1.0 / 240}) peers.push_back(std::make_unique<BulletPeer>(dt, true));
  peers.push_back(std::make_unique<BulletPeer>(1.0 / 60, false));
}

}  // namespace stiction::peers
