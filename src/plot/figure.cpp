#include "plot/figure.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <memory>
#include <stdexcept>

#include "image/png.hpp"
#include "io/atomic_file.hpp"
#include "plot/cairo_font.hpp"
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
constexpr Rgba kSlipEvent{178, 34, 34, 255};
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

struct Stroke {
  Rgba colour{0, 0, 0, 255};
  double width = 2.0;
  std::vector<double> dash;  // pixels; empty: solid
};

struct Extent {
  double width = 0.0;                            // advance
  double ascent = 0.0;                           // of the glyphs present (ink)
  double line_ascent = 0.0, line_descent = 0.0;  // the font's, at this size
};

// Drawing and measuring through one cairo context, recording every text box it draws.
class Painter {
 public:
  Painter(cairo_t* cr, const CairoFont& font, FigureLayout& layout) : cr_(cr), layout_(layout) {
    cairo_set_font_face(cr_, font.face());
    cairo_font_options_t* options = cairo_font_options_create();
    // Unhinted metrics: the same advances on every surface, so PNG, SVG and PDF lay out alike.
    cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_SLIGHT);
    cairo_font_options_set_antialias(options, CAIRO_ANTIALIAS_GRAY);
    cairo_set_font_options(cr_, options);
    cairo_font_options_destroy(options);
    cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  }

  Extent measure(const std::string& text, double size) {
    cairo_set_font_size(cr_, size);
    cairo_font_extents_t font;
    cairo_font_extents(cr_, &font);
    cairo_text_extents_t ink;
    cairo_text_extents(cr_, text.c_str(), &ink);
    return {ink.x_advance, -ink.y_bearing, font.ascent, font.descent};
  }

  // Text at the pen origin (x, baseline); rotated: reads bottom to top, the pen origin at the
  // bottom end of the baseline. Returns the recorded box.
  Rect text(const std::string& s, double x, double baseline, double size, Rgba colour,
            TextRole role, int panel, bool rotated = false) {
    const Extent e = measure(s, size);
    set_colour(colour);
    cairo_save(cr_);
    cairo_translate(cr_, x, baseline);
    if (rotated) cairo_rotate(cr_, -0.5 * std::acos(-1.0));
    cairo_move_to(cr_, 0.0, 0.0);
    cairo_show_text(cr_, s.c_str());
    cairo_new_path(cr_);
    cairo_restore(cr_);
    const Rect box =
        rotated ? Rect{x - e.line_ascent, baseline - e.width, x + e.line_descent, baseline}
                : Rect{x, baseline - e.line_ascent, x + e.width, baseline + e.line_descent};
    layout_.texts.push_back({s, role, box, panel});
    return box;
  }

  // Stroked in pieces of at most kPiece segments: cairo's stroker holds the polygon of the
  // whole path it strokes, and a dense series that swings across its panel (a quaternion
  // over a long run) took over 100 MB in one stroke. Each piece starts where the last one
  // ended, its dash pattern carried on (cairo restarts the pattern at every sub-path).
  void polyline(const std::vector<Point>& points, const Stroke& stroke) {
    constexpr int kPiece = 512;
    apply(stroke);
    bool open = false;
    int segments = 0;
    double along = 0.0;  // length since the sub-path began, for the dash offset
    Point last{};
    for (const Point& p : points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
        open = false;
        continue;
      }
      if (!open) {
        cairo_move_to(cr_, p.x, p.y);
        open = true;
        along = 0.0;
      } else {
        cairo_line_to(cr_, p.x, p.y);
        along += std::hypot(p.x - last.x, p.y - last.y);
        if (++segments == kPiece) {
          cairo_stroke(cr_);
          segments = 0;
          set_dash_offset(stroke, along);
          cairo_move_to(cr_, p.x, p.y);
        }
      }
      last = p;
    }
    cairo_stroke(cr_);
  }
  void line(Point a, Point b, const Stroke& stroke) { polyline({a, b}, stroke); }
  void fill_rect(const Rect& r, Rgba colour) {
    cairo_rectangle(cr_, r.x0, r.y0, r.width(), r.height());
    set_colour(colour);
    cairo_fill(cr_);
  }
  void stroke_rect(const Rect& r, const Stroke& stroke) {
    cairo_rectangle(cr_, r.x0, r.y0, r.width(), r.height());
    apply(stroke);
    cairo_stroke(cr_);
  }
  void clip(const Rect& r) {
    cairo_save(cr_);
    cairo_rectangle(cr_, r.x0, r.y0, r.width(), r.height());
    cairo_clip(cr_);
  }
  void unclip() { cairo_restore(cr_); }

 private:
  void set_colour(Rgba c) {
    cairo_set_source_rgba(cr_, c.r / 255.0, c.g / 255.0, c.b / 255.0, c.a / 255.0);
  }
  void apply(const Stroke& stroke) {
    set_colour(stroke.colour);
    cairo_set_line_width(cr_, stroke.width);
    set_dash_offset(stroke, 0.0);
  }
  void set_dash_offset(const Stroke& stroke, double offset) {
    // A dot is an "on" length of zero with round caps; cairo drops such pieces between
    // longer dashes, so they get a length too small to see.
    std::vector<double> dash = stroke.dash;
    for (std::size_t i = 0; i < dash.size(); i += 2) dash[i] = std::max(dash[i], 0.01);
    cairo_set_dash(cr_, dash.empty() ? nullptr : dash.data(), static_cast<int>(dash.size()),
                   offset);
  }

  cairo_t* cr_;
  FigureLayout& layout_;
};

