// A panel's legend: its entries (labelled series, then labelled reference lines), their
// labels (shortened only when they cannot fit), the box's size in rows and columns, and where
// it goes: inside the axes at the most preferred place (a corner first) with no data under
// it; when every place inside has data, above the panel (entries side by side) or beside the
// axes on the right, rather than over the data. Internal to src/plot.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "plot/data_ink.hpp"
#include "plot/figure.hpp"
#include "plot/painter.hpp"
#include "plot/style.hpp"

namespace stiction::plot {

enum class LegendPlace { inside, above, right };

struct Legend {
  std::vector<int> entries;  // series indices, then -1 - k for reference line k
  std::vector<std::string> labels;
  double size = 0.0;  // font size
  double width = 0.0, height = 0.0, row = 0.0, sample = 0.0, pad = 0.0, column = 0.0;
  int columns = 1, rows = 0;
  bool by_rows = false;    // entries fill rows first (a wide legend reads left to right)
  bool shortened = false;  // some label shortened to fit
  LegendPlace place = LegendPlace::inside;
};

// The entries of a panel's legend; none when the panel has fewer than two labelled lines
// (one series: the axis label already names it).
std::vector<int> legend_entries(const Panel& panel);

// The legend in `columns` columns (entries down each column), its labels shortened to fit
// `max_width` in all, at font size `size`.
Legend shape_legend(const Panel& panel, const std::vector<int>& entries, Painter& painter,
                    const Metrics& m, int columns, double max_width, double size);

// Beside the axes: as many columns as its height needs within max_height (in the pixel
// design the font shrinks to 75% first).
Legend legend_beside(const Panel& panel, Painter& painter, const Metrics& m, double max_width,
                     double max_height);

// Above the panel: as many entries side by side as fit max_width, labels whole if they can be.
Legend legend_above(const Panel& panel, Painter& painter, const Metrics& m, double max_width);

// Inside the frame: the first place, in order of preference (the corners: top right, top
// left, bottom right, bottom left; then the middles of the edges; then along the edges), in
// the first shape (one column, then more) that has no data under it within a margin. None
// when every place has data.
struct InsidePlace {
  Legend legend;
  Rect box;
};
std::optional<InsidePlace> free_place_inside(const Panel& panel, Painter& painter, const Metrics& m,
                                             const Rect& frame, const DataInk& ink);

// The place inside with the least data under it, for a figure with no room outside the axes
// (`ink_under` gets the count of inked pixels under its box).
InsidePlace least_inked_place_inside(const Panel& panel, Painter& painter, const Metrics& m,
                                     const Rect& frame, const DataInk& ink, long& ink_under);

// The box and its entries: a line sample in the series' style, then the label.
void draw_legend(Painter& painter, const Panel& panel, const Legend& legend, const Rect& box,
                 int panel_index, const Metrics& m);

}  // namespace stiction::plot
