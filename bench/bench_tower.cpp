// The implicit step on a tower of N boxes (each on the one below: one island, a chain of
// contacts), its matrix formed one column per evaluation or by compressed differences
// (core/jacobian_pattern.hpp), factored dense or sparse (issue 36 item 3). Each iteration
// is 0.25 s simulated at dt = 1 ms (4x its time is the CPU per simulated second); counters:
// matrices formed, island evaluations spent per matrix.
//   build/bench/bench_tower --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <sstream>
#include <string>

#include "core/implicit_euler.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

// Boxes of 0.3 x 0.3 x 0.1 m and 1 kg, alternately turned by +-10 degrees about z, each
// pressed into the one below by about its static sinking; the top one slides off at 0.3 m/s.
std::string tower_text(int count) {
  std::ostringstream text;
  text.precision(17);
  text << "name = \"tower\"\ngravity = [0.0, 0.0, -9.81]\n[simulation]\nintegrator = "
          "\"implicit\"\ndt = 0.001\nduration = 1.0\n";
  for (int k = 0; k < count; ++k) {
    const double yaw = (k % 2 == 0 ? 1.0 : -1.0) * 10.0 * M_PI / 180.0;
    text << "[bodies.b" << k << "]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"box\"\n"
         << "size = [0.3, 0.3, 0.1]\nposition = [0.0, 0.0, " << 0.05 + 0.1 * k
         << "]\norientation = [" << std::cos(0.5 * yaw) << ", 0.0, 0.0, " << std::sin(0.5 * yaw)
         << "]\n";
    if (k + 1 == count) text << "velocity = [0.3, 0.0, 0.0]\n";
    text << "[impedances.c" << k << "]\ntype = \"kikuuwe_contact\"\nbody = \"b" << k << "\"\n";
    if (k > 0) text << "other = \"b" << k - 1 << "\"\n";
    text << "stiffness = 1e6\ndamping = 500.0\nmu = 0.5\n";
  }
  return text.str();
}

void tower(benchmark::State& state, bool compress, bool sparse) {
  const int count = static_cast<int>(state.range(0));
  auto scene = scene::load_scene(scene::SceneSource::from_text(tower_text(count), "tower.toml"));
  const double dt = 1e-3, duration = 0.25;
  long matrices = 0, evaluations = 0;
  for (auto _ : state) {
    core::ImplicitEulerStepper stepper(scene.network->state_dim(), dt);
    stepper.set_compressed_differences(compress);
    stepper.set_sparse_unknowns(sparse ? 128 : (1 << 30));
    core::Vec x = scene.network->initial_state();
    for (double t = 0.0; t < duration - 1e-12;) {
      t += stepper.advance(*scene.network, t, duration - t, x);
    }
    benchmark::DoNotOptimize(x.data());
    matrices = stepper.matrices_formed();
    evaluations = stepper.matrix_evaluations();
  }
  state.counters["matrices"] = static_cast<double>(matrices);
  state.counters["evals_per_matrix"] =
      matrices > 0 ? static_cast<double>(evaluations) / static_cast<double>(matrices) : 0.0;
}

}  // namespace

BENCHMARK_CAPTURE(tower, columns_dense, false, false)
    ->Arg(10)
    ->Arg(30)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(tower, compressed_dense, true, false)
    ->Arg(10)
    ->Arg(30)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(tower, compressed_sparse, true, true)
    ->Arg(10)
    ->Arg(30)
    ->Arg(100)
    ->Arg(300)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
