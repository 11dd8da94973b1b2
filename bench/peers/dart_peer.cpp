// DART 6.12: its default world (boxed LCP constraint solver with Dantzig, its default contact
// ERP and CFM) at 1/60 and 1/240 s, with DART's own collision detector instead of the default
// FCL (see reset()). The ground is a welded 100 x 100 x 1 m box (wider for the N spheres'
// lanes) whose top face is z = 0;
// friction mu and restitution 0 on both shape nodes. The N spheres are a skeleton each. The
// pendulum: a bar on a RevoluteJoint to the world with Coulomb joint friction F
// (setCoulombFriction, which DART's constraint solver bounds like a contact's friction).
// The ramp grid is the slope box with the case's gravity and mu. The pinch: the block a
// FreeJoint skeleton, each finger a skeleton on a PrismaticJoint to the world along x whose
// joint force is set before every step (World::step resets it), friction mu on all three.
// Not <dart/dart.hpp>: Debian's package lacks the ikfast header it includes.
#include <dart/collision/dart/DARTCollisionDetector.hpp>
#include <dart/constraint/ConstraintSolver.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/PrismaticJoint.hpp>
#include <dart/dynamics/RevoluteJoint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/SphereShape.hpp>
#include <dart/dynamics/WeldJoint.hpp>
#include <dart/simulation/World.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "peer.hpp"

namespace stiction::peers {
namespace {

using namespace dart;

dynamics::ShapeNode* add_shape(dynamics::BodyNode* body, const dynamics::ShapePtr& shape,
                               double mu) {
  auto* node =
      body->createShapeNodeWith<dynamics::CollisionAspect, dynamics::DynamicsAspect>(shape);
  node->getDynamicsAspect()->setFrictionCoeff(mu);
  node->getDynamicsAspect()->setRestitutionCoeff(0.0);
  return node;
}

class DartPeer final : public Peer {
 public:
  explicit DartPeer(double dt) : dt_(dt) {}
  std::string engine() const override { return "DART 6.12"; }
  std::string settings() const override { return "Dantzig LCP, DART collision"; }
  double dt() const override { return dt_; }

  void reset(const Case& c) override {
    world_ = simulation::World::create();
    double g[3];
    gravity_of(c, g);
    world_->setGravity(Eigen::Vector3d(g[0], g[1], g[2]));
    world_->setTimeStep(dt_);
    bodies_.clear();
    fingers_.clear();
    if (c.problem == Problem::pendulum) {
      add_pendulum();
      return;
    }
    // DART's own collision detector (exact spheres and boxes): the default FCL meshes the
    // sphere, which then sinks 16 mm and bumps along its facets (stick time off by 0.2 s).
    world_->getConstraintSolver()->setCollisionDetector(collision::DARTCollisionDetector::create());
    // DART keeps at most 1000 contacts per step by default: room for every sphere's.
    world_->getConstraintSolver()->getCollisionOption().maxNumContacts =
        std::max<std::size_t>(1000u, 4u * static_cast<std::size_t>(c.count));
    const double mu = mu_of(c);
    if (c.problem == Problem::pinch) {
      add_pinch(c);
      return;
    }

    auto ground = dynamics::Skeleton::create("ground");
    auto [weld, floor] = ground->createJointAndBodyNodePair<dynamics::WeldJoint>();
    Eigen::Isometry3d below = Eigen::Isometry3d::Identity();
    below.translation() = Eigen::Vector3d(0, 0, -0.5);
    weld->setTransformFromParentBodyNode(below);
    // Wide enough for every lane (1000 spheres reach y = 500 m).
    const double width = 100.0 + 2.0 * spheres_lane(c.count);
    add_shape(floor, std::make_shared<dynamics::BoxShape>(Eigen::Vector3d(width, width, 1)), mu);
    world_->addSkeleton(ground);

    const bool spheres = c.problem == Problem::sphere || c.problem == Problem::spheres;
    for (int i = 0; i < c.count; ++i) {
      auto skeleton = dynamics::Skeleton::create("body" + std::to_string(i));
      auto [free, body] = skeleton->createJointAndBodyNodePair<dynamics::FreeJoint>();
      dynamics::ShapePtr shape;
      double mass = 0, z = 0;
      if (spheres) {
        shape = std::make_shared<dynamics::SphereShape>(kSphere.radius);
        mass = kSphere.mass;
        z = kSphere.radius;
      } else {
        shape = std::make_shared<dynamics::BoxShape>(
            Eigen::Vector3d(kBox.size[0], kBox.size[1], kBox.size[2]));
        mass = kBox.mass;
        z = kBox.size[2] / 2;
      }
      add_shape(body, shape, mu);
      dynamics::Inertia inertia;
      inertia.setMass(mass);
      inertia.setMoment(shape->computeInertia(mass));
      body->setInertia(inertia);
      Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
      start.translation() = Eigen::Vector3d(0, spheres ? spheres_lane(i) : 0.0, z);
      free->setPositions(dynamics::FreeJoint::convertToPositions(start));
      if (spheres) free->setLinearVelocity(Eigen::Vector3d(spheres_v0(i, c.count), 0, 0));
      world_->addSkeleton(skeleton);
      bodies_.push_back(body);
    }
  }

