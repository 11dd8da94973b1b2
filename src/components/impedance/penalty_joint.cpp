#include "components/impedance/penalty_joint.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "components/impedance/kikuuwe_friction.hpp"

namespace stiction::components {

using core::Quat;
using core::Vec3;

namespace {

struct Frame {
  Vec3 p, v, w;
  Quat q;
};

Frame frame_at(core::ConstVecRef x_hat, int offset) {
  Frame f;
  f.p = x_hat.segment<3>(offset);
  f.v = x_hat.segment<3>(offset + 3);
  f.q = Quat(x_hat[offset + 6], x_hat[offset + 7], x_hat[offset + 8], x_hat[offset + 9]);
  f.w = x_hat.segment<3>(offset + 10);
  return f;
}

// Wraps an angle into [-pi, pi).
double wrap_angle(double a) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  return a - two_pi * std::floor((a + std::numbers::pi) / two_pi);
}

}  // namespace

PenaltyJoint::PenaltyJoint(std::string name, const PenaltyJointParams& params)
    : core::Impedance(std::move(name)),
      core::StiffnessHint(params.separation_stiffness, params.separation_damping),
      params_(params) {
  const auto& p = params_;
  auto fail = [this](const std::string& what) {
    throw std::invalid_argument("penalty_joint '" + this->name() + "': " + what);
  };
  if (!(p.axis_child.norm() > 0.0) || !(p.axis_parent.norm() > 0.0)) fail("axes must be nonzero");
  if (!(p.separation_stiffness >= 0.0) || !(p.separation_damping >= 0.0) ||
      !(p.bending_stiffness >= 0.0) || !(p.bending_damping >= 0.0)) {
    fail("separation and bending stiffness/damping must be >= 0");
  }
  // Kf > 0 keeps (Bf + tau Kf) > 0 in (19c) for every stage.
  if (!(p.friction_stiffness > 0.0) || !(p.friction_damping >= 0.0) || !(p.friction_limit >= 0.0)) {
    fail("friction needs stiffness > 0, damping >= 0, limit >= 0");
  }
  if (!(std::abs(p.reference.norm() - 1.0) < 1e-6)) fail("reference must be a unit quaternion");
  params_.axis_child.normalize();
  params_.axis_parent.normalize();
  params_.reference.normalize();
  reference_inverse_ = params_.reference.conjugate();
}

namespace {

// The mean joint axis in the world; falls back to the parent's axis when the two are
// opposite (the bending spring then has no preferred direction either).
Vec3 mean_axis(const Vec3& a_c, const Vec3& a_p) {
  const Vec3 s = a_c + a_p;
  const double norm = s.norm();
  return norm > 1e-9 ? Vec3(s / norm) : a_p;
}

}  // namespace

namespace {

// The parts of u that are not friction, and the friction's input about the axis.
struct JointLaw {
  Vec3 separation;  // force: Ks d + Bs d_dot
  Vec3 bending;     // torque perpendicular to n
  Vec3 n;           // mean axis
  double omega;     // relative rate about n
};

JointLaw joint_law(const PenaltyJointParams& p, core::ConstVecRef x_hat) {
  const Frame c = frame_at(x_hat, 0);
  const Frame b = frame_at(x_hat, 13);
  JointLaw law;
  // Separation of the articulation points.
  law.separation = p.separation_stiffness * (c.p - b.p) + p.separation_damping * (c.v - b.v);
  // Bending of the axes: rotation vector taking a_p to a_c.
  const Vec3 a_c = c.q * p.axis_child;
  const Vec3 a_p = b.q * p.axis_parent;
  const Vec3 cross = a_p.cross(a_c);
  const double s = cross.norm();
  const double angle = std::atan2(s, a_p.dot(a_c));
  const Vec3 bend = s > 1e-12 ? Vec3(cross * (angle / s)) : cross;
  law.n = mean_axis(a_c, a_p);
  const Vec3 w_rel = c.w - b.w;
  law.omega = law.n.dot(w_rel);
  const Vec3 w_perp = w_rel - law.omega * law.n;
  law.bending = p.bending_stiffness * bend + p.bending_damping * w_perp;
  return law;
}

}  // namespace

