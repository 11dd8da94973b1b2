// Drawing and measuring through one cairo context, recording every text box drawn in the
// figure's layout. Internal to src/plot.
#pragma once

#include <cairo.h>

#include <string>
#include <vector>

#include "plot/cairo_font.hpp"
#include "plot/layout.hpp"
#include "plot/style.hpp"

namespace stiction::plot {

struct Extent {
  double width = 0.0;                            // advance
  double ascent = 0.0;                           // of the glyphs present (ink)
  double line_ascent = 0.0, line_descent = 0.0;  // the font's, at this size
};

class Painter {
 public:
  Painter(cairo_t* cr, const CairoFont& font, FigureLayout& layout);

  Extent measure(const std::string& text, double size);

  // Text at the pen origin (x, baseline); rotated: reads bottom to top, the pen origin at the
  // bottom end of the baseline. Returns the recorded box.
  Rect text(const std::string& s, double x, double baseline, double size, image::Rgba colour,
            TextRole role, int panel, bool rotated = false);

  void polyline(const std::vector<Point>& points, const Stroke& stroke);
  void line(Point a, Point b, const Stroke& stroke) { polyline({a, b}, stroke); }
  void fill_rect(const Rect& r, image::Rgba colour);
  void stroke_rect(const Rect& r, const Stroke& stroke);
  void clip(const Rect& r);
  void unclip();

 private:
  void set_colour(image::Rgba c);
  void apply(const Stroke& stroke);
  void set_dash_offset(const Stroke& stroke, double offset);

  cairo_t* cr_;
  FigureLayout& layout_;
};

}  // namespace stiction::plot
