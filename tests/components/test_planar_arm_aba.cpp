// The O(n) articulated-body forward dynamics of PlanarArm against the mass-matrix method
// (H from dynamics(), Cholesky solve) on random arms and states, n = 1..64: the same joint
// accelerations to rounding, and the O(n) kinetic energy against 0.5 omega^T H omega.
#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "components/admittance/planar_arm.hpp"

using namespace stiction;
using components::ArmLink;
using components::PlanarArm;
using components::PlanarArmParams;

TEST_CASE("planar arm: articulated-body dynamics equal the mass-matrix solve, n = 1..64") {
  std::mt19937 rng(20261130);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto between = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  double worst = 0.0, worst_residual = 0.0;
  for (int n = 1; n <= 64; ++n) {
    for (int trial = 0; trial < 3; ++trial) {
      PlanarArmParams p;
      for (int i = 0; i < n; ++i) {
        ArmLink l;
        l.length = between(0.05, 0.5);
        l.mass = between(0.05, 2.0);
        l.com = between(-0.2, 1.2) * l.length;              // also outside the link
        l.inertia = trial == 2 ? 0.0 : between(0.0, 0.02);  // point masses too
        p.links.push_back(l);
      }
      p.base = core::Vec3(between(-1, 1), between(-1, 1), 0.0);
      const PlanarArm arm("arm", p);
      core::Vec theta(n), omega(n), tau(n);
      for (int i = 0; i < n; ++i) {
        theta[i] = between(-3.2, 3.2);
        omega[i] = between(-4.0, 4.0);
        tau[i] = between(-2.0, 2.0);
      }
      Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
      core::Vec c = core::Vec::Zero(n);
      arm.dynamics(theta, omega, H, c);
      const core::Vec reference = H.llt().solve(tau - c);
      core::Vec qdd(n);
      arm.forward_dynamics(theta, omega, tau, qdd);

      // Rounding in either method is amplified by the conditioning of H; measure the
      // difference in H's own norm (the residual of the equations of motion), which is
      // what both methods solve, and the plain difference relative to the solution.
      const double scale = (tau - c).norm() + H.norm() * reference.norm();
      const double residual = (H * qdd + c - tau).norm() / scale;
      const double residual_ref = (H * reference + c - tau).norm() / scale;
      INFO("n = " << n << ", trial " << trial << ": residual " << residual << " (mass-matrix "
                  << residual_ref << ")");
      CHECK(residual < 1e-13);
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(H);
      const double condition = svd.singularValues()(0) / svd.singularValues()(n - 1);
      const double relative = (qdd - reference).norm() / reference.norm();
      worst = std::max(worst, relative / condition);
      worst_residual = std::max(worst_residual, residual);
      CHECK(relative < 1e-13 * condition);

      const double energy = 0.5 * omega.dot(H * omega);
      CHECK(std::abs(arm.kinetic_energy(theta, omega) - energy) <= 1e-12 * energy);
    }
  }
  // Measured: 1.5e-14 and 7.7e-15, i.e. a few dozen ulps.
  INFO("largest relative difference / cond(H): " << worst << "; largest residual "
                                                 << worst_residual);
  CHECK(worst < 1e-13);
  CHECK(worst_residual < 1e-13);
}
