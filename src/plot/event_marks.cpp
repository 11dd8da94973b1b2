#include "plot/event_marks.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace stiction::plot {

EventRows place_event_rows(Painter& painter, const std::vector<EventMarker>& events,
                           const std::vector<std::string>& texts, const Axis& x_axis,
                           const Rect& top_frame, const Metrics& m, double figure_width,
                           double key_width) {
  const double s = m.s;
  const std::size_t event_count = events.size();
  std::vector<std::vector<std::pair<double, double>>> rows(1);
  if (key_width > 0.0)
    rows[0].push_back({figure_width - m.margin() - key_width, figure_width - m.margin()});
  EventRows placed;
  placed.row_of.assign(event_count, -1);
  std::vector<std::size_t> order(event_count);
  for (std::size_t e = 0; e < event_count; ++e) order[e] = e;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return events[a].x < events[b].x; });
  for (std::size_t e : order) {
    const double cx = x_axis.map(events[e].x);
    if (!std::isfinite(cx) || cx < top_frame.x0 - 1 || cx > top_frame.x1 + 1) continue;
    const double w = painter.measure(texts[e], m.event()).width;
    const double a = std::clamp(cx - 0.5 * w, m.margin(), figure_width - m.margin() - w);
    const double b = a + w;
    std::size_t row = 0;
    for (; row < rows.size(); ++row) {
      bool free = true;
      for (auto [u, v] : rows[row]) {
        if (a < v + 16 * s && b > u - 16 * s) free = false;
      }
      if (free) break;
    }
    if (row == rows.size()) {
      if (static_cast<int>(rows.size()) == kMaxEventRows) {
        placed.all = false;
        continue;
      }
      rows.emplace_back();
    }
    rows[row].push_back({a, b});
    placed.row_of[e] = static_cast<int>(row);
  }
  placed.rows = static_cast<int>(event_count == 0 ? 0 : rows.size());
  return placed;
}

void draw_event_lines(Painter& painter, const std::vector<EventMarker>& events, const Axis& x_axis,
                      const Rect& f, bool rug, const Metrics& m) {
  const double s = m.s;
  for (const EventMarker& e : events) {
    const double px = x_axis.map(e.x);
    if (!std::isfinite(px) || px < f.x0 || px > f.x1) continue;
    if (rug) {
      Stroke mark = event_stroke(e.kind, m.line);
      mark.dash.clear();
      const double len = std::min(24 * s, 0.2 * f.height());
      painter.line({px, f.y0}, {px, f.y0 + len}, mark);
      painter.line({px, f.y1 - len}, {px, f.y1}, mark);
    } else {
      painter.line({px, f.y0}, {px, f.y1}, event_stroke(e.kind, m.line));
    }
  }
}

}  // namespace stiction::plot
