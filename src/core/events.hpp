// Stick/slip events of a contact or joint, detected at every integration step from its slip
// velocity (and, for contacts, whether the normal force is zero).
//
// The model: an element is at every moment in one state, `stick` (slip speed at or below the
// threshold, or held by its friction law: Kikuuwe friction within its limit), `slip` (above
// it) or, for a contact, `open` (normal force zero: nothing to stick or slip on). Its events are
// the moments it changes state, so they are time-ordered and never two of one kind in a row; an
// `open` event is a lift-off, the `stick` or `slip` event after it a touch-down. The state at t = 0
// is `initial_state()`, not an event.
//
// Times. A state change is seen at the end of the step in which the speed crosses the
// threshold; the threshold biases that moment (the speed is not zero yet when it falls
// under the threshold, and already nonzero when it rises over it). Both directions get the
// same correction: the speed near the crossing is fitted by s = c |t - t0|^p from the last
// (stick) or first (slip) three sliding steps, p in [1, 3] from the ratio of the first two
// derivatives (p = 1: constant deceleration, a sphere sliding to rolling; p = 2: a force
// ramped through the friction limit, a torque ramp), and t0 is the event time. The fit is
// used only where the speed follows it across the crossing step (a drop faster than the fit,
// an impact, keeps the threshold crossing), and t0 always lies between the neighbouring
// events: a stick time past the end of its step waits until a step reaches it with the
// element still stuck (else the crossing is used), a slip onset is never earlier than the
// previous event. A reversal of the slip direction between two sliding steps is passing
// through zero, not a stick. Touch-down and lift-off are placed where the contact's closure
// (core::NormalContact::contact_closure, continuous, > 0 while pressed) crosses zero within
// the step, interpolated linearly between the step's ends (the contact force already acts in
// the landing step's later stages: the paper's sphere lands 1.6e-7 s late at 1e-4 s, generated
// drops within 0.03 steps); without a closure on both sides, at the end of the first step
// with the new contact state.
//
// A creep is a stick (issue 35): an element whose law has released it (saturated) while its
// speed stays below the threshold, because other elements hold the body, is stuck; its onset
// is where its speed starts rising to pass the threshold, not the release. The law's bracket
// places the onset only when the speed rose from the release (observe and settle_pending_slip
// say how that is told); a creep's onset lies in the step after its last calm step (one whose
// speed did not start rising). Where the law held the element in its stuck stretch, the onset
// fit is made to the speed above the level it rose from (at the last held step, or for a
// creep at its last calm step), not from zero: a stuck or creeping element moves.
//
// Resolution: a stick shorter than `resolution` (default one step), or of zero length, is not
// reported: the slip (or the touch-down) around it continues.
//
// Bound (issue 25): an element that chatters for a long run would keep millions of events
// (400 a second for 1000 s: a 96 MB summary). The monitor keeps the first kKeptHead and the
// last kKeptTail events and counts the rest by kind: its memory is constant in the duration.
// The events in between are "dropped": intervals() covers them with one interval of kind
// "dropped", from the first dropped event to the first event kept after them.
#pragma once

#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"

namespace stiction::core {

struct SlipEvent {
  std::string kind;  // "stick", "slip" or "open"
  double time = 0.0;
  // How precisely `time` was located (s): the width of the interval it was known to lie in
  // from how it was found, where a fit that converges with the step did not place it. Not
  // in summary.json (the services read it from here).
  //   - an onset placed in (or clamped to) the law's bracket, between the last step the law
  //     held the element and the first it released it: the bracket's width (one step,
  //     typically);
  //   - a creep's onset, placed in the step after its last calm step (the speed started
  //     rising in it): that step; a fit past that step is kept, and carries one step (a
  //     fit converges with the step, which a companion run measures);
  //   - a time taken at a step's end (touch-down, lift-off without a closure on both sides,
  //     a slip seen already above the
  //     threshold), a threshold crossing interpolated in its step (the fit rejected), a
  //     fitted zero clamped to its step's start: that step (the time since the previous
  //     observation);
  //   - a time from the zero fit (fit_zero), within its bounds, or a touch-down or lift-off
  //     interpolated on the closure: 0. Zero is not "exact": a fit is as good as the speed
  //     follows it, which a companion run at half the step measures.
  double uncertainty = 0.0;
};

// One stretch of a single state, from one event (or t = 0) to the next (or the end).
struct SlipInterval {
  std::string kind;
  double start = 0.0;
  double end = 0.0;
  double duration() const { return end - start; }
};

class SlipMonitor {
 public:
  static constexpr std::size_t kKeptHead = 500;  // the first events, kept
  static constexpr std::size_t kKeptTail = 500;  // the last events, kept
  // Steps after the law's release within which a speed not rising (or the fitted zero) is
  // still the release's own onset; later, it shows a creep (events.cpp).
  static constexpr int kCreepSteps = 3;

