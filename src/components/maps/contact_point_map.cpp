#include "components/maps/contact_point_map.hpp"

namespace stiction::components {

using core::Vec3;

ContactPointMap::ContactPointMap(const core::Body& body, double radius, const Vec3& normal)
    : body_(body), offset_(-radius * normal.normalized()) {}

void ContactPointMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const auto m = body_.motion(x.segment(slot_.state_offset, slot_.state_size));
  // (27d): contact point velocity v + w x a, with a the lever arm in world coordinates.
  x_hat.segment<3>(0) = m.p + offset_;
  x_hat.segment<3>(3) = m.v + m.w_world.cross(offset_);
}

void ContactPointMap::apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const {
  const auto xs = x.segment(slot_.state_offset, slot_.state_size);
  body_.add_wrench(xs, offset_, -Vec3(u.head<3>()), Vec3::Zero(),
                   u_hat.segment(slot_.input_offset, slot_.input_size));
}

}  // namespace stiction::components
