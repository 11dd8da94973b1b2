// Planar n-link arm dynamics (paper eq. 8) from the link Jacobians.
//
// Link i has absolute angle phi_i = theta_0 + ... + theta_i and absolute rate
// Phi_i = omega_0 + ... + omega_i. With u(phi) = (cos phi, sin phi) and z x r = (-r_y, r_x)
// in the plane, joint positions are P_0 = base, P_{i+1} = P_i + l_i u(phi_i), and the centre
// of mass of link i is C_i = P_i + com_i u(phi_i). Joint k turns every link i >= k about
// P_k, so the columns of the link Jacobians are
//   J_v,i[:, k] = z x (C_i - P_k),   J_w,i[k] = 1        (k <= i; zero otherwise).
// Then (Lagrange, or Kane's equations)
//   H = sum_i m_i J_v,i^T J_v,i + I_i J_w,i^T J_w,i
//     => H_kl = sum_{i >= max(k,l)} m_i (C_i - P_k).(C_i - P_l) + I_i
//        (rotating both vectors by 90 degrees keeps their dot product),
//   c = sum_i m_i J_v,i^T (dJ_v,i/dt omega),
// where dJ_v,i/dt omega is the acceleration of C_i when every joint acceleration is zero:
// the links then turn at constant rates, so only centripetal terms remain,
//   a_i = -sum_{j<i} l_j Phi_j^2 u(phi_j) - com_i Phi_i^2 u(phi_i).
// The rotational part contributes nothing to c because J_w is constant. Gravity g2 (its
// component in the plane) gives the generalized force G_k = sum_{i>=k} m_i J_v,i[:, k] . g2,
// taken into c as -G (c is the bias force, as MuJoCo's qfrc_bias). Plane coordinates start
// at the base, so the base point itself never enters. This is O(n^2) and allocation-free;
// the 2-link case reduces to the textbook closed form (tested).
#include "components/admittance/planar_arm.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace stiction::components {

ArmLink box_link(double length, double width, double mass) {
  ArmLink link;
  link.length = length;
  link.mass = mass;
  link.com = 0.5 * length;
  // In-plane rotation of a box: the dimensions in the plane are its length and width.
  link.inertia = mass * (length * length + width * width) / 12.0;
  return link;
}

void arm_plane(const core::Vec3& axis, core::Vec3& e1, core::Vec3& e2) {
  core::Vec3 x = core::Vec3::UnitX() - axis.x() * axis;
  if (x.norm() < 1e-6) x = core::Vec3::UnitY() - axis.y() * axis;
  e1 = x.normalized();
  e2 = axis.cross(e1);
}

PlanarArm::PlanarArm(std::string name, const PlanarArmParams& params)
    : core::JointSpace(std::move(name)), params_(params) {
  const int n = joint_count();
  if (!(params_.axis.norm() > 1e-12) || !params_.gravity.allFinite()) {
    throw std::invalid_argument("planar_arm '" + this->name() +
                                "': the axis must be non-zero and gravity finite");
  }
  params_.axis.normalize();
  arm_plane(params_.axis, e1_, e2_);
  g_plane_ = Eigen::Vector2d(params_.gravity.dot(e1_), params_.gravity.dot(e2_));
  if (n < 1) throw std::invalid_argument("planar_arm '" + this->name() + "': no links");
  for (int i = 0; i < n; ++i) {
    const ArmLink& l = params_.links[i];
    if (!(l.mass > 0.0) || !(l.inertia >= 0.0) || !(l.length >= 0.0) || !std::isfinite(l.com)) {
      throw std::invalid_argument("planar_arm '" + this->name() + "': link " + std::to_string(i) +
                                  " needs mass > 0, inertia >= 0 and length >= 0");
    }
  }
  if (params_.angles.size() != 0 && params_.angles.size() != n) {
    throw std::invalid_argument("planar_arm '" + this->name() + "': angles must have " +
                                std::to_string(n) + " entries");
  }
  if (params_.rates.size() != 0 && params_.rates.size() != n) {
    throw std::invalid_argument("planar_arm '" + this->name() + "': rates must have " +
                                std::to_string(n) + " entries");
  }
  joints_ = Eigen::Matrix2Xd::Zero(2, n);
  coms_ = Eigen::Matrix2Xd::Zero(2, n);
  accel_ = Eigen::Matrix2Xd::Zero(2, n);
  for (auto* v : {&aba_.S, &aba_.c, &aba_.pA, &aba_.U}) v->assign(n, Eigen::Vector3d::Zero());
  aba_.IA.assign(n, Eigen::Matrix3d::Zero());
  aba_.D.assign(n, 0.0);
  aba_.u.assign(n, 0.0);
}

