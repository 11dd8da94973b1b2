// Writes the run's rows, [t, signal...] at the output rate (RunOptions::output_rate),
// independent of the step: into the result's trajectory, or in blocks of kBlockRows to a
// RowSink. Angles reported modulo 2 pi are unwrapped: each value is moved by whole turns to
// the nearest of the previous row's.
//
// - A fixed step: rows at step ends are the step's signals; a row strictly inside a step is
//   the linear blend of the signals at its two ends (an O(dt^2) error of the output only, and
//   the rows of every existing run, bit for bit). The signals at a step's end are kept: they are
//   the next step's start signals (same time, same state, same tau), so a step with rows
//   inside it evaluates the network once for its rows, not twice.
// - A stepper that interpolates its own steps (Stepper::interpolates: sdirk on several
//   islands, each on its own steps) gives the state at each row's time inside the step
//   just taken; the rows are written at once.
// - A variable step (rk4_adaptive, whose steps span several rows in smooth phases): rows come
//   from the state interpolated by a cubic Hermite (core/hermite.hpp) from both ends' values
//   and derivatives, quaternions renormalized (Network::project), then
//   Network::write_signals at the row's time with the step taken as tau. The derivative at a
//   step's start is the stepper's own first evaluation (Stepper::start_derivative), and at
//   its end that of the next step: a step's rows are written once the next step is taken
//   (no extra evaluation), and the last step's at finish(), which evaluates the network once.
#pragma once

#include <vector>

#include "core/integrator.hpp"
#include "core/network.hpp"
#include "core/row_sink.hpp"
#include "core/run_observer.hpp"
#include "core/simulation.hpp"

namespace stiction::core {

class RowSampler final : public RunObserver {
 public:
  // Writes the row at t = 0 from x0 at once.
  RowSampler(Network& network, const RunOptions& options, const Stepper& stepper, RunResult& result,
             RowSink* sink, const Vec& x0);
  Before before_step(const StepPlan& plan) override;
  Verdict after_step(const StepTaken& step) override;
  // Writes what is pending, flushes the sink and keeps the last row in the trajectory. Sets
  // the result's end_row: the signals at the state the run ended in (RunResult::end_row).
  void finish(const Vec& x) override;

 private:
  void emit(double ts, const Vec& values);

  // A row with a value that is not finite, from a finite state (the state itself is the
  // InstabilityObserver's): an instability at that row, never a run that ends `ok`.
  Verdict stop_if_non_finite();
  void flush();
  void sample_linear(const StepTaken& step);
  // Writes the rows in (t0_, t1_] from the pending step, its end derivative in f1_.
  void sample_dense();
  // Writes the rows in (t, t_now] of a step from the stepper's own interpolation
  // (Stepper::interpolates: groups that took steps of their own within it).
  void sample_interpolated(const StepTaken& step);

  // Rows per block to the sink: at most kBlockRows, and at most kBlockBytes of them (a scene
  // of 120000 columns would otherwise fill a 245 MB block).
  static constexpr std::size_t kBlockRows = 256;
  static constexpr std::size_t kBlockBytes = 256 * 1024;
  std::size_t block_capacity_ = kBlockRows;

  Network& network_;
  const Stepper& stepper_;
  RunResult& result_;
  RowSink* sink_;
  bool dense_;
  double T_;  // RunOptions::dt
  double sample_period_;
  long total_samples_;
  long sample_ = 0;           // the next row to write
  int n_;                     // signals per row
  std::vector<int> wrapped_;  // signal columns that are angles modulo 2 pi
  std::vector<double> block_;
  std::size_t block_rows_ = 0;
  std::vector<double> row_, last_row_;
  bool emitted_ = false;
  int non_finite_column_ = -1;  // the first column of a row found not finite
  double non_finite_time_ = 0.0;
  double t_reached_ = 0.0;      // the end of the last step this sampler saw
  long steps_seen_ = 0;
  Vec row_prev_, row_now_;  // signals at a step's two ends (linear) or at a row (dense)
  Vec row_blend_;           // a row between them (linear)
  // The signals at the end of the last step that wrote rows, before unwrapping, and that
  // step's end time (NaN: none): the next step's start signals if it starts there.
  Vec end_signals_;
  double end_signals_t_;
  // Dense output: the step whose rows wait for its end derivative.
  bool pending_ = false;
  double t0_ = 0.0, t1_ = 0.0;
  Vec x0_, f0_, x1_, f1_, x_row_;
};

}  // namespace stiction::core
