#include "components/maps/frame_pair_map.hpp"

#include <stdexcept>

namespace stiction::components {

using core::Vec3;

namespace {

void write_frame(const core::BodyMotion& m, const Vec3& point, core::VecRef frame) {
  frame.segment<3>(0) = point;
  frame.segment<3>(3) = m.point_velocity(point);
  frame.segment<4>(6) << m.q.w(), m.q.x(), m.q.y(), m.q.z();
  frame.segment<3>(10) = m.w_world;
}

}  // namespace

FramePairMap::FramePairMap(const core::Body* parent, Vec3 parent_local_point,
                           const core::Body& child, Vec3 child_local_point)
    : parent_(parent),
      parent_local_(std::move(parent_local_point)),
      child_(child),
      child_local_(std::move(child_local_point)) {
  // The element produces torques (bending, friction about the axis): a body without
  // orientation could neither report an axis nor take them.
  if (!child_.can_rotate() || (parent_ != nullptr && !parent_->can_rotate())) {
    throw std::invalid_argument("frame pair map: '" + child_.name() + "'" +
                                (parent_ ? " and '" + parent_->name() + "'" : std::string()) +
                                " must be rigid bodies (a joint applies torques)");
  }
}

std::vector<const core::Admittance*> FramePairMap::admittances() const {
  if (parent_ == nullptr) return {&child_};
  return {&child_, parent_};
}

void FramePairMap::bind(const std::vector<core::Slot>& slots) {
  child_slot_ = slots.at(0);
  if (parent_ != nullptr) parent_slot_ = slots.at(1);
}

void FramePairMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const auto mc = child_.motion(x.segment(child_slot_.state_offset, child_slot_.state_size));
  write_frame(mc, mc.point(child_local_), x_hat.segment<kFrameSize>(0));
  if (parent_ != nullptr) {
    const auto mp = parent_->motion(x.segment(parent_slot_.state_offset, parent_slot_.state_size));
    write_frame(mp, mp.point(parent_local_), x_hat.segment<kFrameSize>(kFrameSize));
  } else {
    write_frame(core::BodyMotion{}, parent_local_, x_hat.segment<kFrameSize>(kFrameSize));
  }
}

void FramePairMap::apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const {
  const Vec3 f = u.head<3>();
  const Vec3 torque = u.tail<3>();
  const auto mc = child_.motion(x.segment(child_slot_.state_offset, child_slot_.state_size));
  child_.add_wrench(mc, mc.q * child_local_, -f, -torque,
                    u_hat.segment(child_slot_.input_offset, child_slot_.input_size));
  if (parent_ != nullptr) {
    const auto mp = parent_->motion(x.segment(parent_slot_.state_offset, parent_slot_.state_size));
    parent_->add_wrench(mp, mp.q * parent_local_, f, torque,
                        u_hat.segment(parent_slot_.input_offset, parent_slot_.input_size));
  }
}

}  // namespace stiction::components
