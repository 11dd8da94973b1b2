#include "core/row_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/hermite.hpp"

namespace stiction::core {
namespace {

double unwrap_toward(double value, double reference) {
  constexpr double kTurn = 2.0 * 3.14159265358979323846;
  return value + kTurn * std::round((reference - value) / kTurn);
}

}  // namespace

RowSampler::RowSampler(Network& network, const RunOptions& options, const Stepper& stepper,
                       RunResult& result, RowSink* sink, const Vec& x0)
    : network_(network),
      stepper_(stepper),
      result_(result),
      sink_(sink),
      dense_(options.integrator == "rk4_adaptive"),
      T_(options.dt),
      sample_period_(1.0 / options.output_rate),
      total_samples_(static_cast<long>(std::floor(options.duration / sample_period_ + 1e-9)) + 1),
      n_(network.signal_count()),
      row_(n_ + 1),
      last_row_(n_ + 1),
      row_prev_(n_),
      row_now_(n_) {
  if (dense_ && stepper.start_derivative() == nullptr) {
    throw std::logic_error("RowSampler: a variable step without its start derivative");
  }
  std::vector<std::string> columns{"t"};
  for (auto& c : network.signal_columns()) columns.push_back(std::move(c));
  result.trajectory = Trajectory(columns);
  // Rows go to the sink in blocks (one buffer, reused), or into the trajectory, reserved up
  // to a bound: the rows actually produced may be far fewer (instability, interrupt), and a
  // long run should grow rather than ask for everything up front.
  if (sink != nullptr) {
    block_.resize(kBlockRows * columns.size());
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
    if (++block_rows_ == kBlockRows) flush();
  } else {
    result_.trajectory.append(row_.data());
  }
  ++result_.rows;
  last_row_ = row_;
  emitted_ = true;
}

void RowSampler::flush() {
  if (block_rows_ > 0) sink_->write(block_.data(), block_rows_, row_.size());
  block_rows_ = 0;
}

RunObserver::Before RowSampler::before_step(const StepPlan& plan) {
  if (dense_) return {};  // keeps its own copies of the pending step
  // A row strictly inside the step is blended with the signals at its start.
  const double next_sample = static_cast<double>(sample_) * sample_period_;
  const bool inside = sample_ < total_samples_ && next_sample <= plan.t_next + 1e-9 * T_ &&
                      (next_sample - plan.t) / (plan.t_next - plan.t) <= 1.0 - 1e-9;
  return {Verdict::go_on, inside};
}

Verdict RowSampler::after_step(const StepTaken& step) {
  if (!dense_) {
    sample_linear(step);
    return Verdict::go_on;
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
  return Verdict::go_on;
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
      have_now = true;
    }
    const double alpha = (ts - step.t) / (step.t_now - step.t);
    if (alpha > 1.0 - 1e-9) {
      emit(ts, row_now_);
    } else {
      if (!have_prev) {
        // before_step asked for the start state for exactly this row.
        network_.write_signals(step.t, step.x_prev, T_, row_prev_);
        for (int c : wrapped_) row_now_[c] = unwrap_toward(row_now_[c], row_prev_[c]);
        have_prev = true;
      }
      emit(ts, (1.0 - alpha) * row_prev_ + alpha * row_now_);
    }
    ++sample_;
  }
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

void RowSampler::finish(const Vec&) {
  if (pending_) {
    // The last step's end derivative: no next step evaluates it, so one evaluation here.
    network_.derivative(t1_, x1_, t1_ - t0_, f1_);
    ++result_.evaluations;
    sample_dense();
    pending_ = false;
  }
  if (sink_ != nullptr) {
    flush();
    sink_->finish();
    result_.trajectory.append(last_row_.data());
  }
}

}  // namespace stiction::core
