// DART 6.12: its default world (boxed LCP constraint solver with Dantzig, its default contact
// ERP and CFM) at 1/60 and 1/240 s, with DART's own collision detector instead of the default
// FCL (see reset()). The ground is a welded 100 x 100 x 1 m box whose top face is z = 0;
// friction mu and restitution 0 on both shape nodes.
// Not <dart/dart.hpp>: Debian's package lacks the ikfast header it includes.
#include <dart/collision/dart/DARTCollisionDetector.hpp>
#include <dart/constraint/ConstraintSolver.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/SphereShape.hpp>
#include <dart/dynamics/WeldJoint.hpp>
#include <dart/simulation/World.hpp>

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

  void reset(Problem problem) override {
    world_ = simulation::World::create();
    double g[3];
    gravity_of(problem, g);
    world_->setGravity(Eigen::Vector3d(g[0], g[1], g[2]));
    world_->setTimeStep(dt_);
    // DART's own collision detector (exact spheres and boxes): the default FCL meshes the
    // sphere, which then sinks 16 mm and bumps along its facets (stick time off by 0.2 s).
    world_->getConstraintSolver()->setCollisionDetector(collision::DARTCollisionDetector::create());
    const double mu = mu_of(problem);

    auto ground = dynamics::Skeleton::create("ground");
    auto [weld, floor] = ground->createJointAndBodyNodePair<dynamics::WeldJoint>();
    Eigen::Isometry3d below = Eigen::Isometry3d::Identity();
    below.translation() = Eigen::Vector3d(0, 0, -0.5);
    weld->setTransformFromParentBodyNode(below);
    add_shape(floor, std::make_shared<dynamics::BoxShape>(Eigen::Vector3d(100, 100, 1)), mu);
    world_->addSkeleton(ground);

    auto skeleton = dynamics::Skeleton::create("body");
    auto [free, body] = skeleton->createJointAndBodyNodePair<dynamics::FreeJoint>();
    dynamics::ShapePtr shape;
    double mass = 0, z = 0;
    if (problem == Problem::sphere) {
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
    start.translation() = Eigen::Vector3d(0, 0, z);
    free->setPositions(dynamics::FreeJoint::convertToPositions(start));
    if (problem == Problem::sphere) free->setLinearVelocity(Eigen::Vector3d(kSphere.v0, 0, 0));
    world_->addSkeleton(skeleton);
    body_ = body;
  }

  void step() override { world_->step(); }

  void read(Sample& s) const override {
    const Eigen::Vector3d p = body_->getCOM();
    const Eigen::Vector3d v = body_->getCOMLinearVelocity();
    const Eigen::Vector3d w = body_->getAngularVelocity();
    fill_sample(s, p, v, w);
  }

 private:
  double dt_;
  simulation::WorldPtr world_;
  dynamics::BodyNode* body_ = nullptr;
};

}  // namespace

void add_dart_peers(Peers& peers) {
  for (double dt : {1.0 / 60, 1.0 / 240}) peers.push_back(std::make_unique<DartPeer>(dt));
}

}  // namespace stiction::peers
