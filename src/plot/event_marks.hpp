// Events on a figure. A labelled event (EventMarker::labelled) is a line through every panel
// and a label AT its mark above the top panel: centred on it, or next to it with a short
// leader, or in a higher row (a column of labels over one mark, or a thin line up from the
// mark); labels never overlap one another. An event that is not labelled is a light tick at
// the top and bottom edge of each panel. A label with no room even in the highest row, even
// shortened, is left out and reported (FigureLayout::event_labels). Internal to src/plot.
#pragma once

#include <string>
#include <vector>

#include "plot/figure.hpp"
#include "plot/painter.hpp"
#include "plot/style.hpp"
#include "plot/y_axis.hpp"

namespace stiction::plot {

inline constexpr int kMaxEventRows = 4;
// More labelled events than this: their lines become marks at the panels' edges too, so the
// data stays visible.
inline constexpr int kMaxEventLines = 12;

// Where each labelled event's label goes, for one horizontal mapping.
struct EventLabelPlan {
  struct Label {
    std::size_t event = 0;      // index in Figure::events
    double mark_x = 0.0;        // pixel x of the mark
    std::string text;           // possibly shortened in the middle
    double x0 = 0.0, x1 = 0.0;  // the label's box, horizontally
    int row = -1;               // 0 right above the top panel; -1: no room
    bool beside = false;        // next to its mark, joined by a leader, not over it
    bool shortened = false;     // the text shortened (in the middle) to find room
  };
  std::vector<Label> labels;  // the labelled events inside the window, in time order
  int rows = 0;               // rows used
  bool all_placed = true;
};

// Places the labels of the labelled events whose mark lies on the top frame (x between its
// edges), within the figure's margins [left, right].
EventLabelPlan place_event_labels(Painter& painter, const std::vector<EventMarker>& events,
                                  const Axis& x_axis, const Rect& top_frame, double left,
                                  double right, const Metrics& m);

// Height of `rows` label rows above the top panel (0 for none).
double event_rows_height(Painter& painter, int rows, const Metrics& m);

// The event marks of one panel: labelled events as lines through it (marks at its edges when
// `rug`), the others as light ticks at its edges.
void draw_event_marks(Painter& painter, const std::vector<EventMarker>& events, const Axis& x_axis,
                      const Rect& frame, bool rug, const Metrics& m);

// The labels of `plan` over the top frame, with their leaders; reported in the layout.
void draw_event_labels(Painter& painter, const EventLabelPlan& plan,
                       const std::vector<EventMarker>& events, const Rect& top_frame,
                       const Metrics& m, FigureLayout& layout);

// The key of the event marks' styles (one sample and name per kind), for figures where some
// event is drawn without a label. Its width, and its drawing at pen origin (x, baseline).
struct EventKey {
  std::vector<std::string> kinds;
  double width = 0.0;
};
EventKey event_key(Painter& painter, const std::vector<EventMarker>& events, const Metrics& m);
void draw_event_key(Painter& painter, const EventKey& key, double x, double baseline,
                    const Metrics& m);

}  // namespace stiction::plot
