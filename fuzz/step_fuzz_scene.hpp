// Steps a scene the fuzzer built for a short stretch, as `stiction run --force-step` would
// (no step guard: the run loop's own monitors must catch what the guard would have refused),
// and checks the invariant of issue 39: a run either reports an instability (exit 3) or a
// model fault (exit 2), or ends with only finite numbers in its rows. A run that ends as a
// success with a non-finite number would be exit 0 with non-finite output: that throws
// NonFiniteFinish, which the fuzz target does not catch (a finding, input saved).
//
// The stretch is at most `max_steps` steps of the scene's dt, at most `work` state entries
// times steps (a scene of 2000 pair contacts steps less than one ball) and about `seconds`
// of wall time, so that an input costs about the same whatever it builds.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/run_limits.hpp"
#include "core/simulation.hpp"
#include "scene/scene.hpp"

namespace stiction::fuzz {

struct NonFiniteFinish : std::logic_error {
  using std::logic_error::logic_error;
};

// What the inputs of one fuzz process came to, printed at exit (docs/sanitizers_fuzzing.md
// quotes these lines): inputs refused as input errors, scenes built, and of those stepped,
// how many finished and how many stopped as unstable or on a model fault.
struct Tally {
  const char* target = "fuzz";
  long inputs = 0, refused = 0, built = 0, finished = 0, unstable = 0, faulted = 0, cut = 0;
  ~Tally() {
    if (inputs == 0) return;
    std::fprintf(stderr,
                 "%s: %ld inputs: %ld refused as input errors, %ld built; stepped: %ld finished "
                 "finite (%ld of them cut at the time budget), %ld unstable, %ld model faults; "
                 "0 finished with non-finite output\n",
                 target, inputs, refused, built, finished, cut, unstable, faulted);
  }
};

inline Tally& tally() {
  static Tally t;
  return t;
}

enum class StepOutcome { finished, unstable, faulted };

inline StepOutcome step_briefly(scene::Scene& scene, long max_steps = 200, long work = 20000,
                                double seconds = 1.0) {
  core::RunOptions options = scene.run;
  const long states = std::max(1, scene.network->state_dim());
  const long steps = std::clamp(work / states, 2L, max_steps);
  options.duration = std::min(options.duration, static_cast<double>(steps) * options.dt);
  options.output_rate = std::min(options.output_rate, 100.0 / options.duration);
  if (core::check_run_limits(options)) {
    ++tally().faulted;  // not reachable for a scene that passed the limits with its own values
    return StepOutcome::faulted;
  }
  // And at most `seconds` of wall time (an implicit or adaptive integrator on a stiff pile
  // takes many evaluations a step, 20 to 50 times slower instrumented): the run is stopped
  // through RunOptions::stop as an interrupt would stop it, and its rows so far are checked.
  // A single step that does not end is left to libFuzzer's -timeout (a hang).
  std::atomic<bool> stop{false};
  options.stop = &stop;
  const auto start = std::chrono::steady_clock::now();
  const auto watch = [&](double) {
    if (std::chrono::steady_clock::now() - start > std::chrono::duration<double>(seconds)) {
      stop = true;
    }
  };
  core::RunResult result;
  try {
    result = core::simulate(*scene.network, options, watch);
  } catch (const scene::InputError&) {  // a model fault (an expression's non-finite value)
    ++tally().faulted;
    return StepOutcome::faulted;
  }
  if (result.instability) {
    ++tally().unstable;
    return StepOutcome::unstable;
  }
  const auto check = [&](const double* row, std::size_t size, const char* what) {
    for (std::size_t c = 0; c < size; ++c) {
      if (!std::isfinite(row[c])) {
        throw NonFiniteFinish(std::string("a run that ended without an instability has a "
                                          "non-finite value in ") +
                              what + ", column " + std::to_string(c));
      }
    }
  };
  check(result.end_row.data(), result.end_row.size(), "its last row");
  const core::Trajectory& rows = result.trajectory;
  for (int r = 0; r < rows.row_count(); ++r) {
    check(rows.row(r), static_cast<std::size_t>(rows.column_count()), "a row");
  }
  ++tally().finished;
  if (result.interrupted) ++tally().cut;
  return StepOutcome::finished;
}

}  // namespace stiction::fuzz
