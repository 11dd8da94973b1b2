// A panel's legend: its entries (labelled series, then labelled reference lines), their
// labels shortened to fit, the box's size in rows and columns, where it goes (the place
// inside the axes with the least data under it, or beside the axes) and its drawing.
// Internal to src/plot.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "plot/figure.hpp"
#include "plot/painter.hpp"
#include "plot/style.hpp"

namespace stiction::plot {

struct Legend {
  std::vector<int> entries;  // series indices, then -1 - k for reference line k
  std::vector<std::string> labels;
  double size = 0.0;  // font size
  double width = 0.0, height = 0.0, row = 0.0, sample = 0.0, pad = 0.0, column = 0.0;
  int columns = 1, rows = 0;
  bool outside = false;
};

// The legend of a panel within max_width x max_height; no entries when the panel has fewer
// than two labelled lines (one series: the axis label already names it).
Legend make_legend(const Panel& panel, Painter& painter, const Metrics& m, double max_width,
                   double max_height);

// How much of the data lies under a rectangle (samples every ~2 pixels along each line).
double occupancy(const std::vector<std::vector<Point>>& lines, const Rect& r);

// The six places inside a frame a legend may take, in order of preference: the corners
// (top right, top left, bottom right, bottom left), then top and bottom centre.
std::array<Rect, 6> legend_places(const Rect& frame, const Legend& legend, double s);

// The place with the least data under it (the first of equals) and how much is there.
struct LegendPlace {
  Rect box;
  double occupancy = 0.0;
};
LegendPlace emptiest_place(const std::vector<std::vector<Point>>& lines, const Rect& frame,
                           const Legend& legend, double s);

// The box and its entries: a line sample in the series' style, then the label.
void draw_legend(Painter& painter, const Panel& panel, const Legend& legend, const Rect& box,
                 int panel_index, const Metrics& m);

}  // namespace stiction::plot
