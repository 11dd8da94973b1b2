// PlanarArm (paper eq. 8): inertia matrix and Coriolis vector against closed forms, energy
// conservation of the free arm under RK4, and the observed order of RK4 on it.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <vector>

#include "components/admittance/planar_arm.hpp"
#include "core/integrator.hpp"
#include "core/network.hpp"

using namespace stiction;
using components::ArmLink;
using components::PlanarArm;
using components::PlanarArmParams;

namespace {

// Unequal links so that a swapped index or a wrong com would show.
PlanarArmParams two_link_params() {
  PlanarArmParams p;
  p.links = {ArmLink{0.3, 0.5, 0.12, 0.004}, ArmLink{0.25, 0.2, 0.1, 0.0015}};
  p.angles = core::Vec(2);
  p.angles << 0.4, -1.1;
  p.rates = core::Vec(2);
  p.rates << 3.0, -5.0;
  return p;
}

struct Dyn {
  Eigen::MatrixXd H;
  core::Vec c;
};

Dyn dynamics_of(const PlanarArm& arm, const core::Vec& theta, const core::Vec& omega) {
  const int n = arm.joint_count();
  Dyn d{Eigen::MatrixXd::Zero(n, n), core::Vec::Zero(n)};
  arm.dynamics(theta, omega, d.H, d.c);
  return d;
}

// Runs the free arm with one integrator; returns the final state. With `samples`, also
// records the state every `sample_period` seconds.
core::Vec run_free(const PlanarArmParams& params, const core::Tableau& tableau, double dt,
                   double duration, double* energy0 = nullptr, double* energy1 = nullptr,
                   std::vector<core::Vec>* samples = nullptr, double sample_period = 0.02) {
  core::Network net;
  net.add_admittance(std::make_unique<PlanarArm>("arm", params));
  net.finalize();
  core::Vec x = net.initial_state();
  if (energy0) *energy0 = net.energy(x);
  core::RungeKuttaStepper stepper(tableau, net.state_dim());
  const long steps = std::lround(duration / dt);
  const long every = std::lround(sample_period / dt);
  for (long k = 0; k < steps; ++k) {
    stepper.step(net, k * dt, dt, x);
    if (samples && (k + 1) % every == 0) samples->push_back(x);
  }
  if (energy1) *energy1 = net.energy(x);
  return x;
}

}  // namespace

TEST_CASE("planar arm: box_link is a uniform box", "[planar_arm]") {
  const ArmLink l = components::box_link(0.2, 0.02, 0.2);
  CHECK(l.com == Approx(0.1));
  CHECK(l.inertia == Approx(0.2 * (0.04 + 0.0004) / 12.0));
}

TEST_CASE("planar arm: one link has H = m c^2 + I and no Coriolis term", "[planar_arm]") {
  PlanarArmParams p;
  p.links = {ArmLink{0.4, 0.7, 0.15, 0.01}};
  PlanarArm arm("arm", p);
  core::Vec theta(1), omega(1);
  theta << 1.3;
  omega << 4.0;
  const Dyn d = dynamics_of(arm, theta, omega);
  CHECK(d.H(0, 0) == Approx(0.7 * 0.15 * 0.15 + 0.01).epsilon(1e-14));
  CHECK(std::abs(d.c[0]) < 1e-14);
}

TEST_CASE("planar arm: two links match the textbook closed form", "[planar_arm]") {
  const PlanarArmParams p = two_link_params();
  PlanarArm arm("arm", p);
  const double m1 = 0.5, l1 = 0.3, lc1 = 0.12, I1 = 0.004;
  const double m2 = 0.2, lc2 = 0.1, I2 = 0.0015;
  for (double q2 : {-2.5, -1.1, 0.0, 0.7, 3.0}) {
    core::Vec theta(2), omega(2);
    theta << 0.9, q2;
    omega << 2.0, -3.5;
    const Dyn d = dynamics_of(arm, theta, omega);
    // Spong, Hutchinson & Vidyasagar, "Robot Modeling and Control", two-link planar arm.
    const double H11 =
        m1 * lc1 * lc1 + I1 + m2 * (l1 * l1 + lc2 * lc2 + 2 * l1 * lc2 * std::cos(q2)) + I2;
    const double H12 = m2 * (lc2 * lc2 + l1 * lc2 * std::cos(q2)) + I2;
    const double H22 = m2 * lc2 * lc2 + I2;
    const double h = -m2 * l1 * lc2 * std::sin(q2);
    const double c1 = h * (2 * omega[0] * omega[1] + omega[1] * omega[1]);
    const double c2 = -h * omega[0] * omega[0];
    INFO("q2 = " << q2);
    CHECK(d.H(0, 0) == Approx(H11).epsilon(1e-13));
    CHECK(d.H(0, 1) == Approx(H12).epsilon(1e-13));
    CHECK(d.H(1, 0) == Approx(H12).epsilon(1e-13));
    CHECK(d.H(1, 1) == Approx(H22).epsilon(1e-13));
    CHECK(d.c[0] == Approx(c1).epsilon(1e-12).margin(1e-14));
    CHECK(d.c[1] == Approx(c2).epsilon(1e-12).margin(1e-14));
  }
}

