// Events on a figure: their lines through the panels and their labels above the top panel.
// Internal to src/plot.
#pragma once

#include <string>
#include <vector>

#include "plot/figure.hpp"
#include "plot/painter.hpp"
#include "plot/style.hpp"
#include "plot/y_axis.hpp"

namespace stiction::plot {

inline constexpr int kMaxEventRows = 3;

// Labels in rows above the top panel, centred on their lines, no overlaps within a row; with
// `key_width` > 0 the key of the line styles takes the right end of the first row.
struct EventRows {
  std::vector<int> row_of;  // per event: its row, -1 unlabelled
  bool all = true;          // every event inside the axes got a row
  int rows = 0;
};
EventRows place_event_rows(Painter& painter, const std::vector<EventMarker>& events,
                           const std::vector<std::string>& texts, const Axis& x_axis,
                           const Rect& top_frame, const Metrics& m, double figure_width,
                           double key_width);

// The event lines of one panel: full height, or short marks at its top and bottom edge when
// `rug` (many events).
void draw_event_lines(Painter& painter, const std::vector<EventMarker>& events, const Axis& x_axis,
                      const Rect& frame, bool rug, const Metrics& m);

}  // namespace stiction::plot
