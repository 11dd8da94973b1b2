#include "components/maps/cylinder_twist_map.hpp"

#include <utility>

namespace stiction::components {

namespace {

template <std::size_t... I>
std::array<CylinderRimMap, sizeof...(I)> make_rim(const core::Body& body,
                                                  const CylinderShape& shape,
                                                  const core::Vec3& normal,
                                                  std::index_sequence<I...>) {
  return {CylinderRimMap(body, shape, normal, static_cast<int>(I))...};
}

}  // namespace

std::array<CylinderRimMap, CylinderTwistMap::kPoints> CylinderTwistMap::rim_maps(
    const core::Body& body, const CylinderShape& shape, const core::Vec3& normal) {
  return make_rim(body, shape, normal, std::make_index_sequence<kPoints>{});
}

CylinderTwistMap::CylinderTwistMap(const core::Body& body, const CylinderShape& shape,
                                   const core::Vec3& normal)
    : body_(body), axis_(shape.axis.normalized()), rim_(rim_maps(body, shape, normal)) {}

void CylinderTwistMap::bind(const std::vector<core::Slot>& slots) {
  slot_ = slots.at(0);
  for (CylinderRimMap& r : rim_) r.bind(slots);
}

void CylinderTwistMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const core::BodyMotion m = body_.motion(x.segment(slot_.state_offset, slot_.state_size));
  x_hat.segment<3>(0) = m.p;
  x_hat.segment<3>(3) = m.v;
  x_hat.segment<3>(6) = m.w_world;
  x_hat.segment<3>(9) = m.q * axis_;
  for (int i = 0; i < kPoints; ++i) {
    rim_[static_cast<std::size_t>(i)].motion(x, x_hat.segment(kRimOffset + 6 * i, 6));
  }
}

void CylinderTwistMap::apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const {
  const core::BodyMotion m = body_.motion(x.segment(slot_.state_offset, slot_.state_size));
  body_.add_wrench(m, core::Vec3::Zero(), core::Vec3::Zero(), -core::Vec3(u.head<3>()),
                   u_hat.segment(slot_.input_offset, slot_.input_size));
}

}  // namespace stiction::components
