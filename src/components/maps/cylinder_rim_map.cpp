#include "components/maps/cylinder_rim_map.hpp"

#include <cmath>
#include <stdexcept>

namespace stiction::components {

core::Vec3 CylinderShape::radial() const {
  // Any unit vector normal to the axis; fixed, so the flat-face tripod stays put in the body.
  const core::Vec3 seed = std::abs(axis.x()) < 0.9 ? core::Vec3::UnitX() : core::Vec3::UnitY();
  return (seed - axis.dot(seed) * axis).normalized();
}

CylinderRimMap::CylinderRimMap(const core::Body& body, const CylinderShape& shape,
                               const core::Vec3& normal, int index)
    : body_(body),
      normal_(normal.normalized()),
      rim_(core::RimPoint::leg(shape.radius, shape.length, shape.axis, shape.radial(), index)) {
  if (index < 0 || index >= kPoints) throw std::invalid_argument("cylinder rim point out of range");
  if (!(shape.radius > 0.0) || !(shape.length >= 0.0))
    throw std::invalid_argument("a cylinder needs radius > 0 and length >= 0");
}

void CylinderRimMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const core::BodyMotion m = body_.motion(x.segment(slot_.state_offset, slot_.state_size));
  const core::Vec3 a = lever(m.q);
  x_hat.segment<3>(0) = m.p + a;
  x_hat.segment<3>(3) = m.v + m.w_world.cross(a);  // the material point's velocity
}

void CylinderRimMap::apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const {
  const core::BodyMotion m = body_.motion(x.segment(slot_.state_offset, slot_.state_size));
  body_.add_wrench(m, lever(m.q), -core::Vec3(u.head<3>()), core::Vec3::Zero(),
                   u_hat.segment(slot_.input_offset, slot_.input_size));
}

}  // namespace stiction::components
