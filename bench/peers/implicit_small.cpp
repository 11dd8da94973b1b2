// bench_implicit_small: the implicit step alone on bench_peers' one-body problems (the sphere,
// the hold, the slide; scenes/*.toml) at 1/60 s, as StictionPeer steps them, for profiling
// its per-step overhead on tiny islands (issue 36: at most 1.0x ODE on these). Prints, per
// problem, the thread CPU per step (median over the repeats), the work per step (evaluations
// in whole-network units, iteration matrices formed) and a hash of the final state's bits, so
// that two builds can be checked to step every problem to the same bits. Usage:
//   bench_implicit_small [--repeats N] [--problems sphere,slope_hold,slope_slide] [--dt S]
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "core/implicit_euler.hpp"
#include "core/network.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// FNV-1a over the state's bytes: equal hashes, equal bits (to a collision's odds).
std::uint64_t hash_bits(const core::Vec& x) {
  std::uint64_t h = 1469598103934665603ULL;
  const auto* bytes = reinterpret_cast<const unsigned char*>(x.data());
  for (std::size_t k = 0; k < static_cast<std::size_t>(x.size()) * sizeof(double); ++k) {
    h = (h ^ bytes[k]) * 1099511628211ULL;
  }
  return h;
}

struct Outcome {
  double cpu = 0.0;
  long steps = 0;
  long evaluations = 0;
  long matrices = 0;
  std::uint64_t hash = 0;
};

// The problem's duration (bench/peers/problems.cpp, plan_of) stepped at dt as
// StictionPeer::step does; the stepper is made (untimed) before, as its reset() makes it. The
// network is the problem's, loaded once: a run reads and writes no state of its own.
Outcome run(core::Network& network, double duration, double dt) {
  core::ImplicitEulerStepper stepper(network.state_dim(), dt);
  core::Vec x = network.initial_state();
  const long n = std::lround(duration / dt);
  double t = 0.0;
  const double start = thread_cpu_seconds();
  for (long k = 1; k <= n; ++k) {
    const double target = static_cast<double>(k) * dt;
    while (t < target - 1e-9 * dt) t += stepper.advance(network, t, target - t, x);
  }
  Outcome out;
  out.cpu = thread_cpu_seconds() - start;
  out.steps = n;
  out.evaluations = stepper.evaluations();
  out.matrices = stepper.matrices_formed();
  out.hash = hash_bits(x);
  return out;
}

double duration_of(const std::string& problem) {
  if (problem == "sphere") return 1.0;
  if (problem == "slope_hold") return 100.0;
  if (problem == "slope_slide") return 3.0;
  return 1.0;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 200;
  double dt = 1.0 / 60;
  std::string list = "sphere,slope_hold,slope_slide";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--problems")) list = argv[i + 1];
    if (!std::strcmp(argv[i], "--dt")) dt = std::atof(argv[i + 1]);
  }
  std::stringstream names(list);
  std::string problem;
  std::printf("| problem | steps | us per step | evaluations per step | matrices | state hash |\n");
  std::printf("|---|---|---|---|---|---|\n");
  while (std::getline(names, problem, ',')) {
    std::vector<double> cpu;
    Outcome last;
    scene::Scene scene =
        scene::load_scene(std::string(STICTION_PEERS_SCENE_DIR) + "/" + problem + ".toml");
    for (int r = 0; r < repeats; ++r) {
      last = run(*scene.network, duration_of(problem), dt);
      cpu.push_back(last.cpu);
    }
    std::nth_element(cpu.begin(), cpu.begin() + static_cast<long>(cpu.size() / 2), cpu.end());
    const double median = cpu[cpu.size() / 2];
    std::printf("| %s | %ld | %.3f | %.2f | %ld | %016llx |\n", problem.c_str(), last.steps,
                1e6 * median / static_cast<double>(last.steps),
                static_cast<double>(last.evaluations) / static_cast<double>(last.steps),
                last.matrices, static_cast<unsigned long long>(last.hash));
  }
  return 0;
}
