// Axes of a figure: the mapping of values to pixels, and a panel's vertical axis with its
// ticks, tick labels and title. Internal to src/plot.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "plot/figure.hpp"
#include "plot/painter.hpp"

namespace stiction::plot {

// A vertical or horizontal axis: value -> pixel.
struct Axis {
  double lo = 0.0, hi = 1.0;  // in data units (log axes: exponents)
  bool log = false;
  double p0 = 0.0, p1 = 1.0;  // pixels of lo and hi
  double map(double v) const;
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

// v within [lo, hi] up to rounding.
bool in_range(double v, double lo, double hi);

// "⁻¹²" for -12.
std::string superscript(int value);

// The vertical axis of a panel over the horizontal window [x_lo, x_hi], with about `target`
// labelled ticks (pixels not yet set: p0 = p1 is the caller's).
YAxis make_y_axis(const Panel& panel, double x_lo, double x_hi, int target);

// "label [×10ⁿ unit]", "label [unit]", "[unit]" or "label".
std::string axis_title(const std::string& label, const std::string& unit, int exponent);

// A vertical axis title fitted to the panel's height by the text rule (text_fit.hpp): wrapped
// onto up to `max_lines` lines, smaller down to `floor`, then shortened at whole words.
struct YTitle {
  std::vector<std::string> lines;
  double size = 0.0;
  std::string given;  // the title as given
  bool shortened = false;
};
YTitle fit_y_title(Painter& painter, const std::string& title, double panel_height,
                   double full_size, double floor, std::size_t max_lines);

// A log axis whose decades give fewer than two labels in view also labels its minor ticks at
// 2 and 5 times a decade ("2×10⁻⁷", "5×10⁻⁷").
void label_minor_ticks(YAxis& y);

// The tick labels drawn on the left of the frame (y.axis mapped to the frame): a label that
// would touch one in `taken` (the time axis' labels and those of the panels above) is left
// out, its tick stays. The boxes of the labels kept are added to `taken`.
struct YLabel {
  std::size_t tick = 0;  // index in y.ticks
  Rect box;
  double baseline = 0.0;
};
std::vector<YLabel> select_y_labels(Painter& painter, const YAxis& y, const Rect& frame,
                                    const Metrics& m, std::vector<Rect>& taken);

// Tick marks on both sides of the frame and the labels selected.
void draw_y_ticks(Painter& painter, const YAxis& y, const Rect& frame, const Metrics& m,
                  const Stroke& stroke, const std::vector<YLabel>& labels, int panel_index);

// The title centred on the panel's height, one rotated line per wrapped line, from the left
// margin of the figure.
void draw_y_title(Painter& painter, const YTitle& title, const Rect& frame, const Metrics& m,
                  int panel_index);

}  // namespace stiction::plot
