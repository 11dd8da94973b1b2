// Drawing and measuring through one cairo context, recording every text box drawn in the
// figure's layout. Text is either drawn by cairo (glyphs) or, for an SVG that keeps its text
// as text, handed back as PlacedText at the place cairo measured (svg_text.hpp).
// Internal to src/plot.
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

// A text as placed on the figure: pen origin (x, baseline) in pixels, font size in pixels;
// rotated texts read bottom to top about the pen origin.
struct PlacedText {
  std::string text;
  double x = 0.0, baseline = 0.0, size = 0.0;
  image::Rgba colour{0, 0, 0, 255};
  bool rotated = false;
};

class Painter {
 public:
  // With `deferred`, text is measured and recorded but not drawn: it is appended there.
  Painter(cairo_t* cr, const CairoFont& font, FigureLayout& layout,
          std::vector<PlacedText>* deferred = nullptr);

  // Advances include the font's kerning (as SVG viewers and word processors apply it).
  Extent measure(const std::string& text, double size);

  // Text at the pen origin (x, baseline); rotated: reads bottom to top, the pen origin at the
  // bottom end of the baseline. Returns the recorded box.
  Rect text(const std::string& s, double x, double baseline, double size, image::Rgba colour,
            TextRole role, int panel, bool rotated = false);

  void polyline(const std::vector<Point>& points, const Stroke& stroke);
  void line(Point a, Point b, const Stroke& stroke) { polyline({a, b}, stroke); }
  void fill_rect(const Rect& r, image::Rgba colour);
  void fill_polygon(const std::vector<Point>& points, image::Rgba colour);
  void stroke_rect(const Rect& r, const Stroke& stroke);
  void clip(const Rect& r);
  void unclip();

 private:
  void set_colour(image::Rgba c);
  void apply(const Stroke& stroke);
  void set_dash_offset(const Stroke& stroke, double offset);

  // The text's glyphs at the current font size, from the pen origin (0, 0), kerned.
  struct Glyphs;
  Glyphs shape(const std::string& text);

  cairo_t* cr_;
  const CairoFont& font_;
  FigureLayout& layout_;
  std::vector<PlacedText>* deferred_;
};

}  // namespace stiction::plot
