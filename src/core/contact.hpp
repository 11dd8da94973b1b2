// Capability of an impedance whose contact can open: one that pushes along a normal only
// while it is pressed (a contact with a surface). Its events include `open` (the normal force
// is zero: no stick or slip while it lasts) and touch-down; elements without it (joints) are
// always closed. A capability of its own rather than one more virtual of Impedance.
#pragma once

#include "core/types.hpp"

namespace stiction::core {

class NormalContact {
 public:
  virtual ~NormalContact() = default;
  // Normal force (>= 0) the element exerts at input x_hat; 0 while the contact is open.
  virtual double contact_normal_force(ConstVecRef x_hat) const = 0;
};

}  // namespace stiction::core
