// Kikuuwe contact with normal force against a flat surface {x : n . x = offset}
// (paper eqs. 23-24, DESIGN section 1). Input x_hat = [p_c (3), v_c (3)], the world
// position and velocity of the body's contact point. With penetration d = offset - n.p_c
// and normal speed v_n = n.v_c, the normal force on the body is N = max(0, K d - B v_n);
// the tangential friction is eq. (19) in the surface plane with F = mu N and a 2-D state e
// (coordinates along the tangent basis t1, t2). With N = 0 the force is zero and e relaxes
// toward zero through eps = -K e / (B + tau K).
// Output u = -(force on the body) (the moving side's force on the element).
// Signals: f (force on the body, world), slip (tangential contact-point velocity, world),
// e (axes 0 1 along t1, t2), and the normal force n_force.
// The surface may have an extent (a rectangle or half-plane of its plane, surface_extent.hpp):
// a contact point whose projection lies outside it is not in contact (N = 0). The law
// itself is contact_law.hpp, shared with the moving surfaces (moving_contact.hpp).
#pragma once

#include <algorithm>
#include <limits>

#include "components/impedance/contact_capabilities.hpp"
#include "components/impedance/contact_law.hpp"
#include "components/impedance/surface_extent.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct KikuuweContactParams {
  core::Vec3 normal{0.0, 0.0, 1.0};
  double offset = 0.0;        // surface height along the normal (m)
  double stiffness = 1e7;     // K: normal and tangential (N/m)
  double damping = 10.0;      // B (N s/m)
  double mu = 0.1;                 // kinetic coefficient
  double mu_static = -1.0;         // static coefficient, >= mu; < 0: equal to mu
  double stribeck_velocity = 0.0;  // m/s, 0: none (friction_law.hpp)
  double viscous = 0.0;            // N s/m, while sliding
  // Anisotropic friction (issue 38 item 2; contact_law.hpp's elliptic limit): mu along
  // `friction_axis`, mu_2 across it in the surface; mu_2 < 0 or mu_2 == mu: isotropic.
  double mu_2 = -1.0;
  // mu's direction, world, in the surface plane at rest (its part along the normal is
  // dropped); zero: the surface's first tangent t1.
  core::Vec3 friction_axis = core::Vec3::Zero();
  // Body-fixed axes: the map appends mu's direction in world coordinates to x_hat (input
  // [p_c, v_c, axis], 9 entries; contact_point_map.hpp), taken in the surface plane at every
  // evaluation; `friction_axis` is then only the fallback for an axis along the normal.
  bool body_axes = false;
  // Tangential stiffness/damping of the friction element; default: equal to the normal ones
  // as in the paper.
  double tangential_stiffness = -1.0;
  double tangential_damping = -1.0;
  SurfaceExtent extent;                                 // default: the whole plane
  Eigen::Vector2d initial_e = Eigen::Vector2d::Zero();  // friction state at t = 0 (m)
};

class KikuuweContact final : public core::Impedance, public ContactCapabilities {
 public:
  KikuuweContact(std::string name, const KikuuweContactParams& params);
  std::string_view type() const override { return "kikuuwe_contact"; }
  int input_size() const override { return params_.body_axes ? 9 : 6; }
  int output_size() const override { return 3; }
  int state_size() const override { return 2; }
  std::vector<std::string> state_labels() const override { return {"e.0", "e.1"}; }
  void initial_state(core::VecRef y) const override { y.head<2>() = params_.initial_e; }
  void set_initial_e(const Eigen::Vector2d& e) { params_.initial_e = e; }
  // Inline: contact couplings fuse it into their straight code (core/coupling.hpp).
  void evaluate(double /*t*/, core::ConstVecRef x_hat, core::ConstVecRef y, double tau,
                core::VecRef u, core::VecRef y_dot) const override {
    if (params_.body_axes) return evaluate_body_axes(x_hat, y, tau, u, y_dot);
    const core::Vec3 v_c = x_hat.segment<3>(3);
    const core::Vec3 on_body = contact_law(frame_, coefficients_, normal_force(x_hat), v_c,
                                           y.head<2>(), tau, y_dot.head<2>());
    // u is the negative of the force on the body.
    u.head<3>() = -on_body;
  }
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  int regime(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const override;
  double stored_energy(core::ConstVecRef x_hat, core::ConstVecRef y) const override;
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override;
  core::Vec3 unloaded_slip(core::ConstVecRef x_hat, core::ConstVecRef y,
                           double tau) const override;
  // The tangential force and e's rate held, the normal force live.
  void evaluate_friction_held(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau,
                              core::ConstVecRef u_ref, core::ConstVecRef y_dot_ref, core::VecRef u,
                              core::VecRef y_dot) const override;
  double contact_normal_force(core::ConstVecRef x_hat) const override { return normal_force(x_hat); }
  double contact_closure(core::ConstVecRef x_hat) const override {
    const core::Vec3 p_c = x_hat.segment<3>(0);
    if (bounded_ && !params_.extent.contains(p_c - params_.extent.centre)) {
      return std::numeric_limits<double>::quiet_NaN();
    }
    return components::contact_closure(coefficients_, params_.offset - n_.dot(p_c),
                                       n_.dot(core::Vec3(x_hat.segment<3>(3))));
  }
  const KikuuweContactParams& params() const { return params_; }
  // The friction coefficients (an anisotropic law's axis along t1, t2 included).
  const ContactFriction& friction() const { return coefficients_.friction; }
  const core::Vec3& tangent1() const { return t1_; }
  const core::Vec3& tangent2() const { return t2_; }
  const core::Vec3& normal() const { return n_; }

 private:
  double normal_force(core::ConstVecRef x_hat) const {
    // (23a) with the clamp of DESIGN section 1: no adhesion, so mu N is never negative.
    const core::Vec3 p_c = x_hat.segment<3>(0);
    if (bounded_ && !params_.extent.contains(p_c - params_.extent.centre)) return 0.0;
    return components::contact_normal_force(coefficients_, params_.offset - n_.dot(p_c),
                                n_.dot(core::Vec3(x_hat.segment<3>(3))));
  }

  // evaluate() with body-fixed axes (x_hat of 9 entries; never inlined into the fused
  // couplings, which carry 6).
  [[gnu::noinline]] void evaluate_body_axes(core::ConstVecRef x_hat, core::ConstVecRef y,
                                            double tau, core::VecRef u, core::VecRef y_dot) const;

  KikuuweContactParams params_;
  core::Vec3 n_, t1_, t2_;
  double kt_, bt_;
  ContactFrame frame_;
  ContactCoefficients coefficients_;
  bool bounded_ = false;
};

}  // namespace stiction::components
