// Capability of an impedance whose contact can open: one that pushes along a normal only
// while it is pressed (a contact with a surface). Its events include `open` (the normal force
// is zero: no stick or slip while it lasts) and touch-down; elements without it (joints) are
// always closed. A capability of its own rather than one more virtual of Impedance.
#pragma once

#include <limits>

#include "core/types.hpp"

namespace stiction::core {

class NormalContact {
 public:
  virtual ~NormalContact() = default;
  // Normal force (>= 0) the element exerts at input x_hat; 0 while the contact is open.
  virtual double contact_normal_force(ConstVecRef x_hat) const = 0;
  // How closed the contact is at x_hat (N), continuous in the state: > 0 exactly when
  // contact_normal_force is, and changing sign where it opens or closes. The run's events
  // place a touch-down or a lift-off where it crosses zero within the step (core/events.hpp);
  // NaN where the element cannot say (a point leaving a bounded surface's extent): the step's
  // end is taken.
  virtual double contact_closure(ConstVecRef /*x_hat*/) const {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // For a contact between two bodies: how far apart their surfaces are at x_hat (m; > 0:
  // apart, so the element exerts no force and its state evolves on its own), and a bound on
  // how fast they approach (m/s). A step of h with gap > 2 h speed leaves the two bodies in
  // separate islands of the implicit step (core/islands.hpp). NaN where the element cannot
  // say: it then always joins its bodies.
  virtual double gap(ConstVecRef /*x_hat*/) const { return std::numeric_limits<double>::quiet_NaN(); }
  virtual double approach_speed(ConstVecRef /*x_hat*/) const {
    return std::numeric_limits<double>::quiet_NaN();
  }
};

}  // namespace stiction::core
