// bench_pendulum_cost: error against CPU on bench_peers' pendulum with joint friction
// (problem 5, bench/peers/problems.hpp) for stiction's integrators, each over a range of
// steps (fixed-step methods) or tolerances (adaptive ones), so that the methods can be
// compared at equal CPU (issue 36: the second-order method's phase and amplitude errors
// within 2x of rk4's at equal CPU).
//
//   bench_pendulum_cost [--rounds N]
//
// Each row: the integrator, its step or tolerance, steps taken, the thread CPU of stepping
// and reading (the least over the rounds), and the errors bench_peers reports (phase: largest
// |time error| of the turning points; amplitude: largest |angle error| of the turning points
// and the rest angle; the stop time error). Fixed-step methods are sampled every step, the
// adaptive ones at every step they take (they land on each turning point, where the joint's
// slip reverses: core/step_control.hpp), with no bound on their step.
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/body.hpp"
#include "core/integrator.hpp"
#include "core/integrator_traits.hpp"
#include "pendulum.hpp"
#include "problems.hpp"
#include "scene/scene.hpp"

using namespace stiction;
using namespace stiction::peers;

namespace {

struct Setting {
  std::string integrator;
  double dt = 0.0;         // the step, or the first step of an adaptive integrator
  double tolerance = 0.0;  // adaptive only
};

struct Outcome {
  long steps = 0;
  double cpu = std::numeric_limits<double>::infinity();
  Errors errors;  // against the ideal Coulomb pendulum (bench_peers' measure)
  Errors model;   // against the same Kikuuwe model converged (the integrator's own error)
  Swings swings;
  bool failed = false;
};

Outcome run(const Setting& s, double duration, const Swings* converged) {
  Outcome out;
  scene::Scene scene = scene::load_scene(std::string(STICTION_PEERS_SCENE_DIR) + "/pendulum.toml");
  core::Network& network = *scene.network;
  const auto* arm = dynamic_cast<const core::JointSpace*>(network.admittances()[0].get());
  auto stepper = core::make_stepper(s.integrator, network.state_dim(), s.dt, s.tolerance);
  core::Vec x = network.initial_state();
  std::vector<Sample> samples;
  samples.reserve(200000);
  auto read = [&](double t) {
    // planar_arm about -y: theta from +x towards +z, hanging at -pi/2 (as stiction_peer.cpp).
    const double phi = arm->joint_angle(x, 0) + 0.5 * std::numbers::pi;
    const double rate = arm->joint_rate(x, 0), l = kPendulum.com();
    Sample sample;
    sample.t = t;
    sample.p[0] = l * std::sin(phi);
    sample.p[2] = -l * std::cos(phi);
    sample.v[0] = l * rate * std::cos(phi);
    sample.v[2] = l * rate * std::sin(phi);
    sample.w[1] = -rate;
    samples.push_back(sample);
  };
  const bool fixed = !core::is_adaptive(s.integrator);
  const double start = thread_cpu_seconds();
  double t = 0.0;
  read(t);
  try {
    for (long k = 1; t < duration - 1e-12; ++k) {
      // Fixed steps: time from the step count, as the run loop does.
      const double h = stepper->advance(network, t, duration - t, x);
      t = fixed ? std::min(duration, static_cast<double>(k) * s.dt) : t + h;
      read(t);
      ++out.steps;
      if (!x.allFinite()) throw std::runtime_error("not finite");
    }
  } catch (const std::runtime_error&) {
    out.failed = true;
    return out;
  }
  out.cpu = thread_cpu_seconds() - start;
  out.swings = swings_of(samples);
  out.errors = compare_swings(out.swings, pendulum_reference(duration));
  if (converged != nullptr) out.model = compare_swings(out.swings, *converged);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int rounds = 3;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--rounds" && i + 1 < argc) rounds = std::max(1, std::atoi(argv[++i]));
  }
  const double duration = plan_of(Problem::pendulum, false).duration;
  pendulum_reference(duration);  // computed once, not timed
  // The model's own converged solution: the same scene (Kikuuwe joint friction, K = 5000
  // N m/rad) by rk4 at 1e-5 and 5e-6 s, extrapolated (fixed steps cross each turning point
  // somewhere inside a step: their turn times converge at first order, 1.9e-4 s at 1e-4 s),
  // T = 2 T(h/2) - T(h). Against the ideal Coulomb reference every integrator converges to
  // the model's difference from it (7.4e-3 s, 1.2e-5 rad: the stick stiffness,
  // docs/study.md), which hides the integrators' own errors.
  const Swings coarse = run({"rk4", 1e-5, 0.0}, duration, nullptr).swings;
  Swings converged = run({"rk4", 5e-6, 0.0}, duration, nullptr).swings;
  if (coarse.turns.size() != converged.turns.size()) {
    std::fprintf(stderr, "the converged runs turn %zu and %zu times\n", coarse.turns.size(),
                 converged.turns.size());
    return 1;
  }
  for (std::size_t i = 0; i < converged.turns.size(); ++i) {
    converged.turns[i].t = 2.0 * converged.turns[i].t - coarse.turns[i].t;
    converged.turns[i].angle = 2.0 * converged.turns[i].angle - coarse.turns[i].angle;
  }
  converged.stop_time = 2.0 * converged.stop_time - coarse.stop_time;
  converged.rest_angle = 2.0 * converged.rest_angle - coarse.rest_angle;
  std::printf("extrapolation's correction to rk4 at 5e-6 s: stop %.2e s, rest angle %.2e rad\n\n",
              converged.stop_time - coarse.stop_time, converged.rest_angle - coarse.rest_angle);
  std::vector<Setting> settings;
  for (double dt : {2e-3, 1e-3, 4e-4, 2e-4, 1e-4}) settings.push_back({"rk4", dt, 0.0});
  for (double dt : {1e-3, 1.0 / 240, 1.0 / 60}) settings.push_back({"implicit", dt, 0.0});
  for (const char* name : {"rk4_adaptive", "sdirk2", "sdirk4"}) {
    for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) settings.push_back({name, 1e-4, tol});
  }
  std::printf("pendulum with joint friction, %g s, thread CPU (least of %d rounds)\n\n", duration,
              rounds);
  std::printf("Errors against the model converged (rk4 at 1e-5 and 5e-6 s, extrapolated), then "
              "against the ideal Coulomb pendulum\n\n");
  std::printf("| integrator | step / tolerance | steps | CPU ms | phase s | amplitude rad | stop s "
              "| Coulomb: phase s | amplitude rad | note |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Setting& s : settings) {
    Outcome best;
    for (int r = 0; r < rounds; ++r) {
      Outcome o = run(s, duration, &converged);
      if (o.failed) {
        best = o;
        break;
      }
      if (o.cpu < best.cpu) best = o;
    }
    char what[64];
    if (s.tolerance > 0.0) {
      std::snprintf(what, sizeof what, "tol %g", s.tolerance);
    } else {
      std::snprintf(what, sizeof what, "dt %.4g", s.dt);
    }
    if (best.failed) {
      std::printf("| %s | %s | failed | | | | | | | |\n", s.integrator.c_str(), what);
      continue;
    }
    std::printf("| %s | %s | %ld | %.3f | %.2e | %.2e | %.2e | %.2e | %.2e | %s |\n",
                s.integrator.c_str(), what, best.steps, 1e3 * best.cpu, best.model.first,
                best.model.second, best.model.third, best.errors.first, best.errors.second,
                best.model.note.c_str());
    std::fflush(stdout);
  }
  return 0;
}
