// The integrators on the network: Euler reproduces the discrete model (14) step for step;
// observed orders on a smooth case; conservation in torque-free rigid-body flight.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "components/admittance/point_mass.hpp"
#include "components/admittance/rigid_body.hpp"
#include "components/impedance/kikuuwe_friction.hpp"
#include "components/impedance/torque_source.hpp"
#include "components/maps/point_map.hpp"
#include "core/integrator.hpp"
#include "core/simulation.hpp"

using namespace stiction;
using core::Vec;
using core::Vec3;

TEST_CASE("forward Euler on the network reproduces the discrete model (14)", "[integrator]") {
  using namespace components;
  const double M = 1.5, K = 200.0, B = 2.0, F = 0.8, T = 1e-3, push = 0.5;
  core::Network net;
  PointMassParams pm;
  pm.mass = M;
  pm.gravity = Vec3::Zero();
  pm.velocity = Vec3(0.3, 0, 0);
  auto mass = std::make_unique<PointMass>("m", pm);
  const auto& mass_ref = *mass;
  net.add_admittance(std::move(mass));
  net.add_impedance(std::make_unique<KikuuweFriction>("fr", KikuuweFrictionParams{K, B, F, 3}),
                    std::make_unique<PointMap>(mass_ref, Vec3::Zero(), nullptr, Vec3::Zero()));
  // A constant push along x that is below F: the mass slides, then sticks.
  std::vector<TorqueSource::Profile> profiles{[=](double) { return push; },
                                              [](double) { return 0.0; },
                                              [](double) { return 0.0; }};
  net.add_impedance(std::make_unique<TorqueSource>("push", profiles, "f"),
                    std::make_unique<PointMap>(mass_ref, Vec3::Zero(), nullptr, Vec3::Zero()));
  net.finalize();

  core::RungeKuttaStepper euler(core::euler_tableau(), net.state_dim());
  Vec x = net.initial_state();
  // By hand, 1-D: f(k) = gsat(F, (B + T K) v(k) + K e(k-1)); e(k) = (B e(k-1) + T f(k)) /
  // (B + T K); the mass gets push - f(k).
  double p = 0.0, v = 0.3, e = 0.0;
  bool stuck_seen = false;
  for (int k = 0; k < 2000; ++k) {
    double f = (B + T * K) * v + K * e;
    if (std::abs(f) > F) f = F * f / std::abs(f);
    else stuck_seen = true;
    e = (B * e + T * f) / (B + T * K);
    const double a = (push - f) / M;
    p += T * v;
    v += T * a;
    euler.step(net, k * T, T, x);
    REQUIRE(x[0] == Approx(p).margin(1e-13));
    REQUIRE(x[3] == Approx(v).margin(1e-13));
    REQUIRE(x[6] == Approx(e).margin(1e-13));
  }
  CHECK(stuck_seen);
}

namespace {

// Torque-free flight of an asymmetric spinning body: smooth and nonlinear.
std::unique_ptr<core::Network> spinning_body() {
  components::RigidBodyParams rb;
  rb.mass = 1.0;
  rb.inertia = Eigen::Vector3d(0.1, 0.2, 0.3).asDiagonal();
  rb.gravity = Vec3::Zero();
  rb.velocity = Vec3(0.3, -0.2, 0.1);
  rb.angular_velocity = Vec3(1.0, 5.0, 0.5);  // near the unstable middle axis
  auto net = std::make_unique<core::Network>();
  net->add_admittance(std::make_unique<components::RigidBody>("body", rb));
  net->finalize();
  return net;
}

Vec integrate(const std::string& method, double dt, double duration) {
  auto net = spinning_body();
  core::RungeKuttaStepper stepper(core::tableau_by_name(method), net->state_dim());
  Vec x = net->initial_state();
  const long n = std::lround(duration / dt);
  for (long k = 0; k < n; ++k) stepper.step(*net, k * dt, dt, x);
  return x;
}

double observed_order(const std::string& method, double dt) {
  const double duration = 1.0;
  const Vec reference = integrate("rk4", 1e-5, duration);
  const double e1 = (integrate(method, dt, duration) - reference).norm();
  const double e2 = (integrate(method, dt / 2, duration) - reference).norm();
  return std::log2(e1 / e2);
}

}  // namespace

TEST_CASE("observed orders: rk4 about 4, heun about 2, euler about 1", "[integrator]") {
  const double rk4 = observed_order("rk4", 0.01);
  const double heun = observed_order("heun", 0.002);
  const double euler = observed_order("euler", 0.0005);
  std::printf("observed order: rk4 %.3f heun %.3f euler %.3f\n", rk4, heun, euler);
  CHECK(rk4 > 3.8);
  CHECK(rk4 < 4.2);
  CHECK(heun > 1.9);
  CHECK(heun < 2.1);
  CHECK(euler > 0.9);
  CHECK(euler < 1.1);
}

TEST_CASE("torque-free flight conserves energy and angular momentum", "[integrator]") {
  auto net = spinning_body();
  core::RungeKuttaStepper stepper(core::rk4_tableau(), net->state_dim());
  Vec x = net->initial_state();
  const Eigen::Matrix3d J = Eigen::Vector3d(0.1, 0.2, 0.3).asDiagonal();
  auto momentum = [&](const Vec& s) {
    const core::Quat q(s[6], s[7], s[8], s[9]);
    return Vec3(q * (J * Vec3(s.segment<3>(10))));
  };
  const double E0 = net->energy(x);
  const Vec3 L0 = momentum(x);
  for (int k = 0; k < 10000; ++k) stepper.step(*net, k * 1e-3, 1e-3, x);
  CHECK(std::abs(net->energy(x) - E0) / E0 < 1e-8);
  CHECK((momentum(x) - L0).norm() / L0.norm() < 1e-8);
  CHECK(std::abs(Vec(x.segment<4>(6)).norm() - 1.0) < 1e-14);
}
