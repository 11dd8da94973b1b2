#include "services/dynamics_fingerprint.hpp"

#include <algorithm>
#include <cmath>

#include "core/admittance.hpp"
#include "core/capabilities.hpp"

namespace stiction::services {

// Push with a unit force through the map of impedance i at the initial state, let the
// admittances accelerate for a unit time
// and read the velocity conjugate to the force back from x_hat (the map says where it is:
// a point's velocity, a body's angular velocity for a torque). The largest entry gives the
// stiffest mode, the one that limits the step. NaN for a map that names no such velocity.
double largest_mobility(core::Network& network, int i, const core::Vec& x0, double* work) {
  const core::CoordinateMap& map = network.map_of(i);
  const int n = map.force_size();
  const int velocity = map.conjugate_velocity_offset();
  if (velocity < 0 || velocity + n > map.motion_size()) return std::nan("");
  core::Vec base_hat(map.motion_size()), pushed_hat(map.motion_size());
  map.motion(x0, base_hat);
  double largest = 0.0;
  for (int k = 0; k < n; ++k) {
    core::Vec u = core::Vec::Zero(n);
    u[k] = 1.0;
    core::Vec u_hat = core::Vec::Zero(network.input_dim());
    map.apply(x0, u, u_hat);
    core::Vec x1 = x0;
    for (std::size_t a = 0; a < network.admittances().size(); ++a) {
      const core::Admittance& adm = *network.admittances()[a];
      const core::Slot s = network.admittance_slot(static_cast<int>(a));
      // A body the push does not reach does not move: a tree of n joints is pushed once per
      // element that acts on it, not once per element of the scene.
      if (u_hat.segment(s.input_offset, s.input_size).isZero(0.0)) continue;
      if (work != nullptr) *work += 2.0 * s.state_size;
      core::Vec with(s.state_size), without(s.state_size);
      adm.derivative(x0.segment(s.state_offset, s.state_size),
                     u_hat.segment(s.input_offset, s.input_size), with);
      adm.derivative(x0.segment(s.state_offset, s.state_size), core::Vec::Zero(s.input_size),
                     without);
      x1.segment(s.state_offset, s.state_size) += with - without;
    }
    map.motion(x1, pushed_hat);
    // The moving side receives -u: a positive mobility shows as a negative response.
    largest = std::max(largest, -(pushed_hat[velocity + k] - base_hat[velocity + k]));
  }
  return largest;
}

bool DynamicsFingerprint::operator==(const DynamicsFingerprint& other) const {
  if (integrator != other.integrator || pilot_dt != other.pilot_dt || duration != other.duration ||
      state_dim != other.state_dim || numbers.size() != other.numbers.size()) {
    return false;
  }
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    const double a = numbers[i], b = other.numbers[i];
    // Equal, both NaN (no damping declared), or equal to rounding.
    if (!(a == b || (std::isnan(a) && std::isnan(b)) ||
          std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)))) {
      return false;
    }
  }
  return true;
}

DynamicsFingerprint dynamics_fingerprint(scene::Scene& scene) {
  core::Network& network = *scene.network;
  DynamicsFingerprint f;
  f.integrator = scene.run.integrator;
  f.pilot_dt = std::min(scene.run.dt, scene.authored_dt);
  f.duration = scene.run.duration;
  f.state_dim = network.state_dim();
  const core::Vec x0 = network.initial_state();
  double work = 0.0;
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const core::StiffnessHint* hint = network.capabilities(static_cast<int>(i)).stiffness;
    if (hint == nullptr) continue;
    f.numbers.push_back(hint->stiffness());
    f.numbers.push_back(hint->damping());
    // Past the bound, NaN: the bodies' responses below still tell a change of mass.
    f.numbers.push_back(work > kMobilityWork
                            ? std::nan("")
                            : largest_mobility(network, static_cast<int>(i), x0, &work));
  }
  // Every body's response to a unit input on each of its inputs at the initial state (its
  // inverse mass or inertia, as its derivative sees it), so that a change of mass shows even
  // where no element declares a stiffness (an element supplied in code).
  for (std::size_t a = 0; a < network.admittances().size(); ++a) {
    const core::Admittance& adm = *network.admittances()[a];
    const core::Slot s = network.admittance_slot(static_cast<int>(a));
    const auto x = x0.segment(s.state_offset, s.state_size);
    core::Vec base(s.state_size), pushed(s.state_size);
    core::Vec u = core::Vec::Zero(s.input_size);
    adm.derivative(x, u, base);
    for (int k = 0; k < s.input_size; ++k) {
      u.setZero();
      u[k] = 1.0;
      adm.derivative(x, u, pushed);
      for (int r = 0; r < s.state_size; ++r) f.numbers.push_back(pushed[r] - base[r]);
    }
  }
  return f;
}

}  // namespace stiction::services
