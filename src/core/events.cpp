#include "core/events.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace stiction::core {
namespace {

// Relative rate of rise (1/s) below which a stuck element's speed is calm (observe).
constexpr double kCalmRate = 10.0;

// Speed of the fitted curve s = s_ref |(t - t0) / (t_ref - t0)|^p at t; zero on the far
// side of t0 (before it for an onset, after it for a stick).
double fitted_speed(double t, double t0, double p, double t_ref, double s_ref, bool growing) {
  const double sigma = growing ? t - t0 : t0 - t;
  const double sigma_ref = growing ? t_ref - t0 : t0 - t_ref;
  if (sigma <= 0.0) return 0.0;
  if (sigma_ref <= 0.0) return s_ref;
  return s_ref * std::pow(sigma / sigma_ref, p);
}

}  // namespace

const char* SlipMonitor::name(State s) {
  switch (s) {
    case State::stick:
      return "stick";
    case State::slip:
      return "slip";
    case State::open:
      return "open";
  }
  return "stick";
}

bool SlipMonitor::fit_zero(std::span<const Sample> samples, bool growing, double& t0, double& p) {
  const std::size_t n = samples.size();
  if (n < 2) return false;
  const Sample& ref = growing ? samples.front() : samples.back();
  double slope = 0.0;
  double curvature = 0.0;
  if (n == 2) {
    slope = (samples[1].s - samples[0].s) / (samples[1].t - samples[0].t);
  } else {
    // The quadratic through the three samples (Newton's divided differences).
    const Sample& a = samples[n - 3];
    const Sample& b = samples[n - 2];
    const Sample& c = samples[n - 1];
    const double f_ab = (b.s - a.s) / (b.t - a.t);
    const double f_bc = (c.s - b.s) / (c.t - b.t);
    const double f_abc = (f_bc - f_ab) / (c.t - a.t);
    slope = f_ab + f_abc * (2.0 * ref.t - a.t - b.t);
    curvature = 2.0 * f_abc;
  }
  // The speed must move away from zero (onset) or toward it (stick).
  if (growing ? !(slope > 0.0) : !(slope < 0.0)) return false;
  const double a_ratio = ref.s / std::abs(slope);  // s / |s'| = |t - t0| / p
  p = 1.0;
  if (curvature > 0.0) {
    const double b_ratio = std::abs(slope) / curvature;  // |s'| / s'' = |t - t0| / (p - 1)
    p = b_ratio > a_ratio ? b_ratio / (b_ratio - a_ratio) : 3.0;
    p = std::clamp(p, 1.0, 3.0);
  }
  const double reach = p * a_ratio;
  t0 = growing ? ref.t - reach : ref.t + reach;
  return std::isfinite(t0);
}

std::pair<double, double> SlipMonitor::contact_change(double t, double closure) const {
  // A lift-off from closure1_ > 0 to closure <= 0; a touch-down from closure1_ < 0 (a contact
  // exactly at zero before, open there, touches down after it, not at it).
  const bool crossed = closure1_ > 0.0 ? closure <= 0.0 : closure1_ < 0.0 && closure > 0.0;
  if (std::isfinite(closure1_) && std::isfinite(closure) && crossed) {
    return {t1_ + (t - t1_) * closure1_ / (closure1_ - closure), 0.0};
  }
  return {t, t - t1_};
}

