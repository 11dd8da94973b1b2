// ns per integration step of the bundled scenes through the modular network, and the
// hand-fused Simulation I beside it (the price of modularity, issue 5).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/integrator.hpp"
#include "fused_sphere.hpp"
#include "loop_cost.hpp"
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

// The fused stage inside RK4 on dynamic-size vectors, as RungeKuttaStepper combines them:
// splits the modularity cost into the stepper's share (this against fused_sphere_rk4) and
// the network's (step_scene/sphere_roll_rk4 against this).
struct DynamicRk4FusedStage {
  bench::FusedSphere sphere;
  core::Vec x = core::Vec(15);
  std::vector<core::Vec> xi = std::vector<core::Vec>(4, core::Vec::Zero(15));
  core::Vec stage_x = core::Vec(15);

  DynamicRk4FusedStage() { restart(); }
  void restart() {
    x.head<13>() = bench::FusedSphere().x;
    x.tail<2>().setZero();
  }
  void step(double T) {
    static constexpr double offset[4] = {0.0, 0.5, 0.5, 1.0};
    static constexpr double tau[4] = {0.5, 0.5, 1.0, 1.0};
    Eigen::Matrix<double, 13, 1> rates;
    Eigen::Vector2d eps;
    for (int r = 0; r < 4; ++r) {
      if (r == 0) {
        stage_x = x;
      } else {
        stage_x.noalias() = x + (offset[r] * T) * xi[r - 1];
      }
      sphere.stage(stage_x.head<13>(), stage_x.tail<2>(), tau[r] * T, rates, eps);
      xi[r].head<13>() = rates;
      xi[r].tail<2>() = eps;
    }
    x.noalias() = x + (T / 6) * xi[0] + (T * 2 / 6) * xi[1] + (T * 2 / 6) * xi[2] + (T / 6) * xi[3];
    x.segment<4>(6).normalize();
  }
};

void dynamic_rk4_fused_stage(benchmark::State& state) {
  DynamicRk4FusedStage run;
  long k = 0;
  for (auto _ : state) {
    run.step(1e-4);
    if (++k == 20000) {
      k = 0;
      run.restart();
    }
    benchmark::DoNotOptimize(run.x.data());
  }
}

// The fused loop must compute what the network computes, or the ratio means nothing.
void check_fused_matches_network() {
  auto scene = scene::load_scene("sphere_roll");
  core::Network& net = *scene.network;
  core::RungeKuttaStepper stepper(core::rk4_tableau(), net.state_dim());
  core::Vec x = net.initial_state();
  bench::FusedSphere fused;
  DynamicRk4FusedStage dynamic;
  // 300 steps take the sphere through its first landing (at about step 203). Over longer
  // runs the bounces amplify rounding differences (the lever arm (p + a) - p versus a).
  for (int k = 0; k < 300; ++k) {
    stepper.step(net, k * 1e-4, 1e-4, x);
    fused.step_rk4(1e-4);
    dynamic.step(1e-4);
  }
  const double diff = (x.head<13>() - fused.x).norm() + (x.segment<2>(13) - fused.e).norm();
  const double diff_dynamic = (dynamic.x - x).norm();
  std::printf("fused vs modular sphere_roll after 300 rk4 steps: |difference| = %.3g "
              "(dynamic-vector stepper around the fused stage: %.3g)\n", diff, diff_dynamic);
  if (!(diff < 1e-9) || !(diff_dynamic < 1e-9)) {
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
BENCHMARK(dynamic_rk4_fused_stage);

int main(int argc, char** argv) {
  check_fused_matches_network();
  // --ratios-only: just the loop and arm figures of issue 13 (README, Performance).
  bool ratios_only = false;
  for (int i = 1; i < argc; ++i) ratios_only |= std::string(argv[i]) == "--ratios-only";
  stiction::bench::print_loop_ratios();
  stiction::bench::print_arm_exponents();
  if (ratios_only) return 0;
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
