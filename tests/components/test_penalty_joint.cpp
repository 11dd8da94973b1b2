// PenaltyJoint + FramePairMap (paper Simulation III): links held together by penalty
// springs, the joint angle signal against the bodies' relative rotation and against the
// constraint-based arm (Simulation II), and friction (19) about the axis.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "components/admittance/planar_arm.hpp"
#include "components/admittance/rigid_body.hpp"
#include "components/impedance/kikuuwe_friction.hpp"
#include "components/impedance/penalty_joint.hpp"
#include "components/impedance/torque_source.hpp"
#include "components/maps/frame_pair_map.hpp"
#include "components/maps/joint_map.hpp"
#include "core/integrator.hpp"
#include "core/network.hpp"

using namespace stiction;
using components::FramePairMap;
using components::PenaltyJoint;
using components::PenaltyJointParams;
using components::RigidBody;
using core::Vec3;

namespace {

constexpr double kPi = std::numbers::pi;

double wrap(double a) { return a - 2 * kPi * std::floor((a + kPi) / (2 * kPi)); }

// A joint motor between the same two frames as a joint: torque tau(t) about world z on the
// child, -tau(t) on the parent (u is what the child exerts on the element: -tau z).
class Motor final : public core::Impedance {
 public:
  explicit Motor(std::function<double(double)> tau)
      : core::Impedance("motor"), tau_(std::move(tau)) {}
  std::string_view type() const override { return "motor"; }
  int input_size() const override { return 26; }
  int output_size() const override { return 6; }
  void evaluate(double t, core::ConstVecRef, core::ConstVecRef, double, core::VecRef u,
                core::VecRef) const override {
    u << 0, 0, 0, 0, 0, -tau_(t);
  }
  std::vector<core::SignalInfo> signals() const override { return {{"tau", {}}}; }
  void write_signals(core::ConstVecRef, core::ConstVecRef, core::ConstVecRef u,
                     core::VecRef out) const override {
    out[0] = -u[5];
  }

 private:
  std::function<double(double)> tau_;
};

// Simulation II/III link: a 0.2 m x 0.02 m x 0.02 m box of 0.2 kg along its body x axis.
components::RigidBodyParams link_at(double x_centre) {
  components::RigidBodyParams p;
  const double m = 0.2, L = 0.2, w = 0.02;
  p.mass = m;
  p.inertia =
      Eigen::Vector3d(m * (w * w + w * w) / 12, m * (L * L + w * w) / 12, m * (L * L + w * w) / 12)
          .asDiagonal();
  p.position = Vec3(x_centre, 0, 0);
  p.gravity = Vec3::Zero();  // DESIGN section 1: gravity off in the arm scenes
  return p;
}

double yaw_of(const core::BodyMotion& m) {
  const core::Mat3 R = m.q.toRotationMatrix();
  return std::atan2(R(1, 0), R(0, 0));
}

// The paper's motor torques (28c)-(28d).
double tau_m0(double t) {
  return t < 4 ? std::min(0.52, 0.3 * t) : 0.336 + 0.144 * std::sin(100 * t);
}
double tau_m1(double t) {
  return t < 4 ? std::min(0.52, 0.5 * t) : 0.336 + 0.144 * std::cos(100 * t);
}

struct Stepper {
  core::Network& net;
  core::Vec x;
  core::RungeKuttaStepper rk;
  double t = 0.0;
  explicit Stepper(core::Network& n)
      : net(n), x(n.initial_state()), rk(core::rk4_tableau(), n.state_dim()) {}
  void step(double dt) {
    rk.step(net, t, dt, x);
    t += dt;
  }
  core::BodyMotion motion(int admittance) const {
    const auto s = net.admittance_slot(admittance);
    return static_cast<const core::Body&>(*net.admittances()[admittance])
        .motion(x.segment(s.state_offset, s.state_size));
  }
  // All signals at the current state, by column name.
  double signal(const std::string& column) {
    const auto cols = net.signal_columns();
    core::Vec row(net.signal_count());
    net.write_signals(t, x, 1e-4, row);
    for (std::size_t i = 0; i < cols.size(); ++i)
      if (cols[i] == column) return row[i];
    FAIL("no column " << column);
    return 0.0;
  }
};

PenaltyJointParams arm_joint() {
  PenaltyJointParams p;  // separation 1e6/200, bending 1e3/0.01 by default
  p.friction_stiffness = 5000.0;
  p.friction_damping = 1.0;
  p.friction_limit = 0.5;
  return p;
}

}  // namespace

