#include "plot/event_selection.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "text/number_text.hpp"

namespace stiction::plot {
namespace {

// The kinds a figure marks; "open" only shapes the roles of the events after it.
const std::vector<std::string>& markable_kinds() {
  // A body's "partial_slip" (some touching points slip, others stick) is marked as a tick: it
  // is the way into a slide or a tip, which are labelled.
  static const std::vector<std::string> kinds{"stick", "slip", "slide",       "lift_off",
                                              "land",  "tip",  "partial_slip"};
  return kinds;
}

bool is_markable(const std::string& kind) {
  const auto& kinds = markable_kinds();
  return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
}

bool leaves_surface(const std::string& kind) { return kind == "open" || kind == "lift_off"; }
bool is_motion(const std::string& kind) { return kind == "slip" || kind == "slide"; }

// The roles of one element's (or one body's) events, given in time order.
void assign_roles(std::vector<ClassifiedEvent*>& history, bool told_by_body) {
  bool first_stick_seen = false;
  std::set<std::string> kinds_seen;
  for (std::size_t i = 0; i < history.size(); ++i) {
    ClassifiedEvent& c = *history[i];
    const PlotEvent& e = c.event;
    const std::string previous = i > 0 ? history[i - 1]->event.kind : std::string();
    const std::string next = i + 1 < history.size() ? history[i + 1]->event.kind : std::string();
    EventRoles& r = c.roles;
    r.first_of_kind = kinds_seen.insert(e.kind).second;
    r.touch_down = e.touch_down || leaves_surface(previous);
    if (e.kind == "stick") {
      r.first_stick = !r.touch_down && !first_stick_seen;
      first_stick_seen = first_stick_seen || r.first_stick;
      r.final_stop = i + 1 == history.size();
    } else if (is_motion(e.kind)) {
      // From the stick the element starts in (a first slip differs from the initial state,
      // so it was stuck) or from its first stick, and not straight into a lift-off (a contact
      // leaving the ground while slipping bounces). The labels bracket the labelled stick
      // intervals; later re-sticks and the slips ending them, the chatter of an element
      // settling (two_link's joint 1 before its stop), are ticks.
      const bool from_labelled_stick = previous.empty() || previous == "tip" ||
                                       (previous == "stick" && history[i - 1]->roles.first_stick);
      r.break_away = !r.touch_down && from_labelled_stick && !leaves_surface(next);
    }
    if (e.body_level) {
      r.important = e.kind == "tip" || e.kind == "lift_off" || e.kind == "land" || r.first_stick ||
                    r.final_stop || r.break_away;
    } else {
      r.important = !told_by_body && (r.first_stick || r.final_stop || r.break_away);
    }
  }
}

}  // namespace

std::vector<ClassifiedEvent> classify_events(const std::vector<PlotEvent>& events) {
  std::vector<ClassifiedEvent> all;
  for (const PlotEvent& e : events) {
    if (std::isfinite(e.time)) all.push_back({e, {}});
  }
  std::stable_sort(all.begin(), all.end(), [](const ClassifiedEvent& a, const ClassifiedEvent& b) {
    return a.event.time < b.event.time;
  });
  std::set<std::string> bodies_with_events;
  for (const ClassifiedEvent& c : all) {
    if (c.event.body_level) bodies_with_events.insert(c.event.element);
  }
  // One history per element, and a body's own events apart from a contact of the same name.
  std::map<std::pair<bool, std::string>, std::vector<ClassifiedEvent*>> histories;
  for (ClassifiedEvent& c : all) histories[{c.event.body_level, c.event.element}].push_back(&c);
  for (auto& [key, history] : histories) {
    const PlotEvent& e = history.front()->event;
    assign_roles(history, !e.body_level && bodies_with_events.count(e.body) > 0);
  }
  std::erase_if(all, [](const ClassifiedEvent& c) { return !is_markable(c.event.kind); });
  return all;
}

std::string event_word(const ClassifiedEvent& event) {
  const std::string& kind = event.event.kind;
  if (!event.event.body_level && event.roles.touch_down && (kind == "stick" || kind == "slip")) {
    return "touch-down";
  }
  if (kind == "stick" && event.roles.final_stop && !event.roles.first_stick) return "stop";
  if (kind == "lift_off") return "lift-off";
  if (kind == "partial_slip") return "partial slip";
  return kind;
}

std::string event_label(const ClassifiedEvent& event, bool with_element) {
  std::string label = with_element && !event.event.element.empty() ? event.event.element + " " : "";
  return label + event_word(event) + " " +
         text::significant(event.event.time, text::kLabelTimeDigits) + " s";
}

const std::vector<std::string>& selector_words() {
  static const std::vector<std::string> words = [] {
    std::vector<std::string> w = markable_kinds();
    for (const char* role : {"first_stick", "final_stop", "touch_down", "break_away"}) {
      w.push_back(role);
    }
    for (const std::string& kind : markable_kinds()) w.push_back(kind + "_time");
    return w;
  }();
  return words;
}

std::optional<EventSelector> parse_event_selector(const std::string& text, std::string& why) {
  std::size_t dot = text.rfind('.');
  // "floor.1": the whole text names one contact point of a contact with several.
  if (dot != std::string::npos && dot + 1 < text.size() &&
      text.find_first_not_of("0123456789", dot + 1) == std::string::npos) {
    dot = std::string::npos;
  }
  EventSelector selector{text.substr(0, dot), dot == std::string::npos ? "" : text.substr(dot + 1)};
  if (selector.element.empty()) {
    why = "'" + text + "' names no element (expected \"ELEMENT\" or \"ELEMENT.EVENT\")";
    return std::nullopt;
  }
  const auto& words = selector_words();
  if (dot != std::string::npos &&
      std::find(words.begin(), words.end(), selector.what) == words.end()) {
    std::string list;
    for (const std::string& w : words) list += (list.empty() ? "" : ", ") + w;
    why = "'" + text + "': unknown event '" + selector.what + "' (expected one of " + list + ")";
    return std::nullopt;
  }
  return selector;
}

bool selects(const EventSelector& selector, const ClassifiedEvent& event) {
  const PlotEvent& e = event.event;
  const EventRoles& r = event.roles;
  if (selector.element != e.element) return false;
  const std::string& what = selector.what;
  if (what.empty() || what == e.kind) return true;
  if (what == "first_stick") return r.first_stick;
  if (what == "final_stop") return r.final_stop;
  if (what == "touch_down") return r.touch_down;
  if (what == "break_away") return r.break_away;
  return r.first_of_kind && what == e.kind + "_time";
}

}  // namespace stiction::plot