// Byte offsets where UTF-8 code points start.
std::vector<std::size_t> code_point_starts(const std::string& s) {
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if ((static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) starts.push_back(i);
  }
  return starts;
}

// The text itself if it fits in max_width, else its beginning and end around "…", as long as
// fits (a third from the beginning, two thirds from the end: long names differ at either end,
// a component and a signal, a run and its axis, and more often at the end).
std::string fit(Painter& painter, const std::string& text, double size, double max_width) {
  if (painter.measure(text, size).width <= max_width) return text;
  const std::vector<std::size_t> starts = code_point_starts(text);
  const int n = static_cast<int>(starts.size());
  auto shortened = [&](int keep) {
    const int head = (keep + 2) / 3, tail = keep - head;  // the end tells names apart more often
    return text.substr(0, head < n ? starts[head] : text.size()) + "\u2026" +
           text.substr(tail > 0 ? starts[n - tail] : text.size());
  };
  int lo = 0, hi = n - 1;  // largest `keep` that fits, by bisection
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (painter.measure(shortened(mid), size).width <= max_width) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return shortened(lo);
}

// Splits text into lines no longer than max_width, breaking at spaces; the bracketed unit
// part moves to its own line first. A word longer than a line is shortened with "…".
std::vector<std::string> wrap(Painter& painter, const std::string& text, double max_width,
                              double size, std::size_t max_lines) {
  if (painter.measure(text, size).width <= max_width) return {text};
  // Words end at spaces; a long name also breaks after '_' and '.' (the break is marked by
  // the character itself staying at the end of the line: "joint0_" / "friction.tau").
  std::vector<std::string> words;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) words.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  std::vector<std::string> pieces;
  for (const std::string& w : words) {
    if (w.front() == '[' || painter.measure(w, size).width <= max_width) {
      pieces.push_back(w);
      continue;
    }
    std::size_t from = 0;
    for (std::size_t i = 0; i < w.size(); ++i) {
      if ((w[i] == '_' || w[i] == '.') && i + 1 < w.size()) {
        pieces.push_back(w.substr(from, i + 1 - from) + "\x01");  // \x01: no space after
        from = i + 1;
      }
    }
    pieces.push_back(w.substr(from));
  }
  words = std::move(pieces);
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
  auto joined = [](const std::string& a, const std::string& b) {
    if (a.empty()) return b;
    if (a.back() == '\x01') return a.substr(0, a.size() - 1) + b;
    return a + " " + b;
  };
  for (const std::string& g : groups) {
    const std::string candidate = joined(current, g);
    const bool unit = g.front() == '[';
    if (!current.empty() && (unit || painter.measure(candidate, size).width > max_width)) {
      lines.push_back(current);
      current = g;
    } else {
      current = candidate;
    }
  }
  if (!current.empty()) lines.push_back(current);
  // Too many lines: the unit line stays, the words before it join into one shortened line.
  if (lines.size() > max_lines && max_lines >= 2) {
    const bool unit_last = lines.back().front() == '[';
    std::string rest;
    const std::size_t keep = max_lines - (unit_last ? 2 : 1);  // lines kept as they are
    for (std::size_t i = keep; i + (unit_last ? 1 : 0) < lines.size(); ++i) {
      rest = joined(rest, lines[i]);
    }
    std::vector<std::string> merged(lines.begin(), lines.begin() + static_cast<long>(keep));
    merged.push_back(rest);
    if (unit_last) merged.push_back(lines.back());
    lines = std::move(merged);
  }
  for (std::string& line : lines) {
    if (!line.empty() && line.back() == '\x01') line.pop_back();
    std::erase(line, '\x01');
    line = fit(painter, line, size, max_width);
  }
  return lines;
}

