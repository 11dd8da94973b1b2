#include "components/maps/body_frame_point_map.hpp"

namespace stiction::components {

using core::Vec3;

void BodyFramePointMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const auto m = body_.motion(x.segment(slot_.state_offset, slot_.state_size));
  const Vec3 p = m.point(local_);
  const core::Quat to_body = m.q.conjugate();
  x_hat.segment<3>(0) = to_body * p;
  x_hat.segment<3>(3) = to_body * m.point_velocity(p);
}

void BodyFramePointMap::apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const {
  const auto m = body_.motion(x.segment(slot_.state_offset, slot_.state_size));
  const Vec3 f_world = m.q * Vec3(u.head<3>());
  body_.add_wrench(m, m.q * local_, -f_world, Vec3::Zero(),
                   u_hat.segment(slot_.input_offset, slot_.input_size));
}

}  // namespace stiction::components
