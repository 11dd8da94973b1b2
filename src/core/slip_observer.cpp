#include "core/slip_observer.hpp"

#include <limits>
#include <optional>

#include "core/body.hpp"
#include "core/body_events.hpp"

namespace stiction::core {
namespace {

// The body (or the two bodies of a pair) a contact acts on and its contact point in each
// body's frame at x0: from the map's contact_site, else from x_hat's first three entries (a
// contact's x_hat starts with the contact point's world position) for a one-body contact.
void locate_on_body(Network& network, int impedance, const Vec& x0, SlipHistory& history) {
  const CoordinateMap& map = network.map_of(impedance);
  std::vector<const Body*> bodies;
  for (const Admittance* a : map.admittances()) {
    if (const auto* b = dynamic_cast<const Body*>(a)) bodies.push_back(b);
  }
  if (bodies.empty() || bodies.size() > 2) return;
  const auto motion_of = [&](const Body* body) -> std::optional<BodyMotion> {
    const auto& admittances = network.admittances();
    for (std::size_t k = 0; k < admittances.size(); ++k) {
      if (admittances[k].get() != body) continue;
      const Slot s = network.admittance_slot(static_cast<int>(k));
      return body->motion(x0.segment(s.state_offset, s.state_size));
    }
    return std::nullopt;
  };
  Vec3 world;
  if (const auto site = map.contact_site(x0)) {
    world = site->world;
    history.rolling = site->rolling;
  } else {
    const ConstVecRef x_hat = network.impedance_input(impedance, x0);
    if (bodies.size() != 1 || x_hat.size() < 3) return;
    world = x_hat.head<3>();
  }
  const std::optional<BodyMotion> m = motion_of(bodies[0]);
  if (!m) return;
  history.body = bodies[0]->name();
  history.point = m->q.conjugate() * (world - m->p);
  if (bodies.size() == 2) {
    if (const std::optional<BodyMotion> o = motion_of(bodies[1])) {
      history.other_body = bodies[1]->name();
      history.other_point = o->q.conjugate() * (world - o->p);
    }
  }
}

}  // namespace

SlipObserver::SlipObserver(Network& network, const RunOptions& options, const Stepper& stepper,
                           RunResult& result, const Vec& x0)
    : network_(network), stepper_(stepper), result_(result), histories_(result.slip_events) {
  const double resolution = options.event_resolution >= 0.0 ? options.event_resolution : options.dt;
  for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
    const auto& imp = *network.impedances()[i];
    if (network.capabilities(i).slip == nullptr) continue;
    const auto it = options.stick_thresholds.find(imp.name());
    const double threshold =
        it != options.stick_thresholds.end() ? it->second : options.default_stick_threshold;
    slipping_.push_back(i);
    contacts_.push_back(network.capabilities(i).contact);
    histories_.push_back({imp.name(), SlipMonitor(threshold, resolution)});
    histories_.back().static_ratio = network.capabilities(i).slip->static_ratio();
    if (contacts_.back() != nullptr) locate_on_body(network, i, x0, histories_.back());
    observe(slipping_.size() - 1, 0.0, x0, options.dt);
  }
  capture_ = !slipping_.empty() && stepper.evaluates_start_first();
  if (stepper.interpolates()) part_state_ = x0;
  if (capture_) {
    for (int i : slipping_) {
      captured_inputs_.push_back(network.captured_input(i));
      captured_states_.push_back(network.captured_state(i));
    }
  }
}

void SlipObserver::observe_from(std::size_t m, double time, ConstVecRef x_hat, ConstVecRef y,
                                double tau) {
  const Capabilities& c = network_.capabilities(slipping_[m]);
  SlipMonitor& monitor = histories_[m].monitor;
  const bool open = contacts_[m] != nullptr && !(contacts_[m]->contact_normal_force(x_hat) > 0.0);
  const Vec3 slip = c.slip->slip_velocity(x_hat);
  // The friction law (Kikuuwe: stuck while within its limit), asked only where it matters
  // (it costs an evaluation): while stuck, to bound a slip onset, and above the threshold.
  SlipMonitor::Law law = SlipMonitor::Law::unknown;
  if (!open && c.friction != nullptr && (monitor.sticking() || slip.norm() > monitor.threshold())) {
    law = c.friction->regime(x_hat, y, tau) == 1 ? SlipMonitor::Law::held
                                                 : SlipMonitor::Law::released;
  }
  const double closure = contacts_[m] != nullptr ? contacts_[m]->contact_closure(x_hat)
                                                : std::numeric_limits<double>::quiet_NaN();
  monitor.observe(time, slip, open, law, closure);
}

void SlipObserver::observe(std::size_t m, double time, const Vec& state, double tau) {
  const int i = slipping_[m];
  const Slot s = network_.impedance_slot(i);
  observe_from(m, time, network_.impedance_input(i, state),
               state.segment(s.state_offset, s.state_size), tau);
}

void SlipObserver::settle(const Vec& state) {
  if (!pending_) return;
  pending_ = false;
  const bool served = requested_ && !network_.capture_pending();
  requested_ = false;
  if (!served) {
    network_.cancel_capture();
    for (std::size_t m = 0; m < slipping_.size(); ++m)
      observe(m, pending_time_, state, pending_tau_);
    return;
  }
  for (std::size_t m = 0; m < slipping_.size(); ++m) {
    observe_from(m, pending_time_, captured_inputs_[m], captured_states_[m], pending_tau_);
  }
}

RunObserver::Before SlipObserver::before_step(const StepPlan&) {
  if (pending_) {
    network_.capture_slip_inputs_next();
    requested_ = true;
  }
  return {};
}

// Served by the step's first evaluation; a fixed stepper that threw changed x only once it
// had evaluated, so x is then still the pending state.
void SlipObserver::after_advance(const Vec& x) { settle(x); }

Verdict SlipObserver::after_step(const StepTaken& step) {
  const double tau = step.t_now - step.t;
  if (stepper_.interpolates()) {
    // Each element at the ends of its own part's steps (exact states, its own step as tau),
    // as if its part were stepped alone: not at the run loop's steps, where its state may be
    // interpolated inside a step of its own.
    for (std::size_t m = 0; m < slipping_.size(); ++m) {
      stepper_.part_step_ends(slipping_[m], step.t, step.t_now, ends_);
      for (const PartStepEnd& end : ends_) {
        stepper_.part_step_state(slipping_[m], end.segment, part_state_);
        observe(m, end.time, part_state_, end.length);
      }
    }
  } else if (capture_) {
    pending_ = true;
    pending_time_ = step.t_now;
    pending_tau_ = tau;
  } else {
    for (std::size_t m = 0; m < slipping_.size(); ++m) observe(m, step.t_now, step.x, tau);
  }
  return Verdict::go_on;
}

void SlipObserver::finish(const Vec& x) {
  settle(x);  // the state the run ends at (no step after it)
  for (auto& history : histories_) history.monitor.finish();
  result_.body_events = body_events(histories_);
}

}  // namespace stiction::core
