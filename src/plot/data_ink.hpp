// Where a panel's data is: whatever a function draws into the frame (the panel's series as
// they are drawn, polylines and dense bands at their line widths, its reference lines and
// its event marks) rasterized into a coverage mask and summed, so that the ink under any
// rectangle is counted at once. Used to put a legend where there is no data. Internal to
// src/plot.
#pragma once

#include <functional>
#include <vector>

#include "plot/cairo_font.hpp"
#include "plot/layout.hpp"
#include "plot/painter.hpp"

namespace stiction::plot {

class DataInk {
 public:
  // `draw` paints into a painter whose user space is the figure's pixels, clipped to `frame`.
  DataInk(const Rect& frame, const CairoFont& font, const std::function<void(Painter&)>& draw);

  // Pixels with any ink within the rectangle (clipped to the frame).
  long count(const Rect& r) const;

 private:
  Rect frame_;
  int width_ = 0, height_ = 0;
  std::vector<long> sums_;  // summed-area table, (width_ + 1) x (height_ + 1)
};

}  // namespace stiction::plot
