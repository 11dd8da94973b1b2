#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "app/commands.hpp"
#include "app/network_graph.hpp"
#include "app/pilot.hpp"
#include "core/integrator.hpp"
#include "core/stability.hpp"
#include "scene/scene.hpp"
#include "sys/interrupt.hpp"

namespace stiction::app {
namespace {

// Mobility (inverse effective mass or inertia) that impedance i sees at the initial state:
// push with a unit force through its map, let the admittances accelerate for a unit time
// and read the velocity part of x_hat back. The largest entry gives the stiffest mode, the
// one that limits the step. Works for every map whose x_hat is [position (n), velocity (n)]
// with n = force size; NaN otherwise.
double largest_mobility(core::Network& network, int i) {
  const core::CoordinateMap& map = network.map_of(i);
  const int n = map.force_size();
  if (map.motion_size() != 2 * n) return std::nan("");
  const core::Vec x0 = network.initial_state();
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
      core::Vec with(s.state_size), without(s.state_size);
      adm.derivative(x0.segment(s.state_offset, s.state_size),
                     u_hat.segment(s.input_offset, s.input_size), with);
      adm.derivative(x0.segment(s.state_offset, s.state_size), core::Vec::Zero(s.input_size),
                     without);
      x1.segment(s.state_offset, s.state_size) += with - without;
    }
    map.motion(x1, pushed_hat);
    // The moving side receives -u: a positive mobility shows as a negative response.
    largest = std::max(largest, -(pushed_hat[n + k] - base_hat[n + k]));
  }
  return largest;
}

std::string labels_of(const core::LayoutEntry& entry) {
  std::string out;
  for (const auto& l : entry.labels) out += (out.empty() ? "" : " ") + l;
  return out;
}

}  // namespace

int check_command(const std::string& scene_name, const std::string& graph_path) {
  scene::Scene scene = scene::load_scene(scene_name);
  core::Network& network = *scene.network;
  const core::RunOptions& run = scene.run;
  std::printf("%s: ok (%s)\n", scene.name.c_str(), scene.path.c_str());
  if (!scene.description.empty()) std::printf("  %s\n", scene.description.c_str());
  std::printf("simulation: %s, dt = %g s, duration = %g s, %g rows/s\n", run.integrator.c_str(),
              run.dt, run.duration, run.output_rate);

  std::printf("\nstate layout (%d numbers):\n", network.state_dim());
  for (const core::LayoutEntry& e : network.layout()) {
    if (e.size == 0) {
      std::printf("  %-9s %s (%s): no state\n", "-", e.component.c_str(), e.type.c_str());
      continue;
    }
    std::string range = "[";  // appended piecewise: GCC 12 -Wrestrict false positive
    range += std::to_string(e.offset) + ".." + std::to_string(e.offset + e.size - 1) + "]";
    std::printf("  %-9s %s (%s): %s\n", range.c_str(), e.component.c_str(), e.type.c_str(),
                labels_of(e).c_str());
  }

  std::printf("\nstiffest elements (linearized at the initial state):\n");
  bool any = false;
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const core::Impedance& imp = *network.impedances()[i];
    const double K = imp.stiffness();
    if (!(K > 0.0)) continue;
    any = true;
    const double mobility = largest_mobility(network, static_cast<int>(i));
    if (!(mobility > 0.0)) {
      std::printf("  %s (%s): K = %g; no effective mass could be computed for its wiring\n",
                  imp.name().c_str(), std::string(imp.type()).c_str(), K);
      continue;
    }
    const double omega = std::sqrt(K * mobility);
    const double B = imp.damping();
    const double zeta = std::isfinite(B) ? B * mobility / (2.0 * omega) : std::nan("");
    std::printf("  %s (%s): K = %g against an effective mass/inertia %g: omega = %.5g rad/s, "
                "damping ratio %.3g; an undamped mode at this omega limits rk4 to dt < 2.83 / "
                "omega = %.3g s\n",
                imp.name().c_str(), std::string(imp.type()).c_str(), K, 1.0 / mobility, omega,
                zeta, 2.8284271247461903 / omega);
  }
  if (!any) std::printf("  no stiff elements\n");

  // The real limit depends on all elements at once, on the friction laws' stage sizes and on
  // the states the scene passes through: linearize the actual step map along a run.
  std::printf("\npredicted largest stable step (step map linearized at up to 10 states of each "
              "regime of a run at the scene's settings; a mode growing > 5%% per step counts as "
              "unstable):\n");
  const Pilot pilot = bounded_pilot(network, run);
  if (pilot.shortened) {
    std::printf("  (pilot run bounded to its first %g s of %g s, see docs/limits.md)\n",
                pilot.options.duration, run.duration);
  }
  const auto states = core::sample_states(network, pilot.options, 10);
  if (sys::interrupted()) throw sys::Interrupted{};
  for (const std::string name : {"euler", "symplectic_euler", "heun", "rk4"}) {
    const core::StepLimit limit = core::predict_step_limit(network, name, states);
    if (limit.unbounded) {
      std::printf("  %-17s no limit found up to 1 s\n", name.c_str());
      continue;
    }
    if (limit.max_step <= 0.0) {
      std::printf("  %-17s unstable at every step size tried\n", name.c_str());
      continue;
    }
    std::printf("  %-17s dt < %.3g s (limited at t = %.3g s)%s\n", name.c_str(), limit.max_step,
                limit.limiting_time,
                name == run.integrator ? (run.dt < limit.max_step ? "  scene dt: ok" : "  scene dt: TOO LARGE") : "");
    if (limit.chatter_free_step < limit.max_step) {
      std::printf("  %-17s   above %.3g s stuck friction chatters (bounded by its limit force)\n",
                  "", limit.chatter_free_step);
    }
  }
  if (!graph_path.empty()) {
    write_network_dot(scene, graph_path);
    std::printf("\nwrote %s\n", graph_path.c_str());
  }
  return kExitOk;
}

int scenes_command() {
  const auto scenes = scene::bundled_scenes();
  std::size_t width = 0;
  for (const auto& [name, description] : scenes) width = std::max(width, name.size());
  for (const auto& [name, description] : scenes) {
    std::printf("%-*s  %s\n", static_cast<int>(width), name.c_str(), description.c_str());
  }
  return kExitOk;
}

}  // namespace stiction::app