// A panel's legend: entries, their (possibly shortened) labels and the box size.
struct Legend {
  std::vector<int> entries;  // series indices, then -1 - k for reference line k
  std::vector<std::string> labels;
  double size = 0.0;  // font size
  double width = 0.0, height = 0.0, row = 0.0, sample = 0.0, pad = 0.0, column = 0.0;
  int columns = 1, rows = 0;
  bool outside = false;
};

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
    if (L.columns == 1 || L.size < 0.76 * m.legend()) break;
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

LineStyle reference_style() { return LineStyle{kEvent, {5, 4}, 2.0}; }

Stroke event_stroke(const std::string& kind, double s) {
  if (kind == "slip") return Stroke{kSlipEvent, 2.0 * s, {14 * s, 5 * s, 2 * s, 5 * s}};
  return Stroke{kEvent, 2.0 * s, {9 * s, 6 * s}};
}
Rgba event_colour(const std::string& kind) { return kind == "slip" ? kSlipEvent : kEvent; }

constexpr int kMaxEventRows = 3;

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

std::optional<Format> parse_format(const std::string& name) {
  std::string lower;
  for (char c : name) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "png") return Format::png;
  if (lower == "svg") return Format::svg;
  if (lower == "pdf") return Format::pdf;
  return std::nullopt;
}

const char* extension(Format format) {
  switch (format) {
    case Format::svg:
      return ".svg";
    case Format::pdf:
      return ".pdf";
    case Format::png:
      break;
  }
  return ".png";
}

