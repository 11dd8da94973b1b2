// Siconos 4.4 (Debian's libsiconos-mechanics-dev): nonsmooth contact dynamics, Moreau-Jean
// time stepping (theta 0.5, its examples' choice) with the Coulomb law solved exactly at the
// velocity level each step, at 1/60 and 1/240 s. It expresses the problems whose contacts its
// native relations have:
// - the sphere and the N spheres: a SphereNEDS each (Newton-Euler sphere) with a
//   SphereNEDSPlanR contact on the plane z = 0 and a NewtonImpactFrictionNSL (restitution 0,
//   mu), all solved together by a FrictionContact(3) problem (NSGS, tolerance 1e-10 instead
//   of the default 1e-4: each contact's local solve is then exact to rounding);
// - the pendulum: a one-degree-of-freedom LagrangianDS (the angle, inertia about the hinge,
//   gravity as its internal force) whose rate a RelayNSL bounds: Coulomb friction on the joint
//   is a relay between -F h and F h on the step's impulse (Moreau-Jean's multipliers are
//   impulses: with bounds of +-F the joint held against 24x F), solved by a Relay problem.
// The box on the slope is not expressed: its face contact needs the Bullet-based collision
// of siconos-mechanics (SiconosBulletCollisionManager), a different build of Bullet's
// collision than the one bench_peers measures.
//
// Built as C++17 (CMakeLists.txt): Boost 1.74's uBLAS, under Siconos's matrices, calls
// std::allocator::construct, which C++20 removed.
//
// The mechanics classes must be declared before the kernel's visitor is: MechanicsFwd.hpp
// first, or every mechanics class's visitor hook is ambiguous.
#include <siconos/mechanics/MechanicsFwd.hpp>
// (MechanicsFwd.hpp before the kernel)
#include <siconos/kernel/SiconosKernel.hpp>
#include <siconos/mechanics/SphereNEDS.hpp>
#include <siconos/numerics/SolverOptions.h>
#include <siconos/mechanics/SphereNEDSPlanR.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "peer.hpp"

namespace stiction::peers {
namespace {

// The pendulum's gravity torque as Siconos's internal force (M q'' + F_int = p) and its
// Jacobians, as the C plugin functions LagrangianDS takes.
void gravity_torque(double, unsigned int, double* q, double*, double* f, unsigned int, double*) {
  const PendulumParams& k = kPendulum;
  f[0] = k.mass * kG * k.com() * std::sin(q[0]);
}
void gravity_stiffness(double, unsigned int, double* q, double*, double* j, unsigned int,
                       double*) {
  const PendulumParams& k = kPendulum;
  j[0] = k.mass * kG * k.com() * std::cos(q[0]);
}
void no_damping(double, unsigned int, double*, double*, double* j, unsigned int, double*) {
  j[0] = 0.0;
}

class SiconosPeer final : public Peer {
 public:
  explicit SiconosPeer(double dt) : dt_(dt) {}
  std::string engine() const override { return "Siconos 4.4"; }
  std::string settings() const override { return "Moreau-Jean 0.5, exact Coulomb"; }
  double dt() const override { return dt_; }
  bool expresses(Problem problem) const override {
    return problem == Problem::sphere || problem == Problem::spheres ||
           problem == Problem::pendulum;
  }

  void reset(const Case& c) override {
    try {
      build(c);
    } catch (const std::exception&) {
      throw;
    } catch (...) {  // Siconos throws its own types
      throw std::runtime_error("Siconos refused the model");
    }
  }

  void step() override {
    simulation_->computeOneStep();
    simulation_->nextStep();
  }

  void read(int i, Sample& s) const override {
    if (pendulum_) {
      const double phi = pendulum_->q()->getValue(0);
      const double rate = pendulum_->velocity()->getValue(0), l = kPendulum.com();
      const double p[3] = {l * std::sin(phi), 0.0, -l * std::cos(phi)};
      const double v[3] = {l * rate * std::cos(phi), 0.0, l * rate * std::sin(phi)};
      const double w[3] = {0.0, -rate, 0.0};
      fill_sample(s, p, v, w);
      return;
    }
    // Newton-Euler: q = position, quaternion (w x y z); twist = world velocity, body rate.
    const SiconosVector& q = *spheres_[i]->q();
    const SiconosVector& t = *spheres_[i]->twist();
    const Eigen::Quaterniond rotation(q(3), q(4), q(5), q(6));
    const Eigen::Vector3d w = rotation * Eigen::Vector3d(t(3), t(4), t(5));
    const double p[3] = {q(0), q(1), q(2)}, v[3] = {t(0), t(1), t(2)};
    fill_sample(s, p, v, w);
  }

