// A panel's legend: its entries (labelled series, then labelled reference lines), their
// labels (by the text rule, text_fit.hpp), the box's size in rows and columns, and where it
// goes: inside the axes where it covers the least data, as matplotlib's loc="best" (corners
// first on a tie), when that is at most kLegendDataShare of the panel's data; else above the
// panel (entries side by side) or beside the axes on the right. Internal to src/plot.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "plot/data_ink.hpp"
#include "plot/figure.hpp"
#include "plot/painter.hpp"
#include "plot/style.hpp"

namespace stiction::plot {

// Where a legend goes, in the order a layout tries them: inside the axes; in the panel's
// caption row (one unboxed row right of the caption, costing no room); above the panel;
// beside the axes on the right.
enum class LegendPlace { inside, caption, above, right };

struct Legend {
  std::vector<int> entries;  // series indices, then -1 - k for reference line k
  std::vector<std::string> labels;
  std::vector<double> label_sizes;    // each label's size: `size`, or smaller to fit (text_fit)
  std::vector<bool> label_shortened;  // each label: words left out by the text rule
  double size = 0.0;                  // font size
  double width = 0.0, height = 0.0, row = 0.0, sample = 0.0, pad = 0.0, column = 0.0;
  int columns = 1, rows = 0;
  bool by_rows = false;    // entries fill rows first (a wide legend reads left to right)
  bool shortened = false;  // some label shortened (or set under the floor) to fit
  bool shrunk = false;     // the labels set smaller than asked, to fit
  bool boxed = true;       // drawn on a box with a frame (not in a caption row)
  LegendPlace place = LegendPlace::inside;
};

// The entries of a panel's legend; none when the panel has fewer than two labelled lines
// (one series: the axis label already names it).
std::vector<int> legend_entries(const Panel& panel);

// The figure with its legends shared (matplotlib's figure legend, per entry): a series entry
// whose label and style are already in an earlier panel's legend is left out of a later
// one (Fig. 7's "joint 0", "joint 1" in both panels: the torque panel's legend keeps
// "friction level F" alone), unless that would leave a single series entry, which the axis
// label names no better.
Figure shared_legend_entries(const Figure& figure);

// The legend in `columns` columns (entries down each column), at font size `size`, its labels
// fitted to `max_width` in all by the text rule (smaller, then shortened at whole words).
Legend shape_legend(const Panel& panel, const std::vector<int>& entries, Painter& painter,
                    const Metrics& m, int columns, double max_width, double size);

// Beside the axes: as many columns as its height needs within max_height (its text smaller,
// down to its floor, first).
Legend legend_beside(const Panel& panel, Painter& painter, const Metrics& m, double max_width,
                     double max_height);

// Above the panel: its entries side by side, labels whole, at the legend's size or the floor
// of its text, in the shape of the least height (up to `max_rows` rows); else one row,
// shortened.
Legend legend_above(const Panel& panel, Painter& painter, const Metrics& m, double max_width,
                    int max_rows = 2);

// Above the panel when it has no other place (no free corner inside, no room above in two
// rows nor beside the axes): the shape of the least height within `max_width`, labels whole
// if any shape keeps them so, else shortened by the text rule; in one column if nothing
// narrower fits (the caller checks the width).
Legend legend_above_anyhow(const Panel& panel, Painter& painter, const Metrics& m,
                           double max_width);

// In the panel's caption row: its entries side by side in one row without a box, labels whole
// at the legend's size or the floor of its text, at most `max_width` wide (the frame's width
// less the caption's); none when it is wider at the floor.
std::optional<Legend> legend_in_caption_row(const Panel& panel, Painter& painter, const Metrics& m,
                                            double max_width);

// The share of a panel's data (its series and reference lines as drawn) a legend inside may
// cover: a corner that a curve merely grazes is still free. More, and the legend goes outside.
inline constexpr double kLegendDataShare = 0.02;

// What a panel shows, for placing its legend: its data (series and reference lines) and its
// event marks, each rasterized as drawn.
struct PanelInk {
  const DataInk& data;
  const DataInk& marks;
};

// Inside the frame: of every place (the corners: top right, top left, bottom right, bottom
// left; the middles of the edges; places along the edges) and shape (one to four columns),
// the one whose box, with a margin, covers the least data (an event mark counting a quarter
// of a data pixel), its text at `size` (the legend's, or the floor of its text); the first in
// that order on a tie; none when that covers more than kLegendDataShare of the panel's data
// (a legend never goes over data: with no free place it goes outside, legend_above_anyhow).
// Shapes with shortened labels only when no shape keeps them whole. `ink_under` gets the data
// pixels under it.
struct InsidePlace {
  Legend legend;
  Rect box;
};
std::optional<InsidePlace> free_place_inside(const Panel& panel, Painter& painter, const Metrics& m,
                                             const Rect& frame, const PanelInk& ink, double size,
                                             long& ink_under);

// The box and its entries: a line sample in the series' style, then the label.
void draw_legend(Painter& painter, const Panel& panel, const Legend& legend, const Rect& box,
                 int panel_index, const Metrics& m);

}  // namespace stiction::plot
