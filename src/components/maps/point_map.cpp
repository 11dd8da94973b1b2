#include "components/maps/point_map.hpp"

namespace stiction::components {

using core::Vec3;

PointMap::PointMap(const core::Body& a, Vec3 local_a, const core::Body* b, Vec3 local_b)
    : a_(a), local_a_(std::move(local_a)), b_(b), local_b_(std::move(local_b)) {}

std::vector<const core::Admittance*> PointMap::admittances() const {
  if (b_ == nullptr) return {&a_};
  return {&a_, b_};
}

void PointMap::bind(const std::vector<core::Slot>& slots) {
  slot_a_ = slots.at(0);
  if (b_ != nullptr) slot_b_ = slots.at(1);
}

void PointMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const auto ma = a_.motion(x.segment(slot_a_.state_offset, slot_a_.state_size));
  const Vec3 pa = ma.point(local_a_);
  Vec3 p = pa;
  Vec3 v = ma.point_velocity(pa);
  if (b_ != nullptr) {
    const auto mb = b_->motion(x.segment(slot_b_.state_offset, slot_b_.state_size));
    const Vec3 pb = mb.point(local_b_);
    p -= pb;
    v -= mb.point_velocity(pb);
  } else {
    p -= local_b_;
  }
  x_hat.segment<3>(0) = p;
  x_hat.segment<3>(3) = v;
}

void PointMap::apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const {
  const Vec3 f = u.head<3>();
  const auto ma = a_.motion(x.segment(slot_a_.state_offset, slot_a_.state_size));
  a_.add_wrench(ma, ma.q * local_a_, -f, Vec3::Zero(),
                u_hat.segment(slot_a_.input_offset, slot_a_.input_size));
  if (b_ != nullptr) {
    const auto mb = b_->motion(x.segment(slot_b_.state_offset, slot_b_.state_size));
    b_->add_wrench(mb, mb.q * local_b_, f, Vec3::Zero(),
                   u_hat.segment(slot_b_.input_offset, slot_b_.input_size));
  }
}

}  // namespace stiction::components
