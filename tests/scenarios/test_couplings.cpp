// The network evaluates each impedance through a coupling; a map may offer a direct one
// (core/coupling.hpp) that the compiler fuses. It must compute exactly what the map and the
// impedance compute through their interfaces: checked here bit for bit on every bundled
// scene, at states along a run.
#include <catch2/catch.hpp>
#include <string>

#include "core/integrator.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

// x_dot through the public interfaces: Psi, the impedance, Phi, then the admittances.
core::Vec generic_derivative(core::Network& net, double t, const core::Vec& x, double tau) {
  core::Vec x_dot = core::Vec::Zero(net.state_dim());
  core::Vec u_hat = core::Vec::Zero(net.input_dim());
  for (std::size_t i = 0; i < net.impedances().size(); ++i) {
    const core::Impedance& imp = *net.impedances()[i];
    const core::CoordinateMap& map = net.map_of(static_cast<int>(i));
    const core::Slot state = net.impedance_slot(static_cast<int>(i));
    core::Vec x_hat(map.motion_size()), u(map.force_size());
    map.motion(x, x_hat);
    imp.evaluate(t, x_hat, x.segment(state.state_offset, state.state_size), tau, u,
                 x_dot.segment(state.state_offset, state.state_size));
    map.apply(x, u, u_hat);
  }
  for (std::size_t j = 0; j < net.admittances().size(); ++j) {
    const core::Slot s = net.admittance_slot(static_cast<int>(j));
    net.admittances()[j]->derivative(x.segment(s.state_offset, s.state_size),
                                     u_hat.segment(s.input_offset, s.input_size),
                                     x_dot.segment(s.state_offset, s.state_size));
  }
  return x_dot;
}

}  // namespace

TEST_CASE("couplings compute the same bits as the maps and impedances they fuse",
          "[network]") {
  for (const auto& [name, description] : scene::bundled_scenes()) {
    auto scene = scene::load_scene(name);
    core::Network& net = *scene.network;
    core::RungeKuttaStepper stepper(core::rk4_tableau(), net.state_dim());
    core::Vec x = net.initial_state();
    const double T = scene.run.dt;
    // Through the landing of the sphere (~20 ms) and the start of every other scene.
    for (int k = 0; k <= 3000; ++k) {
      if (k % 50 == 0) {
        for (double tau : {0.5 * T, T}) {
          core::Vec through_network(net.state_dim());
          net.derivative(k * T, x, tau, through_network);
          const core::Vec through_interfaces = generic_derivative(net, k * T, x, tau);
          INFO(name << " at step " << k << ", tau " << tau);
          REQUIRE((through_network.array() == through_interfaces.array()).all());
        }
      }
      stepper.step(net, k * T, T, x);
    }
  }
}