void SlipMonitor::observe(double t, const Vec3& slip, bool open, Law law, double closure) {
  const double speed = slip.norm();
  const bool held = law == Law::held;
  const State now = open ? State::open : (speed > threshold_ && !held ? State::slip : State::stick);
  if (held) {
    last_held_ = t;
    held_speed_ = speed;
    first_release_ = -1.0;
    crept_ = false;
  } else if (law == Law::released && last_held_ >= 0.0) {
    if (first_release_ < 0.0) {
      first_release_ = t;
      since_release_ = 0;
    } else {
      ++since_release_;
    }
  }
  if (!started_) {
    started_ = true;
    state_ = initial_state_ = now;
    initial_ = name(now);
    t_first_ = t;
    if (now == State::slip) sliding_ = {{t, speed}};
    t1_ = t;
    s1_ = speed;
    v1_ = slip;
    closure1_ = closure;
    return;
  }
  // What waited for this step.
  if (stick_pending_) {
    if (now != State::stick) {
      settle_pending_stick(false);
    } else if (t >= stick_fit_) {
      settle_pending_stick(true);
    }
  }
  if (slip_pending_) {
    if (now == State::slip) onset_.push_back({t, speed});
    if (now != State::slip || onset_.size() >= 3) settle_pending_slip();
  }

  switch (state_) {
    case State::slip:
      if (now == State::slip) {
        // A reversal between two sliding steps passed through zero within the step: a
        // stick of zero length, not reported; the fit starts again from here.
        if (slip.dot(v1_) < 0.0) sliding_.clear();
        sliding_.push_back({t, speed});
        if (sliding_.size() > 3) sliding_.erase(sliding_.begin());
      } else if (now == State::stick) {
        double t0 = 0.0;
        double p = 1.0;
        const double step = t - t1_;
        if (speed > threshold_) {
          // Held by its law above the threshold (a stuck spring vibrating): the switch lies
          // in this step, at the fitted zero if that falls in it.
          const bool fits = fit_zero(sliding_, false, t0, p) && t0 <= t;
          if (fits && t0 >= t1_) {
            commit(State::stick, t0, 0.0);
          } else {
            commit(State::stick, fits ? t1_ : t, step);  // known only to lie in this step
          }
          sliding_.clear();
          break;
        }
        const double crossing = t1_ + (s1_ - threshold_) / (s1_ - speed) * (t - t1_);
        const bool fits =
            fit_zero(sliding_, false, t0, p) &&
            fitted_speed(t, t0, p, sliding_.back().t, sliding_.back().s, false) <= threshold_;
        if (!fits) {
          // The speed fell faster than any fit (an impact): the crossing, within its step.
          commit(State::stick, crossing, step);
        } else if (t0 <= t) {
          // A fitted zero before the step is clamped to its start: then only the step is known.
          commit(State::stick, std::max(t0, t1_), t0 >= t1_ ? 0.0 : step);
        } else {
          stick_pending_ = true;
          stick_raw_ = crossing;
          stick_fit_ = t0;
          stick_step_ = step;
        }
        sliding_.clear();
      } else {
        const auto [time, uncertainty] = contact_change(t, closure);
        commit(State::open, time, uncertainty);  // lift-off
        sliding_.clear();
      }
      break;
    case State::stick: {
      // Calm, not yet breaking loose: the speed rose at a relative rate below kCalmRate (0.1%
      // in a 1e-4 s step: a creep's speed drifts slower than that, a break-away's rises by
      // percents within a few such steps; a rate, not a fraction per step, so that a smaller
      // step does not take a break-away's rise for calm), or by less than in the step before
      // (a creep settling to its rate after the law let go; a break-away's rise grows, or
      // stays the same for a step force).
      const double rise = speed - s1_;
      if (now == State::stick &&
          (rise <= kCalmRate * s1_ * (t - t1_) || rise < (1.0 - 1e-3) * rise1_)) {
        calm_ = t;
        calm_speed_ = speed;
      } else if (calm_ == t1_) {
        calm_end_ = t;  // the step in which the speed started rising
      }
      // A creep, seen more than kCreepSteps after the law's release: a speed that rose from
      // the release, s = s_held + c (t - t_held)^p with p >= 1, rises in a step by at least
      // (s - s_held) dt / (t - t_held); one rising by less than half that (or not at all) did
      // not start rising there. Unlike the calm test this does not depend on the step: at
      // 1.25e-5 s a break-away's speed rises by less than 0.1% a step near the threshold.
      if (now == State::stick && first_release_ >= 0.0 && since_release_ > kCreepSteps) {
        const double above = std::max(speed - held_speed_, 0.0);
        if (!(rise > 0.5 * above * (t - t1_) / (t - last_held_))) crept_ = true;
      }
      if (now == State::slip && s1_ > threshold_) {
        // Released by its law while already faster than the threshold: no onset to fit.
        commit(State::slip, t, t - t1_);
        sliding_ = {{t, speed}};
      } else if (now == State::slip) {
        // Where the law was asked while stuck: the onset lies after the last step it held
        // the element and no later than the first step it released it.
        onset_low_ = last_held_;
        onset_high_ = last_held_ >= 0.0 ? (first_release_ >= 0.0 ? first_release_ : t) : -1.0;
        onset_crept_ = crept_;
        last_held_ = first_release_ = -1.0;
        crept_ = false;
        slip_pending_ = true;
        slip_raw_ = t1_ + (threshold_ - s1_) / (speed - s1_) * (t - t1_);
        slip_before_t_ = t1_;
        onset_ = {{t, speed}};
        sliding_ = {{t, speed}};
      } else if (now == State::open) {
        const auto [time, uncertainty] = contact_change(t, closure);
        commit(State::open, time, uncertainty);
        calm_ = -1.0;
      }
      break;
    }
    case State::open:
      if (now != State::open) {
        const auto [time, uncertainty] = contact_change(t, closure);
        commit(now, time, uncertainty);  // touch-down, stuck or sliding
        if (now == State::slip) sliding_ = {{t, speed}};
      }
      break;
  }
  state_ = now;
  t1_ = t;
  closure1_ = closure;
  rise1_ = speed - s1_;
  s1_ = speed;
  v1_ = slip;
}

