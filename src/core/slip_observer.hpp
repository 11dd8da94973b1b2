// The run's stick/slip events: every element with a slip speed (a SlipElement) is observed
// after every step by its SlipMonitor (core/events.hpp), which the result keeps
// (RunResult::slip_events), and at the end the events of every body with several contact
// points (RunResult::body_events, core/body_events.hpp). Where the stepper evaluates the network
// first at the step's start state, the slips of the state a step ends at are read from the next
// step's first evaluation (Network::capture_slip_inputs_next, issue 13): one step later, with the
// same bits, and no second evaluation of the maps. Where the stepper's parts take steps of
// their own (Stepper::interpolates), each element is observed at its part's own step ends.
#pragma once

#include <vector>

#include "core/contact.hpp"
#include "core/integrator.hpp"
#include "core/network.hpp"
#include "core/run_observer.hpp"
#include "core/simulation.hpp"

namespace stiction::core {

class SlipObserver final : public RunObserver {
 public:
  // Observes the initial state x0 at once (with `dt` as the step); histories go to `result`.
  SlipObserver(Network& network, const RunOptions& options, const Stepper& stepper,
               RunResult& result, const Vec& x0);
  Before before_step(const StepPlan& plan) override;
  void after_advance(const Vec& x) override;
  Verdict after_step(const StepTaken& step) override;
  void finish(const Vec& x) override;

 private:
  // `tau`: the step just taken, with which a Kikuuwe element tells stuck from sliding;
  // x_hat and y: the element's input and state at the observed state.
  void observe_from(std::size_t m, double time, ConstVecRef x_hat, ConstVecRef y, double tau);
  // The same with the map evaluated here, at `state`.
  void observe(std::size_t m, double time, const Vec& state, double tau);
  // Observes the pending slips from the capture, or at `state` (the pending state itself) if
  // no evaluation served a request for them.
  void settle(const Vec& state);

  Network& network_;
  const Stepper& stepper_;
  RunResult& result_;  // its body_events are made from the histories at the end
  std::vector<SlipHistory>& histories_;
  std::vector<int> slipping_;                   // impedance index of each history
  std::vector<const NormalContact*> contacts_;  // says when a contact is open, or nullptr
  bool capture_ = false;
  bool pending_ = false;  // the slips of the state at pending_time_ are not observed yet
  bool requested_ = false;
  double pending_time_ = 0.0, pending_tau_ = 0.0;
  std::vector<ConstVecRef> captured_inputs_, captured_states_;  // views, made once
  std::vector<PartStepEnd> ends_;  // a stepper whose parts take steps of their own
  Vec part_state_;
};

}  // namespace stiction::core
