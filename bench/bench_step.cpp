// ns per integration step of the bundled scenes through the modular network, and the
// hand-fused Simulation I beside it (the price of modularity, issue 5).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>

#include "core/integrator.hpp"
#include "fused_sphere.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

void step_scene(benchmark::State& state, const char* scene_name, const char* integrator) {
  auto scene = scene::load_scene(scene_name);
  core::Network& net = *scene.network;
  core::RungeKuttaStepper stepper(core::tableau_by_name(integrator), net.state_dim());
  core::Vec x = net.initial_state();
  const double T = scene.run.dt;
  long k = 0;
  for (auto _ : state) {
    stepper.step(net, k * T, T, x);
    // Restart before the scene ends so every timed step is a real one of the scene.
    if (++k * T >= scene.run.duration) {
      k = 0;
      x = net.initial_state();
    }
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["state_dim"] = net.state_dim();
}

void fused_sphere_rk4(benchmark::State& state) {
  bench::FusedSphere sphere;
  long k = 0;
  for (auto _ : state) {
    sphere.step_rk4(1e-4);
    if (++k == 20000) {
      k = 0;
      sphere = bench::FusedSphere();
    }
    benchmark::DoNotOptimize(sphere.x.data());
  }
}

// The fused loop must compute what the network computes, or the ratio means nothing.
void check_fused_matches_network() {
  auto scene = scene::load_scene("sphere_roll");
  core::Network& net = *scene.network;
  core::RungeKuttaStepper stepper(core::rk4_tableau(), net.state_dim());
  core::Vec x = net.initial_state();
  bench::FusedSphere fused;
  // 300 steps take the sphere through its first landing (at about step 203). Over longer
  // runs the bounces amplify rounding differences (the lever arm (p + a) - p versus a).
  for (int k = 0; k < 300; ++k) {
    stepper.step(net, k * 1e-4, 1e-4, x);
    fused.step_rk4(1e-4);
  }
  const double diff = (x.head<13>() - fused.x).norm() + (x.segment<2>(13) - fused.e).norm();
  std::printf("fused vs modular sphere_roll after 300 rk4 steps: |difference| = %.3g\n", diff);
  if (!(diff < 1e-9)) {
    std::fprintf(stderr, "fused and modular sphere_roll disagree\n");
    std::exit(1);
  }
}

}  // namespace

BENCHMARK_CAPTURE(step_scene, sphere_roll_euler, "sphere_roll", "euler");
BENCHMARK_CAPTURE(step_scene, sphere_roll_rk4, "sphere_roll", "rk4");
BENCHMARK_CAPTURE(step_scene, two_link_euler, "two_link", "euler");
BENCHMARK_CAPTURE(step_scene, two_link_rk4, "two_link", "rk4");
BENCHMARK(fused_sphere_rk4);

int main(int argc, char** argv) {
  check_fused_matches_network();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