void SlipMonitor::settle_pending_stick(bool reached) {
  stick_pending_ = false;
  if (reached) {
    commit(State::stick, stick_fit_, 0.0);
  } else {
    commit(State::stick, stick_raw_, stick_step_);
  }
}

void SlipMonitor::settle_pending_slip() {
  slip_pending_ = false;
  // The crossing is known to lie in its step; the fitted zero converges with the step.
  const double step = onset_.front().t - slip_before_t_;
  // The speed rises from the level it had when it started rising, not from zero: a stuck
  // element creeps at the rate its spring stretches (a block pushed by a ramp at r / K, up
  // to a tenth of the threshold), a released one at the rate the others let it. Fitted from
  // zero, a rise from s_c reaches back too far, by about 2 s_c / s of the reach (0.2 of a
  // 4 ms reach on a block: 9 steps before the law's release). So where the law held the
  // element in this stuck stretch, the fit is made to the speed above such a level (below
  // the threshold: a stuck spring vibrating above it is no creep). Without the law, and
  // after a slip whose speed only dipped under the threshold, it is made from zero, as that
  // is what joins the slips on either side of the dip.
  // onset_above: the onset fitted to the speed above `base` (the fitted zero, left in t0; or
  // the crossing where the fit fails or lies past it) and whether the fit placed it.
  double t0 = 0.0;
  const auto onset_above = [&](double base, bool& fitted) {
    std::array<Sample, 3> above{};
    const std::size_t n = std::min(onset_.size(), above.size());
    for (std::size_t i = 0; i < n; ++i) above[i] = {onset_[i].t, onset_[i].s - base};
    const std::span<const Sample> samples(above.data(), n);
    double p = 1.0;
    const bool fits =
        fit_zero(samples, true, t0, p) &&
        fitted_speed(slip_before_t_, t0, p, samples.front().t, samples.front().s, true) + base <=
            threshold_;
    fitted = fits && t0 < slip_raw_;
    return fitted ? t0 : slip_raw_;
  };
  const auto level = [&](double s) { return s < threshold_ ? s : 0.0; };
  bool fitted = false;
  // With the law: the onset as if the speed rose from the release, from its speed at the
  // last step the law held the element.
  double time = onset_above(onset_low_ >= 0.0 ? level(held_speed_) : 0.0, fitted);
  double uncertainty = fitted ? 0.0 : step;
  // The law's release bounds this onset only if the speed started growing there. A release
  // before that is a creep: the law saturated while other elements hold the body and the
  // speed stays below the threshold, stuck by the model's definition, and no slip begins
  // until the speed rises (a crate's unloaded back corners creep at 1 um/s for half a second
  // before the crate slides; a crate pulled low and fast, for 6 ms). The speed rose from the
  // release if (1) the release lies no further before the onset than the onset lies before
  // the threshold crossing (the fit's reach, at least the crossing step), (2) no step more
  // than kCreepSteps after the release showed a creep (crept_), and (3) the fitted zero, from
  // the speed at the release, lies no more than kCreepSteps crossing steps after it. (1)
  // alone let a creep shorter than the reach, which a slow ramp makes long, take the release
  // as its onset (a crate pulled low: its rear corners slipped 6 ms before it moved); (2)
  // sees a creep that stays flat or settles, (3) one whose speed kept rising steadily.
  const double reach = std::max(slip_raw_ - time, step);
  const bool rose_late = fitted && t0 > onset_high_ + kCreepSteps * step;
  const bool released_here = onset_high_ >= time - reach && !onset_crept_ && !rose_late;
  if (onset_low_ >= 0.0 && released_here) {
    const double high = std::max(onset_low_, onset_high_);
    time = std::clamp(time, onset_low_, high);
    uncertainty = high - onset_low_;  // placed in the bracket: known to that width
  } else if (onset_low_ >= 0.0 && calm_ >= 0.0) {
    // A creep's onset: its speed started rising in the step after its last calm one, the
    // bracket [calm_, calm_end_], from its speed there. The fit is kept in that step (the
    // body's transient as the other elements let go can still draw it back: a crate's
    // corners by 0.4 ms of a 16 ms reach, fitted from zero); a fit past it (the rise there
    // was not the onset's) is kept as a fit: it converges with the step (an elbow loaded
    // slowly by gravity: 1.00527, 1.00580, 1.00611, 1.00626 s at 1e-4 ... 1e-5 s), which a
    // companion run measures, so it carries one step, not its distance from the calm step
    // (1 ms there at every step, which no step could bring within a tolerance).
    time = onset_above(level(calm_speed_), fitted);
    const double high = std::max(calm_end_, calm_);
    if (time <= high) {
      time = std::max(time, calm_);
      uncertainty = high - calm_;
    } else {
      uncertainty = step;
    }
  }
  onset_.clear();
  calm_ = -1.0;  // the next stuck stretch finds its own
  commit(State::slip, time, uncertainty);
}

