// bench_peers: the problems of problems.hpp in stiction and in every peer engine this build
// found, interleaved (each round runs every engine and setting once), the thread CPU time of
// the stepping taken as the median over the rounds. Prints three work-precision tables
// (Markdown): the sphere, the hold and the slide; the N spheres; the pendulum; and the hold
// benchmark of issue 38, the ramp grid and the pinch. Optionally also every row as CSV
// (bench/peers/hold_figure.py draws the ramp grid from it). Usage:
//   bench_peers [--rounds N] [--quick] [--csv FILE] [--problems LIST] [--spheres LIST]
// --quick: short runs and N = 1, 10 (a smoke test; its errors are not the problems' measures).
// --problems: a comma-separated subset of sphere,slope_hold,slope_slide,spheres,pendulum,
//   ramp_grid,pinch (default: all).
// --spheres: the sizes N of the spheres problem (default 1,10,100,1000).
// --engines: a comma-separated list of engine names to keep (stiction,ode,bullet,mujoco,
//   dart,siconos; the start of the name, any case), or of an engine and its settings
//   ("stiction implicit" keeps stiction's implicit rows alone). Ratios are to the rows kept.
#include <time.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "peer.hpp"
#include "pendulum.hpp"

using namespace stiction::peers;

namespace {

struct Result {
  bool expressed = true;
  bool shown = true;  // false: a row the hold benchmark leaves out by choice
  Errors errors;
  std::vector<double> cpu;  // seconds of stepping, one per round
  long steps = 0;
  double simulated = 0.0;
  std::string failure;
};

// Sets the case up (untimed); false with the failure recorded if the engine refused it.
bool set_up(Peer& peer, const Case& c, Result& result) {
  try {
    peer.reset(c);
    return true;
  } catch (const std::exception& e) {
    result.failure = e.what();
    return false;
  }
}

// One run of a one-body problem: the timed loop steps and copies the body's state into a
// buffer reserved beforehand (every step for the sphere and the pendulum, every sample
// interval for the slopes), the same for every engine.
void run_recorded(Peer& peer, const Case& c, bool quick, Result& result) {
  const Plan plan = plan_of(c.problem, quick);
  const long n = std::lround(plan.duration / peer.dt());
  const long stride =
      plan.sample_interval > 0 ? std::max(1L, std::lround(plan.sample_interval / peer.dt())) : 1;
  std::vector<Sample> samples(static_cast<std::size_t>(n / stride + 1));
  if (!set_up(peer, c, result)) return;
  peer.read(0, samples[0]);
  std::size_t next = 1;
  const double start = thread_cpu_seconds();
  for (long k = 1; k <= n; ++k) {
    peer.step();
    if (k % stride == 0) peer.read(0, samples[next++]);
  }
  result.cpu.push_back(thread_cpu_seconds() - start);
  for (std::size_t i = 0; i < next; ++i) samples[i].t = static_cast<double>(i * stride) * peer.dt();
  samples.resize(next);
  result.errors = measure(c.problem, samples, quick);
  result.steps = n;
  result.simulated = static_cast<double>(n) * peer.dt();
}

// One run of the N spheres: the timed loop steps and reads every sphere after every step
// into its StickWatch (no recording: a thousand spheres at 1e-4 s would need 10^7 samples).
void run_spheres(Peer& peer, const Case& c, bool quick, Result& result) {
  const Plan plan = plan_of(c.problem, quick);
  const long n = std::lround(plan.duration / peer.dt());
  std::vector<StickWatch> watches(static_cast<std::size_t>(c.count), StickWatch(peer.dt()));
  if (!set_up(peer, c, result)) return;
  Sample s;
  for (int i = 0; i < c.count; ++i) {
    peer.read(i, s);
    watches[i].add(0.0, slip_of(s));
  }
  const double start = thread_cpu_seconds();
  for (long k = 1; k <= n; ++k) {
    peer.step();
    const double t = static_cast<double>(k) * peer.dt();
    for (int i = 0; i < c.count; ++i) {
      peer.read(i, s);
      watches[i].add(t, slip_of(s));
    }
  }
  result.cpu.push_back(thread_cpu_seconds() - start);
  double worst = 0.0, sum = 0.0;
  int stuck = 0;
  for (int i = 0; i < c.count; ++i) {
    const double exact = stick_time_of(spheres_v0(i, c.count));
    const double error = std::abs(watches[i].stick_time() - exact) / exact;
    if (!std::isfinite(error)) continue;
    worst = std::max(worst, error);
    sum += error;
    ++stuck;
  }
  const double nan = std::nan("");
  result.errors = {stuck > 0 ? worst : nan, stuck > 0 ? sum / stuck : nan,
                   static_cast<double>(c.count - stuck), {}};
  result.steps = n;
  result.simulated = static_cast<double>(n) * peer.dt();
}

// One run of a hold problem (ramp grid point, pinch): the timed loop steps and copies every
// body's state (the box; the block and both fingers) every sample interval.
void run_hold(Peer& peer, const Case& c, bool quick, Result& result) {
  const Plan plan = plan_of(c.problem, quick);
  const long n = std::lround(plan.duration / peer.dt());
  const long stride = std::max(1L, std::lround(plan.sample_interval / peer.dt()));
  const auto bodies = static_cast<std::size_t>(c.count);
  std::vector<std::vector<Sample>> samples(bodies,
                                           std::vector<Sample>(static_cast<std::size_t>(n / stride + 1)));
  if (!set_up(peer, c, result)) return;
  for (std::size_t b = 0; b < bodies; ++b) peer.read(static_cast<int>(b), samples[b][0]);
  std::size_t next = 1;
  const double start = thread_cpu_seconds();
  for (long k = 1; k <= n; ++k) {
    peer.step();
    if (k % stride == 0) {
      for (std::size_t b = 0; b < bodies; ++b) peer.read(static_cast<int>(b), samples[b][next]);
      ++next;
    }
  }
  result.cpu.push_back(thread_cpu_seconds() - start);
  for (auto& record : samples) {
    for (std::size_t i = 0; i < next; ++i) record[i].t = static_cast<double>(i * stride) * peer.dt();
    record.resize(next);
  }
  result.errors = measure_hold(c, samples, quick);
  result.steps = n;
  result.simulated = static_cast<double>(n) * peer.dt();
}

// Whether the ramp's box slides at `angle`: its mean speed along the slope over [settle,
// end] of breakaway_duration() above kBreakawaySpeed (a run that blows up slides). Adds the
// run's steps and CPU to the result.
bool slides_at(Peer& peer, Case c, double angle, bool quick, Result& result, double& cpu) {
  c.angle = angle;
  peer.reset(c);
  const long n = std::lround(breakaway_duration(quick) / peer.dt());
  const long settle = std::lround(settle_time(quick) / peer.dt());
  Sample from, to;
  const double start = thread_cpu_seconds();
  for (long k = 1; k <= n; ++k) {
    peer.step();
    if (k == settle) peer.read(0, from);
  }
  peer.read(0, to);
  cpu += thread_cpu_seconds() - start;
  result.steps += n;
  result.simulated += static_cast<double>(n) * peer.dt();
  const double speed = std::abs(to.p[0] - from.p[0]) / (static_cast<double>(n - settle) * peer.dt());
  return !(speed <= kBreakawaySpeed);
}

// The breakaway search of one mu (once, in the first round: its errors do not change and its
// run count depends on the engine): bisection between the flat plane and atan mu + 5 degrees
// for the smallest angle at which the box slides. Errors: the angle found less the ideal
// Coulomb box's under the same test, breakaway_reference() (degrees), the bracket's half
// width (degrees), the number of runs.
void run_breakaway(Peer& peer, const Case& c, bool quick, Result& result) {
  if (result.steps > 0 || !result.failure.empty()) return;
  const double degree = std::numbers::pi / 180.0;
  const double exact = std::atan(c.mu);
  double lo = 0.0, hi = exact + 5.0 * degree, cpu = 0.0;
  int runs = 0;
  try {
    const bool slides_high = slides_at(peer, c, hi, quick, result, cpu);
    const bool slides_flat = slides_at(peer, c, lo, quick, result, cpu);
    runs = 2;
    const double nan = std::nan("");
    if (!slides_high || slides_flat) {
      result.errors = {nan, nan, static_cast<double>(runs),
                       slides_flat ? "slides on the flat plane" : "holds at atan mu + 5 deg"};
    } else {
      for (int i = 0; i < (quick ? 4 : 16); ++i, ++runs) {
        const double mid = 0.5 * (lo + hi);
        (slides_at(peer, c, mid, quick, result, cpu) ? hi : lo) = mid;
      }
      result.errors = {(0.5 * (lo + hi) - breakaway_reference(c.mu, quick)) / degree,
                       0.5 * (hi - lo) / degree,
                       static_cast<double>(runs), {}};
    }
  } catch (const std::exception& e) {
    result.failure = e.what();
    return;
  }
  result.cpu.push_back(cpu);
}

void run(Peer& peer, const Case& c, bool quick, Result& result) {
  if (!peer.expresses(c.problem)) {
    result.expressed = false;
    return;
  }
  const bool hold = c.problem == Problem::ramp_grid || c.problem == Problem::pinch;
  if (hold && !peer.in_hold_benchmark()) {
    result.shown = false;
    return;
  }
  if (c.problem == Problem::ramp_grid && c.breakaway) {
    run_breakaway(peer, c, quick, result);
  } else if (hold) {
    run_hold(peer, c, quick, result);
  } else if (c.problem == Problem::spheres) {
    run_spheres(peer, c, quick, result);
  } else {
    run_recorded(peer, c, quick, result);
  }
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// CPU per simulated second of a result (NaN where it did not run).
double per_second(const Result& r) {
  if (!r.expressed || !r.failure.empty() || r.cpu.empty()) return std::nan("");
  return median(r.cpu) / r.simulated;
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

std::string number(double x, const char* format = "%.3g") {
  if (!std::isfinite(x)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

struct Options {
  int rounds = 5;
  bool quick = false;
  std::string csv;
  std::vector<Problem> problems{Problem::sphere,   Problem::slope_hold, Problem::slope_slide,
                                Problem::spheres,  Problem::pendulum,   Problem::ramp_grid,
                                Problem::pinch};
  std::vector<int> sizes;  // N of the spheres problem
  std::vector<std::string> engines;  // engine name prefixes to keep (empty: all)
};

[[noreturn]] void usage() {
  std::fprintf(stderr,
               "usage: bench_peers [--rounds N] [--quick] [--csv FILE] [--problems LIST] "
               "[--spheres LIST] [--engines LIST]\n");
  std::exit(2);
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) items.push_back(item);
  return items;
}

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
    } else if (a == "--problems" && i + 1 < argc) {
      o.problems.clear();
      for (const std::string& name : split(argv[++i])) {
        bool known = false;
        for (Problem p : {Problem::sphere, Problem::slope_hold, Problem::slope_slide,
                          Problem::spheres, Problem::pendulum, Problem::ramp_grid,
                          Problem::pinch}) {
          if (problem_name(p) == name) {
            o.problems.push_back(p);
            known = true;
          }
        }
        if (!known) usage();
      }
    } else if (a == "--engines" && i + 1 < argc) {
      o.engines = split(argv[++i]);
    } else if (a == "--spheres" && i + 1 < argc) {
      for (const std::string& n : split(argv[++i])) o.sizes.push_back(std::max(1, std::atoi(n.c_str())));
    } else {
      usage();
    }
  }
  if (o.sizes.empty()) o.sizes = o.quick ? std::vector<int>{1, 10} : std::vector<int>{1, 10, 100, 1000};
  return o;
}

std::vector<Case> cases_of(const Options& o) {
  std::vector<Case> cases;
  for (Problem p : o.problems) {
    if (p == Problem::spheres) {
      for (int n : o.sizes) cases.push_back({p, n});
    } else if (p == Problem::ramp_grid) {
      for (const Case& c : ramp_cases(o.quick)) cases.push_back(c);
    } else if (p == Problem::pinch) {
      for (const Case& c : pinch_cases(o.quick)) cases.push_back(c);
    } else {
      cases.push_back({p, 1});
    }
  }
  return cases;
}

std::string row_head(const Peer& peer) {
  return "| " + peer.engine() + " | " + peer.settings() + " | " + step_text(peer.dt()) + " |";
}

// The least-squares slope of log(cpu) over log(N): cost ~ N^slope.
double exponent(const std::vector<int>& sizes, const std::vector<double>& cpu) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    if (!std::isfinite(cpu[k]) || cpu[k] <= 0) continue;
    const double x = std::log(sizes[k]), y = std::log(cpu[k]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++m;
  }
  if (m < 2) return std::nan("");
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

// The row bench_peers compares the goals of issue 36 against: ODE at 1/60 s (-1: none).
int ode_row(const Peers& peers) {
  for (std::size_t p = 0; p < peers.size(); ++p) {
    if (peers[p]->engine().rfind("ODE", 0) == 0 && std::abs(peers[p]->dt() - 1.0 / 60) < 1e-12)
      return static_cast<int>(p);
  }
  return -1;
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
#ifdef STICTION_PEERS_SICONOS
  add_siconos_peers(peers);
#endif

  if (!options.engines.empty()) {
    // Keep the engines named (by the start of their name, or of their name and settings, any
    // case); the first row stays stiction rk4 whenever all of stiction is kept.
    auto lower = [](std::string text) {
      for (char& ch : text) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      return text;
    };
    Peers kept;
    for (auto& peer : peers) {
      for (const std::string& name : options.engines) {
        // An engine ("ode") or an engine and the start of its settings ("stiction implicit").
        const std::string full = lower(peer->engine() + " " + peer->settings());
        if (lower(peer->engine()).rfind(lower(name), 0) == 0 || full.rfind(lower(name), 0) == 0) {
          kept.push_back(std::move(peer));
          break;
        }
      }
    }
    peers = std::move(kept);
    if (peers.empty()) usage();
  }
  const std::vector<Case> cases = cases_of(options);
  const std::size_t count = cases.size();
  std::vector<Result> results(peers.size() * count);
  auto result = [&](std::size_t p, std::size_t q) -> Result& { return results[p * count + q]; };
  for (int round = 0; round < options.rounds; ++round) {
    for (std::size_t p = 0; p < peers.size(); ++p) {
      for (std::size_t q = 0; q < count; ++q) run(*peers[p], cases[q], options.quick, result(p, q));
    }
  }

  // Ratios: to stiction's paper method (the first row, rk4 at 1e-4 s) and to ODE at 1/60 s.
  const int ode = ode_row(peers);
  auto ratio = [&](std::size_t p, std::size_t q, int reference) {
    if (reference < 0) return std::nan("");
    return per_second(result(p, q)) / per_second(result(static_cast<std::size_t>(reference), q));
  };
  const std::string first = peers[0]->engine() + " " + peers[0]->settings();

  std::FILE* csv = options.csv.empty() ? nullptr : std::fopen(options.csv.c_str(), "w");
  if (!options.csv.empty() && !csv) {
    std::fprintf(stderr, "cannot write %s\n", options.csv.c_str());
    return 1;
  }
  if (csv)
    std::fprintf(csv,
                 "engine,settings,dt,problem,count,error1,error2,error3,note,cpu_per_simulated_s,"
                 "cpu_per_step,ratio_to_reference,ratio_to_ode_60,mu,angle_deg,margin,breakaway\n");

  // Table 1: the one-body problems, one row per engine, setting and problem.
  bool header = false;
  for (std::size_t p = 0; p < peers.size(); ++p) {
    for (std::size_t q = 0; q < count; ++q) {
      const Problem problem = cases[q].problem;
      if (problem == Problem::spheres || problem == Problem::pendulum ||
          problem == Problem::ramp_grid || problem == Problem::pinch)
        continue;
      const Result& r = result(p, q);
      if (!r.expressed) continue;
      if (!header) {
        std::printf("\n| engine | settings | step | problem | error | CPU per simulated s | CPU "
                    "per step | x %s |\n|---|---|---|---|---|---|---|---|\n",
                    first.c_str());
        header = true;
      }
      const std::string head = row_head(*peers[p]) + " " + problem_name(problem) + " |";
      if (!r.failure.empty() || r.cpu.empty()) {
        std::printf("%s failed: %s | | | |\n", head.c_str(), r.failure.c_str());
        continue;
      }
      std::printf("%s %s | %.3g ms | %.3g us | %.2g |\n", head.c_str(),
                  describe(problem, r.errors).c_str(), 1e3 * per_second(r),
                  1e6 * median(r.cpu) / static_cast<double>(r.steps), ratio(p, q, 0));
    }
  }

  // Table 2: the N spheres, one row per engine and setting, one column per N.
  std::vector<std::size_t> sphere_cases;
  for (std::size_t q = 0; q < count; ++q)
    if (cases[q].problem == Problem::spheres) sphere_cases.push_back(q);
  if (!sphere_cases.empty()) {
    std::printf("\nN spheres: CPU per simulated s (ms) | largest relative stick time error "
                "over the spheres\n\n| engine | settings | step |");
    for (std::size_t q : sphere_cases) std::printf(" N = %d |", cases[q].count);
    std::printf(" exponent |");
    for (std::size_t q : sphere_cases) std::printf(" error N = %d |", cases[q].count);
    std::printf(" x %s (N = %d) | x ODE 1/60 (N = %d) |\n|---|---|---|", first.c_str(),
                cases[sphere_cases.back()].count, cases[sphere_cases.back()].count);
    for (std::size_t k = 0; k < 2 * sphere_cases.size() + 3; ++k) std::printf("---|");
    std::printf("\n");
    for (std::size_t p = 0; p < peers.size(); ++p) {
      if (!result(p, sphere_cases[0]).expressed) continue;
      std::vector<int> sizes;
      std::vector<double> cpu;
      std::string line = row_head(*peers[p]);
      for (std::size_t q : sphere_cases) {
        sizes.push_back(cases[q].count);
        cpu.push_back(per_second(result(p, q)));
        const std::string& failure = result(p, q).failure;
        line += " " + (failure.empty() ? number(1e3 * cpu.back()) : "failed: " + failure) + " |";
      }
      line += " " + number(exponent(sizes, cpu), "%.2f") + " |";
      for (std::size_t q : sphere_cases) {
        const Errors& e = result(p, q).errors;
        line += " " + number(e.first, "%.2g");
        if (e.third > 0) line += " (" + number(e.third, "%.0f") + " never stuck)";
        line += " |";
      }
      line += " " + number(ratio(p, sphere_cases.back(), 0), "%.2g") + " | " +
              number(ratio(p, sphere_cases.back(), ode), "%.2g") + " |";
      std::printf("%s\n", line.c_str());
    }
  }

  // Table 3: the pendulum.
  for (std::size_t q = 0; q < count; ++q) {
    if (cases[q].problem != Problem::pendulum) continue;
    const Swings& reference = pendulum_reference(plan_of(Problem::pendulum, options.quick).duration);
    char stop[80] = "does not stop within the run";
    if (std::isfinite(reference.stop_time))
      std::snprintf(stop, sizeof stop, "stops at %.9g s at %.6g rad", reference.stop_time,
                    reference.rest_angle);
    std::printf("\nPendulum with joint friction: reference (ideal Coulomb, rk4 1e-5 s) turns %zu "
                "times, %s\n\n| engine | settings | step | phase | amplitude | stop | note | "
                "CPU per simulated s | x %s | x ODE 1/60 |\n"
                "|---|---|---|---|---|---|---|---|---|---|\n",
                reference.turns.size(), stop, first.c_str());
    for (std::size_t p = 0; p < peers.size(); ++p) {
      const Result& r = result(p, q);
      if (!r.expressed) continue;
      if (!r.failure.empty() || r.cpu.empty()) {
        std::printf("%s failed: %s | | | | | | |\n", row_head(*peers[p]).c_str(), r.failure.c_str());
        continue;
      }
      std::printf("%s %s s | %s rad | %s s | %s | %.3g ms | %s | %s |\n", row_head(*peers[p]).c_str(),
                  number(r.errors.first, "%.2g").c_str(), number(r.errors.second, "%.2g").c_str(),
                  number(r.errors.third, "%+.2g").c_str(), r.errors.note.c_str(), 1e3 * per_second(r),
                  number(ratio(p, q, 0), "%.2g").c_str(), number(ratio(p, q, ode), "%.2g").c_str());
    }
  }

  // The hold benchmark's CPU per simulated second over a set of cases: the sum of the
  // medians over the sum of the simulated time (NaN if one did not run).
  auto grid_per_second = [&](std::size_t p, const std::vector<std::size_t>& qs) {
    double cpu = 0.0, simulated = 0.0;
    for (std::size_t q : qs) {
      const Result& r = result(p, q);
      if (!r.failure.empty() || r.cpu.empty()) return std::nan("");
      cpu += median(r.cpu);
      simulated += r.simulated;
    }
    return simulated > 0 ? cpu / simulated : std::nan("");
  };
  // A row's first cells when the engine cannot express the problem or failed in it; empty
  // when every case ran.
  auto hold_failure = [&](std::size_t p, const std::vector<std::size_t>& qs) -> std::string {
    for (std::size_t q : qs) {
      const Result& r = result(p, q);
      if (!r.expressed) return "cannot express it (see the settings)";
      if (!r.failure.empty()) return "failed (" + case_name(cases[q]) + "): " + r.failure;
    }
    return "";
  };

  // Table 4: the ramp grid (issue 38).
  std::vector<std::size_t> grid, breakaways;
  std::vector<double> ratios;  // tan a / mu of the grid's columns, in order
  for (std::size_t q = 0; q < count; ++q) {
    if (cases[q].problem != Problem::ramp_grid) continue;
    if (cases[q].breakaway) {
      breakaways.push_back(q);
      continue;
    }
    grid.push_back(q);
    const double r = std::tan(cases[q].angle) / cases[q].mu;
    if (std::none_of(ratios.begin(), ratios.end(), [&](double x) { return std::abs(x - r) < 1e-9; }))
      ratios.push_back(r);
  }
  if (!grid.empty() || !breakaways.empty()) {
    std::printf("\nRamp grid: a 0.2 x 0.2 x 0.1 m, 1 kg box at rest on a ramp of angle a, %zu "
                "points of mu x tan a / mu (all below 1: it must hold). Creep: speed along the "
                "slope after %g s (m/s), the largest over mu at each tan a / mu. Breakaway: the "
                "smallest angle at which the box moves faster than %g m/s on average, less the "
                "ideal Coulomb box's (atan mu + 0.002-0.003 deg; degrees; bisection to 4e-4 "
                "deg, one round). CPU: the creep grid's.\n\n"
                "| engine | settings | step |",
                grid.size(), settle_time(options.quick), kBreakawaySpeed);
    for (double r : ratios) std::printf(" creep tan/mu = %.3g |", r);
    if (!grid.empty()) std::printf(" creep median |");
    for (std::size_t q : breakaways) std::printf(" breakaway mu = %g |", cases[q].mu);
    std::printf(" CPU per simulated s | x %s |\n|---|---|---|", first.c_str());
    for (std::size_t k = 0; k < ratios.size() + (grid.empty() ? 0 : 1) + breakaways.size() + 2; ++k)
      std::printf("---|");
    std::printf("\n");
    std::vector<std::size_t> all = grid;
    all.insert(all.end(), breakaways.begin(), breakaways.end());
    const double reference = grid_per_second(0, grid);
    for (std::size_t p = 0; p < peers.size(); ++p) {
      if (!result(p, all[0]).shown) continue;
      std::string line = row_head(*peers[p]);
      const std::string failure = hold_failure(p, all);
      if (!failure.empty()) {
        std::printf("%s %s |\n", line.c_str(), failure.c_str());
        continue;
      }
      std::vector<double> creeps;
      for (double ratio : ratios) {
        double worst = 0.0;
        for (std::size_t q : grid) {
          if (std::abs(std::tan(cases[q].angle) / cases[q].mu - ratio) > 1e-9) continue;
          const double c = result(p, q).errors.first;
          worst = std::isfinite(c) && std::isfinite(worst) ? std::max(worst, c) : std::nan("");
          creeps.push_back(c);
        }
        line += " " + number(worst, "%.2g") + " |";
      }
      if (!grid.empty()) {
        for (double& c : creeps) if (!std::isfinite(c)) c = std::numeric_limits<double>::infinity();
        line += " " + number(median(creeps), "%.2g") + " |";
      }
      for (std::size_t q : breakaways) {
        const Errors& e = result(p, q).errors;
        line += " " + (e.note.empty() ? number(e.first, "%+.2g") : e.note) + " |";
      }
      const double cpu = grid_per_second(p, grid);
      line += " " + number(1e3 * cpu, "%.3g") + " ms | " + number(cpu / reference, "%.2g") + " |";
      std::printf("%s\n", line.c_str());
    }
  }

  // Table 5: the pinch (issue 38).
  std::vector<std::size_t> pinch;
  for (std::size_t q = 0; q < count; ++q)
    if (cases[q].problem == Problem::pinch) pinch.push_back(q);
  if (!pinch.empty()) {
    std::printf("\nPinch: a 0.1 m, 1 kg cube between two fingers pressed with F = margin m g / "
                "(2 mu), mu %g, under gravity. Creep: the block's vertical speed relative to the "
                "fingers after %g s (m/s); drop: the block's largest fall relative to the fingers "
                "over the run (m).\n\n| engine | settings | step |",
                kPinch.mu, settle_time(options.quick));
    for (std::size_t q : pinch) std::printf(" creep %gx |", cases[q].margin);
    std::printf(" drop (largest) | CPU per simulated s | x %s |\n|---|---|---|", first.c_str());
    for (std::size_t k = 0; k < pinch.size() + 3; ++k) std::printf("---|");
    std::printf("\n");
    const double reference = grid_per_second(0, pinch);
    for (std::size_t p = 0; p < peers.size(); ++p) {
      if (!result(p, pinch[0]).shown) continue;
      std::string line = row_head(*peers[p]);
      const std::string failure = hold_failure(p, pinch);
      if (!failure.empty()) {
        std::printf("%s %s |\n", line.c_str(), failure.c_str());
        continue;
      }
      double drop = 0.0;
      for (std::size_t q : pinch) {
        const Errors& e = result(p, q).errors;
        line += " " + number(e.first, "%.2g") + " |";
        drop = std::isfinite(e.third) && std::isfinite(drop) ? std::max(drop, e.third) : std::nan("");
      }
      const double cpu = grid_per_second(p, pinch);
      line += " " + number(drop, "%.2g") + " m | " + number(1e3 * cpu, "%.3g") + " ms | " +
              number(cpu / reference, "%.2g") + " |";
      std::printf("%s\n", line.c_str());
    }
  }

  if (csv) {
    for (std::size_t p = 0; p < peers.size(); ++p) {
      for (std::size_t q = 0; q < count; ++q) {
        const Result& r = result(p, q);
        if (!r.expressed || !r.failure.empty() || r.cpu.empty()) continue;
        const Peer& peer = *peers[p];
        const Case& c = cases[q];
        std::fprintf(csv,
                     "\"%s\",\"%s\",%.17g,%s,%d,%.6g,%.6g,%.6g,\"%s\",%.6g,%.6g,%.6g,%.6g,%.6g,%.9g,"
                     "%.6g,%d\n",
                     peer.engine().c_str(), peer.settings().c_str(), peer.dt(),
                     problem_name(cases[q].problem).c_str(), cases[q].count, r.errors.first,
                     r.errors.second, r.errors.third, r.errors.note.c_str(), per_second(r),
                     median(r.cpu) / static_cast<double>(r.steps), ratio(p, q, 0),
                     ratio(p, q, ode), mu_of(c), c.angle * 180.0 / std::numbers::pi, c.margin,
                     c.breakaway ? 1 : 0);
      }
    }
    std::fclose(csv);
  }
  return 0;
}