std::vector<std::string> PlanarArm::state_labels() const {
  std::vector<std::string> labels;
  const int n = joint_count();
  for (int i = 0; i < n; ++i) labels.push_back("theta." + std::to_string(i));
  for (int i = 0; i < n; ++i) labels.push_back("omega." + std::to_string(i));
  return labels;
}

void PlanarArm::initial_state(core::VecRef x) const {
  const int n = joint_count();
  x.setZero();
  if (params_.angles.size() == n) x.head(n) = params_.angles;
  if (params_.rates.size() == n) x.tail(n) = params_.rates;
}

void PlanarArm::dynamics(core::ConstVecRef theta, core::ConstVecRef omega,
                         Eigen::Ref<Eigen::MatrixXd> H, core::VecRef c) const {
  const int n = joint_count();
  // Forward kinematics and centripetal accelerations, base to tip.
  Eigen::Vector2d p = Eigen::Vector2d::Zero();        // plane coordinates from the base
  Eigen::Vector2d a_joint = Eigen::Vector2d::Zero();  // acceleration of P_i (zero joint accel.)
  double phi = 0.0;
  double rate = 0.0;
  for (int i = 0; i < n; ++i) {
    const ArmLink& l = params_.links[i];
    phi += theta[i];
    rate += omega[i];
    const Eigen::Vector2d u(std::cos(phi), std::sin(phi));
    joints_.col(i) = p;
    coms_.col(i) = p + l.com * u;
    accel_.col(i) = a_joint - (l.com * rate * rate) * u;
    p += l.length * u;
    a_joint -= (l.length * rate * rate) * u;
  }
  for (int k = 0; k < n; ++k) {
    for (int l = k; l < n; ++l) {
      double h = 0.0;
      for (int i = l; i < n; ++i) {
        const ArmLink& link = params_.links[i];
        h += link.mass * (coms_.col(i) - joints_.col(k)).dot(coms_.col(i) - joints_.col(l)) +
             link.inertia;
      }
      H(k, l) = h;
      H(l, k) = h;
    }
    double ck = 0.0;
    for (int i = k; i < n; ++i) {
      const Eigen::Vector2d r = coms_.col(i) - joints_.col(k);
      const Eigen::Vector2d jv(-r.y(), r.x());  // z x r
      ck += params_.links[i].mass * jv.dot(accel_.col(i) - g_plane_);
    }
    c[k] = ck;
  }
}

void PlanarArm::derivative(core::ConstVecRef x, core::ConstVecRef u_hat, core::VecRef x_dot) const {
  const int n = joint_count();
  // O(n) (planar_arm_aba.cpp) instead of building H and factoring it, O(n^2) and O(n^3).
  forward_dynamics(x.head(n), x.tail(n), u_hat, x_dot.tail(n));
  x_dot.head(n) = x.tail(n);
}

std::vector<core::SignalInfo> PlanarArm::signals() const {
  const auto axes = core::index_axes(joint_count());
  // The arm's own angles are continuous state, never wrapped: no unwrapping needed.
  return {{.name = "theta", .axes = axes, .unit = "rad", .frame = "joint",
           .description = "joint angle"},
          {.name = "omega", .axes = axes, .unit = "rad/s", .frame = "joint",
           .description = "joint angular velocity"}};
}

void PlanarArm::write_signals(core::ConstVecRef x, core::VecRef out) const { out = x; }

double PlanarArm::energy(core::ConstVecRef x) const {
  const int n = joint_count();
  // Potential energy -sum m_i g . C_i, with C_i = base + x e1 + y e2 (plane coordinates
  // from the base, built base to tip as in kinetic_energy).
  double potential = 0.0;
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  double phi = 0.0;
  for (int i = 0; i < n; ++i) {
    const ArmLink& l = params_.links[i];
    phi += x[i];
    const Eigen::Vector2d u(std::cos(phi), std::sin(phi));
    potential -= l.mass * (params_.gravity.dot(params_.base) + g_plane_.dot(p + l.com * u));
    p += l.length * u;
  }
  return kinetic_energy(x.head(n), x.tail(n)) + potential;
}

}  // namespace stiction::components
