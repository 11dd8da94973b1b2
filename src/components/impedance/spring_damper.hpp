// Linear spring-damper, paper eq. (10), in n dimensions:
//   u = K (p - rest) + B v
// Input x_hat = [p (n), v (n)]: the displacement and relative velocity of the moving side
// with respect to the other side (the maps give position-then-velocity pairs, e.g.
// PointMap's p_A - p_B). `rest` (n, zero if empty) is the displacement at which the spring
// is relaxed. No state.
// Sign convention (DESIGN section 1): u is the force the moving side exerts on the element;
// the moving side receives -u (pulled back toward rest), the other side +u.
// Signals: the force on the moving side, -u: `tau` when n = 1, `f` when n > 1 (axes x y z
// for n = 3, 0 1 ... otherwise).
#pragma once

#include "core/capabilities.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct SpringDamperParams {
  double stiffness = 1e3;  // K (N/m or Nm/rad)
  double damping = 0.0;    // B (Ns/m or Nms/rad)
  int dimension = 3;
  core::Vec rest;  // n entries, or empty for zero
};

class SpringDamper final : public core::Impedance,
                           public core::EnergyStore,
                           public core::StiffnessHint {
 public:
  SpringDamper(std::string name, const SpringDamperParams& params);
  std::string_view type() const override { return "spring_damper"; }
  int input_size() const override { return 2 * params_.dimension; }
  int output_size() const override { return params_.dimension; }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  // 0.5 K |p - rest|^2, for the energy monitor.
  double stored_energy(core::ConstVecRef x_hat, core::ConstVecRef y) const override;
  const SpringDamperParams& params() const { return params_; }

 private:
  SpringDamperParams params_;
};

}  // namespace stiction::components
