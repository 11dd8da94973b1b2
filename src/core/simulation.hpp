// Owns time: steps a network with one integrator and calls its observers around each step
// (core/run_observer.hpp): rows at the output rate, independent of dt (core/row_sampler.hpp:
// linear between fixed steps, a cubic Hermite of the state between variable ones), slip
// events (core/slip_observer.hpp), the first sign of numerical instability
// (core/instability_observer.hpp), interrupts and progress.
#pragma once

#include <atomic>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "core/body_events.hpp"
#include "core/events.hpp"
#include "core/integrator.hpp"
#include "core/network.hpp"
#include "core/row_sink.hpp"
#include "core/trajectory.hpp"

namespace stiction::core {

struct RunOptions {
  std::string integrator = "rk4";
  double dt = 1e-4;        // the step (rk4_adaptive: its first step)
  double tolerance = 0.0;  // rk4_adaptive only
  double duration = 1.0;
  double output_rate = 1000.0;  // rows per second of simulated time
  // Stop as unstable when the network energy less the sources' work rises above its lowest
  // value by more than this fraction of the scene's energy scale: core/energy_budget.hpp.
  double energy_tolerance = 0.01;
  // Slip speed below which a contact or joint counts as stuck, per impedance name.
  std::map<std::string, double> stick_thresholds;
  double default_stick_threshold = 1e-3;  // m/s or rad/s
  // When set and true, the run stops after the current step and
  // reports itself interrupted (checked every few steps; see app/interrupt.hpp).
  const std::atomic<bool>* stop = nullptr;
  // Sticks shorter than this are not reported as events (SlipMonitor); negative: one step.
  double event_resolution = -1.0;
};

struct SlipHistory {
  std::string component;
  SlipMonitor monitor;
  // A contact on one body: that body's name and the contact point in its frame at t = 0
  // (body_events.hpp groups a body's points and reads their geometry); empty otherwise.
  std::string body{};
  Vec3 point = Vec3::Zero();
  // A contact between two bodies: the second body and the same point in its frame.
  std::string other_body{};
  Vec3 other_point = Vec3::Zero();
  // The point travels over the body as it rolls (contact_site): not an edge or corner.
  bool rolling = false;
  // The element's static level over its kinetic one (SlipElement::static_ratio).
  double static_ratio = 1.0;
};

struct Instability {
  double time = 0.0;
  std::string component;
  std::string reason;
};

struct RunResult {
  // Every row, or with a RowSink only the last one (the rows went to the sink).
  Trajectory trajectory;
  long rows = 0;  // rows produced
  // [t, signal...] at the state the run ended in: the last row, or, when the output rate
  // puts no row at the time reached, the signals there (summary.json's `final`). Empty if
  // no row was written.
  std::vector<double> end_row;
  long steps = 0;
  long evaluations = 0;  // network evaluations (the integrator's cost)
  double wall_seconds = 0.0;
  // Of wall_seconds, the time the run loop spent on rows (core/row_sampler.hpp: signals at
  // row times, interpolation, handing rows to the sink), steady clock, measured only around
  // steps that produce rows. What a sink does on threads of its own is not in it.
  double row_seconds = 0.0;
  std::optional<Instability> instability;
  bool interrupted = false;              // stopped early through RunOptions::stop
  std::vector<SlipHistory> slip_events;  // one per impedance with a slip speed
  // One per body with several contact points, from its points' slip_events (body_events.hpp).
  std::vector<BodyEventHistory> body_events;
};

using ProgressCallback = std::function<void(double fraction_done)>;

// rk4_adaptive's longest step: kAdaptiveRowsPerStep output rows. Its error control alone lets
// a step grow without bound in a smooth phase (a thrown mass took 8 steps over 0.9 s), and
// then (1) the slip and instability monitors, which see the state at step ends only, would
// watch it more coarsely than the rows show it, (2) the signals of a row are written with the
// step taken as tau, and Kikuuwe friction's force depends on tau (its stuck damping is of
// order tau K), so an unbounded step changes the friction shown, and (3) the Hermite rows'
// error grows as h^4 while the step's own error check sees only the step's end. A bound of a
// few rows costs little where the output is dense enough to show the motion anyway.
inline constexpr double kAdaptiveRowsPerStep = 4.0;
double adaptive_step_bound(const RunOptions& options);

// std::invalid_argument when the options break core/run_limits.hpp (checked before anything
// is allocated). With a sink, rows go to it in blocks as they are produced (memory
// independent of the run's length) and the result's trajectory keeps only the last row.
RunResult simulate(Network& network, const RunOptions& options,
                   const ProgressCallback& progress = {}, RowSink* sink = nullptr);

}  // namespace stiction::core
