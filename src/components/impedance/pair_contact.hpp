// Kikuuwe contact between two bodies (issue 23): the law of a contact with a plane
// (contact_law.hpp's normal force, eq. 19 friction with F = mu N) at one contact point whose
// normal turns with the bodies. Input x_hat = [d (1), n (3), v_rel (3)] from PairContactMap:
// the penetration d (> 0 in contact), the unit normal n (the direction the normal force
// pushes the first body, `body`; the second, `other`, gets the opposite) and the velocity
// of the first body's material point at the contact point relative to the second's.
// Output u = -(force on the first body), world frame; the map applies -u to the first body
// and +u to the second, both at the contact point.
//
// Why e is a world 3-vector kept tangent, not a 2-D surface coordinate: a plane has a fixed
// tangent basis, a pair does not (the normal turns as the bodies move and spin), and a basis
// carried along would have to be chosen and would twist with it. So the friction state is
// the spring's elongation in world coordinates, and the law uses its part in the current
// tangent plane, e_t = e - (n.e) n:
//   f = gsat(mu N, (Bt + tau Kt) v_t + Kt e_t);  e_dot = v_t while unsaturated (exactly,
//   as for a plane: drift-free sticking), else (f - Kt e) / (Bt + tau Kt),
// where the sliding (and open) rate uses the whole e, so a normal part left behind by a
// turning normal relaxes as soon as the contact slides or opens. While stuck, a normal that
// turns by an angle a shortens the spring's tangent part by (1 - cos a): second order, and
// it only lowers the stored energy (never a source of energy).
// Signals as a plane contact's: f (force on the first body), slip (tangential v_rel), e
// (world x y z) and n_force.
#pragma once

#include "components/impedance/contact_capabilities.hpp"
#include "components/impedance/contact_law.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct PairContactParams {
  double stiffness = 1e7;  // K (N/m)
  double damping = 10.0;   // B (N s/m)
  double mu = 0.1;                 // kinetic coefficient
  double mu_static = -1.0;         // static coefficient, >= mu; < 0: equal to mu
  double stribeck_velocity = 0.0;  // m/s, 0: none (friction_law.hpp)
  double viscous = 0.0;            // N s/m, while sliding
  double tangential_stiffness = -1.0;  // default: K
  double tangential_damping = -1.0;    // default: B
  // Whether the map's penetration d is minus the distance between the surfaces while they
  // are apart (sphere-sphere, sphere-box), so that gap() can say the bodies are apart; a
  // box corner's d against the pair's face axis is not (the axis switches).
  bool gap_is_distance = false;
};

class PairContact final : public core::Impedance, public ContactCapabilities {
 public:
  PairContact(std::string name, const PairContactParams& params);
  std::string_view type() const override { return "kikuuwe_contact"; }
  int input_size() const override { return 7; }
  int output_size() const override { return 3; }
  int state_size() const override { return 3; }
  std::vector<std::string> state_labels() const override { return {"e.x", "e.y", "e.z"}; }
  void initial_state(core::VecRef y) const override { y.head<3>().setZero(); }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau,
                core::VecRef u, core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  int regime(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const override;
  double stored_energy(core::ConstVecRef x_hat, core::ConstVecRef y) const override;
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override;
  double gap(core::ConstVecRef x_hat) const override;
  double approach_speed(core::ConstVecRef x_hat) const override;
  core::Vec3 unloaded_slip(core::ConstVecRef x_hat, core::ConstVecRef y,
                           double tau) const override;
  void evaluate_friction_held(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau,
                              core::ConstVecRef u_ref, core::ConstVecRef y_dot_ref, core::VecRef u,
                              core::VecRef y_dot) const override;
  double contact_normal_force(core::ConstVecRef x_hat) const override;
  double contact_closure(core::ConstVecRef x_hat) const override;
  const PairContactParams& params() const { return params_; }

 private:
  PairContactParams params_;
  ContactCoefficients coefficients_;
};

}  // namespace stiction::components
