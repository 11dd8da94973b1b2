#include "core/row_sampler.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/hermite.hpp"
#include "core/integrator_traits.hpp"

namespace stiction::core {
namespace {

double unwrap_toward(double value, double reference) {
  constexpr double kTurn = 2.0 * 3.14159265358979323846;
  return value + kTurn * std::round((reference - value) / kTurn);
}

// Adds the time from its construction to its destruction to `total` (RunResult::row_seconds).
class RowTimer {
 public:
  explicit RowTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~RowTimer() {
    total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  RowTimer(const RowTimer&) = delete;
  RowTimer& operator=(const RowTimer&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

RowSampler::RowSampler(Network& network, const RunOptions& options, const Stepper& stepper,
                       RunResult& result, RowSink* sink, const Vec& x0)
    : network_(network),
      stepper_(stepper),
      result_(result),
      sink_(sink),
      dense_(is_adaptive(options.integrator)),
      T_(options.dt),
      sample_period_(1.0 / options.output_rate),
      total_samples_(static_cast<long>(std::floor(options.duration / sample_period_ + 1e-9)) + 1),
      n_(network.signal_count()),
      row_(n_ + 1),
      last_row_(n_ + 1),
      row_prev_(n_),
      row_now_(n_),
      row_blend_(n_),
      end_signals_(n_),
      end_signals_t_(std::numeric_limits<double>::quiet_NaN()) {
  if (dense_ && !stepper.interpolates() && stepper.start_derivative() == nullptr) {
    throw std::logic_error("RowSampler: a variable step without its start derivative");
  }
  std::vector<std::string> columns{"t"};
  for (auto& c : network.signal_columns()) columns.push_back(std::move(c));
  result.trajectory = Trajectory(columns);
  // Rows go to the sink in blocks (one buffer, reused), or into the trajectory, reserved up
  // to a bound: the rows actually produced may be far fewer (instability, interrupt), and a
  // long run should grow rather than ask for everything up front.
  if (sink != nullptr) {
    block_capacity_ = std::max<std::size_t>(
        1, std::min(kBlockRows, kBlockBytes / (sizeof(double) * columns.size())));
    block_.resize(block_capacity_ * columns.size());
  } else {
    result.trajectory.reserve_rows(static_cast<int>(std::min(total_samples_, 1L << 20)));
  }
  const auto flags = network.wrapped_columns();
  for (int i = 0; i < n_; ++i) {
    if (flags[i]) wrapped_.push_back(i);
  }
  if (dense_) {
    x1_ = x0;  // the first step starts here
    x0_.resize(x0.size());
    f0_.resize(x0.size());
    f1_.resize(x0.size());
    x_row_.resize(x0.size());
  }
  network.write_signals(0.0, x0, T_, row_now_);
  if (!dense_) {
    end_signals_ = row_now_;
    end_signals_t_ = 0.0;
  }
  emit(0.0, row_now_);
  ++sample_;
}

void RowSampler::emit(double ts, const Vec& values) {
  row_[0] = ts;
  for (int i = 0; i < n_; ++i) row_[i + 1] = values[i];
  if (emitted_) {
    for (int c : wrapped_) row_[c + 1] = unwrap_toward(row_[c + 1], last_row_[c + 1]);
  }
  if (sink_ != nullptr) {
    std::copy(row_.begin(), row_.end(), block_.begin() + block_rows_ * row_.size());
    if (++block_rows_ == block_capacity_) flush();
  } else {
    result_.trajectory.append(row_.data());
  }
  ++result_.rows;
  if (non_finite_column_ < 0) {
    for (int c = 1; c <= n_; ++c) {
      if (!std::isfinite(row_[c])) {
        non_finite_column_ = c;
        non_finite_time_ = ts;
        break;
      }
    }
  }
  last_row_ = row_;
  emitted_ = true;
}

void RowSampler::flush() {
  if (block_rows_ > 0) sink_->write(block_.data(), block_rows_, row_.size());
  block_rows_ = 0;
}

Verdict RowSampler::stop_if_non_finite() {
  if (non_finite_column_ < 0) return Verdict::go_on;
  if (!result_.instability) {
    const std::string& column = result_.trajectory.columns()[static_cast<std::size_t>(non_finite_column_)];
    result_.instability = Instability{non_finite_time_, column.substr(0, column.find('.')),
                                      "signal " + column + " is not finite"};
  }
  return Verdict::stop;
}

RunObserver::Before RowSampler::before_step(const StepPlan& plan) {
  // The row at t = 0, written at construction, may already be non-finite.
  if (stop_if_non_finite() == Verdict::stop) return {Verdict::stop, false};
  if (dense_) return {};  // keeps its own copies of the pending step
  // A row strictly inside the step is blended with the signals at its start.
  const double next_sample = static_cast<double>(sample_) * sample_period_;
  const bool inside = sample_ < total_samples_ && next_sample <= plan.t_next + 1e-9 * T_ &&
                      (next_sample - plan.t) / (plan.t_next - plan.t) <= 1.0 - 1e-9;
  // The start signals are kept from the step before when it ended here.
  return {Verdict::go_on, inside && !(end_signals_t_ == plan.t)};
}

Verdict RowSampler::after_step(const StepTaken& step) {
  t_reached_ = step.t_now;
  steps_seen_ = step.k + 1;
  if (!dense_) {
    if (sample_ < total_samples_ &&
        static_cast<double>(sample_) * sample_period_ <= step.t_now + 1e-9 * T_) {
      const RowTimer timer(result_.row_seconds);
      sample_linear(step);
    }
    return stop_if_non_finite();
  }
  const RowTimer timer(result_.row_seconds);
  if (stepper_.interpolates()) {
    sample_interpolated(step);
    return stop_if_non_finite();
  }
  const Vec& start_derivative = *stepper_.start_derivative();  // at step.t, the pending end
  if (pending_) {
    f1_ = start_derivative;
    sample_dense();
  }
  x0_.swap(x1_);
  x1_ = step.x;
  f0_ = start_derivative;
  t0_ = step.t;
  t1_ = step.t_now;
  pending_ = true;
  return stop_if_non_finite();
}

void RowSampler::sample_linear(const StepTaken& step) {
  // Rows in (t, t_now]: interpolated between the signals at both ends.
  bool have_prev = false;
  bool have_now = false;
  while (sample_ < total_samples_ &&
         static_cast<double>(sample_) * sample_period_ <= step.t_now + 1e-9 * T_) {
    const double ts = static_cast<double>(sample_) * sample_period_;
    if (!have_now) {
      network_.write_signals(step.t_now, step.x, T_, row_now_);
      end_signals_ = row_now_;
      end_signals_t_ = step.t_now;
      have_now = true;
    }
    const double alpha = (ts - step.t) / (step.t_now - step.t);
    if (alpha > 1.0 - 1e-9) {
      emit(ts, row_now_);
    } else {
      if (!have_prev) {
        if (end_signals_t_ == step.t) {
          row_prev_ = end_signals_;  // the step before ended here
        } else {
          // before_step asked for the start state for exactly this row.
          network_.write_signals(step.t, step.x_prev, T_, row_prev_);
        }
        for (int c : wrapped_) row_now_[c] = unwrap_toward(row_now_[c], row_prev_[c]);
        have_prev = true;
      }
      row_blend_.noalias() = (1.0 - alpha) * row_prev_ + alpha * row_now_;
      emit(ts, row_blend_);
    }
    ++sample_;
  }
}

void RowSampler::sample_interpolated(const StepTaken& step) {
  const double h = step.t_now - step.t;
  while (sample_ < total_samples_ &&
         static_cast<double>(sample_) * sample_period_ <= step.t_now + 1e-9 * T_) {
    const double ts = static_cast<double>(sample_) * sample_period_;
    if ((ts - step.t) / h > 1.0 - 1e-9) {
      network_.write_signals(step.t_now, step.x, h, row_now_);
    } else {
      stepper_.interpolate(ts, x_row_);
      network_.project(x_row_);
      network_.write_signals(ts, x_row_, h, row_now_);
    }
    emit(ts, row_now_);
    ++sample_;
  }
  t1_ = step.t_now;
  t0_ = step.t;
}

void RowSampler::sample_dense() {
  const double h = t1_ - t0_;
  // A derivative that is not finite (the step after blew up in its first evaluation) would
  // spoil finite rows: the quadratic through x0 with slope f0 and x1 then stands in.
  if (!f1_.allFinite()) f1_ = 2.0 / h * (x1_ - x0_) - f0_;
  while (sample_ < total_samples_ &&
         static_cast<double>(sample_) * sample_period_ <= t1_ + 1e-9 * T_) {
    const double ts = static_cast<double>(sample_) * sample_period_;
    const double s = (ts - t0_) / h;
    if (s > 1.0 - 1e-9) {
      network_.write_signals(t1_, x1_, h, row_now_);
    } else {
      hermite_state(x0_, f0_, x1_, f1_, h, s, x_row_);
      network_.project(x_row_);
      network_.write_signals(ts, x_row_, h, row_now_);
    }
    emit(ts, row_now_);
    ++sample_;
  }
}

void RowSampler::finish(const Vec& x) {
  const RowTimer timer(result_.row_seconds);
  const double h_last = dense_ ? t1_ - t0_ : T_;
  if (pending_) {
    // The last step's end derivative: no next step evaluates it, so one evaluation here.
    network_.derivative(t1_, x1_, t1_ - t0_, f1_);
    ++result_.evaluations;
    sample_dense();
    pending_ = false;
  }
  // The end row: the last row written when it is at the time reached, else the signals at
  // the state the run ended in (x, when this sampler saw its step: not after an instability
  // stopped the run before the step was sampled). `final` in summary.json is this row, so it
  // is the state at the end even when the output rate puts no row there (issue 25: `final`
  // held the initial state of a 2 s run at output_rate = 0.1).
  result_.end_row = last_row_;
  const bool x_is_reached = steps_seen_ == result_.steps && steps_seen_ > 0;
  if (x_is_reached && emitted_ && std::abs(last_row_[0] - t_reached_) > 1e-9 * T_ && x.allFinite()) {
    Vec values(n_);
    network_.write_signals(t_reached_, x, h_last, values);
    result_.end_row[0] = t_reached_;
    for (int i = 0; i < n_; ++i) result_.end_row[static_cast<std::size_t>(i) + 1] = values[i];
    for (int c : wrapped_) {
      result_.end_row[static_cast<std::size_t>(c) + 1] =
          unwrap_toward(result_.end_row[static_cast<std::size_t>(c) + 1], last_row_[static_cast<std::size_t>(c) + 1]);
    }
  }
  if (sink_ != nullptr) {
    flush();
    sink_->finish();
    result_.trajectory.append(last_row_.data());
  }
}

}  // namespace stiction::core
