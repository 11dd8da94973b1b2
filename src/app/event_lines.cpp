#include "app/event_lines.hpp"

#include "text/number_text.hpp"

namespace stiction::app {
namespace {

std::string time_text(double t) {
  return "t = " + text::significant(t, text::kEventTimeDigits) + " s";
}

// The estimated error of the element's event of this kind at this time, if any.
const nlohmann::ordered_json* error_of(const nlohmann::ordered_json& accuracy,
                                       const std::string& element, const char* kind, double time) {
  if (!accuracy.is_object()) return nullptr;
  const auto events = accuracy.find("events");
  if (events == accuracy.end() || !events->is_object()) return nullptr;
  const auto list = events->find(element);
  if (list == events->end() || !list->is_array()) return nullptr;
  for (const auto& e : *list) {
    if (e.value("kind", "") == kind && e.value("time", -1.0) == time) {
      const auto error = e.find("error");
      return error != e.end() && error->is_number() ? &*error : nullptr;
    }
  }
  return nullptr;
}

// "first stick at t = ... s (+- ... s)" from the entry's `key`; `from_start` ("sticks from
// t = 0") when the element had no such event, being in that state from the start.
std::string first_of(const nlohmann::ordered_json& entry, const std::string& element,
                     const nlohmann::ordered_json& accuracy, const char* key, const char* kind,
                     const char* from_start) {
  const auto it = entry.find(key);
  if (it == entry.end() || !it->is_number()) return from_start;
  const double t = it->get<double>();
  std::string text = std::string("first ") + kind + " at " + time_text(t);
  if (const nlohmann::ordered_json* error = error_of(accuracy, element, kind, t)) {
    text += " (+- " + text::significant(error->get<double>(), 1) + " s)";
  }
  return text;
}

// "; counts not converged: 56 sticks, 50 at half the step" from accuracy.not_converged
// (docs/accuracy.md): repeated events whose number the step decides.
std::string not_converged(const nlohmann::ordered_json& accuracy, const std::string& element) {
  if (!accuracy.is_object()) return "";
  const auto list = accuracy.find("not_converged");
  if (list == accuracy.end() || !list->is_array()) return "";
  std::string text;
  for (const auto& d : *list) {
    if (d.value("element", "") != element) continue;
    const std::string kind = d.value("kind", "");
    const std::string plural = kind == "open" ? "lift-offs" : kind + "s";
    text += (text.empty() ? "" : "; ") + std::to_string(d.value("run", 0)) + " " + plural +
            " against " + std::to_string(d.value("companion", 0)) + " in the companion";
  }
  return text.empty() ? "" : "; counts not converged: " + text;
}

bool has_interval(const nlohmann::ordered_json& entry, const char* kind) {
  const auto it = entry.find("intervals");
  if (it == entry.end() || !it->is_array()) return false;
  for (const auto& i : *it) {
    if (i.value("kind", "") == kind) return true;
  }
  return false;
}

std::string counted(int n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// How a body's state reads after its name ("box: sticks throughout", "... lands sliding").
const char* body_state_verb(const std::string& state) {
  if (state == "stick") return "sticks";
  if (state == "slide") return "slides";
  if (state == "partial_slip") return "partly slips";
  if (state == "tip") return "rests on an edge";
  if (state == "open") return "is in the air";
  return "is in an unknown state";
}

const char* body_state_adverb(const std::string& state) {
  if (state == "stick") return "sticking";
  if (state == "slide") return "sliding";
  if (state == "partial_slip") return "partly slipping";
  if (state == "tip") return "on an edge";
  if (state == "open") return "in the air";
  return "in an unknown state";
}

std::string body_event_text(const nlohmann::ordered_json& e) {
  const std::string kind = e.value("kind", "");
  const std::string at = time_text(e.value("time", 0.0));
  if (kind == "tip") return "tips at " + at;
  if (kind == "lift_off") return "lifts off at " + at;
  if (kind == "land")
    return std::string("lands ") + body_state_adverb(e.value("state", "")) + " at " + at;
  if (kind == "partial_slip") return "partly slips at " + at;
  return std::string(body_state_verb(kind)) + " at " + at;
}

}  // namespace

std::vector<std::string> event_lines(const nlohmann::ordered_json& events,
                                     const nlohmann::ordered_json& accuracy) {
  std::vector<std::string> lines;
  for (const auto& [element, entry] : events.items()) {
    // Whether it ever stuck or slipped, from the states that tile the run (the initial one
    // included): a contact that never sticks slides throughout the time it touches.
    const bool stuck = has_interval(entry, "stick"), slipped = has_interval(entry, "slip");
    std::string what;
    if (!stuck && !slipped) {
      what = "never touches";
    } else if (!slipped) {
      what = "sticks throughout";
    } else if (!stuck) {
      what = "slides throughout";
    } else {
      what = first_of(entry, element, accuracy, "first_stick", "stick", "sticks from t = 0") +
             ", " + first_of(entry, element, accuracy, "first_slip", "slip", "slips from t = 0");
    }
    // A law with a static level above the kinetic one (mu_static > mu): where it broke away
    // (the first slip itself, unless that was a touch-down).
    const auto breakaway = entry.find("first_breakaway");
    if (breakaway != entry.end() && breakaway->is_number()) {
      const double t = breakaway->get<double>();
      const std::string level = " (static level " +
                                text::significant(entry.value("static_ratio", 1.0), 3) +
                                "x the kinetic)";
      const std::string first_slip = "first slip at " + time_text(t);
      const auto at = what.find(first_slip);
      if (at != std::string::npos) {
        what.replace(at, first_slip.size(), "breaks away at " + time_text(t));
      } else {
        what += ", breaks away at " + time_text(t);
      }
      what += level;
    }
    int sticks = 0, slips = 0, touch_downs = 0, lift_offs = 0;
    if (entry.contains("event_counts")) {  // all events, kept or not (SlipMonitor's bound)
      const auto& c = entry["event_counts"];
      sticks = c.value("stick", 0);
      slips = c.value("slip", 0);
      lift_offs = c.value("open", 0);
      touch_downs = c.value("touch_down", 0);
    } else if (entry.contains("events")) {
      for (const auto& e : entry["events"]) {
        const std::string kind = e.value("kind", "");
        sticks += kind == "stick";
        slips += kind == "slip";
        lift_offs += kind == "open";
        touch_downs += e.value("touch_down", false);
      }
    }
    std::string counts =
        counted(sticks, "stick", "sticks") + ", " + counted(slips, "slip", "slips");
    if (touch_downs > 0) counts += ", " + counted(touch_downs, "touch-down", "touch-downs");
    if (lift_offs > 0) counts += ", " + counted(lift_offs, "lift-off", "lift-offs");
    const std::string initial = entry.value("initial", "");
    if (!initial.empty()) counts = "starts " + initial + "; " + counts;
    lines.push_back(element + ": " + what + " (" + counts + ")" + not_converged(accuracy, element));
  }
  return lines;
}

std::vector<std::string> body_event_lines(const nlohmann::ordered_json& bodies) {
  std::vector<std::string> lines;
  if (!bodies.is_object()) return lines;
  for (const auto& [body, entry] : bodies.items()) {
    const std::string initial = entry.value("initial", "");
    const auto events = entry.find("events");
    const std::size_t n = events != entry.end() && events->is_array() ? events->size() : 0;
    std::string line = body + ": " + body_state_verb(initial);
    if (n == 0) {
      lines.push_back(line + " throughout");
      continue;
    }
    line = body + ": starts " + body_state_adverb(initial);
    for (std::size_t i = 0; i < n && i < static_cast<std::size_t>(kBodyEventsPrinted); ++i)
      line += ", " + body_event_text((*events)[i]);
    if (n > static_cast<std::size_t>(kBodyEventsPrinted)) {
      line += ", ... (" + std::to_string(n) + " events in summary.json)";
    }
    lines.push_back(line);
  }
  return lines;
}

}  // namespace stiction::app
