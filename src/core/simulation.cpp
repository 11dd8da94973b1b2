#include "core/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/contact.hpp"
#include "core/flush_subnormals.hpp"
#include "core/instability_monitor.hpp"
#include "core/run_limits.hpp"

namespace stiction::core {
namespace {

// The component owning the first non-finite state slot.
std::string owner_of_non_finite(Network& network, const Vec& x) {
  for (const auto& entry : network.layout()) {
    if (!x.segment(entry.offset, entry.size).allFinite()) return entry.component;
  }
  return "(unknown)";
}

// Steps between two checks of the monitor: every step, since the energy monitor must see a
// rise of 1% of the energy scale that lasts a few steps (issue 26; about 13% of box_slope's
// CPU time under rk4).
constexpr long kMonitorEvery = 1;

}  // namespace

RunResult simulate(Network& network, const RunOptions& options, const ProgressCallback& progress,
                   RowSink* sink) {
  if (const auto violation = check_run_limits(options)) {
    throw std::invalid_argument(violation->key + ": " + violation->message);
  }
  const FlushSubnormals flush_subnormals;  // a body at rest must not slow the run down
  RunResult result;
  std::vector<std::string> columns{"t"};
  for (auto& c : network.signal_columns()) columns.push_back(std::move(c));
  result.trajectory = Trajectory(columns);

  const double T = options.dt;
  const double end = options.duration;
  const bool fixed_step = options.integrator != "rk4_adaptive";
  const long total_steps = static_cast<long>(std::ceil(end / T - 1e-9));
  const double sample_period = 1.0 / options.output_rate;
  const long total_samples = static_cast<long>(std::floor(end / sample_period + 1e-9)) + 1;
  // Rows go to the sink in blocks of kBlockRows (one buffer, reused), or into the trajectory,
  // reserved up to a bound: the rows actually produced may be far fewer (instability,
  // interrupt), and a long run should grow rather than ask for everything up front.
  constexpr std::size_t kBlockRows = 256;
  std::vector<double> block;
  std::size_t block_rows = 0;
  if (sink != nullptr) {
    block.resize(kBlockRows * columns.size());
  } else {
    result.trajectory.reserve_rows(static_cast<int>(std::min(total_samples, 1L << 20)));
  }
  auto flush = [&] {
    if (block_rows > 0) sink->write(block.data(), block_rows, columns.size());
    block_rows = 0;
  };

  auto stepper = make_stepper(options.integrator, network.state_dim(), T, options.tolerance);
  Vec x = network.initial_state();
  Vec x_prev = x;
  const int n = network.signal_count();
  Vec row_prev(n), row_now(n);
  std::vector<double> row(n + 1), last_row(n + 1);

  // Angles reported modulo 2 pi are unwrapped: each value is moved by whole turns to the
  // nearest of the previous one, both before blending two steps and between rows.
  std::vector<int> wrapped;
  {
    const auto flags = network.wrapped_columns();
    for (int i = 0; i < n; ++i) {
      if (flags[i]) wrapped.push_back(i);
    }
  }
  auto unwrap_toward = [](double value, double reference) {
    constexpr double kTurn = 2.0 * 3.14159265358979323846;
    return value + kTurn * std::round((reference - value) / kTurn);
  };
  bool emitted = false;
  auto emit = [&](double ts, const Vec& values) {
    row[0] = ts;
    for (int i = 0; i < n; ++i) row[i + 1] = values[i];
    if (emitted) {
      for (int c : wrapped) row[c + 1] = unwrap_toward(row[c + 1], last_row[c + 1]);
    }
    if (sink != nullptr) {
      std::copy(row.begin(), row.end(), block.begin() + block_rows * row.size());
      if (++block_rows == kBlockRows) flush();
    } else {
      result.trajectory.append(row.data());
    }
    ++result.rows;
    last_row = row;
    emitted = true;
  };

  // Elements with a slip speed, and for contacts the capability that says when they are open.
  std::vector<int> slipping;
  std::vector<const NormalContact*> contacts;
  const double resolution = options.event_resolution >= 0.0 ? options.event_resolution : T;
  // `tau`: the step just taken, with which a Kikuuwe element tells stuck from sliding;
  // x_hat and y: the element's input and state at the observed state.
  auto observe_slip_from = [&](std::size_t m, double time, ConstVecRef x_hat, ConstVecRef y,
                               double tau) {
    const Capabilities& c = network.capabilities(slipping[m]);
    SlipMonitor& monitor = result.slip_events[m].monitor;
    const bool open = contacts[m] != nullptr && !(contacts[m]->contact_normal_force(x_hat) > 0.0);
    const Vec3 slip = c.slip->slip_velocity(x_hat);
    // The friction law (Kikuuwe: stuck while within its limit), asked only where it matters
    // (it costs an evaluation): while stuck, to bound a slip onset, and above the threshold.
    SlipMonitor::Law law = SlipMonitor::Law::unknown;
    if (!open && c.friction != nullptr &&
        (monitor.sticking() || slip.norm() > monitor.threshold())) {
      law = c.friction->regime(x_hat, y, tau) == 1 ? SlipMonitor::Law::held
                                                   : SlipMonitor::Law::released;
    }
    monitor.observe(time, slip, open, law);
  };
  // The same with the map evaluated here, at `state`.
  auto observe_slip = [&](std::size_t m, double time, const Vec& state, double tau) {
    const int i = slipping[m];
    const Slot s = network.impedance_slot(i);
    observe_slip_from(m, time, network.impedance_input(i, state),
                      state.segment(s.state_offset, s.state_size), tau);
  };
  for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
    const auto& imp = *network.impedances()[i];
    if (network.capabilities(i).slip == nullptr) continue;
    const auto it = options.stick_thresholds.find(imp.name());
    const double threshold =
        it != options.stick_thresholds.end() ? it->second : options.default_stick_threshold;
    slipping.push_back(i);
    contacts.push_back(network.capabilities(i).contact);
    result.slip_events.push_back({imp.name(), SlipMonitor(threshold, resolution)});
    observe_slip(slipping.size() - 1, 0.0, x, T);
  }

