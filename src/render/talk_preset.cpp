#include "render/talk_preset.hpp"

#include <algorithm>

namespace stiction::render {
namespace {

// The signal NAME of the first column "NAME.<suffix>" (suffix ".slip.x": "C.slip"), or "".
std::string first_with(const std::vector<std::string>& columns, const std::string& suffix,
                       const std::string& signal_suffix) {
  for (const std::string& c : columns) {
    if (c.size() > suffix.size() &&
        c.compare(c.size() - suffix.size(), suffix.size(), suffix) == 0) {
      return c.substr(0, c.size() - suffix.size()) + signal_suffix;
    }
  }
  return "";
}

}  // namespace

const std::vector<std::string>& look_preset_names() {
  static const std::vector<std::string> names{"talk"};
  return names;
}

bool is_look_preset(const std::string& name) {
  const auto& names = look_preset_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

InsetSettings talk_inset(const std::vector<std::string>& columns) {
  InsetSettings inset;
  auto add = [&](const std::string& signal, const char* label, const char* unit) {
    if (signal.empty()) return;
    inset.signals.push_back(signal);
    inset.labels.push_back(label);
    inset.units.push_back(unit);
  };
  // The slip speed is what the stick/slip events are judged on; the body's speed shows what
  // the slip does to the motion.
  add(first_with(columns, ".slip.x", ".slip"), "slip speed", "m/s");
  add(first_with(columns, ".v.x", ".v"), "speed", "m/s");
  if (inset.signals.empty())
    add(first_with(columns, ".omega.0", ".omega.0"), "joint speed", "rad/s");
  return inset;
}

void apply_talk_preset(RenderSettings& s, const std::vector<std::string>& columns) {
  s.look = "talk";
  s.width = 1280;
  s.height = 720;
  s.slow_motion_around_events = 0.1;
  s.slowed_events = 3;
  s.overlay.layers.badges = true;
  s.overlay.layers.forces = true;
  s.overlay.trail = true;
  s.inset = talk_inset(columns);
}

}  // namespace stiction::render