void SlipMonitor::finish() {
  if (stick_pending_) settle_pending_stick(false);
  if (slip_pending_) settle_pending_slip();
  if (events_.size() > kKeptHead + kKeptTail) drop_middle(kKeptTail);
}

void SlipMonitor::drop_middle(std::size_t tail) {
  const auto from = events_.begin() + static_cast<std::ptrdiff_t>(kKeptHead);
  const auto to = events_.end() - static_cast<std::ptrdiff_t>(tail);
  if (from >= to) return;
  if (dropped_ == 0) first_dropped_ = from->time;
  // A touch-down is a stick or slip whose previous event is an open.
  std::string previous = (from - 1)->kind;
  for (auto it = from; it != to; ++it) {
    dropped_stick_ += it->kind == "stick";
    dropped_slip_ += it->kind == "slip";
    dropped_open_ += it->kind == "open";
    dropped_touch_ += previous == "open" && it->kind != "open";
    previous = it->kind;
  }
  last_dropped_ = (to - 1)->time;
  last_dropped_kind_ = (to - 1)->kind;
  dropped_ += static_cast<std::size_t>(to - from);
  events_.erase(from, to);
}

std::size_t SlipMonitor::count(const std::string& kind) const {
  std::size_t n = kind == "stick" ? dropped_stick_
                  : kind == "slip" ? dropped_slip_
                  : kind == "open" ? dropped_open_
                                   : 0;
  for (const SlipEvent& e : events_) n += e.kind == kind;
  return n;
}

std::size_t SlipMonitor::touch_downs() const {
  std::size_t n = dropped_touch_;
  std::string previous = initial_;
  for (std::size_t i = 0; i < events_.size(); ++i) {
    // After the gap the previous event is the last dropped one.
    if (dropped_ > 0 && i == kKeptHead) previous = last_dropped_kind_;
    n += previous == "open" && events_[i].kind != "open";
    previous = events_[i].kind;
  }
  return n;
}

SlipMonitor::State SlipMonitor::state_of(const SlipEvent& e) {
  if (e.kind == "slip") return State::slip;
  if (e.kind == "open") return State::open;
  return State::stick;
}

void SlipMonitor::commit(State kind, double time, double uncertainty) {
  const double last = events_.empty() ? t_first_ : events_.back().time;
  time = std::max(time, last);
  const State previous = events_.empty() ? initial_state_ : state_of(events_.back());
  if (previous == kind) return;
  if (previous == State::stick && (time <= last || time - last < resolution_)) {
    // A stick too short to report: the states on either side of it join.
    if (events_.empty()) {  // at the start: the element is in `kind` from the first step
      initial_state_ = kind;
      initial_ = name(kind);
      return;
    }
    const State before =
        events_.size() >= 2 ? state_of(events_[events_.size() - 2]) : initial_state_;
    if (before == kind) {  // slip, short stick, slip: one slip
      events_.pop_back();
    } else if (before == State::open) {  // touch-down, short stick, then `kind`
      events_.back().kind = name(kind);
    } else {  // slip, short stick, lift-off: the slip lasts until the lift-off
      events_.back() = {name(kind), time, uncertainty};
    }
    return;
  }
  events_.push_back({name(kind), time, uncertainty});
  // Trimmed in blocks of kKeptTail, so each event is moved O(1) times on average; the pops
  // and edits above only reach the last two events, which the tail always holds.
  if (events_.size() >= kKeptHead + 2 * kKeptTail) drop_middle(kKeptTail);
}

std::vector<SlipInterval> SlipMonitor::intervals() const {
  std::vector<SlipInterval> out;
  if (!started_) return out;
  std::string kind = initial_;
  double start = t_first_;
  for (std::size_t i = 0; i < events_.size(); ++i) {
    const SlipEvent& e = events_[i];
    if (dropped_ > 0 && i == kKeptHead) {  // the gap: what happened there is only counted
      out.push_back({kind, start, first_dropped_});
      kind = "dropped";
      start = first_dropped_;
    }
    out.push_back({kind, start, e.time});
    kind = e.kind;
    start = e.time;
  }
  out.push_back({kind, start, std::max(start, t1_)});
  return out;
}

double SlipMonitor::first(const char* kind) const {
  for (const auto& e : events_) {
    if (e.kind == kind) return e.time;
  }
  return -1.0;
}

double SlipMonitor::last_stick() const {
  for (auto it = events_.rbegin(); it != events_.rend(); ++it) {
    if (it->kind == "stick") return it->time;
  }
  return -1.0;
}

}  // namespace stiction::core
