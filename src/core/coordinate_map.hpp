// One impedance's share of the paper's coordinate maps (eq. 13): Psi gathers the impedance
// input x_hat from admittance states, Phi scatters its output u into admittance inputs.
// A map knows the admittances it touches; the network tells it where their slices are.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/coupling.hpp"
#include "core/types.hpp"

namespace stiction::core {

class Admittance;
class Impedance;

// Where one admittance's slices live in the system vectors.
struct Slot {
  int state_offset = 0;
  int state_size = 0;
  int input_offset = 0;
  int input_size = 0;
};

class CoordinateMap {
 public:
  virtual ~CoordinateMap() = default;

  virtual int motion_size() const = 0;  // size of x_hat
  virtual int force_size() const = 0;   // size of u
  // Where in x_hat the velocity conjugate to u starts: force_size() entries whose product
  // with u is the power the element exchanges (a contact point's velocity, a body's angular
  // velocity for a torque), the moving side's, so that pushing it with +u shows as a negative
  // change (it receives -u). -1 where x_hat has no such contiguous part. `check` reads each
  // element's effective mass through it (services/dynamics_fingerprint.cpp). Default: x_hat
  // = [position (n), velocity (n)].
  virtual int conjugate_velocity_offset() const {
    return motion_size() == 2 * force_size() ? force_size() : -1;
  }
  // The admittances this map reads and drives, in a fixed order; the network calls bind()
  // with their slots in the same order once the layout is known.
  virtual std::vector<const Admittance*> admittances() const = 0;
  virtual void bind(const std::vector<Slot>& slots) = 0;

  // Where a contact element touches, for the bodies' events (body_events.hpp): the world
  // contact point at state x, and whether it is one fixed point of the bodies (a corner) or
  // one that travels over their surface as they roll (a cylinder rim's lowest point), which
  // tells nothing about the edge a body rests on. nullopt: the map does not say (a contact
  // on one body then reads the point from x_hat's first three entries, fixed).
  struct ContactSite {
    Vec3 world = Vec3::Zero();
    bool rolling = false;
  };
  virtual std::optional<ContactSite> contact_site(ConstVecRef /*x*/) const { return std::nullopt; }

  // Psi: x (whole system state) -> x_hat.
  virtual void motion(ConstVecRef x, VecRef x_hat) const = 0;
  // Phi: accumulate the effect of u into u_hat (whole input vector); x is the state the
  // motion was taken at (lever arms, frames).
  virtual void apply(ConstVecRef x, ConstVecRef u, VecRef u_hat) const = 0;

  // A fused motion-evaluate-apply for `impedance` (whose state is the slice `state` of x),
  // if this map knows its type and its bodies' (see coupling.hpp); nullptr otherwise. Called
  // after bind().
  virtual std::unique_ptr<Coupling> direct_coupling(const Impedance& /*impedance*/,
                                                    const Slot& /*state*/) const {
    return nullptr;
  }
};

}  // namespace stiction::core