 private:
  void build(const Case& c) {
    const double end = 1e6;  // stepped by hand; the horizon only bounds the time grid
    auto nsds = std::make_shared<NonSmoothDynamicalSystem>(0.0, end);
    spheres_.clear();
    pendulum_.reset();
    SP::OneStepNSProblem problem;
    if (c.problem == Problem::pendulum) {
      const PendulumParams& k = kPendulum;
      auto q0 = std::make_shared<SiconosVector>(1, k.angle0);
      auto v0 = std::make_shared<SiconosVector>(1, 0.0);
      auto mass = std::make_shared<SimpleMatrix>(1, 1);
      (*mass)(0, 0) = k.inertia();
      pendulum_ = std::make_shared<LagrangianDS>(q0, v0, mass);
      pendulum_->setComputeFIntFunction(gravity_torque);
      pendulum_->setComputeJacobianFIntqFunction(gravity_stiffness);
      pendulum_->setComputeJacobianFIntqDotFunction(no_damping);
      nsds->insertDynamicalSystem(pendulum_);
      auto rate = std::make_shared<SimpleMatrix>(1, 1);
      (*rate)(0, 0) = 1.0;
      // The relation's position-level output is offset far below zero: Moreau-Jean activates
      // an interaction by that output as if it were a contact gap, and with the angle itself
      // (0.2 rad, "open") it left the joint free every other step.
      auto below = std::make_shared<SiconosVector>(1, -1e3);
      auto friction = std::make_shared<Interaction>(
          std::make_shared<RelayNSL>(1, -k.friction * dt_, k.friction * dt_),
          std::make_shared<LagrangianLinearTIR>(rate, below));
      nsds->link(friction, pendulum_);
      problem = std::make_shared<Relay>();
    } else {
      const SphereParams& k = kSphere;
      auto inertia = std::make_shared<SimpleMatrix>(3, 3);
      inertia->eye();
      *inertia *= 0.4 * k.mass * k.radius * k.radius;
      auto law = std::make_shared<NewtonImpactFrictionNSL>(0.0, 0.0, k.mu, 3);
      for (int i = 0; i < c.count; ++i) {
        auto q0 = std::make_shared<SiconosVector>(7);
        (*q0)(1) = spheres_lane(i);
        (*q0)(2) = k.radius;
        (*q0)(3) = 1.0;
        auto v0 = std::make_shared<SiconosVector>(6);
        (*v0)(0) = spheres_v0(i, c.count);
        auto sphere = std::make_shared<SphereNEDS>(k.radius, k.mass, inertia, q0, v0);
        auto weight = std::make_shared<SiconosVector>(3);
        (*weight)(2) = -k.mass * kG;
        sphere->setFExtPtr(weight);
        nsds->insertDynamicalSystem(sphere);
        auto contact = std::make_shared<Interaction>(
            law, std::make_shared<SphereNEDSPlanR>(k.radius, 0.0, 0.0, 1.0, 0.0));
        nsds->link(contact, sphere);
        spheres_.push_back(sphere);
      }
      problem = std::make_shared<FrictionContact>(3);
      problem->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = 1e-10;
      problem->numericsSolverOptions()->iparam[SICONOS_IPARAM_MAX_ITER] = 1000;
    }
    auto integrator = std::make_shared<MoreauJeanOSI>(0.5);
    auto grid = std::make_shared<TimeDiscretisation>(0.0, dt_);
    simulation_ = std::make_shared<TimeStepping>(nsds, grid, integrator, problem);
  }

  double dt_;
  SP::TimeStepping simulation_;
  std::vector<std::shared_ptr<SphereNEDS>> spheres_;
  SP::LagrangianDS pendulum_;
};

}  // namespace

void add_siconos_peers(Peers& peers) {
  for (double dt : {1.0 / 60, 1.0 / 240}) peers.push_back(std::make_unique<SiconosPeer>(dt));
}

}  // namespace stiction::peers
