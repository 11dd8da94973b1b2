#include "plot/legend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plot/text_fit.hpp"

namespace stiction::plot {

std::vector<int> legend_entries(const Panel& panel) {
  std::vector<int> entries;
  for (std::size_t i = 0; i < panel.series.size(); ++i) {
    if (!panel.series[i].label.empty()) entries.push_back(static_cast<int>(i));
  }
  for (std::size_t k = 0; k < panel.references.size(); ++k) {
    if (!panel.references[k].label.empty()) entries.push_back(-1 - static_cast<int>(k));
  }
  if (entries.size() < 2 && !(entries.size() == 1 && panel.label.empty())) entries.clear();
  return entries;
}

Legend shape_legend(const Panel& panel, const std::vector<int>& entries, Painter& painter,
                    const Metrics& m, int columns, double max_width, double size) {
  Legend L;
  L.entries = entries;
  const int n = static_cast<int>(entries.size());
  L.size = size;
  L.pad = 12 * m.s;
  L.sample = 56 * m.s;
  L.row = 1.45 * size;
  L.columns = std::clamp(columns, 1, std::max(1, n));
  L.rows = (n + L.columns - 1) / L.columns;
  L.by_rows = L.columns >= L.rows;
  const double text_room =
      std::max(40 * m.s, max_width / L.columns - L.pad - L.sample - 12 * m.s - L.pad);
  double text_width = 0.0;
  for (int i : entries) {
    const std::string& label = i >= 0 ? panel.series[i].label : panel.references[-1 - i].label;
    L.labels.push_back(fit(painter, label, size, text_room));
    L.shortened = L.shortened || L.labels.back() != label;
    text_width = std::max(text_width, painter.measure(L.labels.back(), size).width);
  }
  L.column = L.sample + 12 * m.s + text_width + L.pad;
  L.width = L.pad + L.columns * L.column;
  L.height = L.pad * 0.8 + L.row * L.rows + L.pad * 0.6;
  return L;
}

Legend legend_beside(const Panel& panel, Painter& painter, const Metrics& m, double max_width,
                     double max_height) {
  const std::vector<int> entries = legend_entries(panel);
  const int n = static_cast<int>(entries.size());
  // Shrink the font (to 75%, in the pixel design) before adding columns.
  double size = m.legend();
  int columns = 1;
  for (;; size *= 0.9) {
    const double row = 1.45 * size, fixed = 12 * m.s * 1.4;
    const int fit_rows = std::max(1, static_cast<int>((max_height - fixed) / row));
    columns = (n + fit_rows - 1) / fit_rows;
    if (columns <= 1 || !m.shrinks || size < 0.76 * m.legend()) break;
  }
  Legend L = shape_legend(panel, entries, painter, m, columns, max_width, size);
  L.place = LegendPlace::right;
  return L;
}

Legend legend_above(const Panel& panel, Painter& painter, const Metrics& m, double max_width) {
  const std::vector<int> entries = legend_entries(panel);
  const int n = static_cast<int>(entries.size());
  Legend best;
  for (int columns = std::max(1, n); columns >= 1; --columns) {
    Legend L = shape_legend(panel, entries, painter, m, columns, max_width, m.legend());
    best = L;
    if (!L.shortened && L.width <= max_width) break;
  }
  best.place = LegendPlace::above;
  return best;
}

namespace {

// Every candidate place inside, in order of preference, and the ink under each (within a
// margin around the box); stops at the first free one when `first_free`.
std::vector<std::pair<InsidePlace, long>> inside_places(const Panel& panel, Painter& painter,
                                                        const Metrics& m, const Rect& f,
                                                        const DataInk& ink, bool first_free) {
  std::vector<std::pair<InsidePlace, long>> found;
  const std::vector<int> entries = legend_entries(panel);
  if (entries.empty()) return found;
  const double inset = 14 * m.s, margin = std::max(2.0, 3 * m.line);
  const int n = static_cast<int>(entries.size());
  std::vector<Legend> shapes;
  for (int columns = 1; columns <= std::min(n, 4); ++columns) {
    Legend L = shape_legend(panel, entries, painter, m, columns, 0.9 * f.width(), m.legend());
    if (L.width <= f.width() - 2 * inset && L.height <= f.height() - 2 * inset) {
      shapes.push_back(std::move(L));
    }
  }
  // Places as fractions along the free width and height: corners, middles, then along the
  // top and bottom edges and down the sides.
  std::vector<std::pair<double, double>> places{{1, 0},   {0, 0},   {1, 1},   {0, 1},
                                                {0.5, 0}, {0.5, 1}, {0, 0.5}, {1, 0.5}};
  for (double u : {0.25, 0.75, 0.125, 0.375, 0.625, 0.875}) {
    places.push_back({u, 0});
    places.push_back({u, 1});
  }
  for (double v : {0.25, 0.75}) {
    places.push_back({0, v});
    places.push_back({1, v});
  }
  for (const auto& [u, v] : places) {
    for (const Legend& L : shapes) {
      const double x0 = f.x0 + inset + u * (f.width() - 2 * inset - L.width);
      const double y0 = f.y0 + inset + v * (f.height() - 2 * inset - L.height);
      const Rect box{std::round(x0), std::round(y0), std::round(x0 + L.width),
                     std::round(y0 + L.height)};
      const Rect around{box.x0 - margin, box.y0 - margin, box.x1 + margin, box.y1 + margin};
      const long under = ink.count(around);
      found.push_back({InsidePlace{L, box}, under});
      if (first_free && under == 0) return found;
    }
  }
  return found;
}

}  // namespace

std::optional<InsidePlace> free_place_inside(const Panel& panel, Painter& painter, const Metrics& m,
                                             const Rect& f, const DataInk& ink) {
  auto found = inside_places(panel, painter, m, f, ink, true);
  if (found.empty() || found.back().second != 0) return std::nullopt;
  return found.back().first;
}

InsidePlace least_inked_place_inside(const Panel& panel, Painter& painter, const Metrics& m,
                                     const Rect& f, const DataInk& ink, long& ink_under) {
  auto found = inside_places(panel, painter, m, f, ink, false);
  if (found.empty()) {
    // Too big for the frame in every shape: one row, its labels shortened to the frame's
    // width, at the top (the caller checks that it fits the frame's height).
    const std::vector<int> entries = legend_entries(panel);
    Legend L = shape_legend(panel, entries, painter, m, static_cast<int>(entries.size()), f.width(),
                            m.legend());
    const Rect box{std::round(f.x0), std::round(f.y0), std::round(f.x0 + L.width),
                   std::round(f.y0 + L.height)};
    ink_under = ink.count(box);
    return InsidePlace{L, box};
  }
  const auto best = std::min_element(
      found.begin(), found.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  ink_under = best->second;
  return best->first;
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
    const int i = static_cast<int>(k);
    const int column = L.by_rows ? i % L.columns : i / L.rows;
    const int row = L.by_rows ? i / L.columns : i % L.rows;
    const double x0 = box.x0 + L.pad + column * L.column;
    const double cy = box.y0 + 0.8 * L.pad + row * L.row + 0.5 * L.row;
    painter.line({x0, cy}, {x0 + L.sample, cy}, make_stroke(style, m.line));
    painter.text(L.labels[k], x0 + L.sample + 12 * s,
                 cy + 0.5 * (le.line_ascent - le.line_descent) - 1 * s, L.size, kText,
                 TextRole::legend_entry, panel_index);
  }
}

}  // namespace stiction::plot
