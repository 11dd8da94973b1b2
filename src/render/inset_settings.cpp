#include "render/inset_settings.hpp"

#include <algorithm>

#include "render/scene_view.hpp"

namespace stiction::render {
namespace {

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

void read_inset(scene::TableReader& r, InsetSettings& s, const std::vector<std::string>& columns) {
  if (r.has("signals")) {
    // Signals given here replace a preset's (talk_preset.hpp) with its labels and units.
    s.labels.clear();
    s.units.clear();
    s.signals = r.strings("signals");
    if (s.signals.empty()) r.fail("signals", "expected at least one signal name");
    if (s.signals.size() > 6) r.fail("signals", "at most 6 signals fit in the inset");
    for (const std::string& signal : s.signals) {
      const bool known =
          columns.empty() || std::any_of(columns.begin(), columns.end(), [&](const std::string& c) {
            return c != "t" && (c == signal || is_axis_of(c, signal));
          });
      if (!known) {
        std::vector<std::string> names;
        for (const auto& c : columns) {
          if (c != "t") names.push_back(c);
        }
        r.fail("signals", "no signal named '" + signal + "' (signals: " + join(names) + ")");
      }
    }
  }
  const auto per_signal = [&](std::string_view key, std::vector<std::string>& into) {
    if (!r.has(key)) return;
    into = r.strings(key);
    if (into.size() != s.signals.size()) {
      r.fail(key, "expected one entry per signal (" + std::to_string(s.signals.size()) + ")");
    }
  };
  per_signal("labels", s.labels);
  per_signal("units", s.units);
  if (r.has("position")) {
    const std::string p = r.string("position", "");
    if (p == "top_left") {
      s.corner = InsetCorner::top_left;
    } else if (p == "top_right") {
      s.corner = InsetCorner::top_right;
    } else if (p == "bottom_left") {
      s.corner = InsetCorner::bottom_left;
    } else if (p == "bottom_right") {
      s.corner = InsetCorner::bottom_right;
    } else {
      r.fail("position", "unknown position '" + p +
                             "' (one of: top_left, top_right, bottom_left, bottom_right)");
    }
  }
  if (r.has("size")) {
    const std::vector<double> size = r.numbers("size");
    if (size.size() != 2) r.fail("size", "expected [width, height]");
    const bool fractions = size[0] > 0.0 && size[0] <= 1.0 && size[1] > 0.0 && size[1] <= 1.0;
    const bool pixels = size[0] >= 200.0 && size[1] >= 150.0 && size[0] <= 7680.0 &&
                        size[1] <= 7680.0 && size[0] == static_cast<double>(long(size[0])) &&
                        size[1] == static_cast<double>(long(size[1]));
    if (!fractions && !pixels) {
      r.fail("size",
             "expected fractions of the frame (both in (0, 1]) or whole pixels (at least "
             "[200, 150])");
    }
    s.width = size[0];
    s.height = size[1];
    s.in_pixels = pixels;
  }
  if (r.has("window")) s.window = r.positive("window", 1.0);
  if (r.has("opacity")) {
    s.opacity = r.number("opacity", s.opacity);
    if (!(s.opacity >= 0.0 && s.opacity <= 1.0)) r.fail("opacity", "must be in 0..1");
  }
  r.finish();
  if (s.signals.empty() && !r.table().empty()) {
    r.fail("signals", "missing: an [inset] needs the signals it plots");
  }
}

}  // namespace stiction::render