  InstabilityMonitor monitor(network, options, x);

  // Slips without a second evaluation of the maps (issue 13): when the stepper evaluates the
  // network first at the step's start state, the slips of the state a step ends at are read
  // from the next step's first evaluation (Network::capture_slip_inputs_next), one step later
  // but with the same bits; the state the run ends at is observed directly.
  const bool capture_slips = !slipping.empty() && stepper->evaluates_start_first();
  bool slips_pending = false;  // the slips of the state at pending_time are not observed yet
  bool capture_requested = false;
  double pending_time = 0.0, pending_tau = 0.0;
  std::vector<ConstVecRef> captured_inputs, captured_states;  // views, made once
  if (capture_slips) {
    for (int i : slipping) {
      captured_inputs.push_back(network.captured_input(i));
      captured_states.push_back(network.captured_state(i));
    }
  }
  // Observes the pending slips from the capture, or at `state` (the pending state itself)
  // if no evaluation served a request for them.
  auto settle_slips = [&](const Vec& state) {
    if (!slips_pending) return;
    slips_pending = false;
    const bool served = capture_requested && !network.capture_pending();
    capture_requested = false;
    if (!served) {
      network.cancel_capture();
      for (std::size_t m = 0; m < slipping.size(); ++m)
        observe_slip(m, pending_time, state, pending_tau);
      return;
    }
    for (std::size_t m = 0; m < slipping.size(); ++m) {
      observe_slip_from(m, pending_time, captured_inputs[m], captured_states[m], pending_tau);
    }
  };