TEST_CASE("penalty joint: a two-link chain holds together and follows the arm of Simulation II",
          "[penalty_joint]") {
  // Simulation III: two rigid links, ground-link0 and link0-link1 penalty joints.
  core::Network pen;
  auto l0 = std::make_unique<RigidBody>("link0", link_at(0.1));
  auto l1 = std::make_unique<RigidBody>("link1", link_at(0.3));
  const RigidBody* link0 = l0.get();
  const RigidBody* link1 = l1.get();
  pen.add_admittance(std::move(l0));
  pen.add_admittance(std::move(l1));
  pen.add_impedance(
      std::make_unique<PenaltyJoint>("j0", arm_joint()),
      std::make_unique<FramePairMap>(nullptr, Vec3::Zero(), *link0, Vec3(-0.1, 0, 0)));
  pen.add_impedance(
      std::make_unique<PenaltyJoint>("j1", arm_joint()),
      std::make_unique<FramePairMap>(link0, Vec3(0.1, 0, 0), *link1, Vec3(-0.1, 0, 0)));
  pen.add_impedance(
      std::make_unique<Motor>(tau_m0),
      std::make_unique<FramePairMap>(nullptr, Vec3::Zero(), *link0, Vec3(-0.1, 0, 0)));
  pen.add_impedance(
      std::make_unique<Motor>(tau_m1),
      std::make_unique<FramePairMap>(link0, Vec3(0.1, 0, 0), *link1, Vec3(-0.1, 0, 0)));
  pen.finalize();

  // Simulation II: the same arm with constraint-based dynamics and joint friction.
  core::Network arm_net;
  components::PlanarArmParams ap;
  ap.links = {components::box_link(0.2, 0.02, 0.2), components::box_link(0.2, 0.02, 0.2)};
  auto arm_owner = std::make_unique<components::PlanarArm>("arm", ap);
  const components::PlanarArm& arm = *arm_owner;
  arm_net.add_admittance(std::move(arm_owner));
  const char* friction_names[] = {"f0", "f1"};
  const char* motor_names[] = {"m0", "m1"};
  for (int j = 0; j < 2; ++j) {
    components::KikuuweFrictionParams fp{5000.0, 1.0, 0.5, 1};
    arm_net.add_impedance(std::make_unique<components::KikuuweFriction>(friction_names[j], fp),
                          std::make_unique<components::JointMap>(arm, j));
    arm_net.add_impedance(
        std::make_unique<components::TorqueSource>(
            motor_names[j],
            std::vector<components::TorqueSource::Profile>{j == 0 ? tau_m0 : tau_m1}),
        std::make_unique<components::JointMap>(arm, j));
  }
  arm_net.finalize();

  Stepper p(pen), a(arm_net);
  const double dt = 1e-4;
  double worst_gap = 0.0, worst_signal = 0.0, worst_arm = 0.0, travel = 0.0;
  const int steps = 30000;  // 3 s: both joints break free (t = 1 s and 1.67 s) and turn
  for (int k = 1; k <= steps; ++k) {
    p.step(dt);
    a.step(dt);
    const auto m0 = p.motion(0), m1 = p.motion(1);
    worst_gap = std::max(worst_gap, m0.point(Vec3(-0.1, 0, 0)).norm());
    worst_gap =
        std::max(worst_gap, (m1.point(Vec3(-0.1, 0, 0)) - m0.point(Vec3(0.1, 0, 0))).norm());
    if (k % 100 == 0) {
      const double th0 = p.signal("j0.theta"), th1 = p.signal("j1.theta");
      const double yaw0 = yaw_of(m0), yaw1 = yaw_of(m1);
      worst_signal =
          std::max({worst_signal, std::abs(wrap(th0 - yaw0)), std::abs(wrap(th1 - (yaw1 - yaw0)))});
      worst_arm = std::max({worst_arm, std::abs(wrap(th0 - a.x[0])), std::abs(wrap(th1 - a.x[1]))});
      travel = std::max(travel, std::abs(a.x[0]));
    }
  }
  INFO("max separation " << worst_gap << " m; |theta signal - relative yaw| " << worst_signal
                         << " rad; |penalty - arm| " << worst_arm << " rad; arm joint 0 reached "
                         << travel << " rad");
  CHECK(travel > 1.0);  // the comparison covers real motion, not a stuck arm
  CHECK(worst_gap < 1e-4);
  CHECK(worst_signal < 1e-9);
  CHECK(worst_arm < 1e-3);
}

