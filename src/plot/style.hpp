// The look of a figure in one place: its colours, the Okabe-Ito palette, the sizes of its
// parts (fonts, margins, line widths) and the strokes of series, references and events.
// Internal to src/plot: the drawing code's vocabulary, not an API.
#pragma once

#include <algorithm>
#include <array>
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

// A line as cairo strokes it, in pixels.
struct Stroke {
  image::Rgba colour{0, 0, 0, 255};
  double width = 2.0;
  std::vector<double> dash;  // pixels; empty: solid
};

// A series' style (in units of the figure scale) as a stroke in pixels.
Stroke make_stroke(const LineStyle& style, double s);

// Horizontal reference lines: thin, grey, dashed.
LineStyle reference_style();

// Event lines: sticks dashed grey, slips dash-dot red; labels in the same colour.
Stroke event_stroke(const std::string& kind, double s);
image::Rgba event_colour(const std::string& kind);

}  // namespace stiction::plot
