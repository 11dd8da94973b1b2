// The spatial tree's forward dynamics in O(n): Featherstone's articulated-body algorithm,
// every quantity in the world frame at the origin (spatial_algebra.hpp), as planar_arm_aba.cpp
// does in the plane. Link i has parent lambda(i), joint axis S_i and spatial inertia I_i
// (spatial_tree.cpp's kinematics). Gravity g enters as the base's acceleration a_0 = (0, -g).
//   out:  v_i = v_lambda + S_i qd_i,  c_i = (v_i x S_i) qd_i,  p_i = v_i x* (I_i v_i),
//         I^A_i = I_i, p^A_i = p_i
//   in:   U_i = I^A_i S_i, D_i = S_i^T U_i, u_i = tau_i - S_i^T p^A_i, and into the parent
//         I^A_lambda += I^A_i - U_i U_i^T / D_i,
//         p^A_lambda += p^A_i + (I^A_i - U_i U_i^T / D_i) c_i + U_i u_i / D_i
//   out:  qdd_i = (u_i - U_i^T (a_lambda + c_i)) / D_i,  a_i = a_lambda + c_i + S_i qdd_i.
// Parents come before children, so the index order is a valid sweep order both ways. Each
// link costs a fixed number of 6x6 operations: linear in n, and allocation-free (scratch).
#include "components/admittance/spatial_tree.hpp"
#include "components/admittance/spatial_tree_scratch.hpp"

namespace stiction::components {

void SpatialTree::forward_dynamics(core::ConstVecRef q, core::ConstVecRef qd, core::ConstVecRef tau,
                                   core::VecRef qdd) const {
  const int n = joint_count();
  Scratch& s = *scratch_;
  s.kinematics(params_, q);
  for (int i = 0; i < n; ++i) {
    const int parent = params_.links[i].parent;
    s.v[i] = (parent < 0 ? spatial::Vec6::Zero() : s.v[parent]) + s.S[i] * qd[i];
    s.c[i] = spatial::motion_cross(s.v[i], s.S[i]) * qd[i];
    s.IA[i] = s.I[i];
    s.pA[i] = spatial::force_cross(s.v[i], s.I[i] * s.v[i]);
  }
  for (int i = n - 1; i >= 0; --i) {
    s.U[i] = s.IA[i] * s.S[i];
    s.D[i] = s.S[i].dot(s.U[i]);
    s.u[i] = tau[i] - s.S[i].dot(s.pA[i]);
    const int parent = params_.links[i].parent;
    if (parent >= 0) {
      const spatial::Mat6 Ia = s.IA[i] - s.U[i] * s.U[i].transpose() / s.D[i];
      s.IA[parent] += Ia;
      s.pA[parent] += s.pA[i] + Ia * s.c[i] + s.U[i] * (s.u[i] / s.D[i]);
    }
  }
  spatial::Vec6 a_base;
  a_base << core::Vec3::Zero(), -params_.gravity;
  for (int i = 0; i < n; ++i) {
    const int parent = params_.links[i].parent;
    const spatial::Vec6 a_pre = (parent < 0 ? a_base : s.a[parent]) + s.c[i];
    qdd[i] = (s.u[i] - s.U[i].dot(a_pre)) / s.D[i];
    s.a[i] = a_pre + s.S[i] * qdd[i];
  }
}

}  // namespace stiction::components
