#include "core/island_sdirk.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace stiction::core {

std::vector<Island> step_groups(const Network& network) { return find_islands(network, nullptr); }

IslandSdirkStepper::IslandSdirkStepper(const SdirkTableau& tableau, std::vector<Island> groups,
                                       int state_dim, double dt, double tolerance, double max_step)
    : tableau_(tableau),
      implicit_(state_dim, dt),
      dt_(dt),
      tolerance_(tolerance),
      max_step_(max_step),
      controller_{integrator_traits(tableau.name).error_order},
      state_(Vec::Zero(state_dim)),
      k_(static_cast<std::size_t>(tableau.stages), Vec::Zero(state_dim)),
      y_(static_cast<std::size_t>(tableau.stages), Vec::Zero(state_dim)),
      err_(Vec::Zero(state_dim)),
      probe_(Vec::Zero(state_dim)),
      stage_start_(Vec::Zero(state_dim)) {
  if (!(tolerance > 0.0)) throw std::invalid_argument(tableau.name + " needs a tolerance > 0");
  implicit_.keep_start_slope(true);
  implicit_.set_step_groups(groups);
  groups_.resize(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (int i : groups[g].impedances) {
      if (static_cast<std::size_t>(i) >= group_of_impedance_.size()) {
        group_of_impedance_.resize(static_cast<std::size_t>(i) + 1, -1);
      }
      group_of_impedance_[static_cast<std::size_t>(i)] = static_cast<int>(g);
    }
    groups_[g].part = std::move(groups[g]);
  }
}

void IslandSdirkStepper::restart(double t, const Vec& x) {
  state_ = x;
  for (Group& g : groups_) {
    g.t = t;
    g.h = std::min(dt_, max_step_);
    g.crossing = false;
    g.refining = false;
    g.at_switch = false;
    g.used = 0;
  }
  started_ = true;
}

bool IslandSdirkStepper::stages(Network& network, int index, double t, double h, const Vec& x) {
  const std::vector<int>& entries = groups_[static_cast<std::size_t>(index)].part.states;
  const int s = tableau_.stages;
  const double gh = tableau_.gamma * h;
  for (int r = 0; r < s; ++r) {
    Vec& y = y_[static_cast<std::size_t>(r)];
    for (int i : entries) {
      double v = x[i];
      for (int j = 0; j < r; ++j) {
        const double a = tableau_.a_at(r, j);
        if (a != 0.0) v += (h * a) * k_[static_cast<std::size_t>(j)][i];
      }
      y[i] = v;
    }
    // The stage's backward Euler step of gamma h ends at t + c_r h.
    if (!implicit_.solve_stage(network, t + (tableau_.c(r) - tableau_.gamma) * h, gh, y, index)) {
      evaluations_ = implicit_.evaluations();
      return false;
    }
    Vec& k = k_[static_cast<std::size_t>(r)];
    for (int i : entries) k[i] = implicit_.slope()[i];
    if (r == 0) {
      for (int i : entries) stage_start_[i] = implicit_.start_slope()[i];
    }
  }
  evaluations_ = implicit_.evaluations();
  return true;
}

double IslandSdirkStepper::estimate(int index, double h) {
  const std::vector<int>& entries = groups_[static_cast<std::size_t>(index)].part.states;
  const int s = tableau_.stages;
  for (int i : entries) err_[i] = 0.0;
  for (int j = 0; j < s; ++j) {
    const double w = tableau_.a_at(s - 1, j) - tableau_.b_hat[static_cast<std::size_t>(j)];
    if (w == 0.0) continue;
    const Vec& k = k_[static_cast<std::size_t>(j)];
    for (int i : entries) err_[i] += (h * w) * k[i];
  }
  implicit_.apply_inverse(err_, index);
  // scaled_error's measure (floor 1) over the group's entries.
  const Vec& y = y_[static_cast<std::size_t>(s - 1)];
  double worst = 0.0;
  for (int i : entries) {
    worst = std::max(worst, std::abs(err_[i]) / (tolerance_ * (1.0 + std::abs(y[i]))));
  }
  return std::isfinite(worst) ? worst : 1e10;
}

