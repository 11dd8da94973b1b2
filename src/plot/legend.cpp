#include "plot/legend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

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
  if (entries.size() < 2 &&
      !(entries.size() == 1 && (panel.label.empty() || panel.legend_keeps_one_entry))) {
    entries.clear();
  }
  return entries;
}

namespace {

bool same_style(const LineStyle& a, const LineStyle& b) {
  return a.colour.r == b.colour.r && a.colour.g == b.colour.g && a.colour.b == b.colour.b &&
         a.colour.a == b.colour.a && a.dash == b.dash && a.width == b.width;
}

LineStyle style_of(const Panel& panel, std::size_t i) {
  return panel.series[i].style ? *panel.series[i].style : series_style(static_cast<int>(i));
}

}  // namespace

Figure shared_legend_entries(const Figure& given) {
  Figure figure = given;
  struct Shown {
    std::string label;
    LineStyle style;
  };
  std::vector<Shown> shown;
  for (Panel& panel : figure.panels) {
    const std::vector<int> entries = legend_entries(panel);
    if (entries.empty()) continue;
    std::vector<int> repeated;
    for (int i : entries) {
      if (i < 0) continue;
      const LineStyle style = style_of(panel, static_cast<std::size_t>(i));
      if (std::any_of(shown.begin(), shown.end(), [&](const Shown& e) {
            return e.label == panel.series[i].label && same_style(e.style, style);
          })) {
        repeated.push_back(i);
      }
    }
    const std::size_t left = entries.size() - repeated.size();
    // Left out when the legend keeps what the reader cannot get from the earlier one: no
    // entry (the same legend again), a reference line alone, or two entries or more.
    const bool alone_reference =
        left == 1 && std::any_of(entries.begin(), entries.end(), [&](int i) {
          return i < 0 && std::find(repeated.begin(), repeated.end(), i) == repeated.end();
        });
    if (!repeated.empty() && (left == 0 || left >= 2 || alone_reference)) {
      for (int i : repeated) panel.series[i].label.clear();
      panel.legend_keeps_one_entry = alone_reference;
    }
    for (int i : legend_entries(panel)) {
      if (i >= 0) shown.push_back({panel.series[i].label, style_of(panel, i)});
    }
  }
  return figure;
}

Legend shape_legend(const Panel& panel, const std::vector<int>& entries, Painter& painter,
                    const Metrics& m, int columns, double max_width, double size) {
  Legend L;
  L.entries = entries;
  const int n = static_cast<int>(entries.size());
  L.pad = 12 * m.s;
  L.sample = 56 * m.s;
  L.columns = std::clamp(columns, 1, std::max(1, n));
  L.rows = (n + L.columns - 1) / L.columns;
  L.by_rows = L.columns >= L.rows;
  const double text_room =
      std::max(40 * m.s, max_width / L.columns - L.pad - L.sample - 12 * m.s - L.pad);
  // The labels by the text rule, all at one size: the smallest any of them needs down to the
  // floor (a label that needs less than the floor alone is smaller still).
  const double floor = std::min(size, m.floor(m.legend()));
  std::vector<FittedText> fitted;
  double common = size;
  for (int i : entries) {
    const std::string& label = i >= 0 ? panel.series[i].label : panel.references[-1 - i].label;
    fitted.push_back(fit_text(painter, label, TextRule{size, floor, text_room, 1}));
    common = std::min(common, std::max(fitted.back().size, floor));
  }
  L.size = common;
  L.row = 1.45 * common;
  L.shrunk = common < size;
  double text_width = 0.0;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const int i = entries[k];
    const std::string& label = i >= 0 ? panel.series[i].label : panel.references[-1 - i].label;
    if (fitted[k].size > common) {
      fitted[k] = fit_text(painter, label, TextRule{common, common, text_room, 1});
    }
    L.labels.push_back(fitted[k].joined());
    L.label_sizes.push_back(fitted[k].size);
    L.label_shortened.push_back(fitted[k].shortened);
    L.shortened = L.shortened || fitted[k].shortened || fitted[k].below_floor;
    text_width = std::max(text_width, painter.measure(L.labels.back(), fitted[k].size).width);
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
  // Smaller, down to the floor of its text (text_fit.hpp), before a second column.
  const double floor = m.floor(m.legend());
  double size = m.legend();
  int columns = 1;
  for (;; size = std::max(floor, 0.9 * size)) {
    const double row = 1.45 * size, fixed = 12 * m.s * 1.4;
    const int fit_rows = std::max(1, static_cast<int>((max_height - fixed) / row));
    columns = (n + fit_rows - 1) / fit_rows;
    if (columns <= 1 || size <= floor) break;
  }
  Legend L = shape_legend(panel, entries, painter, m, columns, max_width, size);
  L.place = LegendPlace::right;
  return L;
}

