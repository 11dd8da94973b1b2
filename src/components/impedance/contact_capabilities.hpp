// What a Kikuuwe contact offers beyond its law, shared by the fixed and the moving surfaces
// (kikuuwe_contact.hpp, moving_contact.hpp): a normal force that opens (NormalContact), a
// clamped friction (regime, held evaluation), a slip velocity, the energy of its springs and
// its stiffness. The friction's cap, (mu N)^2 / Kt, is the same for both and written here;
// the rest depends on each surface's geometry.
#pragma once

#include "core/capabilities.hpp"
#include "core/contact.hpp"

namespace stiction::components {

class ContactCapabilities : public core::NormalContact,
                            public core::ClampedFriction,
                            public core::SlipElement,
                            public core::EnergyStore,
                            public core::StiffnessHint {
 public:
  // K and B of the normal spring-damper, the largest coefficient (the stuck band's edge), the
  // tangential (friction) stiffness Kt, and mu_static / mu.
  ContactCapabilities(double stiffness, double damping, double mu, double tangential_stiffness,
                      double static_ratio)
      : core::StiffnessHint(stiffness, damping),
        mu_(mu),
        kt_(tangential_stiffness),
        static_ratio_(static_ratio) {}
  double friction_cap_energy(core::ConstVecRef x_hat) const final {
    const double limit = mu_ * contact_normal_force(x_hat);
    return limit * limit / kt_;
  }
  double static_ratio() const final { return static_ratio_; }

 private:
  double mu_, kt_, static_ratio_;
};

}  // namespace stiction::components
