#include "plot/legend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plot/text_fit.hpp"

namespace stiction::plot {

Legend make_legend(const Panel& panel, Painter& painter, const Metrics& m, double max_width,
                   double max_height) {
  Legend L;
  for (std::size_t i = 0; i < panel.series.size(); ++i) {
    if (!panel.series[i].label.empty()) L.entries.push_back(static_cast<int>(i));
  }
  for (std::size_t k = 0; k < panel.references.size(); ++k) {
    if (!panel.references[k].label.empty()) L.entries.push_back(-1 - static_cast<int>(k));
  }
  if (L.entries.size() < 2 && !(L.entries.size() == 1 && panel.label.empty())) {
    L.entries.clear();  // one series: the axis label already names it
    return L;
  }
  const int n = static_cast<int>(L.entries.size());
  L.pad = 12 * m.s;
  L.sample = 56 * m.s;
  // Shrink the font (to 75%) before adding columns.
  for (L.size = m.legend();; L.size *= 0.9) {
    L.row = 1.45 * L.size;
    const double fixed = L.pad * 1.4;
    const int fit_rows = std::max(1, static_cast<int>((max_height - fixed) / L.row));
    L.columns = (n + fit_rows - 1) / fit_rows;
    if (L.columns == 1 || !m.shrinks || L.size < 0.76 * m.legend()) break;
  }
  L.rows = (n + L.columns - 1) / L.columns;
  const double text_room =
      std::max(40 * m.s, max_width / L.columns - L.pad - L.sample - 12 * m.s - L.pad);
  double text_width = 0.0;
  for (int i : L.entries) {
    const std::string& label = i >= 0 ? panel.series[i].label : panel.references[-1 - i].label;
    L.labels.push_back(fit(painter, label, L.size, text_room));
    text_width = std::max(text_width, painter.measure(L.labels.back(), L.size).width);
  }
  L.column = L.sample + 12 * m.s + text_width + L.pad;
  L.width = L.pad + L.columns * L.column;
  L.height = L.pad * 0.8 + L.row * L.rows + L.pad * 0.6;
  return L;
}

double occupancy(const std::vector<std::vector<Point>>& lines, const Rect& r) {
  double count = 0.0;
  for (const auto& pts : lines) {
    for (std::size_t i = 1; i < pts.size(); ++i) {
      const Point a = pts[i - 1], b = pts[i];
      if (!std::isfinite(a.x + a.y + b.x + b.y)) continue;
      if (std::max(a.x, b.x) < r.x0 || std::min(a.x, b.x) > r.x1 || std::max(a.y, b.y) < r.y0 ||
          std::min(a.y, b.y) > r.y1) {
        continue;
      }
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      const int steps = std::max(1, static_cast<int>(len / 2.0));
      for (int k = 0; k < steps; ++k) {
        const double t = static_cast<double>(k) / steps;
        const double px = a.x + t * (b.x - a.x), py = a.y + t * (b.y - a.y);
        if (px >= r.x0 && px <= r.x1 && py >= r.y0 && py <= r.y1) count += 1.0;
      }
    }
  }
  return count;
}

std::array<Rect, 6> legend_places(const Rect& f, const Legend& L, double s) {
  const double inset = 14 * s;
  const double cx = 0.5 * (f.x0 + f.x1 - L.width);
  return {{
      {f.x1 - inset - L.width, f.y0 + inset, f.x1 - inset, f.y0 + inset + L.height},
      {f.x0 + inset, f.y0 + inset, f.x0 + inset + L.width, f.y0 + inset + L.height},
      {f.x1 - inset - L.width, f.y1 - inset - L.height, f.x1 - inset, f.y1 - inset},
      {f.x0 + inset, f.y1 - inset - L.height, f.x0 + inset + L.width, f.y1 - inset},
      {cx, f.y0 + inset, cx + L.width, f.y0 + inset + L.height},
      {cx, f.y1 - inset - L.height, cx + L.width, f.y1 - inset},
  }};
}

LegendPlace emptiest_place(const std::vector<std::vector<Point>>& lines, const Rect& frame,
                           const Legend& legend, double s) {
  const std::array<Rect, 6> places = legend_places(frame, legend, s);
  LegendPlace best{places[0], std::numeric_limits<double>::infinity()};
  for (const Rect& c : places) {
    const double occ = occupancy(lines, c);
    if (occ < best.occupancy - 0.5) best = {c, occ};
  }
  return best;
}

void draw_legend(Painter& painter, const Panel& panel, const Legend& L, const Rect& box,
                 int panel_index, const Metrics& m) {
  const double s = m.s;
  painter.fill_rect(box, kLegendBox);
  painter.stroke_rect(Rect{box.x0 + 0.5, box.y0 + 0.5, box.x1 - 0.5, box.y1 - 0.5},
                      Stroke{kLegendFrame, std::max(1.0, 1.2 * m.line), {}});
  const Extent le = painter.measure("Hg", L.size);
  for (std::size_t k = 0; k < L.entries.size(); ++k) {
    const int entry = L.entries[k];
    LineStyle style = reference_style();
    if (entry >= 0) {
      style = panel.series[entry].style ? *panel.series[entry].style : series_style(entry);
    }
    const int column = static_cast<int>(k) / L.rows, row = static_cast<int>(k) % L.rows;
    const double x0 = box.x0 + L.pad + column * L.column;
    const double cy = box.y0 + 0.8 * L.pad + row * L.row + 0.5 * L.row;
    painter.line({x0, cy}, {x0 + L.sample, cy}, make_stroke(style, m.line));
    painter.text(L.labels[k], x0 + L.sample + 12 * s,
                 cy + 0.5 * (le.line_ascent - le.line_descent) - 1 * s, L.size, kText,
                 TextRole::legend_entry, panel_index);
  }
}

}  // namespace stiction::plot