Legend legend_above(const Panel& panel, Painter& painter, const Metrics& m, double max_width,
                    int max_rows) {
  const std::vector<int> entries = legend_entries(panel);
  const int n = static_cast<int>(entries.size());
  // Side by side, its labels whole, at the legend's size or the floor of its text: the
  // shape of the least height (up to max_rows rows; the legend's size on a tie); failing
  // that, in one row at the legend's size, whatever it takes (shortened: the caller's to
  // refuse).
  std::optional<Legend> lowest;
  for (const double size : {m.legend(), m.floor(m.legend())}) {
    for (int columns = std::max(1, n); columns >= 1; --columns) {
      Legend L = shape_legend(panel, entries, painter, m, columns, max_width, size);
      if (L.rows > max_rows) break;  // fewer columns: more rows still
      if (!L.shortened && !L.shrunk && L.width <= max_width &&
          (!lowest || L.height < lowest->height - 0.5)) {
        lowest = std::move(L);
      }
    }
  }
  Legend L = lowest
                 ? *lowest
                 : shape_legend(panel, entries, painter, m, std::max(1, n), max_width, m.legend());
  L.place = LegendPlace::above;
  return L;
}

Legend legend_above_anyhow(const Panel& panel, Painter& painter, const Metrics& m,
                           double max_width) {
  const std::vector<int> entries = legend_entries(panel);
  const int n = static_cast<int>(entries.size());
  // The least height within max_width: labels whole before shortened, the legend's size
  // before the floor of its text, more columns before fewer.
  std::optional<Legend> pick;
  auto rank = [](const Legend& L) { return std::make_tuple(L.shortened, L.height); };
  for (const double size : {m.legend(), m.floor(m.legend())}) {
    for (int columns = std::max(1, n); columns >= 1; --columns) {
      Legend L = shape_legend(panel, entries, painter, m, columns, max_width, size);
      if (L.width > max_width + 0.5) continue;
      if (!pick || rank(L) < rank(*pick)) pick = std::move(L);
    }
  }
  Legend L = pick ? *pick : shape_legend(panel, entries, painter, m, 1, max_width, m.legend());
  L.place = LegendPlace::above;
  return L;
}

std::optional<Legend> legend_in_caption_row(const Panel& panel, Painter& painter, const Metrics& m,
                                            double max_width) {
  const std::vector<int> entries = legend_entries(panel);
  if (entries.empty()) return std::nullopt;
  const int n = static_cast<int>(entries.size());
  for (const double size : {m.legend(), m.floor(m.legend())}) {
    Legend L;
    L.entries = entries;
    L.boxed = false;
    L.place = LegendPlace::caption;
    L.size = size;
    L.pad = 0.0;
    L.sample = 40 * m.s;
    L.columns = n;
    L.rows = 1;
    L.by_rows = true;
    L.shrunk = size < m.legend();
    const Extent e = painter.measure("Hg", size);
    L.row = e.line_ascent + e.line_descent;
    double text_width = 0.0;
    for (int i : entries) {
      const std::string& label = i >= 0 ? panel.series[i].label : panel.references[-1 - i].label;
      L.labels.push_back(label);
      L.label_sizes.push_back(size);
      L.label_shortened.push_back(false);
      text_width = std::max(text_width, painter.measure(label, size).width);
    }
    // Equal columns, 14 units between an entry's label and the next sample.
    L.column = L.sample + 8 * m.s + text_width + 14 * m.s;
    L.width = n * L.column - 14 * m.s;
    L.height = L.row;
    if (L.width <= max_width) return L;
  }
  return std::nullopt;
}

