#include "core/simulation.hpp"

#include <chrono>
#include <cmath>
#include <limits>

namespace stiction::core {
namespace {

// The component owning the first non-finite state slot.
std::string owner_of_non_finite(const Network& network, const Vec& x) {
  for (const auto& entry : network.layout()) {
    if (!x.segment(entry.offset, entry.size).allFinite()) return entry.component;
  }
  return "(unknown)";
}

}  // namespace

RunResult simulate(Network& network, const RunOptions& options, const ProgressCallback& progress) {
  RunResult result;
  std::vector<std::string> columns{"t"};
  for (auto& c : network.signal_columns()) columns.push_back(std::move(c));
  result.trajectory = Trajectory(columns);

  const double T = options.dt;
  const double end = options.duration;
  const long total_steps = static_cast<long>(std::ceil(end / T - 1e-9));
  const double sample_period = 1.0 / options.output_rate;
  const long total_samples = static_cast<long>(std::floor(end / sample_period + 1e-9)) + 1;
  result.trajectory.reserve_rows(static_cast<int>(total_samples));

  RungeKuttaStepper stepper(tableau_by_name(options.integrator), network.state_dim());
  Vec x = network.initial_state();
  Vec x_prev = x;
  const int n = network.signal_count();
  Vec row_prev(n), row_now(n);
  std::vector<double> row(n + 1);

  auto emit = [&](double ts, const Vec& values) {
    row[0] = ts;
    for (int i = 0; i < n; ++i) row[i + 1] = values[i];
    result.trajectory.append(row.data());
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

  const double initial_energy = network.energy(x);
  const double energy_margin = (std::abs(initial_energy) + 1.0) * options.energy_growth_limit;

  const auto start = std::chrono::steady_clock::now();
  long sample = 0;
  network.write_signals(0.0, x, T, row_now);
  emit(0.0, row_now);
  ++sample;
  long progress_every = std::max(1L, total_steps / 100);

  for (long k = 0; k < total_steps; ++k) {
    const double t = k * T;
    const double h = std::min(T, end - t);
    x_prev = x;
    stepper.step(network, t, h, x);
    const double t_now = (k + 1 == total_steps) ? end : (k + 1) * T;
    result.steps = k + 1;

    if (!x.allFinite()) {
      result.instability = Instability{t_now, owner_of_non_finite(network, x), "state is not finite"};
      break;
    }
    const double energy = network.energy(x);
    if (std::isfinite(initial_energy) && std::isfinite(energy) &&
        energy - initial_energy > energy_margin) {
      result.instability = Instability{t_now, "network", "energy grew without bound"};
      break;
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
          have_prev = true;
        }
        emit(ts, (1.0 - alpha) * row_prev + alpha * row_now);
      }
      ++sample;
    }
    if (progress && (k + 1) % progress_every == 0) progress(double(k + 1) / total_steps);
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.final_state = x;
  return result;
}

}  // namespace stiction::core
