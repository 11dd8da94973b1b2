#include "components/maps/joint_map.hpp"

namespace stiction::components {

void JointMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const auto arm_state = x.segment(slot_.state_offset, slot_.state_size);
  x_hat[0] = arm_.joint_angle(arm_state, joint_);
  x_hat[1] = arm_.joint_rate(arm_state, joint_);
}

void JointMap::apply(core::ConstVecRef /*x*/, core::ConstVecRef u, core::VecRef u_hat) const {
  arm_.add_joint_torque(joint_, -u[0], u_hat.segment(slot_.input_offset, slot_.input_size));
}

}  // namespace stiction::components
