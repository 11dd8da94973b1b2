// `--integrator sdirk2 | sdirk4` on a network of several step groups: every group (bodies that
// no element can couple, core/islands.hpp, contacts between bodies included) takes steps of
// its own size, under its own error control and landing on its own regime switches, as
// core/sdirk.hpp's SdirkStepper steps the whole network.
//
// Why: with one step for all, each switch of any body cuts the step of every body, and each
// contact transient holds every body at its short steps: N spheres that stick one after
// the other took 2677 steps at N = 1 and 39910 at N = 1000, every one of them solving all
// 1000 islands. Apart, each sphere takes about its own 2677 steps, and the work is linear in N.
//
// What the run loop sees: advance() takes one step from t to a common time t + H, the
// earliest of
//   - t + max_step and the limit,
//   - the end of any group's step that landed just before a switch or crossed one (so the
//     observers see every switch at the step it is landed on, as with one step for all);
// every group behind t + H steps until it reaches or passes it (the group furthest behind
// first). A group that passed t + H keeps its own state and time; the state handed back at
// t + H is the cubic Hermite of its step there (each step's two ends and slopes, as the row
// sampler interpolates a variable step), so the next advance() continues each group from
// its own state, never from an interpolated one. interpolate() gives the state at any time
// inside the step just taken from each group's own steps (the rows).
//
// A call whose (t, x) is not the (time, state) the last call handed back (a new run, or a
// caller that set the state) starts every group afresh there.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "core/implicit_euler.hpp"
#include "core/integrator.hpp"
#include "core/islands.hpp"
#include "core/sdirk.hpp"
#include "core/step_control.hpp"

namespace stiction::core {

// The step groups of a network: its islands with every contact between bodies attached
// (bodies that a contact may join step together).
std::vector<Island> step_groups(const Network& network);

class IslandSdirkStepper final : public Stepper {
 public:
  IslandSdirkStepper(const SdirkTableau& tableau, std::vector<Island> groups, int state_dim,
                     double dt, double tolerance,
                     double max_step = std::numeric_limits<double>::infinity());
  const std::string& name() const override { return tableau_.name; }
  int order() const override { return tableau_.order; }
  double advance(Network& network, double t, double limit, Vec& x) override;
  bool interpolates() const override { return true; }
  void interpolate(double t, Vec& x) const override;
  void part_step_ends(int impedance, double t0, double t1,
                      std::vector<PartStepEnd>& ends) const override;
  void part_step_state(int impedance, int segment, Vec& x) const override;

  std::size_t groups() const { return groups_.size(); }
  long group_steps() const { return group_steps_; }  // steps of single groups, all groups
  long switches() const { return switches_; }
  long rejections() const { return rejections_; }

 private:
  // One step of a group, over its entries only: start (t0, x0, slope f0), end (t1, x1, f1).
  struct Segment {
    double t0 = 0.0, t1 = 0.0;
    Vec x0, f0, x1, f1;
  };
  struct Group {
    Island part;
    double t = 0.0;                 // its own time: its entries of state_ are its state there
    double h = 0.0;                 // its next trial step
    bool crossing = false;          // its next step crosses a located switch: not located again
    bool refining = false;          // its next step searches a located switch's window again
    bool at_switch = false;         // its last step landed on or crossed a switch, ending at t
    std::vector<Segment> segments;  // its steps since the run loop's last time (reused)
    std::size_t used = 0;
  };

  void restart(double t, const Vec& x);
  // One accepted step of group g from its time, ending at most at t_limit; returns its
  // length.
  double step_group(Network& network, Group& g, double t_limit);
  // The stages of a step of h from (t, state_) on g's entries; false if one did not converge.
  bool stages(Network& network, int index, double t, double h, const Vec& x);
  // The scaled, filtered error estimate of g's stages just computed.
  double estimate(int index, double h);
  // Takes the step just computed (stages of h from g's time): records it, moves g.
  void take(Group& g, double h, double t_limit);
  // g's state at time s, within [its first segment's start, g.t], on its entries of x.
  void group_state_at(const Group& g, double s, Vec& x) const;
  std::string describe(const Network& network, const Group& g) const;

  SdirkTableau tableau_;
  ImplicitEulerStepper implicit_;
  double dt_, tolerance_, max_step_;
  StepController controller_;
  std::vector<Group> groups_;
  std::vector<int> group_of_impedance_;  // -1: in no group
  Vec state_;                            // each group's entries at its own time
  std::vector<Vec> k_, y_;  // stage slopes and solutions (each group writes its entries)
  Vec err_, probe_, stage_start_;
  bool started_ = false;
  double handed_t_ = 0.0;  // the time and state the last advance() handed back
  Vec handed_x_;
  long group_steps_ = 0, switches_ = 0, rejections_ = 0;
};

}  // namespace stiction::core
