// bench_peers: the problems of problems.hpp in stiction and in every peer engine this build
// found, interleaved (each round runs every engine and setting once), the thread CPU time of
// the stepping taken as the median over the rounds. Prints one work-precision table
// (Markdown), optionally also as CSV. Usage:
//   bench_peers [--rounds N] [--quick] [--csv FILE]
// --quick: short runs (a smoke test; its errors are not the problems' measures).
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "peer.hpp"

using namespace stiction::peers;

namespace {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Result {
  Errors errors;
  std::vector<double> cpu;  // seconds of stepping, one per round
  long steps = 0;
  double simulated = 0.0;
  std::string failure;
};

// One run: set-up untimed; the timed loop steps and copies the body's state into a buffer
// reserved beforehand (every step for the sphere, every sample interval for the slopes), the
// same for every engine.
void run(Peer& peer, Problem problem, bool quick, Result& result) {
  const Plan plan = plan_of(problem, quick);
  const long n = std::lround(plan.duration / peer.dt());
  const long stride =
      plan.sample_interval > 0 ? std::max(1L, std::lround(plan.sample_interval / peer.dt())) : 1;
  std::vector<Sample> samples(static_cast<std::size_t>(n / stride + 1));
  try {
    peer.reset(problem);
  } catch (const std::exception& e) {
    result.failure = e.what();
    return;
  }
  peer.read(samples[0]);
  std::size_t next = 1;
  const double start = thread_cpu_seconds();
  for (long k = 1; k <= n; ++k) {
    peer.step();
    if (k % stride == 0) peer.read(samples[next++]);
  }
  result.cpu.push_back(thread_cpu_seconds() - start);
  for (std::size_t i = 0; i < next; ++i) samples[i].t = static_cast<double>(i * stride) * peer.dt();
  samples.resize(next);
  result.errors = measure(problem, samples, quick);
  result.steps = n;
  result.simulated = static_cast<double>(n) * peer.dt();
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

std::string step_text(double dt) {
  char text[32];
  const double n = 1.0 / dt;
  const double p = std::log10(dt);
  if (std::abs(p - std::round(p)) < 1e-9) {
    std::snprintf(text, sizeof text, "1e%d s", static_cast<int>(std::round(p)));
  } else if (std::abs(n - std::round(n)) < 1e-6 &&
             std::abs(1e3 * dt - std::round(1e3 * dt)) > 1e-9) {
    std::snprintf(text, sizeof text, "1/%d s", static_cast<int>(std::round(n)));
  } else {
    std::snprintf(text, sizeof text, "%g s", dt);
  }
  return text;
}

struct Options {
  int rounds = 5;
  bool quick = false;
  std::string csv;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      o.quick = true;
    } else if (a == "--rounds" && i + 1 < argc) {
      o.rounds = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--csv" && i + 1 < argc) {
      o.csv = argv[++i];
    } else {
      std::fprintf(stderr, "usage: bench_peers [--rounds N] [--quick] [--csv FILE]\n");
      std::exit(2);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  Peers peers;
  add_stiction_peers(peers);
#ifdef STICTION_PEERS_ODE
  add_ode_peers(peers);
#endif
#ifdef STICTION_PEERS_BULLET
  add_bullet_peers(peers);
#endif
#ifdef STICTION_PEERS_MUJOCO
  add_mujoco_peers(peers);
#endif
#ifdef STICTION_PEERS_DART
  add_dart_peers(peers);
#endif

  constexpr int kCount = static_cast<int>(std::size(kProblems));
  std::vector<Result> results(peers.size() * kCount);
  for (int round = 0; round < options.rounds; ++round) {
    for (std::size_t p = 0; p < peers.size(); ++p) {
      for (int q = 0; q < kCount; ++q)
        run(*peers[p], kProblems[q], options.quick, results[p * kCount + q]);
    }
  }

  // The reference: stiction's paper method (the first row, rk4 at 1e-4 s), per problem.
  std::vector<double> reference(kCount);
  for (int q = 0; q < kCount; ++q) reference[q] = median(results[q].cpu) / results[q].simulated;

  std::FILE* csv = options.csv.empty() ? nullptr : std::fopen(options.csv.c_str(), "w");
  if (!options.csv.empty() && !csv) {
    std::fprintf(stderr, "cannot write %s\n", options.csv.c_str());
    return 1;
  }
  if (csv)
    std::fprintf(csv,
                 "engine,settings,dt,problem,error1,error2,cpu_per_simulated_s,cpu_per_step,ratio_"
                 "to_reference\n");
  std::printf(
      "\n| engine | settings | step | problem | error | CPU per simulated s | CPU per step | x %s "
      "%s |\n",
      peers[0]->engine().c_str(), peers[0]->settings().c_str());
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (std::size_t p = 0; p < peers.size(); ++p) {
    for (int q = 0; q < kCount; ++q) {
      const Result& r = results[p * kCount + q];
      const Peer& peer = *peers[p];
      const std::string name = problem_name(kProblems[q]);
      if (!r.failure.empty() || r.cpu.empty()) {
        std::printf("| %s | %s | %s | %s | failed: %s | | | |\n", peer.engine().c_str(),
                    peer.settings().c_str(), step_text(peer.dt()).c_str(), name.c_str(),
                    r.failure.c_str());
        continue;
      }
      const double cpu = median(r.cpu);
      const double per_second = cpu / r.simulated, per_step = cpu / static_cast<double>(r.steps);
      std::printf("| %s | %s | %s | %s | %s | %.3g ms | %.3g us | %.2g |\n", peer.engine().c_str(),
                  peer.settings().c_str(), step_text(peer.dt()).c_str(), name.c_str(),
                  describe(kProblems[q], r.errors).c_str(), 1e3 * per_second, 1e6 * per_step,
                  per_second / reference[q]);
      if (csv) {
        std::fprintf(csv, "\"%s\",\"%s\",%.17g,%s,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                     peer.engine().c_str(), peer.settings().c_str(), peer.dt(), name.c_str(),
                     r.errors.first, r.errors.second, per_second, per_step,
                     per_second / reference[q]);
      }
    }
  }
  if (csv) std::fclose(csv);
  return 0;
}