void PenaltyJoint::evaluate(double /*t*/, core::ConstVecRef x_hat, core::ConstVecRef y, double tau,
                            core::VecRef u, core::VecRef y_dot) const {
  const auto& p = params_;
  const JointLaw law = joint_law(p, x_hat);
  u.head<3>() = law.separation;

  // Friction (19) about n.
  const double K = p.friction_stiffness;
  const double BtK = p.friction_damping + tau * K;
  Eigen::Matrix<double, 1, 1> f;
  f[0] = BtK * law.omega + K * y[0];
  const bool sliding = std::abs(f[0]) > p.friction_limit;
  saturate(p.friction_limit, f);
  // Stuck: eps is omega itself, not (f - K e) / BtK, which would differ by rounding and let
  // the anchor creep.
  y_dot[0] = sliding ? (f[0] - K * y[0]) / BtK : law.omega;

  u.tail<3>() = law.bending + f[0] * law.n;
}

void PenaltyJoint::evaluate_friction_held(double /*t*/, core::ConstVecRef x_hat,
                                          core::ConstVecRef /*y*/, double /*tau*/,
                                          core::ConstVecRef u_ref, core::ConstVecRef y_dot_ref,
                                          core::VecRef u, core::VecRef y_dot) const {
  const JointLaw law = joint_law(params_, x_hat);
  const double held = law.n.dot(Vec3(u_ref.tail<3>()));
  u.head<3>() = law.separation;
  u.tail<3>() = law.bending + held * law.n;
  y_dot[0] = y_dot_ref[0];
}

int PenaltyJoint::regime(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const {
  Eigen::Matrix<double, 6, 1> u;
  Eigen::Matrix<double, 1, 1> y_dot;
  evaluate(0.0, x_hat, y, tau, u, y_dot);
  const Frame c = frame_at(x_hat, 0);
  const Frame b = frame_at(x_hat, 13);
  const Vec3 n = mean_axis(c.q * params_.axis_child, b.q * params_.axis_parent);
  return y_dot[0] == n.dot(c.w - b.w) ? 1 : 2;
}

double PenaltyJoint::stored_energy(core::ConstVecRef x_hat, core::ConstVecRef y) const {
  const auto& p = params_;
  const Frame c = frame_at(x_hat, 0);
  const Frame b = frame_at(x_hat, 13);
  const Vec3 a_c = c.q * p.axis_child;
  const Vec3 a_p = b.q * p.axis_parent;
  const double phi = std::atan2(a_p.cross(a_c).norm(), a_p.dot(a_c));
  return 0.5 * (p.separation_stiffness * (c.p - b.p).squaredNorm() +
                p.bending_stiffness * phi * phi + p.friction_stiffness * y[0] * y[0]);
}

double PenaltyJoint::relative_angle(core::ConstVecRef x_hat) const {
  const Frame c = frame_at(x_hat, 0);
  const Frame b = frame_at(x_hat, 13);
  // Child orientation in the parent frame, relative to the reference: a rotation expressed
  // in the parent frame. Its twist about axis_parent (swing-twist decomposition) is theta.
  const Quat delta = (b.q.conjugate() * c.q) * reference_inverse_;
  const double twist = 2.0 * std::atan2(delta.vec().dot(params_.axis_parent), delta.w());
  // q and -q give twists 2 pi apart: the wrap makes them equal.
  return wrap_angle(twist + params_.angle_offset);
}

core::Vec3 PenaltyJoint::slip_velocity(core::ConstVecRef x_hat) const {
  const Frame c = frame_at(x_hat, 0);
  const Frame b = frame_at(x_hat, 13);
  const Vec3 n = mean_axis(c.q * params_.axis_child, b.q * params_.axis_parent);
  return Vec3(n.dot(c.w - b.w), 0.0, 0.0);
}

std::vector<core::SignalInfo> PenaltyJoint::signals() const {
  return {{.name = "theta",
           .unwrap = true,
           .unit = "rad",
           .frame = "joint",
           .description = "relative rotation of the child about the joint axis"},
          {.name = "omega",
           .unit = "rad/s",
           .frame = "joint",
           .description = "relative angular velocity about the joint axis"},
          {.name = "tau",
           .unit = "N·m",
           .frame = "joint",
           .description = "friction torque about the joint axis on the child"},
          {.name = "e",
           .unit = "rad",
           .frame = "joint",
           .description = "elastic displacement of the joint friction element"}};
}

void PenaltyJoint::write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                                 core::VecRef out) const {
  const Frame c = frame_at(x_hat, 0);
  const Frame b = frame_at(x_hat, 13);
  const Vec3 n = mean_axis(c.q * params_.axis_child, b.q * params_.axis_parent);
  out[0] = relative_angle(x_hat);
  out[1] = n.dot(c.w - b.w);
  out[2] = -n.dot(Vec3(u.tail<3>()));  // the friction torque on the child (see header)
  out[3] = y[0];
}

}  // namespace stiction::components
