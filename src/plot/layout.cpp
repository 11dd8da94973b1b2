#include "plot/layout.hpp"

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
    if (a.role == TextRole::event_label || a.role == TextRole::title) {
      for (const Rect& l : layout.legends) {
        if (shrunk(a.box).overlaps(l)) problems.push_back("over a legend: " + describe(a));
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
