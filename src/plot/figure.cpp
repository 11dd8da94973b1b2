#include "plot/figure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "plot/ticks.hpp"

namespace stiction::plot {
namespace {

using image::Rgba;

constexpr Rgba kWhite{255, 255, 255, 255};
constexpr Rgba kText{25, 25, 25, 255};
constexpr Rgba kFrame{60, 60, 60, 255};
constexpr Rgba kGrid{222, 222, 222, 255};
constexpr Rgba kMinorGrid{240, 240, 240, 255};
constexpr Rgba kEvent{80, 80, 80, 255};
constexpr Rgba kLegendBox{255, 255, 255, 235};
constexpr Rgba kLegendFrame{190, 190, 190, 255};

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Okabe & Ito's colour-blind-safe palette (yellow left out: too light on white).
constexpr std::array<Rgba, 7> kPalette{{{0, 114, 178, 255},
                                        {213, 94, 0, 255},
                                        {0, 158, 115, 255},
                                        {204, 121, 167, 255},
                                        {230, 159, 0, 255},
                                        {86, 180, 233, 255},
                                        {0, 0, 0, 255}}};

std::string superscript(int value) {
  static const char* const digits[] = {"\u2070", "\u00B9", "\u00B2", "\u00B3", "\u2074",
                                       "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::string out = value < 0 ? "\u207B" : "";
  const std::string plain = std::to_string(std::abs(value));
  for (char c : plain) out += digits[c - '0'];
  return out;
}

// Sizes of the figure's parts at scale s (1 at 1600x1000).
struct Metrics {
  double s;
  double title() const { return 32 * s; }
  double label() const { return 27 * s; }
  double tick() const { return 24 * s; }
  double legend() const { return 23 * s; }
  double event() const { return 22 * s; }
  double margin() const { return 22 * s; }
  double tick_length() const { return 9 * s; }
  double frame_width() const { return std::max(1.0, 1.6 * s); }
  double grid_width() const { return std::max(1.0, 1.2 * s); }
};

// A vertical or horizontal axis: value -> pixel.
struct Axis {
  double lo = 0.0, hi = 1.0;  // in data units (log axes: exponents)
  bool log = false;
  double p0 = 0.0, p1 = 1.0;  // pixels of lo and hi
  double map(double v) const {
    double u = v;
    if (log) u = v > 0.0 ? std::log10(v) : kNaN;
    const double p = p0 + (u - lo) / (hi - lo) * (p1 - p0);
    if (!std::isfinite(p)) return kNaN;
    return std::clamp(p, -1e6, 1e6);
  }
};

struct TickMark {
  double value;
  std::string label;  // empty: minor tick (grid only)
};

// Ticks and range of one vertical axis.
struct YAxis {
  Axis axis;
  std::vector<TickMark> ticks;
  int exponent = 0;  // linear axes: labels are value / 10^exponent
};

bool in_range(double v, double lo, double hi) {
  const double eps = (hi - lo) * 1e-9;
  return v >= lo - eps && v <= hi + eps;
}

YAxis make_y_axis(const Panel& panel, double x_lo, double x_hi, int target) {
  std::vector<double> values;
  for (const Series& s : panel.series) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (in_range(s.x[i], x_lo, x_hi)) values.push_back(s.y[i]);
    }
  }
  for (const ReferenceLine& r : panel.references) values.push_back(r.y);
  YAxis y;
  y.axis.log = panel.log;
  if (panel.log) {
    Range r = positive_range(values);
    if (panel.y_min && *panel.y_min > 0.0) r.min = *panel.y_min;
    if (panel.y_max && *panel.y_max > 0.0) r.max = *panel.y_max;
    const LogTicks lt = log_ticks(r.min, r.max, target);
    y.axis.lo = lt.lo_exp;
    y.axis.hi = lt.hi_exp;
    for (double v : lt.minor_values) y.ticks.push_back({v, ""});
    for (int e : lt.major_exponents) y.ticks.push_back({std::pow(10.0, e), "10" + superscript(e)});
    return y;
  }
  Range r = finite_range(values);
  if (panel.y_min) r.min = *panel.y_min;
  if (panel.y_max) r.max = *panel.y_max;
  const Ticks loose = nice_ticks(r.min, r.max, target);
  const bool fixed = panel.y_min && panel.y_max;
  double lo = loose.lo, hi = loose.hi;
  Ticks ticks = loose;
  if (fixed) {
    lo = std::min(*panel.y_min, *panel.y_max);
    hi = std::max(*panel.y_min, *panel.y_max);
    if (hi <= lo) {
      lo = loose.lo;
      hi = loose.hi;
    }
  } else if (std::isfinite(r.min) && std::isfinite(r.max) && loose.step > 0.0 &&
             r.max - r.min > 1e-12 * std::max(std::abs(r.min), std::abs(r.max))) {
    // Data with a real spread: 4% of air above and below, ticks inside.
    const double pad = 0.04 * (r.max - r.min);
    lo = r.min - pad;
    hi = r.max + pad;
    ticks = nice_ticks(lo, hi, target);
  }
  y.axis.lo = lo;
  y.axis.hi = hi;
  Ticks shown = ticks;
  shown.values.clear();
  for (double v : ticks.values) {
    if (in_range(v, lo, hi)) shown.values.push_back(v);
  }
  if (shown.values.size() < 2) {  // cannot happen with the padding above; be safe anyway
    lo = std::min(lo, ticks.lo);
    hi = std::max(hi, ticks.hi);
    y.axis.lo = lo;
    y.axis.hi = hi;
    shown.values = ticks.values;
  }
  shown.lo = shown.values.empty() ? lo : shown.values.front();
  shown.hi = shown.values.empty() ? hi : shown.values.back();
  const TickLabels labels = format_ticks(shown);
  y.exponent = labels.exponent;
  for (std::size_t i = 0; i < shown.values.size(); ++i) {
    y.ticks.push_back({shown.values[i], labels.labels[i]});
  }
  return y;
}

std::string axis_title(const std::string& label, const std::string& unit, int exponent) {
  std::string factor = exponent != 0 ? "\u00D710" + superscript(exponent) : "";
  std::string bracket;
  if (!factor.empty() && !unit.empty()) {
    bracket = factor + " " + unit;
  } else {
    bracket = factor + unit;
  }
  if (bracket.empty()) return label;
  if (label.empty()) return "[" + bracket + "]";
  return label + " [" + bracket + "]";
}

// Splits text into lines no longer than max_width, breaking at spaces; the bracketed unit
// part moves to its own line first.
std::vector<std::string> wrap(text::Font& font, const std::string& text, double max_width,
                              const text::TextStyle& style) {
  if (font.measure(text, style).width <= max_width) return {text};
  std::vector<std::string> words;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) words.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  // Keep "[...]" groups together.
  std::vector<std::string> groups;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (!groups.empty() && groups.back().front() == '[' && groups.back().back() != ']') {
      groups.back() += " " + words[i];
    } else {
      groups.push_back(words[i]);
    }
  }
  std::vector<std::string> lines;
  std::string current;
  for (const std::string& g : groups) {
    const std::string candidate = current.empty() ? g : current + " " + g;
    const bool unit = g.front() == '[';
    if (!current.empty() && (unit || font.measure(candidate, style).width > max_width)) {
      lines.push_back(current);
      current = g;
    } else {
      current = candidate;
    }
  }
  if (!current.empty()) lines.push_back(current);
  return lines;
}