TEST_CASE("planar arm: H is symmetric positive definite and c = Hdot w - d/dq(wHw)/2",
          "[planar_arm]") {
  // Four unequal links, random-ish configurations: c is checked against the Lagrangian
  // identity c = (dH/dt) omega - 0.5 d/dtheta (omega^T H omega) by central differences,
  // which is independent of the Jacobian formulation used in the component.
  PlanarArmParams p;
  p.links = {ArmLink{0.3, 0.5, 0.12, 0.004}, ArmLink{0.25, 0.2, 0.1, 0.0015},
             ArmLink{0.2, 0.3, 0.05, 0.002}, ArmLink{0.1, 0.1, 0.07, 0.0003}};
  PlanarArm arm("arm", p);
  const int n = 4;
  core::Vec theta(n), omega(n);
  theta << 0.3, -1.2, 2.1, 0.8;
  omega << 1.5, -2.0, 0.7, 3.1;
  const Dyn d = dynamics_of(arm, theta, omega);
  CHECK((d.H - d.H.transpose()).norm() == 0.0);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(d.H);
  INFO("smallest eigenvalue " << eig.eigenvalues().minCoeff());
  CHECK(eig.eigenvalues().minCoeff() > 1e-5);

  const double h = 1e-6;
  core::Vec c_fd = core::Vec::Zero(n);
  for (int k = 0; k < n; ++k) {
    core::Vec tp = theta, tm = theta;
    tp[k] += h;
    tm[k] -= h;
    const Dyn dp = dynamics_of(arm, tp, omega), dm = dynamics_of(arm, tm, omega);
    const Eigen::MatrixXd dH_dk = (dp.H - dm.H) / (2 * h);
    c_fd += omega[k] * dH_dk * omega;           // (dH/dt) omega
    c_fd[k] -= 0.5 * omega.dot(dH_dk * omega);  // -0.5 d/dtheta_k (w^T H w)
  }
  INFO("c = " << d.c.transpose() << ", finite differences " << c_fd.transpose());
  CHECK((d.c - c_fd).norm() < 1e-7 * (1.0 + c_fd.norm()));
}

TEST_CASE("planar arm: derivative solves H omega_dot = tau - c", "[planar_arm]") {
  const PlanarArmParams p = two_link_params();
  PlanarArm arm("arm", p);
  core::Vec x(4), u(2), x_dot(4);
  x << 0.4, -1.1, 3.0, -5.0;
  u << 0.3, -0.2;
  arm.derivative(x, u, x_dot);
  const Dyn d = dynamics_of(arm, x.head(2), x.tail(2));
  CHECK(x_dot.head(2) == x.tail(2));
  CHECK((d.H * x_dot.tail(2) + d.c - u).norm() < 1e-12);
  CHECK(arm.energy(x) == Approx(0.5 * x.tail(2).dot(d.H * x.tail(2))));
}

TEST_CASE("planar arm: signals and labels", "[planar_arm]") {
  PlanarArm arm("arm", two_link_params());
  CHECK(arm.state_labels() == std::vector<std::string>{"theta.0", "theta.1", "omega.0", "omega.1"});
  const auto sig = arm.signals();
  REQUIRE(sig.size() == 2);
  CHECK(sig[0].name == "theta");
  CHECK(sig[1].name == "omega");
  CHECK(sig[0].axes == std::vector<std::string>{"0", "1"});
  CHECK_FALSE(sig[0].unwrap);
  core::Vec x(4), out(4);
  arm.initial_state(x);
  CHECK(x[0] == 0.4);
  CHECK(x[3] == -5.0);
  arm.write_signals(x, out);
  CHECK(out == x);
  CHECK_THROWS_AS(PlanarArm("bad", PlanarArmParams{}), std::invalid_argument);
}

TEST_CASE("planar arm: the free arm conserves energy under RK4", "[planar_arm]") {
  double e0 = 0, e1 = 0;
  run_free(two_link_params(), core::rk4_tableau(), 1e-4, 2.0, &e0, &e1);
  const double rel = std::abs(e1 - e0) / e0;
  INFO("E0 = " << e0 << " J, relative change " << rel);
  CHECK(e0 > 0.0);
  CHECK(rel < 1e-9);
}

TEST_CASE("planar arm: RK4 converges with order 4 on the free arm", "[planar_arm]") {
  // Same 2 s case. The error is the largest deviation from a dt = 1e-4 reference over the
  // whole trajectory (sampled every 0.02 s): the error at one instant can pass near zero
  // (at t = 2 s it does, giving a misleading ratio), its envelope cannot.
  const auto p = two_link_params();
  std::vector<core::Vec> ref;
  run_free(p, core::rk4_tableau(), 1e-4, 2.0, nullptr, nullptr, &ref);
  std::vector<double> errors;
  for (double dt : {4e-3, 2e-3, 1e-3}) {
    std::vector<core::Vec> run;
    run_free(p, core::rk4_tableau(), dt, 2.0, nullptr, nullptr, &run);
    REQUIRE(run.size() == ref.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < run.size(); ++i) worst = std::max(worst, (run[i] - ref[i]).norm());
    errors.push_back(worst);
  }
  const double order1 = std::log2(errors[0] / errors[1]);
  const double order2 = std::log2(errors[1] / errors[2]);
  INFO("max errors " << errors[0] << ", " << errors[1] << ", " << errors[2] << ": orders " << order1
                     << ", " << order2);
  CHECK(order1 == Approx(4.0).margin(0.1));
  CHECK(order2 == Approx(4.0).margin(0.1));
}