FigureLayout draw(const Figure& figure, cairo_t* cr) {
  if (figure.width < 200 || figure.height < 150 || figure.width > 16384 || figure.height > 16384) {
    throw std::invalid_argument("figure size must be between 200x150 and 16384x16384 pixels");
  }
  FigureLayout layout;
  layout.width = figure.width;
  layout.height = figure.height;
  const CairoFont font = CairoFont::open_default();
  Painter painter(cr, font, layout);
  painter.fill_rect(
      Rect{0, 0, static_cast<double>(figure.width), static_cast<double>(figure.height)}, kWhite);
  const Metrics m{std::min(figure.width / 1600.0, figure.height / 1000.0)};
  const double s = m.s;

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
  const Extent tick_extent = painter.measure("0123456789", m.tick());
  const Extent label_extent = painter.measure("Hg[]", m.label());
  const Extent event_extent = painter.measure("Hg", m.event());
  const double label_line = label_extent.line_ascent + label_extent.line_descent;
  const double margin_width = figure.width - 2 * m.margin();
  // The title: shrunk to 70% if need be, then shortened.
  double title_size = m.title();
  std::string title = figure.title;
  while (!title.empty() && painter.measure(title, title_size).width > margin_width &&
         title_size > 0.7 * m.title()) {
    title_size *= 0.95;
  }
  title = fit(painter, title, title_size, margin_width);
  const Extent title_extent = painter.measure("Hg", title_size);
  double top = m.margin();
  double title_baseline = 0.0;
  if (!title.empty()) {
    title_baseline = top + title_extent.line_ascent;
    top = title_baseline + title_extent.line_descent + 14 * s;
  }
  const std::size_t event_count = figure.events.size();
  // Event labels, shortened in the middle to at most 45% of the width (long element names).
  std::vector<std::string> event_text;
  for (const EventMarker& e : figure.events) {
    event_text.push_back(fit(painter, e.label, m.event(), 0.45 * margin_width));
  }
  // Many events: full-height lines would hide the data; they become marks along the top and
  // bottom edge of each panel.
  const bool event_rug = event_count > 12;
  const double event_row = event_extent.line_ascent + event_extent.line_descent + 4 * s;
  int event_rows = event_count == 0 ? 0 : 1;

  const double bottom_reserved = m.margin() + label_line + 8 * s + tick_extent.line_ascent +
                                 tick_extent.line_descent + m.tick_length() + 4 * s;
  const std::size_t n_panels = std::max<std::size_t>(1, figure.panels.size());
  // Captions sit above their panel, in a taller gap.
  const bool captions = std::any_of(figure.panels.begin(), figure.panels.end(),
                                    [](const Panel& p) { return !p.caption.empty(); });
  const Extent caption_extent = painter.measure("Hg", m.event());
  const double caption_line =
      captions ? caption_extent.line_ascent + caption_extent.line_descent + 6 * s : 0.0;
  // Log axes (and fixed ranges) put labelled ticks on the frame's edges: the gap then leaves
  // room for a tick label above and one below.
  const bool edge_ticks = std::any_of(figure.panels.begin(), figure.panels.end(),
                                      [](const Panel& p) { return p.log || (p.y_min && p.y_max); });
  const double tick_line = tick_extent.line_ascent + tick_extent.line_descent;
  const double gap = (edge_ticks ? std::max(26 * s, tick_line + 4 * s) : 26 * s) + caption_line;
  const Panel empty_panel;
  auto panel_at = [&](std::size_t p) -> const Panel& {
    return p < figure.panels.size() ? figure.panels[p] : empty_panel;
  };

  // Event kinds and the key that explains their line styles (used when not every event gets
  // a label).
  std::vector<std::string> kinds;
  for (const EventMarker& e : figure.events) {
    const std::string kind = e.kind.empty() ? "event" : e.kind;
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) kinds.push_back(kind);
  }
  const double key_sample = 30 * s;
  double key_width = 0.0;
  for (const std::string& k : kinds) {
    key_width += key_sample + 6 * s + painter.measure(k, m.event()).width + 16 * s;
  }

  // Passes: the layout depends on itself (left margin <- tick labels <- panel height <- event
  // rows <- horizontal mapping <- margins; legends beside the axes move the right edge).
  double left = 0.0, right = 0.0;
  std::vector<Rect> frames;
  std::vector<YAxis> y_axes;
  std::vector<std::vector<std::string>> y_titles;
  std::vector<double> y_title_size;
  std::vector<int> event_row_of(event_count, -1);  // -1: unlabelled
  bool with_key = false;
  std::vector<Legend> legends(n_panels);
  std::vector<bool> outside(n_panels, false);
  Ticks x_ticks;
  TickLabels x_labels;
  std::vector<std::vector<std::vector<Point>>> lines(n_panels);
  for (int pass = 0; pass < 4; ++pass) {
    const double panels_top =
        top + event_rows * event_row + (event_rows ? 6 * s : 0.0) + caption_line;
    const double panels_bottom = figure.height - bottom_reserved;
    const double panel_h = std::max(
        10.0, (panels_bottom - panels_top - gap * (n_panels - 1)) / static_cast<double>(n_panels));
    const int y_target = std::clamp(static_cast<int>(panel_h / (58 * s)), 2, 8);
    y_axes.clear();
    y_titles.clear();
    y_title_size.clear();
    double tick_width = 0.0;
    std::size_t max_lines = 1;
    for (std::size_t p = 0; p < n_panels; ++p) {
      YAxis y = make_y_axis(panel_at(p), x_lo, x_hi, y_target);
      for (const TickMark& t : y.ticks) {
        if (!t.label.empty())
          tick_width = std::max(tick_width, painter.measure(t.label, m.tick()).width);
      }
      // A smaller font (down to 70%) before any word is shortened.
      const std::string y_title = axis_title(panel_at(p).label, panel_at(p).unit, y.exponent);
      double size = m.label();
      std::vector<std::string> lines;
      for (;; size *= 0.9) {
        lines = wrap(painter, y_title, 0.96 * panel_h, size, 3);
        const bool shortened = std::any_of(lines.begin(), lines.end(), [&](const std::string& l) {
          return l.find("\u2026") != std::string::npos &&
                 y_title.find("\u2026") == std::string::npos;
        });
        if (!shortened || size < 0.72 * m.label()) break;
      }
      y_titles.push_back(lines);
      y_title_size.push_back(size);
      max_lines = std::max(max_lines, y_titles.back().size());
      y_axes.push_back(std::move(y));
    }
    left = m.margin() + max_lines * label_line + 10 * s + tick_width + m.tick_length() + 2 * s;

    // Horizontal ticks: as many as fit without their labels touching.
    double outside_width = 0.0;
    for (std::size_t p = 0; p < n_panels; ++p) {
      if (outside[p]) outside_width = std::max(outside_width, legends[p].width + 16 * s);
    }
    for (int x_target = std::max(3, static_cast<int>(figure.width / (190 * s)));; --x_target) {
      const Ticks loose = nice_ticks(x_lo, x_hi, x_target);
      x_ticks = loose;
      x_ticks.values.clear();
      for (double v : loose.values) {
        if (in_range(v, x_lo, x_hi)) x_ticks.values.push_back(v);
      }
      if (x_ticks.values.empty()) x_ticks.values = {x_lo, x_hi};
      x_ticks.lo = x_ticks.values.front();
      x_ticks.hi = x_ticks.values.back();
      x_labels = format_ticks(x_ticks);
      right = figure.width - outside_width -
              std::max(m.margin() + 10 * s,
                       0.5 * painter.measure(x_labels.labels.back(), m.tick()).width + m.margin());
      const Axis probe{x_lo, x_hi, false, left, right};
      bool crowded = false;
      for (std::size_t i = 1; i < x_ticks.values.size(); ++i) {
        const double room = probe.map(x_ticks.values[i]) - probe.map(x_ticks.values[i - 1]);
        const double need = 0.5 * (painter.measure(x_labels.labels[i], m.tick()).width +
                                   painter.measure(x_labels.labels[i - 1], m.tick()).width) +
                            0.8 * m.tick();
        if (room < need) crowded = true;
      }
      if (!crowded || x_target <= 2) break;
    }

    frames.clear();
    for (std::size_t p = 0; p < n_panels; ++p) {
      const double y0 = panels_top + p * (panel_h + gap);
      frames.push_back(
          Rect{std::round(left), std::round(y0), std::round(right), std::round(y0 + panel_h)});
    }
    const Axis x_axis{x_lo, x_hi, false, frames[0].x0, frames[0].x1};

    // Legends: inside where the least data is; beside the axes when data is everywhere.
    bool moved = false;
    for (std::size_t p = 0; p < n_panels; ++p) {
      const Rect& f = frames[p];
      YAxis& y = y_axes[p];
      y.axis.p0 = f.y1;
      y.axis.p1 = f.y0;
      lines[p].clear();
      for (const Series& series : panel_at(p).series)
        lines[p].push_back(to_pixels(series, x_axis, y.axis));
      const double inside_width = 0.6 * f.width(), inside_height = f.height() - 28 * s;
      if (!outside[p]) {
        legends[p] = make_legend(panel_at(p), painter, m, inside_width, inside_height);
        if (legends[p].entries.empty()) continue;
        const Legend& L = legends[p];
        double best = std::numeric_limits<double>::infinity();
        const double inset = 14 * s;
        const double cx = 0.5 * (f.x0 + f.x1 - L.width);
        for (const Rect& c : std::array<Rect, 6>{{
                 {f.x1 - inset - L.width, f.y0 + inset, f.x1 - inset, f.y0 + inset + L.height},
                 {f.x0 + inset, f.y0 + inset, f.x0 + inset + L.width, f.y0 + inset + L.height},
                 {f.x1 - inset - L.width, f.y1 - inset - L.height, f.x1 - inset, f.y1 - inset},
                 {f.x0 + inset, f.y1 - inset - L.height, f.x0 + inset + L.width, f.y1 - inset},
                 {cx, f.y0 + inset, cx + L.width, f.y0 + inset + L.height},
                 {cx, f.y1 - inset - L.height, cx + L.width, f.y1 - inset},
             }}) {
          best = std::min(best, occupancy(lines[p], c));
        }
        const bool too_big = L.columns > 1 || L.height > inside_height;
        if (best > 0.0 || too_big) {
          outside[p] = true;
          moved = true;
        }
      }
      if (outside[p]) {
        const double room = figure.width - m.margin() - (f.x1 + 16 * s);
        legends[p] = make_legend(panel_at(p), painter, m, std::max(room, 0.3 * figure.width),
                                 f.height() + gap - 4 * s);
        legends[p].outside = true;
      }
    }

    // Rows for event labels, centred on their lines, no overlaps within a row; the key of the
    // line styles takes the right end of the first row when some label does not fit.
    auto place_events = [&](bool key) {
      std::vector<std::vector<std::pair<double, double>>> rows(1);
      if (key)
        rows[0].push_back({figure.width - m.margin() - key_width, figure.width - m.margin()});
      std::vector<int> row_of(event_count, -1);
      bool all = true;
      std::vector<std::size_t> order(event_count);
      for (std::size_t e = 0; e < event_count; ++e) order[e] = e;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return figure.events[a].x < figure.events[b].x;
      });
      for (std::size_t e : order) {
        const double cx = x_axis.map(figure.events[e].x);
        if (!std::isfinite(cx) || cx < frames[0].x0 - 1 || cx > frames[0].x1 + 1) continue;
        const double w = painter.measure(event_text[e], m.event()).width;
        const double a = std::clamp(cx - 0.5 * w, m.margin(), figure.width - m.margin() - w);
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
            all = false;
            continue;
          }
          rows.emplace_back();
        }
        rows[row].push_back({a, b});
        row_of[e] = static_cast<int>(row);
      }
      event_row_of = row_of;
      return std::make_pair(all, static_cast<int>(event_count == 0 ? 0 : rows.size()));
    };
    auto [all_labelled, needed] = place_events(false);
    with_key = !all_labelled;
    if (with_key) needed = place_events(true).second;
    if (needed == event_rows && !moved) break;
    event_rows = needed;
  }

  const Axis x_axis{x_lo, x_hi, false, frames[0].x0, frames[0].x1};

  // ---- Title.
  if (!title.empty()) {
    const double w = painter.measure(title, title_size).width;
    const double cx = 0.5 * (frames[0].x0 + frames[0].x1);
    painter.text(title, std::clamp(cx - 0.5 * w, m.margin(), figure.width - w - m.margin()),
                 title_baseline, title_size, kText, TextRole::title, -1);
  }

  const Stroke frame_stroke{kFrame, m.frame_width(), {}};
  const Stroke grid_stroke{kGrid, m.grid_width(), {}};
  const Stroke minor_stroke{kMinorGrid, m.grid_width(), {}};
  std::vector<Rect> tick_label_boxes;  // of every panel: thinned so that none touch
  // The horizontal tick labels under the bottom panel come first: a y label at the bottom
  // corner gives way to the "0.0" of the time axis.
  const double tick_baseline = frames.back().y1 + m.tick_length() + tick_extent.line_ascent;
  for (std::size_t i = 0; i < x_ticks.values.size(); ++i) {
    const double px = std::round(x_axis.map(x_ticks.values[i])) + 0.5;
    const double w = painter.measure(x_labels.labels[i], m.tick()).width;
    tick_label_boxes.push_back(Rect{px - 0.5 * w - 2 * s, tick_baseline - tick_extent.line_ascent,
                                    px + 0.5 * w + 2 * s,
                                    tick_baseline + tick_extent.line_descent});
  }

  for (std::size_t p = 0; p < n_panels; ++p) {
    const Panel& panel = panel_at(p);
    const Rect& f = frames[p];
    const YAxis& y = y_axes[p];
    const int pi = static_cast<int>(p);
    layout.panels.push_back(f);

    // Grid.
    for (const TickMark& t : y.ticks) {
      const double py = std::round(y.axis.map(t.value)) + 0.5;
      painter.line({f.x0, py}, {f.x1, py}, t.label.empty() ? minor_stroke : grid_stroke);
    }
    for (double v : x_ticks.values) {
      const double px = std::round(x_axis.map(v)) + 0.5;
      painter.line({px, f.y0}, {px, f.y1}, grid_stroke);
    }
    // Events.
    for (const EventMarker& e : figure.events) {
      const double px = x_axis.map(e.x);
      if (!std::isfinite(px) || px < f.x0 || px > f.x1) continue;
      if (event_rug) {
        Stroke mark = event_stroke(e.kind, s);
        mark.dash.clear();
        const double len = std::min(24 * s, 0.2 * f.height());
        painter.line({px, f.y0}, {px, f.y0 + len}, mark);
        painter.line({px, f.y1 - len}, {px, f.y1}, mark);
      } else {
        painter.line({px, f.y0}, {px, f.y1}, event_stroke(e.kind, s));
      }
    }
    // Reference lines under the data.
    const Stroke reference_stroke = make_stroke(reference_style(), s);
    for (const ReferenceLine& r : panel.references) {
      const double py = y.axis.map(r.y);
      if (!std::isfinite(py) || py < f.y0 || py > f.y1) continue;
      painter.line({f.x0, py}, {f.x1, py}, reference_stroke);
    }
    // Data, clipped to the frame.
    painter.clip(f);
    for (std::size_t i = 0; i < panel.series.size(); ++i) {
      const Series& series = panel.series[i];
      const LineStyle style = series.style ? *series.style : series_style(static_cast<int>(i));
      painter.polyline(lines[p][i], make_stroke(style, s));
      layout.series.push_back(series.source.empty() ? series.label : series.source);
    }
    painter.unclip();
    // Frame and ticks.
    const Rect crisp{f.x0 + 0.5, f.y0 + 0.5, f.x1 - 0.5, f.y1 - 0.5};
    painter.stroke_rect(crisp, frame_stroke);
    for (const TickMark& t : y.ticks) {
      const double py = std::round(y.axis.map(t.value)) + 0.5;
      const double len = t.label.empty() ? 0.55 * m.tick_length() : m.tick_length();
      painter.line({f.x0, py}, {f.x0 + len, py}, frame_stroke);
      painter.line({f.x1 - len, py}, {f.x1, py}, frame_stroke);
      if (t.label.empty()) continue;
      const double w = painter.measure(t.label, m.tick()).width;
      const double baseline = py + 0.5 * tick_extent.ascent;
      const Rect box{f.x0 - m.tick_length() - w, baseline - tick_extent.line_ascent - 1 * s,
                     f.x0 - m.tick_length(), baseline + tick_extent.line_descent + 1 * s};
      if (std::any_of(tick_label_boxes.begin(), tick_label_boxes.end(),
                      [&](const Rect& r) { return r.overlaps(box); })) {
        continue;  // the tick stays, its label would touch a neighbour's
      }
      tick_label_boxes.push_back(box);
      painter.text(t.label, box.x0, baseline, m.tick(), kText, TextRole::tick_label, pi);
    }
    for (double v : x_ticks.values) {
      const double px = std::round(x_axis.map(v)) + 0.5;
      painter.line({px, f.y1 - m.tick_length()}, {px, f.y1}, frame_stroke);
      painter.line({px, f.y0}, {px, f.y0 + m.tick_length()}, frame_stroke);
    }
    // Vertical axis title, centred on the panel, one rotated line per wrapped line.
    const std::vector<std::string>& title_lines = y_titles[p];
    for (std::size_t k = 0; k < title_lines.size(); ++k) {
      const double size = y_title_size[p], shrink = size / m.label();
      const double w = painter.measure(title_lines[k], size).width;
      const double baseline_x = m.margin() + shrink * (label_extent.line_ascent + k * label_line);
      painter.text(title_lines[k], baseline_x, 0.5 * (f.y0 + f.y1) + 0.5 * w, size, kText,
                   TextRole::axis_label, pi, true);
    }
    // Caption, left-aligned above the frame.
    if (!panel.caption.empty()) {
      painter.text(fit(painter, panel.caption, m.event(), f.width()), f.x0,
                   f.y0 - 5 * s - caption_extent.line_descent, m.event(), kText, TextRole::note,
                   pi);
    }
    // Legend.
    const Legend& L = legends[p];
    if (L.entries.empty()) continue;
    Rect box;
    if (L.outside) {
      box = Rect{f.x1 + 16 * s, f.y0, f.x1 + 16 * s + L.width, f.y0 + L.height};
    } else {
      const double inset = 14 * s;
      const double cx = 0.5 * (f.x0 + f.x1 - L.width);
      const std::array<Rect, 6> corners{{
          {f.x1 - inset - L.width, f.y0 + inset, f.x1 - inset, f.y0 + inset + L.height},
          {f.x0 + inset, f.y0 + inset, f.x0 + inset + L.width, f.y0 + inset + L.height},
          {f.x1 - inset - L.width, f.y1 - inset - L.height, f.x1 - inset, f.y1 - inset},
          {f.x0 + inset, f.y1 - inset - L.height, f.x0 + inset + L.width, f.y1 - inset},
          {cx, f.y0 + inset, cx + L.width, f.y0 + inset + L.height},
          {cx, f.y1 - inset - L.height, cx + L.width, f.y1 - inset},
      }};
      box = corners[0];
      double best = std::numeric_limits<double>::infinity();
      for (const Rect& c : corners) {
        const double occ = occupancy(lines[p], c);
        if (occ < best - 0.5) {
          best = occ;
          box = c;
        }
      }
    }
    box = Rect{std::round(box.x0), std::round(box.y0), std::round(box.x1), std::round(box.y1)};
    layout.legends.push_back(box);
    layout.legend_outside.push_back(L.outside);
    painter.fill_rect(box, kLegendBox);
    painter.stroke_rect(Rect{box.x0 + 0.5, box.y0 + 0.5, box.x1 - 0.5, box.y1 - 0.5},
                        Stroke{kLegendFrame, std::max(1.0, 1.2 * s), {}});
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
      painter.line({x0, cy}, {x0 + L.sample, cy}, make_stroke(style, s));
      painter.text(L.labels[k], x0 + L.sample + 12 * s,
                   cy + 0.5 * (le.line_ascent - le.line_descent) - 1 * s, L.size, kText,
                   TextRole::legend_entry, pi);
    }
  }

  // ---- Horizontal tick labels and axis title under the bottom panel.
  const Rect& bottom = frames.back();
  for (std::size_t i = 0; i < x_ticks.values.size(); ++i) {
    const double px = std::round(x_axis.map(x_ticks.values[i])) + 0.5;
    const double w = painter.measure(x_labels.labels[i], m.tick()).width;
    painter.text(x_labels.labels[i], px - 0.5 * w, tick_baseline, m.tick(), kText,
                 TextRole::tick_label, static_cast<int>(n_panels) - 1);
  }
  const std::string x_title =
      fit(painter, axis_title(figure.x_label, figure.x_unit, x_labels.exponent), m.label(),
          bottom.width());
  const double xw = painter.measure(x_title, m.label()).width;
  painter.text(x_title, 0.5 * (bottom.x0 + bottom.x1) - 0.5 * xw,
               tick_baseline + tick_extent.line_descent + 8 * s + label_extent.line_ascent,
               m.label(), kText, TextRole::axis_label, -1);

  // ---- Event labels above the top panel (row 0 right above it, later rows above that).
  const double rows_bottom = frames[0].y0 - 6 * s - caption_line;
  auto row_baseline = [&](int row) {
    return rows_bottom - event_extent.line_descent - 2 * s - row * event_row;
  };
  for (std::size_t e = 0; e < event_count; ++e) {
    if (event_row_of[e] < 0) continue;
    const double w = painter.measure(event_text[e], m.event()).width;
    const double cx = x_axis.map(figure.events[e].x);
    const double a = std::clamp(cx - 0.5 * w, m.margin(), figure.width - m.margin() - w);
    painter.text(event_text[e], a, row_baseline(event_row_of[e]), m.event(),
                 event_colour(figure.events[e].kind), TextRole::event_label, -1);
  }
  if (with_key) {
    double x = figure.width - m.margin() - key_width;
    const double baseline = row_baseline(0);
    const double cy = baseline - 0.35 * event_extent.line_ascent;
    for (const std::string& k : kinds) {
      Stroke sample = event_stroke(k, s);
      if (event_rug) sample.dash.clear();
      painter.line({x, cy}, {x + key_sample, cy}, sample);
      x += key_sample + 6 * s;
      x = painter.text(k, x, baseline, m.event(), event_colour(k), TextRole::note, -1).x1 + 16 * s;
    }
  }
  return layout;
}

