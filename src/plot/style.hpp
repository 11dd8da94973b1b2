// The look of a figure in one place: its colours, the Okabe-Ito palette, the sizes of its
// parts (fonts, margins, line widths) and the strokes of series, references and events.
// Internal to src/plot: the drawing code's vocabulary, not an API.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "plot/figure.hpp"

namespace stiction::plot {

inline constexpr image::Rgba kWhite{255, 255, 255, 255};
inline constexpr image::Rgba kText{25, 25, 25, 255};
inline constexpr image::Rgba kFrame{60, 60, 60, 255};
inline constexpr image::Rgba kGrid{222, 222, 222, 255};
inline constexpr image::Rgba kMinorGrid{240, 240, 240, 255};
inline constexpr image::Rgba kEvent{80, 80, 80, 255};
inline constexpr image::Rgba kSlipEvent{178, 34, 34, 255};
inline constexpr image::Rgba kOtherEvent{150, 100, 0, 255};  // tip, lift-off, land, ...
inline constexpr image::Rgba kLegendBox{255, 255, 255, 235};
inline constexpr image::Rgba kLegendFrame{190, 190, 190, 255};

// Okabe & Ito's colour-blind-safe palette (yellow left out: too light on white).
inline constexpr std::array<image::Rgba, 7> kPalette{{{0, 114, 178, 255},
                                                      {213, 94, 0, 255},
                                                      {0, 158, 115, 255},
                                                      {204, 121, 167, 255},
                                                      {230, 159, 0, 255},
                                                      {86, 180, 233, 255},
                                                      {0, 0, 0, 255}}};

// Sizes of the figure's parts in pixels. Two designs:
//  - in pixels (no Figure::print): everything scales with s = min(width/1600, height/1000),
//    fonts of 32 (title), 27, 24, 23 and 22 px at 1600x1000; a text that does not fit may
//    shrink to 70% before it is shortened (text_fit.hpp);
//  - in points (Figure::print): the page is width_mm x height_mm at dpi; every text but the
//    title is font_pt (the title font_pt + 1); a text that does not fit wraps, then may
//    shrink to 75% but not below 6 pt (a journal's least), before it is shortened
//    (text_fit.hpp); layout lengths (margins, gaps, paddings, tick length) keep the
//    proportions of the pixel design relative to the tick font, so s = font_pt / 24 pt;
//    lines are in units of 0.3 pt: series 0.96 pt, frame 0.48 pt, grid 0.36 pt, events 0.6 pt.
struct Metrics {
  double s = 1.0;     // pixels per layout unit (a pixel of the 1600x1000 design)
  double line = 1.0;  // pixels per line-width unit (LineStyle widths and dashes)
  double title_size = 32, label_size = 27, tick_size = 24, legend_size = 23, event_size = 22;
  bool shrinks = true;     // the pixel design: titles stay on one line, legends beside shrink
  double px_per_pt = 0.0;  // print: pixels per point (0: the pixel design)
  // Time axis ticks: about one per this many layout units (a print figure is narrower for its
  // type, so its ticks are denser).
  double x_tick_spacing = 190.0;
  // Lines a vertical axis title may wrap onto before it is shortened (print: one more, since
  // its font does not shrink).
  std::size_t y_title_lines = 3;

  // The least size a text set at `size` may shrink to before it is shortened (text_fit.hpp):
  // 70% in the pixel design; in print 75%, not below 6 pt, and a text under 6 pt keeps its size.
  double floor(double size) const {
    if (px_per_pt <= 0.0) return 0.7 * size;
    return std::max(0.75 * size, std::min(size, 6.0 * px_per_pt));
  }

  double title() const { return title_size; }
  double label() const { return label_size; }
  double tick() const { return tick_size; }
  double legend() const { return legend_size; }
  double event() const { return event_size; }
  double margin() const { return 22 * s; }
  double tick_length() const { return 9 * s; }
  double frame_width() const { return std::max(1.0, 1.6 * line); }
  double grid_width() const { return std::max(1.0, 1.2 * line); }
};

// The metrics of a figure drawn at width x height pixels (its pixel_size).
Metrics figure_metrics(const Figure& figure, int width, int height);

// A line as cairo strokes it, in pixels.
struct Stroke {
  image::Rgba colour{0, 0, 0, 255};
  double width = 2.0;
  std::vector<double> dash;  // pixels; empty: solid
};

// A series' style (in line units) as a stroke in pixels (`line`: pixels per line unit).
Stroke make_stroke(const LineStyle& style, double line);

// Horizontal reference lines: thin, grey, dashed.
LineStyle reference_style();

// Event lines: sticks dashed grey, slips (and slides) dash-dot red, other kinds (a body's
// tip, lift-off, landing) dash-dot-dot ochre; labels in the same colour.
Stroke event_stroke(const std::string& kind, double line);
image::Rgba event_colour(const std::string& kind);
// The light tick of an event drawn without a label: solid, thin, in a lighter tint.
Stroke event_tick_stroke(const std::string& kind, double line);

}  // namespace stiction::plot
