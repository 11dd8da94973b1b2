// The planar arm's forward dynamics in O(n): Featherstone's articulated-body algorithm with
// every spatial quantity expressed in the fixed world frame at the origin (so no coordinate
// transforms between links are needed), specialised to the plane.
//
// A planar spatial motion is m = (w, vx, vy): the rate about z and the velocity of the body
// point at the origin; a planar spatial force is f = (n, fx, fy): the moment about the origin
// and the force. Joint i turns about P_i, so its motion subspace is S_i = (1, P_iy, -P_ix)
// (the velocity at the origin of a unit rotation about P_i). Link i's spatial inertia about
// the origin, with mass m, centre of mass C and inertia I about C, is
//   [[I + m |C|^2, -m C_y, m C_x], [-m C_y, m, 0], [m C_x, 0, m]].
// Cross products: m1 x m2 = (0, v1y w2 - w1 v2y, w1 v2x - v1x w2) for motions and
// v x* f = (vx fy - vy fx, -w fy, w fx) for forces. Coordinates are the arm's plane
// coordinates from its base (planar_arm.cpp); gravity g (its component in the plane) enters
// as an upward acceleration of the base, a_0 = (0, -g) (Featherstone's usual device). Then:
//   out:  v_i = v_{i-1} + S_i qd_i,  c_i = (v_i x S_i) qd_i,  p_i = v_i x* (I_i v_i)
//   in:   I^A_i = I_i + I^A_{i+1} - U U^T / D,  p^A_i = p_i + p^A_{i+1} + I^A_{i+1} c_{i+1}
//         + U u / D, with U = I^A_{i+1} S_{i+1}, D = S^T U, u = tau_{i+1} - S^T p^A_{i+1}
//   out:  qdd_i = (tau_i - S_i^T p^A_i - U_i^T (a_{i-1} + c_i)) / D_i,
//         a_i = a_{i-1} + c_i + S_i qdd_i.
// Each link costs a fixed number of 3x3 operations: linear in n.
#include <cmath>

#include "components/admittance/planar_arm.hpp"

namespace stiction::components {
namespace {

using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

V3 motion_cross(const V3& a, const V3& b) {
  return V3(0.0, a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

V3 force_cross(const V3& v, const V3& f) {
  return V3(v[1] * f[2] - v[2] * f[1], -v[0] * f[2], v[0] * f[1]);
}

}  // namespace

void PlanarArm::forward_dynamics(core::ConstVecRef theta, core::ConstVecRef omega,
                                 core::ConstVecRef tau, core::VecRef qdd) const {
  const int n = joint_count();
  auto& s = aba_;
  // Base to tip: joint axes, velocities, bias accelerations and forces, link inertias.
  Eigen::Vector2d p = Eigen::Vector2d::Zero();  // plane coordinates from the base
  double phi = 0.0;
  V3 v = V3::Zero();
  for (int i = 0; i < n; ++i) {
    const ArmLink& l = params_.links[i];
    phi += theta[i];
    const Eigen::Vector2d u(std::cos(phi), std::sin(phi));
    const V3 S(1.0, p.y(), -p.x());
    v += S * omega[i];
    const Eigen::Vector2d C = p + l.com * u;
    M3 I;
    I << l.inertia + l.mass * C.squaredNorm(), -l.mass * C.y(), l.mass * C.x(),  //
        -l.mass * C.y(), l.mass, 0.0,                                            //
        l.mass * C.x(), 0.0, l.mass;
    s.S[i] = S;
    s.c[i] = motion_cross(v, S) * omega[i];
    s.IA[i] = I;
    s.pA[i] = force_cross(v, I * v);
    p += l.length * u;
  }
  // Tip to base: articulated inertias and bias forces.
  for (int i = n - 1; i >= 0; --i) {
    s.U[i] = s.IA[i] * s.S[i];
    s.D[i] = s.S[i].dot(s.U[i]);
    s.u[i] = tau[i] - s.S[i].dot(s.pA[i]);
    if (i > 0) {
      const M3 Ia = s.IA[i] - s.U[i] * s.U[i].transpose() / s.D[i];
      s.IA[i - 1] += Ia;
      s.pA[i - 1] += s.pA[i] + Ia * s.c[i] + s.U[i] * (s.u[i] / s.D[i]);
    }
  }
  // Base to tip: joint and link accelerations, from the base's a_0 = -g.
  V3 a(0.0, -g_plane_.x(), -g_plane_.y());
  for (int i = 0; i < n; ++i) {
    const V3 a_pre = a + s.c[i];
    qdd[i] = (s.u[i] - s.U[i].dot(a_pre)) / s.D[i];
    a = a_pre + s.S[i] * qdd[i];
  }
}

double PlanarArm::kinetic_energy(core::ConstVecRef theta, core::ConstVecRef omega) const {
  // Sum over links of m |v_C|^2 / 2 + I Phi^2 / 2, the centre's velocity built base to tip.
  Eigen::Vector2d v_joint = Eigen::Vector2d::Zero();
  double phi = 0.0, rate = 0.0, energy = 0.0;
  for (int i = 0; i < joint_count(); ++i) {
    const ArmLink& l = params_.links[i];
    phi += theta[i];
    rate += omega[i];
    const Eigen::Vector2d z_cross_u(-std::sin(phi), std::cos(phi));
    const Eigen::Vector2d v_com = v_joint + (l.com * rate) * z_cross_u;
    energy += 0.5 * (l.mass * v_com.squaredNorm() + l.inertia * rate * rate);
    v_joint += (l.length * rate) * z_cross_u;
  }
  return energy;
}

}  // namespace stiction::components
