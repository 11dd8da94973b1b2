// Where a panel's data is: its series (as they are drawn: polylines and dense bands, at their
// line widths) and its reference lines rasterized into a coverage mask of the frame, summed
// so that the ink under any rectangle is counted at once. Used to put a legend where there is
// no data. Internal to src/plot.
#pragma once

#include <vector>

#include "plot/cairo_font.hpp"
#include "plot/figure.hpp"
#include "plot/layout.hpp"
#include "plot/style.hpp"
#include "plot/y_axis.hpp"

namespace stiction::plot {

class DataInk {
 public:
  // `pixels` are the panel's series as to_pixels gives them; `y` its vertical axis.
  DataInk(const Panel& panel, const std::vector<std::vector<Point>>& pixels, const Axis& y,
          const Rect& frame, const Metrics& m, const CairoFont& font);

  // Pixels with any ink within the rectangle (clipped to the frame).
  long count(const Rect& r) const;

 private:
  Rect frame_;
  int width_ = 0, height_ = 0;
  std::vector<long> sums_;  // summed-area table, (width_ + 1) x (height_ + 1)
};

}  // namespace stiction::plot
