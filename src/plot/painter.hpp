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

// Where a drawn text comes from: the text it was given and whether the text rule shortened
// it (recorded in TextBox::given and TextBox::shortened).
struct TextOrigin {
  const std::string& given;
  bool shortened = false;
};

class Painter {
 public:
  // With `deferred`, text is measured and recorded but not drawn: it is appended there.
  Painter(cairo_t* cr, const CairoFont& font, FigureLayout& layout,
          std::vector<PlacedText>* deferred = nullptr);
  ~Painter();
  Painter(const Painter&) = delete;
  Painter& operator=(const Painter&) = delete;

  // Advances include the font's kerning (as SVG viewers and word processors apply it).
  // Measured with a font of its own (unhinted, identity transformation), never with the
  // drawing surface's: cairo merges a surface's font options into a context's (an image
  // surface may round glyph positions, a vector surface does not) and scales by the
  // context's transformation, so a measure taken through the context could differ between
  // the PNG, the SVG and the PDF of one figure, and with it which tick labels fit. The
  // glyphs are then drawn at the positions measured here, on every surface.
  Extent measure(const std::string& text, double size);

  // Text at the pen origin (x, baseline); rotated: reads bottom to top, the pen origin at the
  // bottom end of the baseline. Returns the recorded box, whose `given` is `origin`'s text
  // (`s` itself when there is none: a tick label, drawn as made).
  Rect text(const std::string& s, double x, double baseline, double size, image::Rgba colour,
            TextRole role, int panel, bool rotated = false, const TextOrigin* origin = nullptr);

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

  // The text's glyphs at `size`, from the pen origin (0, 0), kerned, in the measuring font.
  struct Glyphs;
  Glyphs shape(const std::string& text, double size);
  // The measuring font at `size` (created once per size).
  cairo_scaled_font_t* measuring_font(double size);

  cairo_t* cr_;
  const CairoFont& font_;
  FigureLayout& layout_;
  std::vector<PlacedText>* deferred_;
  cairo_font_options_t* measure_options_ = nullptr;
  std::vector<std::pair<double, cairo_scaled_font_t*>> measuring_;  // by size
};

}  // namespace stiction::plot