// Legend box size for a panel's labelled series.
struct LegendLayout {
  std::vector<int> entries;  // series indices, then -1 - k for reference line k
  double width = 0.0, height = 0.0, row = 0.0, sample = 0.0, pad = 0.0;
};

LegendLayout legend_layout(const Panel& panel, text::Font& font, const Metrics& m) {
  LegendLayout L;
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
  const text::TextStyle style{m.legend(), kText, text::Rotation::none};
  double text_width = 0.0;
  for (int i : L.entries) {
    const std::string& label = i >= 0 ? panel.series[i].label : panel.references[-1 - i].label;
    text_width = std::max(text_width, font.measure(label, style).width);
  }
  L.pad = 12 * m.s;
  L.sample = 56 * m.s;
  L.row = 1.45 * m.legend();
  L.width = L.pad + L.sample + 12 * m.s + text_width + L.pad;
  L.height = L.pad * 0.8 + L.row * L.entries.size() + L.pad * 0.6;
  return L;
}

Stroke make_stroke(const LineStyle& style, double s) {
  Stroke stroke;
  stroke.colour = style.colour;
  stroke.width = style.width * s;
  for (double d : style.dash) stroke.dash.push_back(d * s);
  return stroke;
}

std::vector<Point> to_pixels(const Series& series, const Axis& x, const Axis& y) {
  const std::size_t n = std::min(series.x.size(), series.y.size());
  std::vector<Point> points;
  points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) points.push_back({x.map(series.x[i]), y.map(series.y[i])});
  return points;
}

