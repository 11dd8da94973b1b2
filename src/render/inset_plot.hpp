// The live plot inside the video ([inset], inset_settings.hpp): a translucent panel in a
// corner of each frame with the chosen signals drawn up to the frame's time t, a cursor at
// t and the run's events marked (dashed for stick, dash-dot red for slip, as the figures):
// the changes between slip and stick only (a chattering contact's open / touch-down events
// and repeated sticks are left out), labelled when a page has at most four.
//
// Cheap per frame: the plot library (cairo) draws each page of the plot TWICE, once -- the
// empty axes with the event marks, and the same axes with the full curves -- at the inset's
// pixel size. A frame then copies, column by column, the curves left of x(t) and the empty
// axes right of it, draws the cursor and blends the white background at `opacity`: a blit,
// no cairo call. With a `window` shorter than the run, the plot pages (an oscilloscope
// sweep): page k shows [start + k w, start + (k + 1) w), and the two images of a page are
// drawn when a frame first needs it (once per page; only the current page is kept).
#pragma once

#include <string>
#include <vector>

#include "core/trajectory.hpp"
#include "image/image.hpp"
#include "plot/layout.hpp"
#include "render/inset_settings.hpp"
#include "render/overlay.hpp"

namespace stiction::render {

struct InsetEvent {
  double time = 0.0;
  std::string kind;  // "stick", "slip", ...; "" when not known
};

class InsetPlot {
 public:
  // `frame_width` x `frame_height`: the video's frame. Throws RenderError for a signal the
  // trajectory lacks. An inset larger than the frame is cut to it; one smaller than a figure
  // can be (200 x 150 pixels: a compare video's tile) is drawn at that size and scaled down.
  // `reserved_bottom`: pixels at the bottom of the frame that a bottom inset stays above (the
  // caption's band).
  InsetPlot(const InsetSettings& settings, const core::Trajectory& trajectory, int frame_width,
            int frame_height, std::vector<InsetEvent> events = {}, int reserved_bottom = 0);

  // Composites the inset at simulated time t onto `frame` (frame_width x frame_height).
  void draw(image::Image& frame, double t);

  // Where the inset sits on the frame.
  const PixelBox& box() const { return box_; }
  // The cursor's column (frame pixels) and the panels' vertical extent at time t; the curves
  // are revealed in the columns left of cursor_x(t).
  int cursor_x(double t);
  PixelBox panels_box(double t);
  // The time range of the page shown at t.
  std::pair<double, double> page_range(double t);
  // The layout of the page shown at t as plot::draw laid it out (its texts, legends and
  // panels, in the pixels of the figure drawn: at least 200 x 150, before any scaling down to
  // the inset's box), for checks of its text.
  const plot::FigureLayout& drawn_layout(double t);

 private:
  struct Page {
    int index = -1;
    double t0 = 0.0, t1 = 0.0;
    image::Image axes, full;
    plot::FigureLayout layout;  // its panels scaled to the inset's box
    plot::FigureLayout drawn;   // as drawn
  };
  const Page& page(double t);
  void draw_page(Page& page) const;
  double column_of(const Page& page, double t) const;

  InsetSettings settings_;
  std::vector<InsetEvent> events_;
  std::vector<double> times_;
  std::vector<std::vector<double>> values_;        // per signal, at times_
  std::vector<std::pair<double, double>> ranges_;  // per signal: min, max over the run
  double start_ = 0.0, end_ = 0.0;
  double font_px_ = 12.0;
  int figure_width_ = 0, figure_height_ = 0;  // the figure as drawn (at least 200 x 150)
  PixelBox box_;
  Page page_;
};

}  // namespace stiction::render