void IslandSdirkStepper::take(Group& g, double h, double t_limit) {
  const std::vector<int>& entries = g.part.states;
  const auto n = static_cast<Eigen::Index>(entries.size());
  if (g.used == g.segments.size()) {
    g.segments.push_back({0.0, 0.0, Vec(n), Vec(n), Vec(n), Vec(n)});
  }
  Segment& seg = g.segments[g.used++];
  const Vec& y = y_[static_cast<std::size_t>(tableau_.stages - 1)];
  const Vec& k = k_[static_cast<std::size_t>(tableau_.stages - 1)];
  for (Eigen::Index q = 0; q < n; ++q) {
    const int i = entries[static_cast<std::size_t>(q)];
    seg.x0[q] = state_[i];
    seg.f0[q] = stage_start_[i];
    seg.x1[q] = y[i];
    // The end's slope: the last stage's (stiffly accurate: its solution is the step's end),
    // at no cost. F evaluated anew at the end instead cost one evaluation a step and moved
    // the rows of rolling spheres by no more than they already differed (5e-8 under sdirk4
    // at 1e-6, both ways: the stuck contact's slope depends on the stage size it is given).
    seg.f1[q] = k[i];
    state_[i] = y[i];
  }
  seg.t0 = g.t;
  // A step cut to the limit ends on it exactly (not at t + (limit - t), a rounding off).
  seg.t1 = h == t_limit - g.t ? t_limit : g.t + h;
  g.t = seg.t1;
  ++group_steps_;
}

double IslandSdirkStepper::step_group(Network& network, Group& g, double t_limit) {
  const int index = static_cast<int>(&g - groups_.data());
  for (;;) {
    const double h = std::min(g.h, t_limit - g.t);
    const bool converged = stages(network, index, g.t, h, state_);
    const double error = converged ? estimate(index, h) : std::numeric_limits<double>::infinity();
    if (!StepController::accept(error)) {
      ++rejections_;
      g.h = h * (converged ? controller_.factor(error) : 0.25);
      if (g.h < min_adaptive_step(g.t)) {
        std::ostringstream message;
        message << name() << ": step size underflow at t = " << g.t << " s" << describe(network, g)
                << " ("
                << (converged ? "the error estimate stays above the tolerance"
                              : "Newton's iteration does not converge")
                << ")";
        throw std::runtime_error(message.str());
      }
      continue;
    }
    // A step across a change of regime is cut to end just before it, as SdirkStepper's
    // (core/sdirk.hpp's land_before_switch: regimes at tau = 0, a probe past the switch when
    // any of its stages is).
    if (!g.crossing) {
      const std::size_t start_regimes = network.regime_signature(state_, 0.0, &g.part);
      if (stages_switch(network, state_, start_regimes, y_, &g.part)) {
        const double t0 = g.t;
        const double land = land_before_switch(
            network, t0, h, state_, start_regimes, y_,
            [&](double length) { return stages(network, index, t0, length, state_); }, probe_,
            &g.part);
        if (!g.refining) ++switches_;
        if (land < h) {
          if (!stages(network, index, t0, land, state_)) {  // the step to the switch
            g.h = 0.25 * land;
            continue;
          }
          take(g, land, t_limit);
          const SwitchWindow window = window_after_landing(t0, h);
          g.crossing = window.crossing;
          g.refining = !window.crossing;
          g.at_switch = true;
          g.h = window.length;
          return land;
        }
        // The switch is at the step's end: the step stands (its stages computed anew: the
        // probes overwrote them).
        if (!stages(network, index, t0, h, state_)) {
          g.h = 0.25 * h;
          continue;
        }
      }
    }
    g.at_switch = g.crossing;  // the step that crossed a switch ends at one too
    g.crossing = false;
    g.refining = false;
    take(g, h, t_limit);
    // A step cut short by the limit says little about the next one: keep g.h then. A factor
    // of 1..1.2 keeps the step, so that the stages' iteration matrices are reused.
    if (h >= g.h) {
      const double factor = controller_.factor(error);
      if (factor < 1.0 || factor > 1.2) g.h = h * factor;
    }
    g.h = std::min(g.h, max_step_);
    return h;
  }
}