  const auto start = std::chrono::steady_clock::now();
  long sample = 0;
  network.write_signals(0.0, x, T, row_now);
  emit(0.0, row_now);
  ++sample;
  long progress_every = std::max(1L, total_steps / 100);

  double t = 0.0;
  for (long k = 0; t < end; ++k) {
    if (options.stop != nullptr && k % 64 == 0 && options.stop->load(std::memory_order_relaxed)) {
      result.interrupted = true;
      break;
    }
    // The step's start state is copied only when something will read it (with 100 bodies the
    // copy is a few percent of the step): the monitor's check, a sample strictly inside the
    // step (interpolated) and a variable step.
    const double t_next = fixed_step ? ((k + 1 >= total_steps) ? end : (k + 1) * T) : end;
    const double next_sample = static_cast<double>(sample) * sample_period;
    const bool keep_prev = !fixed_step || (k + 1) % kMonitorEvery == 0 || t_next >= end ||
                           (sample < total_samples && next_sample <= t_next + 1e-9 * T &&
                            (next_sample - t) / (t_next - t) <= 1.0 - 1e-9);
    if (keep_prev) x_prev = x;
    if (slips_pending) {
      network.capture_slip_inputs_next();
      capture_requested = true;
    }
    double h = 0.0;
    try {
      h = stepper->advance(network, t, end - t, x);
    } catch (const std::runtime_error& error) {
      settle_slips(x);  // the fixed steppers change x only once they have evaluated
      result.instability = Instability{t, "integrator", error.what()};
      break;
    }
    settle_slips(x);  // served by the step's first evaluation
    // Fixed steps: time from the step count, so a long run does not accumulate rounding.
    const double t_now = fixed_step ? ((k + 1 >= total_steps) ? end : (k + 1) * T) : t + h;
    result.steps = k + 1;
    result.evaluations = stepper->evaluations();

    if (!x.allFinite()) {
      result.instability =
          Instability{t_now, owner_of_non_finite(network, x), "state is not finite"};
      break;
    }
    // Every kMonitorEvery steps (see there).
    if ((k + 1) % kMonitorEvery == 0 || t_now >= end) {
      if (auto found = monitor.check(t_now, x_prev, x)) {
        result.instability = std::move(found);
        break;
      }
    }

    if (capture_slips) {
      slips_pending = true;
      pending_time = t_now;
      pending_tau = t_now - t;
    } else {
      for (std::size_t m = 0; m < slipping.size(); ++m) observe_slip(m, t_now, x, t_now - t);
    }

    // Samples that fall in (t, t_now]: interpolate between the signals at both ends.
    bool have_prev = false;
    bool have_now = false;
    while (sample < total_samples && sample * sample_period <= t_now + 1e-9 * T) {
      const double ts = sample * sample_period;
      // Signals with the step actually taken over (t, t_now] (rk4_adaptive varies it).
      const double tau = fixed_step ? T : h;
      if (!have_now) {
        network.write_signals(t_now, x, tau, row_now);
        have_now = true;
      }
      const double alpha = (ts - t) / (t_now - t);
      if (alpha > 1.0 - 1e-9) {
        emit(ts, row_now);
      } else {
        if (!have_prev) {
          if (!keep_prev)
            throw std::logic_error("simulate: a sample inside a step without its start");
          network.write_signals(t, x_prev, tau, row_prev);
          for (int c : wrapped) row_now[c] = unwrap_toward(row_now[c], row_prev[c]);
          have_prev = true;
        }
        emit(ts, (1.0 - alpha) * row_prev + alpha * row_now);
      }
      ++sample;
    }
    if (progress && (k + 1) % progress_every == 0) progress(t_now / end);
    t = t_now;
  }
  settle_slips(x);  // the state the run ends at (no step after it)
  for (auto& history : result.slip_events) history.monitor.finish();
  if (sink != nullptr) {
    flush();
    sink->finish();
    result.trajectory.append(last_row.data());
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace stiction::core
