#include "components/maps/cylinder_rim_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
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
      axis_(shape.axis.normalized()),
      radial_(shape.radial()),
      radius_(shape.radius),
      half_length_((index < 3 ? 0.5 : -0.5) * shape.length),
      cos_(std::cos(2.0 * std::numbers::pi / 3.0 * (index % 3))),
      sin_(std::sin(2.0 * std::numbers::pi / 3.0 * (index % 3))) {
  if (index < 0 || index >= kPoints) throw std::invalid_argument("cylinder rim point out of range");
  if (!(shape.radius > 0.0) || !(shape.length >= 0.0))
    throw std::invalid_argument("a cylinder needs radius > 0 and length >= 0");
}

core::Vec3 CylinderRimMap::lever(const core::Quat& q) const {
  const core::Vec3 a = q * axis_;
  // The in-cap direction of -n (towards the surface), leaning on the body's radial direction
  // so that it stays defined (and continuous) when the caps lie parallel to the surface.
  // The lean fades out as (1 - |d_perp| / kBlend)^2: exactly zero beyond a tilt of kBlend, so a
  // cylinder on its rim touches at its lowest point (a lean there would be a slope of kBlend).
  const core::Vec3 d_perp = -normal_ + normal_.dot(a) * a;
  const double fade = std::max(0.0, 1.0 - d_perp.norm() / kBlend);
  const core::Vec3 u = (d_perp + kBlend * fade * fade * (q * radial_)).normalized();
  const core::Vec3 v = a.cross(u);
  return half_length_ * a + radius_ * (cos_ * u + sin_ * v);
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
