#include "plot/series_strokes.hpp"

#include <algorithm>

#include "plot/style.hpp"

namespace stiction::plot {

std::vector<Point> to_pixels(const Series& series, const Axis& x, const Axis& y) {
  const std::size_t n = std::min(series.x.size(), series.y.size());
  std::vector<Point> points;
  points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) points.push_back({x.map(series.x[i]), y.map(series.y[i])});
  return points;
}

void draw_series(Painter& painter, const Panel& panel,
                 const std::vector<std::vector<Point>>& pixels, const Rect& frame, double line,
                 FigureLayout& layout) {
  painter.clip(frame);
  for (std::size_t i = 0; i < panel.series.size(); ++i) {
    const Series& series = panel.series[i];
    const LineStyle style = series.style ? *series.style : series_style(static_cast<int>(i));
    painter.polyline(pixels[i], make_stroke(style, line));
    layout.series.push_back(series.source.empty() ? series.label : series.source);
  }
  painter.unclip();
}

}  // namespace stiction::plot
