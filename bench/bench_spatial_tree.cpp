// ns per SpatialTree::forward_dynamics (the articulated-body algorithm) on random chains of
// n = 8..64 joints and on balanced binary trees, and the exponent p of a least-squares fit
// time ~ n^p over the chains (issue 23 asks for p <= 1.1: the algorithm is O(n)). The fit is
// made from the benchmark's own results (CPU time, so time spent descheduled on a shared
// machine does not count), after the runs.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "components/admittance/spatial_tree.hpp"

using namespace stiction;

namespace {

// n links with random axes, origins, rotations and inertias; parent(i) = i - 1 for a chain,
// (i - 1) / 2 for a balanced binary tree.
components::SpatialTree make_tree(int n, bool chain) {
  std::mt19937 rng(static_cast<unsigned>(n));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  components::SpatialTreeParams p;
  for (int i = 0; i < n; ++i) {
    components::SpatialLink l;
    l.joint_name = std::string("j").append(std::to_string(i));
    l.parent = i == 0 ? -1 : (chain ? i - 1 : (i - 1) / 2);
    l.type = i % 5 == 4 ? components::SpatialJointType::prismatic
                        : components::SpatialJointType::revolute;
    l.axis = core::Vec3(u(rng), u(rng), u(rng)) + core::Vec3(0, 0, 2);
    l.origin = 0.1 * core::Vec3(u(rng), u(rng), u(rng));
    l.rotation =
        core::Quat(Eigen::AngleAxisd(u(rng), core::Vec3(u(rng), u(rng), 1.0).normalized()));
    l.mass = 1.0 + 0.5 * u(rng);
    l.com = 0.05 * core::Vec3(u(rng), u(rng), u(rng));
    l.inertia = core::Vec3(0.01, 0.012, 0.015).asDiagonal();
    p.links.push_back(l);
  }
  p.gravity = core::Vec3(0, 0, -9.8);
  return components::SpatialTree("tree", p);
}

void forward_dynamics(benchmark::State& state, bool chain) {
  const int n = static_cast<int>(state.range(0));
  const components::SpatialTree tree = make_tree(n, chain);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  core::Vec q(n), qd(n), tau(n), qdd(n);
  for (int i = 0; i < n; ++i) q[i] = u(rng), qd[i] = u(rng), tau[i] = u(rng);
  for (auto _ : state) {
    tree.forward_dynamics(q, qd, tau, qdd);
    q[0] += 1e-12 * qdd[n - 1];  // a dependency, so the calls are not hoisted
    benchmark::DoNotOptimize(qdd.data());
  }
  state.SetComplexityN(n);
}

void chain(benchmark::State& state) { forward_dynamics(state, true); }
void binary_tree(benchmark::State& state) { forward_dynamics(state, false); }

// Keeps each chain run's CPU time per iteration, for the fit.
class FitReporter : public benchmark::ConsoleReporter {
 public:
  std::map<long, double> chain_ns;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.run_name.function_name != "chain") continue;
      const double ns = run.GetAdjustedCPUTime();  // in the run's time unit: ns by default
      auto [it, fresh] = chain_ns.emplace(static_cast<long>(run.complexity_n), ns);
      if (!fresh) it->second = std::min(it->second, ns);  // repetitions: the least
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

}  // namespace

BENCHMARK(chain)->Arg(8)->Arg(16)->Arg(32)->Arg(64);
BENCHMARK(binary_tree)->Arg(15)->Arg(63);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  FitReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  // Least-squares slope of log t against log n.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double m = static_cast<double>(reporter.chain_ns.size());
  for (const auto& [n, ns] : reporter.chain_ns) {
    const double x = std::log(static_cast<double>(n)), y = std::log(ns);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  if (m >= 2) {
    std::printf("spatial_tree forward dynamics, chains n = 8..64: time ~ n^%.3f\n",
                (m * sxy - sx * sy) / (m * sxx - sx * sx));
  }
  return 0;
}
