#include "plot/layout.hpp"

#include <algorithm>
#include <sstream>

namespace stiction::plot {
namespace {

std::string describe(const TextBox& t) {
  std::ostringstream out;
  out << '\'' << t.text << "' at [" << t.box.x0 << ", " << t.box.y0 << ", " << t.box.x1 << ", "
      << t.box.y1 << ']';
  return out.str();
}

// Boxes that merely touch (rounding of a pixel) are not an overlap.
Rect shrunk(const Rect& r, double by = 0.5) { return {r.x0 + by, r.y0 + by, r.x1 - by, r.y1 - by}; }

// Whether the segment a-b passes through the rectangle (Liang-Barsky clipping).
bool crosses(Point a, Point b, const Rect& r) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x - r.x0, r.x1 - a.x, a.y - r.y0, r.y1 - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
    } else {
      const double t = q[i] / p[i];
      if (p[i] < 0.0) {
        t0 = std::max(t0, t);
      } else {
        t1 = std::min(t1, t);
      }
    }
  }
  return t0 < t1;
}

}  // namespace

std::vector<std::string> layout_problems(const FigureLayout& layout) {
  std::vector<std::string> problems;
  const Rect image{0.0, 0.0, static_cast<double>(layout.width), static_cast<double>(layout.height)};
  for (std::size_t i = 0; i < layout.texts.size(); ++i) {
    const TextBox& a = layout.texts[i];
    if (!shrunk(a.box).inside(image)) problems.push_back("outside the image: " + describe(a));
    for (std::size_t j = i + 1; j < layout.texts.size(); ++j) {
      const TextBox& b = layout.texts[j];
      if (shrunk(a.box).overlaps(shrunk(b.box))) {
        problems.push_back("overlap: " + describe(a) + " and " + describe(b));
      }
    }
    // A legend's box is filled: over any text but its own entries it would hide that text
    // in a PNG or PDF (drawn in order) and not in an SVG (its text drawn last).
    for (std::size_t l = 0; l < layout.legends.size(); ++l) {
      const bool own = a.role == TextRole::legend_entry && l < layout.legend_panels.size() &&
                       a.panel == layout.legend_panels[l] &&
                       shrunk(a.box).inside(layout.legends[l]);
      if (!own && shrunk(a.box).overlaps(shrunk(layout.legends[l]))) {
        problems.push_back("under legend " + std::to_string(l) + ": " + describe(a));
      }
    }
  }
  for (int p : layout.legends_left_out) {
    problems.push_back("the legend of panel " + std::to_string(p) + " has no room");
  }
  // Leaders from event marks to their labels cross no text (their own label is where they end).
  for (const EventLabelReport& e : layout.event_labels) {
    for (std::size_t k = 1; k < e.leader.size(); ++k) {
      for (std::size_t t = 0; t < layout.texts.size(); ++t) {
        if (static_cast<int>(t) == e.text) continue;
        if (crosses(e.leader[k - 1], e.leader[k], shrunk(layout.texts[t].box, 1.0))) {
          problems.push_back("an event's leader crosses " + describe(layout.texts[t]));
        }
      }
    }
  }
  for (std::size_t i = 0; i < layout.legends.size(); ++i) {
    if (!shrunk(layout.legends[i]).inside(image)) {
      problems.push_back("legend " + std::to_string(i) + " leaves the image");
    }
    for (std::size_t j = i + 1; j < layout.legends.size(); ++j) {
      if (shrunk(layout.legends[i]).overlaps(shrunk(layout.legends[j]))) {
        problems.push_back("legends " + std::to_string(i) + " and " + std::to_string(j) +
                           " overlap");
      }
    }
  }
  return problems;
}

}  // namespace stiction::plot