void IslandSdirkStepper::group_state_at(const Group& g, double s, Vec& x) const {
  const std::vector<int>& entries = g.part.states;
  if (g.used == 0 || s >= g.t) {
    for (int i : entries) x[i] = state_[i];
    return;
  }
  std::size_t k = g.used - 1;
  while (k > 0 && g.segments[k].t0 > s) --k;
  const Segment& seg = g.segments[k];
  const double h = seg.t1 - seg.t0;
  const double u = std::clamp((s - seg.t0) / h, 0.0, 1.0);
  // core/hermite.hpp's weights, entry by entry.
  const double u2 = u * u, u3 = u2 * u;
  const double w_x0 = 2.0 * u3 - 3.0 * u2 + 1.0, w_x1 = 1.0 - w_x0;
  const double w_f0 = h * (u3 - 2.0 * u2 + u), w_f1 = h * (u3 - u2);
  for (std::size_t q = 0; q < entries.size(); ++q) {
    const auto e = static_cast<Eigen::Index>(q);
    x[entries[q]] = w_x0 * seg.x0[e] + w_x1 * seg.x1[e] + w_f0 * seg.f0[e] + w_f1 * seg.f1[e];
  }
}

double IslandSdirkStepper::advance(Network& network, double t, double limit, Vec& x) {
  if (!started_ || t != handed_t_ || !(x.array() == handed_x_.array()).all()) restart(t, x);
  const double end = t + limit;
  double target = t + std::min(limit, max_step_);
  for (Group& g : groups_) {
    // The steps that end by t are not needed any more (the rows before t are written).
    std::size_t first = 0;
    while (first < g.used && g.segments[first].t1 <= t) ++first;
    for (std::size_t k = first; k < g.used; ++k) std::swap(g.segments[k - first], g.segments[k]);
    g.used -= first;
    // A group ahead whose last step ended at a switch: the run loop's step ends there.
    if (g.at_switch && g.t > t) target = std::min(target, g.t);
  }
  // The groups behind the target step, the one furthest behind first; the target comes
  // down to the end of any step that lands on a switch or crosses one.
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> behind;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    if (groups_[g].t < target) behind.emplace(groups_[g].t, static_cast<int>(g));
  }
  while (!behind.empty()) {
    Group& g = groups_[static_cast<std::size_t>(behind.top().second)];
    behind.pop();
    if (g.t >= target) continue;
    step_group(network, g, end);
    if (g.at_switch) target = std::min(target, g.t);
    if (g.t < target) behind.emplace(g.t, static_cast<int>(&g - groups_.data()));
  }
  // The run loop's time after this step is t + h, which may differ from target in its last
  // bit; a group keeps its own time all the same (its steps do not depend on the run loop's).
  const double h = target - t;
  const double t_now = t + h;
  for (Group& g : groups_) {
    group_state_at(g, t_now, x);
    if (g.t > t_now) network.project(x, &g.part);
  }
  handed_t_ = t_now;
  handed_x_ = x;
  evaluations_ = implicit_.evaluations();
  return h;
}

void IslandSdirkStepper::part_step_ends(int impedance, double t0, double t1,
                                        std::vector<PartStepEnd>& ends) const {
  ends.clear();
  const int index = group_of_impedance_[static_cast<std::size_t>(impedance)];
  if (index < 0) return;
  const Group& g = groups_[static_cast<std::size_t>(index)];
  // The run loop's times are t + h, which may be a rounding off a group's (the run's end
  // included): a step ending within that of t1 is in (t0, t1]. Steps are far longer
  // (min_adaptive_step).
  const double slack = 1e-15 * std::max(1.0, std::abs(t1));
  for (std::size_t k = 0; k < g.used; ++k) {
    const Segment& seg = g.segments[k];
    if (seg.t1 > t0 + slack && seg.t1 <= t1 + slack) {
      ends.push_back({seg.t1, seg.t1 - seg.t0, static_cast<int>(k)});
    }
  }
}

void IslandSdirkStepper::part_step_state(int impedance, int segment, Vec& x) const {
  const Group& g =
      groups_[static_cast<std::size_t>(group_of_impedance_[static_cast<std::size_t>(impedance)])];
  const Segment& seg = g.segments[static_cast<std::size_t>(segment)];
  for (std::size_t q = 0; q < g.part.states.size(); ++q) {
    x[g.part.states[q]] = seg.x1[static_cast<Eigen::Index>(q)];
  }
}

void IslandSdirkStepper::interpolate(double t, Vec& x) const {
  for (const Group& g : groups_) group_state_at(g, t, x);
}

std::string IslandSdirkStepper::describe(const Network& network, const Group& g) const {
  return in_island_of(network, g.part);
}

}  // namespace stiction::core
