// One impedance wired to the admittances through its coordinate map: Psi, the impedance and
// Phi (eqs. 13d, 22, 13f) as one call. The network evaluates its derivative through these.
//
// The generic coupling (network.cpp) calls the map and the impedance through their
// interfaces, handing x_hat and u through the network's vectors. A map may offer a direct
// coupling for impedance and body types it knows (CoordinateMap::direct_coupling): the same
// calls on final classes whose hot paths are inline, which the compiler fuses into straight
// code with x_hat and u in registers. Same arithmetic in the same order, so the same bits;
// it removes most of what the network costs over a hand-written loop (README, Performance).
#pragma once

#include <memory>

#include "core/types.hpp"

namespace stiction::core {

class Coupling {
 public:
  virtual ~Coupling() = default;
  // Writes the impedance's state rate into its slice of x_dot and adds the force it puts
  // on the admittances to u_hat. Plain pointers to the network's whole vectors (state,
  // state rate, admittance inputs; the coupling knows its slices): views passed by value
  // live on the stack, and every call would read them back from there first.
  virtual void exchange(double t, const double* x, double tau, double* x_dot, double* u_hat) = 0;
  // The same coupling, except that each exchange() also copies the x_hat it computes to
  // `motion_out` and the impedance's state to `state_out` (Network::capture_slip_inputs_next),
  // or nullptr if this coupling has no such twin (the network then wraps it).
  virtual std::unique_ptr<Coupling> capturing(double* /*motion_out*/, double* /*state_out*/) const {
    return nullptr;
  }
};

}  // namespace stiction::core