  explicit SlipMonitor(double threshold, double resolution = 0.0)
      : threshold_(threshold), resolution_(resolution) {}
  // What the element's friction law says at a step, where it was asked (Kikuuwe friction:
  // held = within its limit, regime 1; released = saturated).
  enum class Law { unknown, held, released };
  // The state at step end t: slip velocity, whether the contact is open, and the law. Held
  // by its law, an element sticks even above the threshold (a stuck contact's spring
  // vibrating); a slip onset lies between the last step the law held it and the first it
  // released it, where both are known. `closure`: the contact's contact_closure (NaN: none).
  void observe(double t, const Vec3& slip, bool open = false, Law law = Law::unknown,
               double closure = std::numeric_limits<double>::quiet_NaN());
  // Whether the element is stuck as of the last observation (the law is worth asking then).
  bool sticking() const { return started_ && state_ == State::stick; }
  // Settles what still waits for later steps (at the end of a run); observe() may go on.
  void finish();

  double threshold() const { return threshold_; }
  double resolution() const { return resolution_; }
  // The kept events: all of them, or the first kKeptHead and the last kKeptTail (after
  // finish(); during the run up to kKeptTail more, trimmed in blocks).
  const std::vector<SlipEvent>& events() const { return events_; }
  // Events not kept (between the head and the tail), and all events by kind.
  std::size_t dropped() const { return dropped_; }
  std::size_t total() const { return dropped_ + events_.size(); }
  // Count of all events of a kind ("stick", "slip", "open"), kept or dropped, and of the
  // touch-downs (a stick or slip right after an open).
  std::size_t count(const std::string& kind) const;
  std::size_t touch_downs() const;
  // Times of the first and the last dropped event (meaningful when dropped() > 0).
  double first_dropped() const { return first_dropped_; }
  double last_dropped() const { return last_dropped_; }
  // The kind of the last dropped event, which precedes the first kept one after the gap.
  const std::string& last_dropped_kind() const { return last_dropped_kind_; }
  // State at the first observation ("stick", "slip" or "open"; empty before any).
  const std::string& initial_state() const { return initial_; }
  // The states from t = 0 to the last observation, each with its duration.
  std::vector<SlipInterval> intervals() const;
  // First stick event (kept for compatibility), or a negative value if none.
  double stick_time() const { return first("stick"); }
  double first_slip() const { return first("slip"); }
  double last_stick() const;

 private:
  struct Sample {
    double t = 0.0;
    double s = 0.0;
  };
  enum class State { stick, slip, open };
  static const char* name(State s);
  // The time of a touch-down or lift-off seen at step end t (closure `closure`), and its
  // uncertainty: interpolated where the closure changed sign, else t and the step.
  std::pair<double, double> contact_change(double t, double closure) const;
  static State state_of(const SlipEvent& e);
  double first(const char* kind) const;
  // Appends an event, applying the order and the resolution (drops short sticks);
  // `uncertainty` as SlipEvent's.
  void commit(State kind, double time, double uncertainty);
  // Drops the events between the head and the last `tail` events, counting them.
  void drop_middle(std::size_t tail);
  void settle_pending_stick(bool reached);
  void settle_pending_slip();
  // Zero time t0 of s = c |t - t0|^p fitted to the samples; `growing`: the speed rises away
  // from t0 (slip onset, fit at the first sample) or falls toward it (stick, at the last).
  // Returns false when the samples do not fit such a curve.
  static bool fit_zero(std::span<const Sample> samples, bool growing, double& t0, double& p);

  double threshold_;
  double resolution_;
  bool started_ = false;
  State state_ = State::stick;          // at the last observation
  State initial_state_ = State::stick;  // at the first, after dropping a short first stick
  std::string initial_;
  double t_first_ = 0.0;
  double t1_ = 0.0, s1_ = 0.0;  // the previous observation
  double rise1_ = 0.0;          // its speed's rise over the observation before it
  Vec3 v1_ = Vec3::Zero();
  double closure1_ = std::numeric_limits<double>::quiet_NaN();  // its contact closure
  std::vector<Sample> sliding_;  // the last (up to 3) samples of the current slip

  bool stick_pending_ = false;  // a stick whose fitted time lies past the last step
  double stick_raw_ = 0.0, stick_fit_ = 0.0;
  double stick_step_ = 0.0;    // the step of stick_raw_'s crossing
  bool slip_pending_ = false;  // a slip onset waiting for its first sliding samples
  double slip_raw_ = 0.0, slip_before_t_ = 0.0;
  double last_held_ = -1.0;      // last step the law held it while stuck (< 0: none)
  double held_speed_ = 0.0;      // the speed there
  double first_release_ = -1.0;  // first step after that the law released it (< 0: none)
  int since_release_ = 0;        // observations since first_release_
  bool crept_ = false;           // a creep seen more than kCreepSteps after the release
  bool onset_crept_ = false;     // crept_ when the pending onset crossed the threshold
  double onset_low_ = -1.0, onset_high_ = -1.0;  // the pending onset's bounds (< 0: none)
  // Last step, while stuck, whose speed was calm (did not start to rise: a relative rate
  // below kCalmRate, or a rise smaller than the step before's; < 0: none).
  double calm_ = -1.0;
  double calm_end_ = -1.0;   // the observation after calm_ (the speed rose there)
  double calm_speed_ = 0.0;  // the speed at calm_
  std::vector<Sample> onset_;

  std::vector<SlipEvent> events_;
  std::size_t dropped_ = 0;
  std::size_t dropped_stick_ = 0, dropped_slip_ = 0, dropped_open_ = 0, dropped_touch_ = 0;
  double first_dropped_ = -1.0, last_dropped_ = -1.0;
  std::string last_dropped_kind_;
};

}  // namespace stiction::core