namespace {

struct Candidate {
  InsidePlace place;
  long data = 0;  // data pixels under the box and its margin
  double score = 0.0;
};

// Every candidate place inside, in order of preference, with the ink under each (within a
// margin around the box).
std::vector<Candidate> inside_places(const Panel& panel, Painter& painter, const Metrics& m,
                                     const Rect& f, const PanelInk& ink, double size) {
  std::vector<Candidate> found;
  const std::vector<int> entries = legend_entries(panel);
  if (entries.empty()) return found;
  const double inset = 14 * m.s, margin = std::max(2.0, 3 * m.line);
  const int n = static_cast<int>(entries.size());
  // Shapes with whole labels; shortened ones only when no shape keeps them whole.
  std::vector<Legend> shapes, shortened;
  for (int columns = 1; columns <= std::min(n, 4); ++columns) {
    Legend L = shape_legend(panel, entries, painter, m, columns, 0.9 * f.width(), size);
    if (L.width <= f.width() - 2 * inset && L.height <= f.height() - 2 * inset) {
      (L.shortened ? shortened : shapes).push_back(std::move(L));
    }
  }
  if (shapes.empty()) shapes = std::move(shortened);
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
      const long data = ink.data.count(around);
      const double score = static_cast<double>(data) + 0.25 * ink.marks.count(around);
      found.push_back({InsidePlace{L, box}, data, score});
    }
  }
  return found;
}

// The candidate with the least score, the first on a tie (the order of preference).
const Candidate* best(const std::vector<Candidate>& found) {
  const Candidate* pick = nullptr;
  for (const Candidate& c : found) {
    if (!pick || c.score < pick->score) pick = &c;
  }
  return pick;
}

}  // namespace

std::optional<InsidePlace> free_place_inside(const Panel& panel, Painter& painter, const Metrics& m,
                                             const Rect& f, const PanelInk& ink, double size,
                                             long& ink_under) {
  const long allowed =
      static_cast<long>(std::floor(kLegendDataShare * static_cast<double>(ink.data.count(f))));
  std::vector<Candidate> free;
  for (const Candidate& c : inside_places(panel, painter, m, f, ink, size)) {
    if (c.data <= allowed) free.push_back(c);
  }
  if (const Candidate* pick = best(free)) {
    ink_under = pick->data;
    return pick->place;
  }
  return std::nullopt;
}

void draw_legend(Painter& painter, const Panel& panel, const Legend& L, const Rect& box,
                 int panel_index, const Metrics& m) {
  const double s = m.s;
  if (L.boxed) {
    painter.fill_rect(box, kLegendBox);
    painter.stroke_rect(Rect{box.x0 + 0.5, box.y0 + 0.5, box.x1 - 0.5, box.y1 - 0.5},
                        Stroke{kLegendFrame, std::max(1.0, 1.2 * m.line), {}});
  }
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
    const TextOrigin origin{
        entry >= 0 ? panel.series[entry].label : panel.references[-1 - entry].label,
        L.label_shortened[k]};
    painter.text(L.labels[k], x0 + L.sample + (L.boxed ? 12 : 8) * s,
                 cy + 0.5 * (le.line_ascent - le.line_descent) - (L.boxed ? 1 : 0) * s,
                 L.label_sizes[k], kText, TextRole::legend_entry, panel_index, false, &origin);
  }
}

}  // namespace stiction::plot
