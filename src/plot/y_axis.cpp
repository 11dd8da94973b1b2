#include "plot/y_axis.hpp"

#include <algorithm>

#include "plot/text_fit.hpp"
#include "plot/ticks.hpp"

namespace stiction::plot {

double Axis::map(double v) const {
  double u = v;
  if (log) u = v > 0.0 ? std::log10(v) : std::numeric_limits<double>::quiet_NaN();
  const double p = p0 + (u - lo) / (hi - lo) * (p1 - p0);
  if (!std::isfinite(p)) return std::numeric_limits<double>::quiet_NaN();
  return std::clamp(p, -1e6, 1e6);
}

bool in_range(double v, double lo, double hi) {
  const double eps = (hi - lo) * 1e-9;
  return v >= lo - eps && v <= hi + eps;
}

std::string superscript(int value) {
  static const char* const digits[] = {"\u2070", "\u00B9", "\u00B2", "\u00B3", "\u2074",
                                       "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::string out = value < 0 ? "\u207B" : "";
  const std::string plain = std::to_string(std::abs(value));
  for (char c : plain) out += digits[c - '0'];
  return out;
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

YTitle fit_y_title(Painter& painter, const std::string& title, double panel_height,
                   double full_size, double floor, std::size_t max_lines) {
  const FittedText fitted =
      fit_text(painter, title, TextRule{full_size, floor, 0.96 * panel_height, max_lines});
  return YTitle{fitted.lines, fitted.size, title, fitted.shortened};
}

void label_minor_ticks(YAxis& y) {
  if (!y.axis.log) return;
  for (TickMark& t : y.ticks) {
    if (!t.label.empty() || !(t.value > 0.0)) continue;
    const int exponent = static_cast<int>(std::floor(std::log10(t.value) + 1e-9));
    const double mantissa = t.value / std::pow(10.0, exponent);
    for (int shown : {2, 5}) {
      if (std::abs(mantissa - shown) < 1e-6) {
        t.label = std::to_string(shown) + "\u00D710" + superscript(exponent);
      }
    }
  }
}

std::vector<YLabel> select_y_labels(Painter& painter, const YAxis& y, const Rect& f,
                                    const Metrics& m, std::vector<Rect>& taken) {
  const Extent digits = painter.measure("0123456789", m.tick());
  std::vector<YLabel> labels;
  for (std::size_t i = 0; i < y.ticks.size(); ++i) {
    const TickMark& t = y.ticks[i];
    if (t.label.empty()) continue;
    const double py = std::round(y.axis.map(t.value)) + 0.5;
    if (!std::isfinite(py) || py < f.y0 - 1 || py > f.y1 + 1) continue;
    const double w = painter.measure(t.label, m.tick()).width;
    const double baseline = py + 0.5 * digits.ascent;
    const Rect box{f.x0 - m.tick_length() - w, baseline - digits.line_ascent - 1 * m.s,
                   f.x0 - m.tick_length(), baseline + digits.line_descent + 1 * m.s};
    if (std::any_of(taken.begin(), taken.end(), [&](const Rect& r) { return r.overlaps(box); })) {
      continue;  // the tick stays, its label would touch a neighbour's
    }
    taken.push_back(box);
    labels.push_back({i, box, baseline});
  }
  return labels;
}

void draw_y_ticks(Painter& painter, const YAxis& y, const Rect& f, const Metrics& m,
                  const Stroke& stroke, const std::vector<YLabel>& labels, int panel_index) {
  for (const TickMark& t : y.ticks) {
    const double py = std::round(y.axis.map(t.value)) + 0.5;
    if (!std::isfinite(py)) continue;
    const double len = t.label.empty() ? 0.55 * m.tick_length() : m.tick_length();
    painter.line({f.x0, py}, {f.x0 + len, py}, stroke);
    painter.line({f.x1 - len, py}, {f.x1, py}, stroke);
  }
  for (const YLabel& l : labels) {
    painter.text(y.ticks[l.tick].label, l.box.x0, l.baseline, m.tick(), kText, TextRole::tick_label,
                 panel_index);
  }
}

void draw_y_title(Painter& painter, const YTitle& title, const Rect& f, const Metrics& m,
                  int panel_index) {
  const Extent full = painter.measure("Hg[]", m.label());
  const double line = full.line_ascent + full.line_descent;
  const double shrink = title.size / m.label();
  for (std::size_t k = 0; k < title.lines.size(); ++k) {
    const double w = painter.measure(title.lines[k], title.size).width;
    const double baseline_x = m.margin() + shrink * (full.line_ascent + k * line);
    const TextOrigin origin{title.given, title.shortened};
    painter.text(title.lines[k], baseline_x, 0.5 * (f.y0 + f.y1) + 0.5 * w, title.size, kText,
                 TextRole::axis_label, panel_index, true, &origin);
  }
}

}  // namespace stiction::plot
