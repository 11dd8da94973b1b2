// A CPU rasterizer for figures: anti-aliased thick lines with round joins and caps, dash
// patterns, filled rectangles, all drawn into an image::Image. Coverage is analytic: a pixel's
// coverage by a stroke of width w is clamp(w/2 + 0.5 - d, 0, 1), d the distance from the
// pixel centre to the path. A polyline's coverage is the maximum over its pieces, collected
// in a mask and blended once, so joins and overlapping pieces are never blended twice (no
// dark beads at vertices, no seams between dashes). Deterministic to the bit.
#pragma once

#include <optional>
#include <vector>

#include "image/image.hpp"

namespace stiction::plot {

struct Point {
  double x = 0.0;
  double y = 0.0;
};

// An axis-aligned rectangle in pixels (x0 <= x1, y0 <= y1; y down).
struct Rect {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
};

struct Stroke {
  image::Rgba colour{0, 0, 0, 255};
  double width = 2.0;        // pixels
  std::vector<double> dash;  // on, off, on, off ... lengths in pixels; empty: solid
};

class Canvas {
 public:
  explicit Canvas(image::Image& image);

  image::Image& image() { return image_; }

  // Strokes are drawn only inside the clip rectangle (default: the whole image).
  void set_clip(const Rect& clip);
  void reset_clip();

  // A polyline; a point with a non-finite coordinate breaks it into separate pieces. The dash
  // pattern runs along the path's length in pixels and continues across vertices.
  void polyline(const std::vector<Point>& points, const Stroke& stroke);
  void line(Point a, Point b, const Stroke& stroke) { polyline({a, b}, stroke); }
  // Fills with coverage by area, so fractional edges are anti-aliased. Not clipped.
  void fill_rect(const Rect& rect, image::Rgba colour);
  void stroke_rect(const Rect& rect, const Stroke& stroke);
  void fill_disc(Point centre, double radius, image::Rgba colour);

 private:
  void add_capsule(Point a, Point b, double half_width);
  void flush(image::Rgba colour);

  image::Image& image_;
  Rect clip_;
  std::vector<float> mask_;   // coverage of the stroke being built, per pixel
  std::vector<int> touched_;  // indices of mask_ entries that are non-zero
};

}  // namespace stiction::plot
