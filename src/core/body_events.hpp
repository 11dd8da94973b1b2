// Events of a body as a whole: for a body with several contact points (a box's eight corners;
// the points of one or several contacts on the same body), what the body does, derived from
// its points' own histories (SlipMonitor, events.hpp: observed at every step, event times
// corrected for the threshold's bias).
//
// At every moment the body is in one state, from the states of its contact points:
//   - `open`: every point is open (the body is in the air);
//   - `tip`: some points touch and they span no area: they are one point or lie on one line
//     (a corner, an edge of a box), while a point of the body off that line is open. The body
//     rests on that edge or corner and can turn about it; every point on the far side of the
//     edge, away from the touching ones, is in the air. Whether the edge's own points stick or
//     slip does not change the state;
//   - otherwise, with the touching points spanning an area: `stick` (every touching point
//     sticks), `slide` (every touching point slips), `partial_slip` (some stick, some slip: a
//     body turning about a stuck point, or breaking loose one point after the other).
// Its events are the moments the state changes, named after the state entered (`stick`,
// `slide`, `partial_slip`, `tip`), except `lift_off` (entering `open`) and `land` (leaving
// it, into the state in the event's `state`). So they are time-ordered, never two of one
// kind in a row (a land's state excepted), and the state at t = 0 is `initial`, not an event.
// Times are those of the point events that change the state (several at one time count as
// one change): a slide comes when the last touching point starts to slip, a tip when the last
// point off the edge opens, a land when the first point touches down. A state that lasts no
// longer than the points' resolution (one step by default; SlipMonitor) is not reported, as
// a short stick is not: each point's change is seen at a step, so corners that break loose
// together may be one step apart. Its time goes to the state before it, except after `open`
// (a landing on a corner, then at once on the face, lands at the first touch).
//
// The geometry is the points' positions in the body frame (for a contact with a radius, the
// contact point at t = 0: the body point moved by the radius along the normal), compared
// within 1e-6 of the body's point spread.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/events.hpp"
#include "core/types.hpp"

namespace stiction::core {

struct SlipHistory;

// `dropped`: some point's events there were not kept (SlipMonitor's bound), so the body's
// state is not known; no event marks entering or leaving it.
enum class BodyState { open, stick, slide, partial_slip, tip, dropped };
const char* body_state_name(BodyState state);

struct BodyEvent {
  std::string kind;  // "stick", "slide", "partial_slip", "tip", "lift_off" or "land"
  double time = 0.0;
  std::string state;  // the state entered (for `land`, the one it lands in)
  // How precisely `time` was located (s), as SlipEvent::uncertainty: that of the point
  // event(s) that changed the body's state at `time`, the largest of them.
  double uncertainty = 0.0;
};

struct BodyEventHistory {
  std::string body;
  std::vector<std::string> points;  // its contact elements, in the network's order
  std::string initial;              // the state at t = 0
  std::vector<BodyEvent> events;
  std::vector<SlipInterval> intervals;  // the states from t = 0 to the end, tiling the run
  // Time of the first event of this kind, or a negative value if none.
  double first(std::string_view kind) const;
};

// The body's state from its points: `points` in the body frame, `states` the points' element
// states ("stick", "slip", "open" or "dropped"), one per point; `tolerance` the distance below
// which a point counts as on a line or at a point (body_events: 1e-6 of the points' extent).
// `rolling`: some points travel over the body (a cylinder's rim points): their place at t = 0
// says nothing about an edge, so the body is never in `tip`.
BodyState body_state(const std::vector<Vec3>& points, const std::vector<std::string>& states,
                     double tolerance, bool rolling = false);

// One history per body with at least two contact points (SlipHistory::body set; a contact
// between two bodies counts for both, SlipHistory::other_body), in the order of their first
// point.
std::vector<BodyEventHistory> body_events(const std::vector<SlipHistory>& histories);

}  // namespace stiction::core
