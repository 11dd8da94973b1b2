#include "plot/canvas.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::plot {
namespace {

bool finite(Point p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// Length of [a0, a1] inside the pixel [i, i + 1].
double overlap(double a0, double a1, int i) {
  return std::max(0.0, std::min(a1, i + 1.0) - std::max(a0, static_cast<double>(i)));
}

}  // namespace

Canvas::Canvas(image::Image& image)
    : image_(image),
      clip_{0.0, 0.0, static_cast<double>(image.width), static_cast<double>(image.height)},
      mask_(static_cast<std::size_t>(image.width) * image.height, 0.0f) {}

void Canvas::set_clip(const Rect& clip) {
  clip_ = Rect{std::max(0.0, clip.x0), std::max(0.0, clip.y0),
               std::min<double>(image_.width, clip.x1), std::min<double>(image_.height, clip.y1)};
}

void Canvas::reset_clip() {
  clip_ = Rect{0.0, 0.0, static_cast<double>(image_.width), static_cast<double>(image_.height)};
}

void Canvas::add_capsule(Point a, Point b, double hw) {
  const double reach = hw + 1.0;
  const int x0 = std::max(static_cast<int>(std::floor(std::min(a.x, b.x) - reach)),
                          static_cast<int>(std::floor(clip_.x0)));
  const int x1 = std::min(static_cast<int>(std::ceil(std::max(a.x, b.x) + reach)),
                          static_cast<int>(std::ceil(clip_.x1)) - 1);
  const int y0 = std::max(static_cast<int>(std::floor(std::min(a.y, b.y) - reach)),
                          static_cast<int>(std::floor(clip_.y0)));
  const int y1 = std::min(static_cast<int>(std::ceil(std::max(a.y, b.y) + reach)),
                          static_cast<int>(std::ceil(clip_.y1)) - 1);
  if (x0 > x1 || y0 > y1) return;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      double t = len2 > 0.0 ? ((px - a.x) * dx + (py - a.y) * dy) / len2 : 0.0;
      t = std::clamp(t, 0.0, 1.0);
      const double ex = px - (a.x + t * dx), ey = py - (a.y + t * dy);
      const double d = std::sqrt(ex * ex + ey * ey);
      // A stroke thinner than a pixel covers at most its width.
      const double c = std::min(std::clamp(hw + 0.5 - d, 0.0, 1.0), 2.0 * hw);
      if (c <= 0.0) continue;
      const std::size_t i = static_cast<std::size_t>(y) * image_.width + x;
      if (mask_[i] == 0.0f) touched_.push_back(static_cast<int>(i));
      mask_[i] = std::max(mask_[i], static_cast<float>(c));
    }
  }
}

void Canvas::flush(image::Rgba colour) {
  for (int i : touched_) {
    image_.blend(i % image_.width, i / image_.width, colour, mask_[i]);
    mask_[i] = 0.0f;
  }
  touched_.clear();
}

void Canvas::polyline(const std::vector<Point>& points, const Stroke& stroke) {
  const double hw = 0.5 * stroke.width;
  double pattern_total = 0.0;
  for (double d : stroke.dash) pattern_total += std::max(0.0, d);
  const bool dashed = stroke.dash.size() >= 2 && pattern_total > 0.0;

  std::size_t phase = 0;  // index into the dash pattern; even = on
  double remaining = dashed ? std::max(0.0, stroke.dash[0]) : 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Point a = points[i - 1], b = points[i];
    if (!finite(a) || !finite(b)) continue;
    if (!dashed) {
      add_capsule(a, b, hw);
      continue;
    }
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const double ux = len > 0.0 ? (b.x - a.x) / len : 0.0;
    const double uy = len > 0.0 ? (b.y - a.y) / len : 0.0;
    double pos = 0.0;
    while (true) {
      const double take = std::min(remaining, len - pos);
      if (phase % 2 == 0) {
        add_capsule(Point{a.x + ux * pos, a.y + uy * pos},
                    Point{a.x + ux * (pos + take), a.y + uy * (pos + take)}, hw);
      }
      pos += take;
      remaining -= take;
      if (remaining > 0.0) break;  // the segment ended inside this dash or gap
      phase = (phase + 1) % stroke.dash.size();
      remaining = std::max(0.0, stroke.dash[phase]);
      if (pos >= len && remaining > 0.0) break;
    }
  }
  flush(stroke.colour);
}

void Canvas::fill_rect(const Rect& r, image::Rgba colour) {
  const int x0 = std::max(0, static_cast<int>(std::floor(r.x0)));
  const int x1 = std::min(image_.width - 1, static_cast<int>(std::ceil(r.x1)) - 1);
  const int y0 = std::max(0, static_cast<int>(std::floor(r.y0)));
  const int y1 = std::min(image_.height - 1, static_cast<int>(std::ceil(r.y1)) - 1);
  for (int y = y0; y <= y1; ++y) {
    const double cy = overlap(r.y0, r.y1, y);
    for (int x = x0; x <= x1; ++x) {
      image_.blend(x, y, colour, static_cast<float>(cy * overlap(r.x0, r.x1, x)));
    }
  }
}

void Canvas::stroke_rect(const Rect& r, const Stroke& stroke) {
  polyline({{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}, {r.x0, r.y0}}, stroke);
}

void Canvas::fill_disc(Point centre, double radius, image::Rgba colour) {
  // A zero-length capsule is a disc of radius half_width.
  add_capsule(centre, centre, radius);
  flush(colour);
}

}  // namespace stiction::plot
