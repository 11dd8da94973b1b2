// Which of a run's events a figure marks, and which of those it labels (issue 21).
//
// A run has many events: a sphere that lands sliding and then rolls on a stiff contact
// touches down some 70 times; an arm that settles sticks and slips a few times before its
// final stop. A figure labels the events that carry its story at their marks and draws the
// rest as unlabelled ticks. The IMPORTANT events, labelled by default, are, per element:
//   - its first stick (the first stick that is not a touch-down);
//   - its final stop: its last stick, after which it stays stuck to the end of the run
//     (labelled "stop", unless it is also the first stick);
//   - a slip onset ("break-away") from the stick it starts in or from its first stick, unless
//     that slip ends in a lift-off (the element leaving the surface, as in a bounce); the
//     re-sticks after the first stick and the slips that end them (an element settling in
//     short stick-slips before its stop) are ticks, so the labels bracket the labelled
//     stick intervals;
// and every body-level event (a body with several contact points): "tip", "lift_off",
// "land", a "slide" onset from a stick, the body's first stick and final stop. A contact
// point that belongs to a body with body-level events is told by its body: its own events
// are ticks by default. Touch-downs (the stick or slip after a lift-off) and re-sticks
// between them are ticks.
//
// Selectors name events in a [[plots]] `events` or `labels` list:
//   "<element>"              every event of an element or body ("ground", "arm", "box"), or
//                            of one point of a contact with several ("floor.0")
//   "<element>.<kind>"       every event of a kind: stick, slip, slide, lift_off, land, tip,
//                            partial_slip (a body: some touching points slip; a tick)
//   "<element>.first_stick"  the first stick (above)      "<element>.final_stop"  the stop
//   "<element>.touch_down"   every touch-down             "<element>.break_away"  slip onsets
//   "<element>.<kind>_time"  the first event of a kind, touch-down or not ("ground.stick_time",
//                            summary.json's stick_time)
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace stiction::plot {

// An event of a run, as the run reports it.
struct PlotEvent {
  std::string element;  // a contact or joint; for a body-level event, the body's name
  // An element's "stick", "slip" or "open" (a lift-off; not marked, but it makes the next
  // stick or slip a touch-down); a body's "slide", "stick", "lift_off", "land" or "tip".
  std::string kind;
  double time = 0.0;
  // A touch-down that no "open" event before it shows: the element's first contact when it
  // starts open (core::SlipMonitor::initial_state() == "open").
  bool touch_down = false;
  bool body_level = false;  // an event of a body as a whole (element = the body's name)
  // For a contact point's event: the body it belongs to. When that body has body-level
  // events, they tell the story and this contact's events are not important.
  std::string body{};
};

// What an event is within its element's history.
struct EventRoles {
  bool touch_down = false;     // the first stick or slip after a lift-off (or a start in the air)
  bool first_stick = false;    // the element's first stick that is not a touch-down
  bool final_stop = false;     // its last stick, with no event of the element after it
  bool break_away = false;     // a slip or slide from the first (or initial) stick, see above
  bool first_of_kind = false;  // the element's first event of this kind (for "<kind>_time")
  bool important = false;      // labelled by default (see the top of this file)
};

struct ClassifiedEvent {
  PlotEvent event;
  EventRoles roles;
};

// The events that can be marked (an element's stick and slip, every body-level kind), each
// with its roles, in time order (ties keep the input order). "open" events and non-finite
// times are used for the roles and then dropped.
std::vector<ClassifiedEvent> classify_events(const std::vector<PlotEvent>& events);

// The word for an event in a label: "stick", "stop" (a final stop that is not the first
// stick), "slip", "touch-down", "slide", "lift-off", "land", "tip".
std::string event_word(const ClassifiedEvent& event);
// "stick 0.5843 s"; "ground stick 0.5843 s" with `with_element` (figures showing the events
// of several elements). Times by the number rule (text::significant, kLabelTimeDigits).
std::string event_label(const ClassifiedEvent& event, bool with_element);

// A parsed selector ("ground.first_stick": element "ground", what "first_stick").
struct EventSelector {
  std::string element;
  std::string what;  // empty: every event of the element
};
// Parses a selector; nullopt with `why` set when it is not one (an unknown kind after the
// element: "ground.stik"). The element is not checked here (read_plot_specs checks it
// against the run's components).
std::optional<EventSelector> parse_event_selector(const std::string& text, std::string& why);
bool selects(const EventSelector& selector, const ClassifiedEvent& event);

// The event kinds and roles a selector may name after the element, for messages.
const std::vector<std::string>& selector_words();

}  // namespace stiction::plot