// How much of the data lies under a rectangle (samples every ~2 pixels along each line).
double occupancy(const std::vector<std::vector<Point>>& lines, const Rect& r) {
  double count = 0.0;
  for (const auto& pts : lines) {
    for (std::size_t i = 1; i < pts.size(); ++i) {
      const Point a = pts[i - 1], b = pts[i];
      if (!std::isfinite(a.x + a.y + b.x + b.y)) continue;
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

LineStyle reference_style() { return LineStyle{kEvent, {5, 4}, 2.0}; }

}  // namespace

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

image::Image render(const Figure& figure, text::Font& font) {
  if (figure.width < 200 || figure.height < 150 || figure.width > 16384 || figure.height > 16384) {
    throw std::invalid_argument("figure size must be between 200x150 and 16384x16384 pixels");
  }
  image::Image img(figure.width, figure.height, kWhite);
  Canvas canvas(img);
  const Metrics m{std::min(figure.width / 1600.0, figure.height / 1000.0)};
  const double s = m.s;

  const text::TextStyle title_style{m.title(), kText, text::Rotation::none};
  const text::TextStyle label_style{m.label(), kText, text::Rotation::none};
  const text::TextStyle ylabel_style{m.label(), kText, text::Rotation::ccw90};
  const text::TextStyle tick_style{m.tick(), kText, text::Rotation::none};
  const text::TextStyle legend_style{m.legend(), kText, text::Rotation::none};
  const text::TextStyle event_style{m.event(), kEvent, text::Rotation::none};

  // ---- The shared horizontal axis range.
  std::vector<double> xs;
  for (const Panel& p : figure.panels) {
    for (const Series& series : p.series) xs.insert(xs.end(), series.x.begin(), series.x.end());
  }
  Range xr = finite_range(xs);
  if (figure.x_min) xr.min = *figure.x_min;
  if (figure.x_max) xr.max = *figure.x_max;
  double x_lo = xr.min, x_hi = xr.max;
  if (!std::isfinite(x_lo) || !std::isfinite(x_hi) || !(x_hi > x_lo)) {
    const Ticks t = nice_ticks(x_lo, x_hi, 2);
    x_lo = t.lo;
    x_hi = t.hi;
  }

  // ---- Vertical layout.
  const text::Extent title_extent = font.measure("Hg", title_style);
  const text::Extent tick_extent = font.measure("0123456789", tick_style);
  const text::Extent label_extent = font.measure("Hg[]", label_style);
  const text::Extent event_extent = font.measure("Hg", event_style);
  const double label_line = label_extent.line_ascent + label_extent.line_descent;
  double top = m.margin();
  double title_baseline = 0.0;
  if (!figure.title.empty()) {
    title_baseline = top + title_extent.line_ascent;
    top = title_baseline + title_extent.line_descent + 14 * s;
  }
  // Event labels go in rows above the top panel; rows are decided once x pixels are known,
  // so reserve the rows now from a first, conservative estimate (one row per two events).
  const std::size_t event_count = figure.events.size();
  const double event_row = event_extent.line_ascent + event_extent.line_descent + 4 * s;
  int event_rows = event_count == 0 ? 0 : 1;

  const double bottom_reserved = m.margin() + label_line + 8 * s + tick_extent.line_ascent +
                                 tick_extent.line_descent + m.tick_length() + 4 * s;
  const std::size_t n_panels = std::max<std::size_t>(1, figure.panels.size());
  const double gap = 26 * s;

  // Horizontal tick labels determine the right margin; compute them first.
  const int x_target = std::max(3, static_cast<int>(figure.width / (190 * s)));
  Ticks x_loose = nice_ticks(x_lo, x_hi, x_target);
  Ticks x_ticks = x_loose;
  x_ticks.values.clear();
  for (double v : x_loose.values) {
    if (in_range(v, x_lo, x_hi)) x_ticks.values.push_back(v);
  }
  if (x_ticks.values.empty()) x_ticks.values = {x_lo, x_hi};
  x_ticks.lo = x_ticks.values.front();
  x_ticks.hi = x_ticks.values.back();
  const TickLabels x_labels = format_ticks(x_ticks);
  const double right =
      figure.width -
      std::max(m.margin() + 10 * s,
               0.5 * font.measure(x_labels.labels.back(), tick_style).width + m.margin());

  // Event label rows: place greedily once the horizontal mapping is known; this needs the left
  // margin, which needs the y tick labels, which need the panel heights. Iterate twice.
  double left = 0.0;
  std::vector<Rect> frames;
  std::vector<YAxis> y_axes;
  std::vector<std::vector<std::string>> y_titles;
  std::vector<int> event_row_of(event_count, 0);
  for (int pass = 0; pass < 2; ++pass) {
    const double panels_top = top + event_rows * event_row + (event_rows ? 6 * s : 0.0);
    const double panels_bottom = figure.height - bottom_reserved;
    const double panel_h =
        (panels_bottom - panels_top - gap * (n_panels - 1)) / static_cast<double>(n_panels);
    const int y_target = std::clamp(static_cast<int>(panel_h / (58 * s)), 3, 8);
    y_axes.clear();
    y_titles.clear();
    double tick_width = 0.0;
    std::size_t max_lines = 1;
    for (std::size_t p = 0; p < n_panels; ++p) {
      const Panel empty_panel;
      const Panel& panel = p < figure.panels.size() ? figure.panels[p] : empty_panel;
      YAxis y = make_y_axis(panel, x_lo, x_hi, y_target);
      for (const TickMark& t : y.ticks) {
        if (!t.label.empty())
          tick_width = std::max(tick_width, font.measure(t.label, tick_style).width);
      }
      y_titles.push_back(
          wrap(font, axis_title(panel.label, panel.unit, y.exponent), 0.96 * panel_h, label_style));
      max_lines = std::max(max_lines, y_titles.back().size());
      y_axes.push_back(std::move(y));
    }
    left = m.margin() + max_lines * label_line + 10 * s + tick_width + m.tick_length() + 2 * s;
    frames.clear();
    for (std::size_t p = 0; p < n_panels; ++p) {
      const double y0 = panels_top + p * (panel_h + gap);
      frames.push_back(
          Rect{std::round(left), std::round(y0), std::round(right), std::round(y0 + panel_h)});
    }
    // Rows for event labels, centred on their lines, no overlaps within a row.
    Axis x_axis{x_lo, x_hi, false, frames[0].x0, frames[0].x1};
    std::vector<std::vector<std::pair<double, double>>> rows;
    for (std::size_t e = 0; e < event_count; ++e) {
      const double w = font.measure(figure.events[e].label, event_style).width;
      const double cx = x_axis.map(figure.events[e].x);
      double a = std::clamp(cx - 0.5 * w, m.margin(), figure.width - m.margin() - w);
      double b = a + w;
      std::size_t row = 0;
      for (; row < rows.size(); ++row) {
        bool free = true;
        for (auto [u, v] : rows[row]) {
          if (a < v + 16 * s && b > u - 16 * s) free = false;
        }
        if (free) break;
      }
      if (row == rows.size()) rows.emplace_back();
      rows[row].push_back({a, b});
      event_row_of[e] = static_cast<int>(row);
    }
    const int needed = static_cast<int>(rows.size());
    if (needed == event_rows) break;
    event_rows = needed;
  }

  const Axis x_axis{x_lo, x_hi, false, frames[0].x0, frames[0].x1};

  // ---- Title.
  if (!figure.title.empty()) {
    const double w = font.measure(figure.title, title_style).width;
    const double cx = 0.5 * (frames[0].x0 + frames[0].x1);
    font.draw(img, figure.title,
              std::clamp(cx - 0.5 * w, m.margin(), figure.width - w - m.margin()), title_baseline,
              title_style);
  }

  const Stroke frame_stroke{kFrame, m.frame_width(), {}};
  const Stroke grid_stroke{kGrid, m.grid_width(), {}};
  const Stroke minor_stroke{kMinorGrid, m.grid_width(), {}};
  const Stroke event_stroke{kEvent, 2.0 * s, {9 * s, 6 * s}};

  for (std::size_t p = 0; p < n_panels; ++p) {
    const Panel empty_panel;
    const Panel& panel = p < figure.panels.size() ? figure.panels[p] : empty_panel;
    const Rect& f = frames[p];
    YAxis& y = y_axes[p];
    y.axis.p0 = f.y1;
    y.axis.p1 = f.y0;

    // Grid.
    for (const TickMark& t : y.ticks) {
      const double py = std::round(y.axis.map(t.value)) + 0.5;
      canvas.line({f.x0, py}, {f.x1, py}, t.label.empty() ? minor_stroke : grid_stroke);
    }
    for (double v : x_ticks.values) {
      const double px = std::round(x_axis.map(v)) + 0.5;
      canvas.line({px, f.y0}, {px, f.y1}, grid_stroke);
    }
    // Events.
    for (const EventMarker& e : figure.events) {
      const double px = x_axis.map(e.x);
      if (!std::isfinite(px) || px < f.x0 || px > f.x1) continue;
      canvas.line({px, f.y0}, {px, f.y1}, event_stroke);
    }
    // Reference lines under the data.
    const Stroke reference_stroke = make_stroke(reference_style(), s);
    for (const ReferenceLine& r : panel.references) {
      const double py = y.axis.map(r.y);
      if (!std::isfinite(py) || py < f.y0 || py > f.y1) continue;
      canvas.line({f.x0, py}, {f.x1, py}, reference_stroke);
    }
    // Data, clipped to the frame.
    std::vector<std::vector<Point>> lines;
    canvas.set_clip(f);
    for (std::size_t i = 0; i < panel.series.size(); ++i) {
      const Series& series = panel.series[i];
      const LineStyle style = series.style ? *series.style : series_style(static_cast<int>(i));
      lines.push_back(to_pixels(series, x_axis, y.axis));
      canvas.polyline(lines.back(), make_stroke(style, s));
    }
    canvas.reset_clip();
    // Frame and ticks.
    const Rect crisp{f.x0 + 0.5, f.y0 + 0.5, f.x1 - 0.5, f.y1 - 0.5};
    canvas.stroke_rect(crisp, frame_stroke);
    for (const TickMark& t : y.ticks) {
      const double py = std::round(y.axis.map(t.value)) + 0.5;
      const double len = t.label.empty() ? 0.55 * m.tick_length() : m.tick_length();
      canvas.line({f.x0, py}, {f.x0 + len, py}, frame_stroke);
      canvas.line({f.x1 - len, py}, {f.x1, py}, frame_stroke);
      if (t.label.empty()) continue;
      const double w = font.measure(t.label, tick_style).width;
      const double baseline = py + 0.5 * tick_extent.ascent;
      font.draw(img, t.label, f.x0 - m.tick_length() - w, baseline, tick_style);
    }
    for (double v : x_ticks.values) {
      const double px = std::round(x_axis.map(v)) + 0.5;
      canvas.line({px, f.y1 - m.tick_length()}, {px, f.y1}, frame_stroke);
      canvas.line({px, f.y0}, {px, f.y0 + m.tick_length()}, frame_stroke);
    }
    // Vertical axis title, centred on the panel, one rotated line per wrapped line.
    const std::vector<std::string>& title_lines = y_titles[p];
    for (std::size_t k = 0; k < title_lines.size(); ++k) {
      const double w = font.measure(title_lines[k], ylabel_style).width;
      const double baseline_x = m.margin() + label_extent.line_ascent + k * label_line;
      font.draw(img, title_lines[k], baseline_x, 0.5 * (f.y0 + f.y1) + 0.5 * w, ylabel_style);
    }
    // Legend in the corner with the least data under it.
    const LegendLayout L = legend_layout(panel, font, m);
    if (!L.entries.empty()) {
      const double inset = 14 * s;
      const std::array<Rect, 4> corners{{
          {f.x1 - inset - L.width, f.y0 + inset, f.x1 - inset, f.y0 + inset + L.height},
          {f.x0 + inset, f.y0 + inset, f.x0 + inset + L.width, f.y0 + inset + L.height},
          {f.x1 - inset - L.width, f.y1 - inset - L.height, f.x1 - inset, f.y1 - inset},
          {f.x0 + inset, f.y1 - inset - L.height, f.x0 + inset + L.width, f.y1 - inset},
      }};
      Rect box = corners[0];
      double best = std::numeric_limits<double>::infinity();
      for (const Rect& c : corners) {
        const double occ = occupancy(lines, c);
        if (occ < best - 0.5) {
          best = occ;
          box = c;
        }
      }
      box = Rect{std::round(box.x0), std::round(box.y0), std::round(box.x1), std::round(box.y1)};
      canvas.fill_rect(box, kLegendBox);
      canvas.stroke_rect(Rect{box.x0 + 0.5, box.y0 + 0.5, box.x1 - 0.5, box.y1 - 0.5},
                         Stroke{kLegendFrame, std::max(1.0, 1.2 * s), {}});
      const text::Extent le = font.measure("Hg", legend_style);
      for (std::size_t k = 0; k < L.entries.size(); ++k) {
        const int entry = L.entries[k];
        const std::string& label =
            entry >= 0 ? panel.series[entry].label : panel.references[-1 - entry].label;
        LineStyle style = reference_style();
        if (entry >= 0) {
          style = panel.series[entry].style ? *panel.series[entry].style : series_style(entry);
        }
        const double row_top = box.y0 + 0.8 * L.pad + k * L.row;
        const double cy = row_top + 0.5 * L.row;
        canvas.line({box.x0 + L.pad, cy}, {box.x0 + L.pad + L.sample, cy}, make_stroke(style, s));
        font.draw(img, label, box.x0 + L.pad + L.sample + 12 * s,
                  cy + 0.5 * (le.line_ascent - le.line_descent) - 1 * s, legend_style);
      }
    }
  }

  // ---- Horizontal tick labels and axis title under the bottom panel.
  const Rect& bottom = frames.back();
  const double tick_baseline = bottom.y1 + m.tick_length() + tick_extent.line_ascent;
  for (std::size_t i = 0; i < x_ticks.values.size(); ++i) {
    const double px = std::round(x_axis.map(x_ticks.values[i])) + 0.5;
    const double w = font.measure(x_labels.labels[i], tick_style).width;
    font.draw(img, x_labels.labels[i], px - 0.5 * w, tick_baseline, tick_style);
  }
  const std::string x_title = axis_title(figure.x_label, figure.x_unit, x_labels.exponent);
  const double xw = font.measure(x_title, label_style).width;
  font.draw(img, x_title, 0.5 * (bottom.x0 + bottom.x1) - 0.5 * xw,
            tick_baseline + tick_extent.line_descent + 8 * s + label_extent.line_ascent,
            label_style);

  // ---- Event labels above the top panel.
  const double rows_bottom = frames[0].y0 - 6 * s;
  for (std::size_t e = 0; e < event_count; ++e) {
    const double w = font.measure(figure.events[e].label, event_style).width;
    const double cx = x_axis.map(figure.events[e].x);
    if (!std::isfinite(cx)) continue;
    const double a = std::clamp(cx - 0.5 * w, m.margin(), figure.width - m.margin() - w);
    // Row 0 sits right above the panel, later rows above it.
    const double baseline =
        rows_bottom - event_extent.line_descent - 2 * s - event_row_of[e] * event_row;
    font.draw(img, figure.events[e].label, a, baseline, event_style);
  }
  return img;
}

}  // namespace stiction::plot
