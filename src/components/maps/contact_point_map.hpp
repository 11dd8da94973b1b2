// Psi/Phi for a contact against a flat surface of normal n: the contact point of a body of
// round shape `radius` about its body-frame point `local` is that sphere's point nearest the
// surface, p + R local - radius n (local 0, radius 0: the body origin, e.g. a point mass;
// a box corner: local the corner, radius 0). x_hat = [p_c (3), v_c (3)] with
// v_c = v + w x (p_c - p); the body receives -u at p_c (force and the matching torque).
// With a body-fixed friction axis (an anisotropic contact's, kikuuwe_contact.hpp), x_hat
// also carries that axis in world coordinates: [p_c, v_c, R axis] (9 entries).
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

class ContactPointMap final : public core::CoordinateMap {
 public:
  ContactPointMap(const core::Body& body, double radius, const core::Vec3& normal,
                  const core::Vec3& local = core::Vec3::Zero());
  // Appends R axis (world) to x_hat: a body-fixed friction axis.
  void carry_axis(const core::Vec3& axis) {
    axis_ = axis;
    carries_axis_ = true;
  }
  int motion_size() const override { return carries_axis_ ? 9 : 6; }
  int force_size() const override { return 3; }
  // [p_c, v_c] then, with body-fixed friction axes, the first axis.
  int conjugate_velocity_offset() const override { return 3; }
  std::vector<const core::Admittance*> admittances() const override { return {&body_}; }
  void bind(const std::vector<core::Slot>& slots) override { slot_ = slots.at(0); }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override {
    const core::BodyMotion m = motion_of(body_, x.data(), x_hat);
    if (carries_axis_) x_hat.segment<3>(6) = m.q * axis_;
  }
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override {
    apply_to(body_, body_.motion(x.segment(slot_.state_offset, slot_.state_size)), u, u_hat.data());
  }
  // Kikuuwe contacts on rigid bodies and point masses.
  std::unique_ptr<core::Coupling> direct_coupling(const core::Impedance& impedance,
                                                  const core::Slot& state) const override;

  // Psi and Phi for `body` (this map's body, as its own type: a final body class makes the
  // calls direct, which direct couplings rely on), on the network's whole state and input
  // vectors. motion_of returns the body's motion for apply_to.
  // Always inline: with a plain and a capturing coupling per body type (coupling.hpp) the
  // compiler would otherwise keep one out-of-line copy, a call on the step's critical path
  // that made the 100-sphere step 25% slower.
  template <typename BodyType>
  [[gnu::always_inline]] inline core::BodyMotion motion_of(const BodyType& body, const double* x,
                                                           core::VecRef x_hat) const {
    const core::BodyMotion m =
        body.motion(Eigen::Map<const core::Vec>(x + slot_.state_offset, slot_.state_size));
    // (27d): contact point velocity v + w x a, with a the lever arm in world coordinates.
    const core::Vec3 a = lever(m);
    x_hat.segment<3>(0) = m.p + a;
    x_hat.segment<3>(3) = m.v + m.w_world.cross(a);
    return m;
  }
  template <typename BodyType>
  void apply_to(const BodyType& body, const core::BodyMotion& at, core::ConstVecRef u,
                double* u_hat) const {
    body.add_wrench(at, lever(at), -core::Vec3(u.head<3>()), core::Vec3::Zero(),
                    Eigen::Map<core::Vec>(u_hat + slot_.input_offset, slot_.input_size));
  }

 private:
  // Contact point minus body origin, world frame.
  core::Vec3 lever(const core::BodyMotion& m) const {
    return body_point_ ? core::Vec3(m.q * local_ + offset_) : offset_;
  }

  const core::Body& body_;
  core::Vec3 offset_;                     // -radius n, world frame
  core::Vec3 local_;                      // the body-frame point the contact sits about
  bool body_point_;                       // local_ != 0: the lever turns with the body
  core::Vec3 axis_ = core::Vec3::Zero();  // a body-fixed friction axis (body frame)
  bool carries_axis_ = false;
  core::Slot slot_;
};

}  // namespace stiction::components
