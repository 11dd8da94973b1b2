// Rolling and spinning resistance between two bodies in contact (issue 38 item 3): a
// Kikuuwe element (eq. 19, plain gsat) on the first body's angular velocity relative to the
// second's, w_rel = w_a - w_b, with the level c N, N the pair contact's own normal force
// (pair_contact.hpp, computed by a copy of that contact from the same input, bit for bit):
// - part `rolling`: the tangential part w_t = w_rel - (n.w_rel) n, level
//   `rolling_resistance` * N;
// - part `spin`: the normal part n.w_rel, a 1-D state e (rad), level `spin_friction` * N.
// Why the rolling state is a world 3-vector kept tangent, as PairContact's e: the normal
// turns with the pair, so no fixed tangent basis exists; the law uses e_t = e - (n.e) n,
//   f = gsat(c N, (B + tau K) w_t + K e_t);  e_dot = w_t while unsaturated (exactly: a pair
//   that has stopped rolling on each other does not creep), else (f - K e) / (B + tau K).
// For a sphere resting on a fixed body this is the sphere-on-plane element
// (rolling_resistance.hpp) with the plane's basis replaced by the world one.
// Input x_hat = [d (1), n (3), v_rel (3), w_rel (3)] (PairTwistMap: PairContactMap's input,
// then w_a - w_b, world). Output u = the torque the first body exerts on the element
// (world): the first body receives -u, the second +u, free torques (the pair's angular
// momentum is kept).
// Signals: tau (x y z, the torque on the first body, world) and e (rolling: x y z, world;
// spin: one entry).
#pragma once

#include "components/impedance/friction_capabilities.hpp"
#include "components/impedance/pair_contact.hpp"
#include "components/impedance/rolling_resistance.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

class PairRollingResistance final : public core::Impedance,
                                    public FrictionSpring,
                                    public core::ClampedFriction,
                                    public core::SlipElement {
 public:
  // params.body and params.radius are not read (the pair map gives the contact).
  PairRollingResistance(std::string name, const PairContactParams& contact,
                        const RollingResistanceParams& params);
  std::string_view type() const override { return "kikuuwe_contact"; }
  int input_size() const override { return 10; }
  int output_size() const override { return 3; }
  int state_size() const override { return dimension(); }
  std::vector<std::string> state_labels() const override;
  void initial_state(core::VecRef y) const override { y.setZero(); }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  int regime(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const override;
  // The whole output is friction: held entirely.
  void evaluate_friction_held(double /*t*/, core::ConstVecRef /*x_hat*/, core::ConstVecRef /*y*/,
                              double /*tau*/, core::ConstVecRef u_ref, core::ConstVecRef y_dot_ref,
                              core::VecRef u, core::VecRef y_dot) const override {
    u = u_ref;
    y_dot = y_dot_ref;
  }
  double friction_cap_energy(core::ConstVecRef x_hat) const override {
    const double level = params_.coefficient * contact_.contact_normal_force(x_hat.head<7>());
    return level * level / params_.stiffness;
  }
  // The relative angular slip (world, rad/s): w_t for rolling, (n.w_rel) n for spin.
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override;
  core::Vec3 unloaded_slip(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const override;
  const RollingResistanceParams& params() const { return params_; }

 private:
  int dimension() const { return params_.part == RollingPart::rolling ? 3 : 1; }

  PairContact contact_;  // the pair's contact, for its normal force
  RollingResistanceParams params_;
};

}  // namespace stiction::components
