#include "core/simulation.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace stiction::core {
namespace {

// The component owning the first non-finite state slot.
std::string owner_of_non_finite(Network& network, const Vec& x) {
  for (const auto& entry : network.layout()) {
    if (!x.segment(entry.offset, entry.size).allFinite()) return entry.component;
  }
  return "(unknown)";
}

// The admittance whose energy grew the most over the last step.
std::string fastest_growing(Network& network, const Vec& before, const Vec& after) {
  std::string name = "network";
  double worst = -1.0;
  for (std::size_t j = 0; j < network.admittances().size(); ++j) {
    const Slot s = network.admittance_slot(static_cast<int>(j));
    const auto& a = *network.admittances()[j];
    const double growth = a.energy(after.segment(s.state_offset, s.state_size)) -
                          a.energy(before.segment(s.state_offset, s.state_size));
    if (growth > worst) {
      worst = growth;
      name = a.name();
    }
  }
  return name;
}

}  // namespace

RunResult simulate(Network& network, const RunOptions& options, const ProgressCallback& progress) {
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
  result.trajectory.reserve_rows(static_cast<int>(total_samples));

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
    result.trajectory.append(row.data());
    last_row = row;
    emitted = true;
  };

  std::vector<int> slipping;
  for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
    const auto& imp = *network.impedances()[i];
    if (!imp.has_slip()) continue;
    const auto it = options.stick_thresholds.find(imp.name());
    const double threshold =
        it != options.stick_thresholds.end() ? it->second : options.default_stick_threshold;
    slipping.push_back(i);
    result.slip_events.push_back({imp.name(), SlipMonitor(threshold)});
    result.slip_events.back().monitor.observe(0.0, network.slip_velocity(i, x));
  }

  // States with a bound the exact model keeps (Impedance::state_bound), checked with the
  // energy: twice the bound (or the initial value, if larger) is past any rounding.
  struct BoundedState {
    std::string component;
    int offset, size;
    double limit;
  };
  std::vector<BoundedState> bounded;
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const Impedance& imp = *network.impedances()[i];
    const Slot s = network.impedance_slot(static_cast<int>(i));
    if (!std::isfinite(imp.state_bound()) || s.state_size == 0) continue;
    const double start = x.segment(s.state_offset, s.state_size).lpNorm<Eigen::Infinity>();
    bounded.push_back({imp.name(), s.state_offset, s.state_size,
                       2.0 * std::max(imp.state_bound(), start)});
  }
  auto beyond_bound = [&]() -> const BoundedState* {
    for (const auto& b : bounded) {
      if (x.segment(b.offset, b.size).lpNorm<Eigen::Infinity>() > b.limit) return &b;
    }
    return nullptr;
  };

  const double initial_energy = network.energy(x);
  const bool has_sources = network.has_sources();
  double work_in = 0.0;  // |work| done by sources so far
  double power_checked = has_sources ? std::abs(network.source_power(0.0, x)) : 0.0;
  double t_checked = 0.0;
  constexpr long kEnergyCheckEvery = 8;

  const auto start = std::chrono::steady_clock::now();
  long sample = 0;
  network.write_signals(0.0, x, T, row_now);
  emit(0.0, row_now);
  ++sample;
  long progress_every = std::max(1L, total_steps / 100);

  double t = 0.0;
  for (long k = 0; t < end; ++k) {
    x_prev = x;
    double h = 0.0;
    try {
      h = stepper->advance(network, t, end - t, x);
    } catch (const std::runtime_error& error) {
      result.instability = Instability{t, "integrator", error.what()};
      break;
    }
    // Fixed steps: time from the step count, so a long run does not accumulate rounding.
    const double t_now = fixed_step ? ((k + 1 >= total_steps) ? end : (k + 1) * T) : t + h;
    result.steps = k + 1;
    result.evaluations = stepper->evaluations();

    if (!x.allFinite()) {
      result.instability = Instability{t_now, owner_of_non_finite(network, x), "state is not finite"};
      break;
    }
    // Energy every few steps: a numerical instability grows geometrically, so a short
    // delay in noticing it costs nothing, while checking every step would.
    if ((k + 1) % kEnergyCheckEvery == 0 || t_now >= end) {
      if (has_sources) {
        const double power = std::abs(network.source_power(t_now, x));
        work_in += 0.5 * (power_checked + power) * (t_now - t_checked);
        power_checked = power;
        t_checked = t_now;
      }
      const double energy = network.energy(x);
      if (std::isfinite(initial_energy) && std::isfinite(energy) &&
          energy - initial_energy > energy_margin(options, initial_energy, work_in)) {
        result.instability = Instability{t_now, fastest_growing(network, x_prev, x),
                                         "energy grew beyond what the sources put in"};
        break;
      }
      if (const BoundedState* b = beyond_bound()) {
        result.instability = Instability{t_now, b->component,
                                         "state past twice the bound its model keeps"};
        break;
      }
    }

    for (std::size_t m = 0; m < slipping.size(); ++m) {
      result.slip_events[m].monitor.observe(t_now, network.slip_velocity(slipping[m], x));
    }

    // Samples that fall in (t, t_now]: interpolate between the signals at both ends.
    bool have_prev = false;
    bool have_now = false;
    while (sample < total_samples && sample * sample_period <= t_now + 1e-9 * T) {
      const double ts = sample * sample_period;
      if (!have_now) {
        network.write_signals(t_now, x, T, row_now);
        have_now = true;
      }
      const double alpha = (ts - t) / (t_now - t);
      if (alpha > 1.0 - 1e-9) {
        emit(ts, row_now);
      } else {
        if (!have_prev) {
          network.write_signals(t, x_prev, T, row_prev);
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
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace stiction::core
