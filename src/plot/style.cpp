#include "plot/style.hpp"

namespace stiction::plot {

Stroke make_stroke(const LineStyle& style, double s) {
  Stroke stroke;
  stroke.colour = style.colour;
  stroke.width = style.width * s;
  for (double d : style.dash) stroke.dash.push_back(d * s);
  return stroke;
}

LineStyle reference_style() { return LineStyle{kEvent, {5, 4}, 2.0}; }

Stroke event_stroke(const std::string& kind, double s) {
  if (kind == "slip") return Stroke{kSlipEvent, 2.0 * s, {14 * s, 5 * s, 2 * s, 5 * s}};
  return Stroke{kEvent, 2.0 * s, {9 * s, 6 * s}};
}

image::Rgba event_colour(const std::string& kind) { return kind == "slip" ? kSlipEvent : kEvent; }

LineStyle series_style(int index) {
  static const std::array<std::vector<double>, 5> dashes{{
      {},                   // solid
      {13, 7},              // dashed
      {0, 7},               // dotted (round dots)
      {16, 6, 0, 6},        // dash-dot
      {24, 6, 0, 6, 0, 6},  // long dash, two dots
  }};
  const int i = std::max(0, index);
  LineStyle style;
  style.colour = kPalette[i % kPalette.size()];
  style.dash = dashes[i % dashes.size()];
  style.width = i % dashes.size() == 2 ? 4.2 : 3.2;  // dots need more ink to read as a line
  return style;
}

}  // namespace stiction::plot
