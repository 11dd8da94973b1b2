#include "scene/axis_torque_map.hpp"

#include <cmath>

namespace stiction::scene {

using core::Vec3;

AxisTorqueMap::AxisTorqueMap(const core::Body& child, const core::Body* parent,
                             const Vec3& axis_local)
    : child_(child), parent_(parent), axis_(axis_local.normalized()) {}

std::vector<const core::Admittance*> AxisTorqueMap::admittances() const {
  if (parent_ == nullptr) return {&child_};
  return {&child_, parent_};
}

void AxisTorqueMap::bind(const std::vector<core::Slot>& slots) {
  child_slot_ = slots.at(0);
  if (parent_ != nullptr) parent_slot_ = slots.at(1);
}

void AxisTorqueMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const auto mc = child_.motion(x.segment(child_slot_.state_offset, child_slot_.state_size));
  core::BodyMotion mp;
  if (parent_ != nullptr) mp = parent_->motion(x.segment(parent_slot_.state_offset, parent_slot_.state_size));
  const Vec3 axis_world = mc.q * axis_;
  // Twist angle of the relative rotation about the axis (swing-twist decomposition).
  const core::Quat rel = mp.q.conjugate() * mc.q;
  x_hat[0] = 2.0 * std::atan2(rel.vec().dot(axis_), rel.w());
  x_hat[1] = (mc.w_world - mp.w_world).dot(axis_world);
}

void AxisTorqueMap::apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const {
  const auto mc = child_.motion(x.segment(child_slot_.state_offset, child_slot_.state_size));
  const Vec3 torque = -u[0] * (mc.q * axis_);
  child_.add_wrench(mc, Vec3::Zero(), Vec3::Zero(), torque,
                    u_hat.segment(child_slot_.input_offset, child_slot_.input_size));
  if (parent_ != nullptr) {
    const auto mp = parent_->motion(x.segment(parent_slot_.state_offset, parent_slot_.state_size));
    parent_->add_wrench(mp, Vec3::Zero(), Vec3::Zero(), -torque,
                        u_hat.segment(parent_slot_.input_offset, parent_slot_.input_size));
  }
}

}  // namespace stiction::scene
