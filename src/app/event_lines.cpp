#include "app/event_lines.hpp"

#include <cstdio>

namespace stiction::app {
namespace {

std::string first_of(const nlohmann::ordered_json& entry, const char* key, const char* what,
                     const char* never) {
  const auto it = entry.find(key);
  if (it == entry.end() || !it->is_number()) return never;
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "first %s at t = %.7g s", what, it->get<double>());
  return buffer;
}

}  // namespace

std::vector<std::string> event_lines(const nlohmann::ordered_json& events) {
  std::vector<std::string> lines;
  for (const auto& [element, entry] : events.items()) {
    std::string line = element + ": " + first_of(entry, "first_stick", "stick", "never sticks") +
                       ", " + first_of(entry, "first_slip", "slip", "never slips");
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