namespace {

image::Image to_image(cairo_surface_t* surface) {
  cairo_surface_flush(surface);
  const int w = cairo_image_surface_get_width(surface), h = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  image::Image img(w, h);
  for (int y = 0; y < h; ++y) {
    const auto* row =
        reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(y) * stride);
    for (int x = 0; x < w; ++x) {
      // Premultiplied ARGB in native byte order; the figure is opaque (white background).
      const std::uint32_t p = row[x];
      img.set(x, y,
              Rgba{static_cast<std::uint8_t>(p >> 16), static_cast<std::uint8_t>(p >> 8),
                   static_cast<std::uint8_t>(p), 255});
    }
  }
  return img;
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// Draws into a vector surface writing into `bytes`, scaled from pixels by `scale`.
FigureLayout draw_vector(const Figure& figure, cairo_surface_t* surface, double scale) {
  ContextPtr cr(cairo_create(surface));
  cairo_scale(cr.get(), scale, scale);
  FigureLayout layout = draw(figure, cr.get());
  cr.reset();
  cairo_surface_finish(surface);
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    throw io::IoError(std::string("cairo: ") +
                      cairo_status_to_string(cairo_surface_status(surface)));
  }
  return layout;
}

}  // namespace

image::Image render(const Figure& figure, FigureLayout* layout) {
  if (figure.width < 200 || figure.height < 150 || figure.width > 16384 || figure.height > 16384) {
    throw std::invalid_argument("figure size must be between 200x150 and 16384x16384 pixels");
  }
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, figure.width, figure.height));
  ContextPtr cr(cairo_create(surface.get()));
  FigureLayout drawn = draw(figure, cr.get());
  cr.reset();
  if (layout) *layout = std::move(drawn);
  return to_image(surface.get());
}

