#include "app/event_lines.hpp"

#include <cstdio>

namespace stiction::app {
namespace {

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

std::string first_of(const nlohmann::ordered_json& entry, const char* key, const char* what,
                     const char* never, const nlohmann::ordered_json* error) {
  const auto it = entry.find(key);
  if (it == entry.end() || !it->is_number()) return never;
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "first %s at t = %.7g s", what, it->get<double>());
  std::string text = buffer;
  if (error != nullptr) {
    std::snprintf(buffer, sizeof buffer, " (+- %.1g s)", error->get<double>());
    text += buffer;
  }
  return text;
}

const nlohmann::ordered_json* error_of_first(const nlohmann::ordered_json& accuracy,
                                             const std::string& element,
                                             const nlohmann::ordered_json& entry, const char* key,
                                             const char* kind) {
  const auto it = entry.find(key);
  if (it == entry.end() || !it->is_number()) return nullptr;
  return error_of(accuracy, element, kind, it->get<double>());
}

}  // namespace

std::vector<std::string> event_lines(const nlohmann::ordered_json& events,
                                     const nlohmann::ordered_json& accuracy) {
  std::vector<std::string> lines;
  for (const auto& [element, entry] : events.items()) {
    std::string line = element + ": " +
                       first_of(entry, "first_stick", "stick", "never sticks",
                                error_of_first(accuracy, element, entry, "first_stick", "stick")) +
                       ", " +
                       first_of(entry, "first_slip", "slip", "never slips",
                                error_of_first(accuracy, element, entry, "first_slip", "slip"));
    int sticks = 0, slips = 0, touch_downs = 0;
    if (entry.contains("events")) {
      for (const auto& e : entry["events"]) {
        const std::string kind = e.value("kind", "");
        sticks += kind == "stick";
        slips += kind == "slip";
        touch_downs += e.value("touch_down", false);
      }
    }
    std::string counts = std::to_string(sticks) + (sticks == 1 ? " stick, " : " sticks, ") +
                         std::to_string(slips) + (slips == 1 ? " slip" : " slips");
    if (touch_downs > 0) {
      counts +=
          ", " + std::to_string(touch_downs) + (touch_downs == 1 ? " touch-down" : " touch-downs");
    }
    const std::string initial = entry.value("initial", "");
    if (!initial.empty()) counts = "starts " + initial + "; " + counts;
    lines.push_back(line + " (" + counts + ")");
  }
  return lines;
}

}  // namespace stiction::app
