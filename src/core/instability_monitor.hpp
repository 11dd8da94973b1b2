// The run's monitor beyond finiteness (core::simulate asks it every step): the network
// energy less what the sources put in, against its lowest value so far (core/energy_budget.hpp:
// any rise past a tolerance of the scene's energy scale is numerical), and every state with
// a bound its model keeps (BoundedState) against twice that bound, for instabilities whose
// error dissipates and so does not show in the energy.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/energy_budget.hpp"
#include "core/feedback_monitor.hpp"
#include "core/network.hpp"
#include "core/simulation.hpp"

namespace stiction::core {

class InstabilityMonitor {
 public:
  InstabilityMonitor(Network& network, const RunOptions& options, const Vec& x0);
  // The instability seen at state x reached at time t (x_prev: the state checked before),
  // if any.
  std::optional<Instability> check(double t, const Vec& x_prev, const Vec& x);

 private:
  struct BoundedState {
    std::string component;
    Slot slot;
    double limit;
  };
  Network& network_;
  bool has_sources_;
  double work_in_ = 0.0;  // |work| done by sources so far
  double power_checked_;
  double t_checked_ = 0.0;
  std::vector<BoundedState> bounded_;
  EnergyBudget budget_;       // with the work of all sources credited
  FeedbackMonitor feedback_;  // feedback sources' work: core/feedback_monitor.hpp
};

}  // namespace stiction::core