image::Image render(const Figure& figure, text::Font& /*font*/) { return render(figure, nullptr); }

FigureLayout write_figure(const Figure& figure, const std::filesystem::path& path, Format format,
                          double dpi) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  if (format == Format::png) {
    FigureLayout layout;
    const image::Image img = render(figure, &layout);
    image::write_png(path, img, image::PngSpeed::small, dpi);
    return layout;
  }
  std::string bytes;
  FigureLayout layout;
  if (format == Format::svg) {
    // One user unit per pixel; the document says "px" so viewers show it at its pixel size.
    SurfacePtr surface(
        cairo_svg_surface_create_for_stream(append_to_string, &bytes, figure.width, figure.height));
    cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PX);
    layout = draw_vector(figure, surface.get(), 1.0);
  } else {
    // The page is the figure's size at `dpi`: 1600 px at 100 dpi is 16 in (1152 pt) wide.
    const double scale = 72.0 / (dpi > 0.0 ? dpi : 100.0);
    SurfacePtr surface(cairo_pdf_surface_create_for_stream(
        append_to_string, &bytes, figure.width * scale, figure.height * scale));
    // Reproducible files: the creation date comes from SOURCE_DATE_EPOCH when it is set.
    if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
      const std::time_t t = static_cast<std::time_t>(std::strtoll(epoch, nullptr, 10));
      char date[32];
      std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%S", std::gmtime(&t));
      cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, date);
    }
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "stiction");
    layout = draw_vector(figure, surface.get(), scale);
  }
  io::write_file_atomically(path, bytes);
  return layout;
}

}  // namespace stiction::plot