TEST_CASE("penalty joint: stuck below F without drift, saturates at F above it",
          "[penalty_joint]") {
  // One link hinged to the ground at its end; I about the hinge = Izz + m (L/2)^2.
  const auto body = link_at(0.1);
  const double I_hinge = body.inertia(2, 2) + body.mass * 0.01;
  auto run = [&](std::function<double(double)> motor, double duration, auto&& check) {
    core::Network net;
    auto b = std::make_unique<RigidBody>("link", body);
    const RigidBody* link = b.get();
    net.add_admittance(std::move(b));
    net.add_impedance(
        std::make_unique<PenaltyJoint>("j", arm_joint()),
        std::make_unique<FramePairMap>(nullptr, Vec3::Zero(), *link, Vec3(-0.1, 0, 0)));
    net.add_impedance(
        std::make_unique<Motor>(std::move(motor)),
        std::make_unique<FramePairMap>(nullptr, Vec3::Zero(), *link, Vec3(-0.1, 0, 0)));
    net.finalize();
    Stepper s(net);
    const long steps = std::lround(duration / 1e-4);
    for (long k = 0; k < steps; ++k) s.step(1e-4);
    check(s);
  };

  SECTION("0.3 Nm < F: the joint sticks and theta - e stays put") {
    double anchor_half = 0.0;
    run([](double t) { return std::min(0.3, 3.0 * t); }, 0.5,
        [&](Stepper& s) { anchor_half = s.signal("j.theta") - s.signal("j.e"); });
    run([](double t) { return std::min(0.3, 3.0 * t); }, 1.0,
        [&](Stepper& s) {
          const double theta = s.signal("j.theta"), e = s.signal("j.e");
          INFO("theta " << theta << ", e " << e << ", tau " << s.signal("j.tau")
                        << ", anchor drift 0.5-1 s " << (theta - e) - anchor_half);
          CHECK(theta == Approx(0.3 / 5000.0).epsilon(1e-3));
          CHECK(s.signal("j.tau") == Approx(-0.3).epsilon(1e-6));
          CHECK(std::abs((theta - e) - anchor_half) < 1e-10);
        });
  }
  SECTION("0.8 Nm > F: friction torque is exactly F, the link accelerates at (0.8 - F)/I") {
    run([](double) { return 0.8; }, 0.3,
        [&](Stepper& s) {
          const double omega = s.signal("j.omega"), tau = s.signal("j.tau"),
                       theta = s.signal("j.theta");
          const double yaw = yaw_of(s.motion(0));
          INFO("omega " << omega << " (expected about " << 0.3 * 0.3 / I_hinge << "), tau " << tau
                        << ", theta " << theta << ", yaw " << yaw);
          CHECK(std::abs(tau + 0.5) < 1e-12);  // on the child, opposite to its rotation
          CHECK(omega == Approx(0.3 * 0.3 / I_hinge).epsilon(0.01));
          CHECK(theta >= -kPi);
          CHECK(theta < kPi);
          CHECK(std::abs(wrap(theta - yaw)) < 1e-9);
          CHECK(std::abs(theta - yaw) < 1e-9);  // past one half turn: the signal is wrapped
        });
  }
}

