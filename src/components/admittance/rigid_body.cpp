#include "components/admittance/rigid_body.hpp"

#include "core/safe_normalize.hpp"

#include <Eigen/Eigenvalues>
#include <stdexcept>

namespace stiction::components {

using core::ConstVecRef;
using core::Quat;
using core::Vec3;
using core::VecRef;

RigidBody::RigidBody(std::string name, const RigidBodyParams& params)
    : Body(std::move(name)), params_(params) {
  if (!(params_.mass > 0.0)) throw std::invalid_argument("rigid body: mass must be > 0");
  Eigen::SelfAdjointEigenSolver<core::Mat3> eig(params_.inertia);
  if (eig.eigenvalues().minCoeff() <= 0.0) {
    throw std::invalid_argument("rigid body: inertia must be positive definite");
  }
  inertia_inverse_ = params_.inertia.inverse();
  inertia_diagonal_ = params_.inertia.diagonal();
  diagonal_inertia_ = params_.inertia.isDiagonal(0.0);
  const auto q = core::safe_normalized(params_.orientation.coeffs());
  if (!q) throw std::invalid_argument("rigid body: orientation must be a finite, non-zero quaternion");
  params_.orientation.coeffs() = *q;
}

std::vector<std::string> RigidBody::state_labels() const {
  return {"p.x", "p.y", "p.z", "v.x", "v.y", "v.z", "q.w",
          "q.x", "q.y", "q.z", "w.x", "w.y", "w.z"};
}

void RigidBody::initial_state(VecRef x) const {
  x.segment<3>(0) = params_.position;
  x.segment<3>(3) = params_.velocity;
  const Quat& q = params_.orientation;
  x.segment<4>(6) << q.w(), q.x(), q.y(), q.z();
  x.segment<3>(10) = params_.angular_velocity;
}

void RigidBody::derivative_at(const double* x_data, const double* u_data, double* x_dot_data) const {
  // (26): p_dot = v, v_dot = f/M (+ g), q_dot = 0.5 q (x) (0, w), w_dot = J^-1 (tau - w x Jw).
  const Eigen::Map<const Eigen::Matrix<double, 13, 1>> x(x_data);
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>> u_hat(u_data);
  Eigen::Map<Eigen::Matrix<double, 13, 1>> x_dot(x_dot_data);
  const Vec3 w = x.segment<3>(10);
  const double qw = x[6];
  const Vec3 qv = x.segment<3>(7);
  x_dot.segment<3>(0) = x.segment<3>(3);
  x_dot.segment<3>(3) = u_hat.segment<3>(0) / params_.mass + params_.gravity;
  x_dot[6] = -0.5 * qv.dot(w);
  x_dot.segment<3>(7) = 0.5 * (qw * w + qv.cross(w));
  if (diagonal_inertia_) {
    const Vec3 Jw = inertia_diagonal_.cwiseProduct(w);
    x_dot.segment<3>(10) = (u_hat.segment<3>(3) - w.cross(Jw)).cwiseQuotient(inertia_diagonal_);
  } else {
    x_dot.segment<3>(10) =
        inertia_inverse_ * (u_hat.segment<3>(3) - w.cross(params_.inertia * w));
  }
}

void RigidBody::project(VecRef x) const { x.segment<4>(6).normalize(); }

void RigidBody::solve_kinematics(const double* start, double* iterate, double h) const {
  // q = q0 + h/2 q (x) (0, w) with w the iterate's: q = (I - a)^-1 q0 where a, the right
  // product by (0, h w / 2), is skew with a^2 = -|h w / 2|^2 I, so (I - a)^-1 = (I + a) /
  // (1 + |h w / 2|^2).
  const Vec3 a = 0.5 * h * Vec3(iterate[10], iterate[11], iterate[12]);
  const double qw = start[6];
  const Vec3 qv(start[7], start[8], start[9]);
  const double scale = 1.0 / (1.0 + a.squaredNorm());
  const Vec3 v = qw * a + qv.cross(a);
  iterate[6] = (qw - qv.dot(a)) * scale;
  iterate[7] = (qv[0] + v[0]) * scale;
  iterate[8] = (qv[1] + v[1]) * scale;
  iterate[9] = (qv[2] + v[2]) * scale;
}

std::vector<core::SignalInfo> RigidBody::signals() const {
  return {{.name = "p", .axes = core::xyz_axes(), .unit = "m", .frame = "world",
           .description = "position of the centre of mass"},
          {.name = "v", .axes = core::xyz_axes(), .unit = "m/s", .frame = "world",
           .description = "velocity of the centre of mass"},
          {.name = "q", .axes = core::wxyz_axes(), .unit = "1", .frame = "world",
           .description = "orientation, unit quaternion from body to world"},
          {.name = "w", .axes = core::xyz_axes(), .unit = "rad/s", .frame = "body",
           .description = "angular velocity in the body frame"}};
}

void RigidBody::write_signals(ConstVecRef x, VecRef out) const { out.head<13>() = x.head<13>(); }

double RigidBody::energy(ConstVecRef x) const {
  const Vec3 v = x.segment<3>(3);
  const Vec3 w = x.segment<3>(10);
  return 0.5 * params_.mass * v.squaredNorm() + 0.5 * w.dot(params_.inertia * w) -
         params_.mass * params_.gravity.dot(x.segment<3>(0));
}

}  // namespace stiction::components