  void step() override {
    for (std::size_t f = 0; f < fingers_.size(); ++f)
      fingers_[f]->setForce(0, (f == 0 ? 1.0 : -1.0) * squeeze_);
    world_->step();
  }

  void read(int i, Sample& s) const override {
    const Eigen::Vector3d p = bodies_[i]->getCOM();
    const Eigen::Vector3d v = bodies_[i]->getCOMLinearVelocity();
    const Eigen::Vector3d w = bodies_[i]->getAngularVelocity();
    fill_sample(s, p, v, w);
  }

 private:
  // The block (body 0) and the fingers at -x (1) and +x (2).
  void add_pinch(const Case& c) {
    const PinchParams& k = kPinch;
    auto block = dynamics::Skeleton::create("block");
    auto [free, body] = block->createJointAndBodyNodePair<dynamics::FreeJoint>();
    auto cube = std::make_shared<dynamics::BoxShape>(Eigen::Vector3d::Constant(k.size));
    add_shape(body, cube, c.mu);
    dynamics::Inertia inertia;
    inertia.setMass(k.mass);
    inertia.setMoment(cube->computeInertia(k.mass));
    body->setInertia(inertia);
    Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
    start.translation() = Eigen::Vector3d(0, 0, k.height);
    free->setPositions(dynamics::FreeJoint::convertToPositions(start));
    world_->addSkeleton(block);
    bodies_.push_back(body);
    for (int side : {-1, 1}) {
      auto skeleton = dynamics::Skeleton::create(side < 0 ? "left" : "right");
      dynamics::PrismaticJoint::Properties joint;
      joint.mAxis = Eigen::Vector3d::UnitX();
      joint.mT_ParentBodyToJoint.translation() = Eigen::Vector3d(side * (k.finger_x() - k.start_overlap), 0, k.height);
      auto [slider, finger] =
          skeleton->createJointAndBodyNodePair<dynamics::PrismaticJoint>(nullptr, joint);
      auto shape = std::make_shared<dynamics::BoxShape>(
          Eigen::Vector3d(k.finger[0], k.finger[1], k.finger[2]));
      add_shape(finger, shape, c.mu);
      dynamics::Inertia moments;
      moments.setMass(k.finger_mass);
      moments.setMoment(shape->computeInertia(k.finger_mass));
      finger->setInertia(moments);
      world_->addSkeleton(skeleton);
      bodies_.push_back(finger);
      fingers_.push_back(slider);
    }
    squeeze_ = k.squeeze(c.margin);
  }

  // The bar's frame at its centre, the hinge (axis -y) at its top end (local z = +l_c) and
  // at the world origin; no shape (nothing touches it), the box's inertia set directly.
  void add_pendulum() {
    const PendulumParams& k = kPendulum;
    auto skeleton = dynamics::Skeleton::create("pendulum");
    dynamics::RevoluteJoint::Properties joint;
    joint.mAxis = Eigen::Vector3d(0, -1, 0);
    joint.mT_ChildBodyToJoint.translation() = Eigen::Vector3d(0, 0, k.com());
    auto [hinge, bar] = skeleton->createJointAndBodyNodePair<dynamics::RevoluteJoint>(
        nullptr, joint);
    dynamics::Inertia inertia;
    inertia.setMass(k.mass);
    inertia.setMoment(
        dynamics::BoxShape::computeInertia(Eigen::Vector3d(k.width, k.width, k.length), k.mass));
    bar->setInertia(inertia);
    hinge->setCoulombFriction(0, k.friction);
    hinge->setPosition(0, k.angle0);
    world_->addSkeleton(skeleton);
    bodies_.push_back(bar);
  }

  double dt_;
  simulation::WorldPtr world_;
  std::vector<dynamics::BodyNode*> bodies_;
  std::vector<dynamics::PrismaticJoint*> fingers_;  // the pinch's, at -x then +x
  double squeeze_ = 0.0;                            // the pinch's force on each finger (N)
};

}  // namespace

void add_dart_peers(Peers& peers) {
  for (double dt : {1.0 / 60, 1.0 / 240}) peers.push_back(std::make_unique<DartPeer>(dt));
}

}  // namespace stiction::peers