TEST_CASE("penalty joint: friction decelerates a spinning link at F / I", "[penalty_joint]") {
  auto body = link_at(0.1);
  const double I_hinge = body.inertia(2, 2) + body.mass * 0.01;
  body.angular_velocity = Vec3(0, 0, 10.0);
  body.velocity = Vec3(0, 1.0, 0);  // w x (p - hinge): turning about the hinge
  core::Network net;
  auto b = std::make_unique<RigidBody>("link", body);
  const RigidBody* link = b.get();
  net.add_admittance(std::move(b));
  net.add_impedance(std::make_unique<PenaltyJoint>("j", arm_joint()),
                    std::make_unique<FramePairMap>(nullptr, Vec3::Zero(), *link, Vec3(-0.1, 0, 0)));
  net.finalize();
  Stepper s(net);
  for (int k = 0; k < 300; ++k) s.step(1e-4);
  const double omega = s.signal("j.omega");
  INFO("omega(0.03 s) " << omega << ", expected " << 10.0 - 0.5 / I_hinge * 0.03 << ", tau "
                        << s.signal("j.tau"));
  CHECK(omega == Approx(10.0 - 0.5 / I_hinge * 0.03).epsilon(0.01));
  CHECK(s.signal("j.tau") == Approx(-0.5).epsilon(1e-12));
  for (int k = 0; k < 2000; ++k) s.step(1e-4);
  INFO("omega(0.23 s) " << s.signal("j.omega"));
  CHECK(std::abs(s.signal("j.omega")) < 1e-3);  // it stopped near 10 I / F = 0.053 s
}

TEST_CASE("penalty joint: restoring separation force and bending torque", "[penalty_joint]") {
  PenaltyJointParams params;
  params.friction_limit = 0.0;
  PenaltyJoint joint("j", params);
  core::Vec x_hat = core::Vec::Zero(26), y = core::Vec::Zero(1), u(6), y_dot(1);
  x_hat[6] = x_hat[19] = 1.0;                       // identity quaternions
  x_hat.segment<3>(0) = Vec3(1e-3, -2e-3, 0.5e-3);  // child point displaced
  // Child tilted by 0.01 rad about world x: its z axis leans toward -y.
  const core::Quat tilt(Eigen::AngleAxisd(0.01, Vec3::UnitX()));
  x_hat.segment<4>(6) << tilt.w(), tilt.x(), tilt.y(), tilt.z();
  joint.evaluate(0.0, x_hat, y, 1e-4, u, y_dot);
  // u is what the child exerts: the child receives -u, back toward the parent's point.
  CHECK((u.head<3>() - 1e6 * Vec3(1e-3, -2e-3, 0.5e-3)).norm() < 1e-9);
  // Bending: 1e3 * 0.01 about +x; the child receives -10 mNm about x, tilting it back.
  CHECK((u.tail<3>() - Vec3(10.0, 0, 0)).norm() < 1e-9);
  CHECK(y_dot[0] == 0.0);
  y[0] = 2e-3;
  CHECK(joint.stored_energy(x_hat, y) ==
        Approx(0.5 * (1e6 * 5.25e-6 + 1e3 * 1e-4 + 5000.0 * 4e-6)).epsilon(1e-9));
  CHECK_THROWS_AS(PenaltyJoint("bad",
                               [] {
                                 PenaltyJointParams p;
                                 p.axis_child = Vec3::Zero();
                                 return p;
                               }()),
                  std::invalid_argument);
}
