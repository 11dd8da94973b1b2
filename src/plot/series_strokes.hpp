// The data of a panel: each series as pixels, and its line in its style. Internal to
// src/plot.
#pragma once

#include <vector>

#include "plot/figure.hpp"
#include "plot/painter.hpp"
#include "plot/y_axis.hpp"

namespace stiction::plot {

// The series' samples as pixels (NaN where a sample cannot be placed: non-finite, or not
// positive on a log axis).
std::vector<Point> to_pixels(const Series& series, const Axis& x, const Axis& y);

// Every series of the panel in its style (series_style(index) unless it has its own),
// clipped to the frame; records each series drawn in the layout.
void draw_series(Painter& painter, const Panel& panel,
                 const std::vector<std::vector<Point>>& pixels, const Rect& frame, double line,
                 FigureLayout& layout);

}  // namespace stiction::plot
