#include "plot/style.hpp"

namespace stiction::plot {

Metrics figure_metrics(const Figure& figure, int width, int height) {
  Metrics m;
  if (!figure.print) {
    const double s = std::min(width / 1600.0, height / 1000.0);
    m.s = m.line = s;
    m.title_size = 32 * s;
    m.label_size = 27 * s;
    m.tick_size = 24 * s;
    m.legend_size = 23 * s;
    m.event_size = 22 * s;
    return m;
  }
  const double pixels_per_point = figure.print->dpi / 72.0;
  const double body = figure.print->font_pt * pixels_per_point;
  m.s = body / 24.0;
  m.line = 0.3 * pixels_per_point;
  m.title_size = (figure.print->font_pt + 1.0) * pixels_per_point;
  m.label_size = m.tick_size = m.legend_size = m.event_size = body;
  m.shrinks = false;
  m.px_per_pt = pixels_per_point;
  m.x_tick_spacing = 140.0;
  m.y_title_lines = 4;
  return m;
}

Stroke make_stroke(const LineStyle& style, double line) {
  Stroke stroke;
  stroke.colour = style.colour;
  stroke.width = style.width * line;
  for (double d : style.dash) stroke.dash.push_back(d * line);
  return stroke;
}

LineStyle reference_style() { return LineStyle{kEvent, {5, 4}, 2.0}; }

namespace {

enum class EventClass { stick, slip, other };

EventClass event_class(const std::string& kind) {
  if (kind == "slip" || kind == "slide") return EventClass::slip;
  if (kind == "stick" || kind == "event" || kind.empty()) return EventClass::stick;
  return EventClass::other;
}

}  // namespace

Stroke event_stroke(const std::string& kind, double line) {
  const double u = line;
  switch (event_class(kind)) {
    case EventClass::slip:
      return Stroke{kSlipEvent, 2.0 * u, {14 * u, 5 * u, 2 * u, 5 * u}};
    case EventClass::other:
      return Stroke{kOtherEvent, 2.0 * u, {12 * u, 4 * u, 2 * u, 4 * u, 2 * u, 4 * u}};
    case EventClass::stick:
      break;
  }
  return Stroke{kEvent, 2.0 * u, {9 * u, 6 * u}};
}

image::Rgba event_colour(const std::string& kind) {
  switch (event_class(kind)) {
    case EventClass::slip:
      return kSlipEvent;
    case EventClass::other:
      return kOtherEvent;
    case EventClass::stick:
      break;
  }
  return kEvent;
}

Stroke event_tick_stroke(const std::string& kind, double line) {
  image::Rgba c = event_colour(kind);
  c.a = 150;
  return Stroke{c, 1.6 * line, {}};
}

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
