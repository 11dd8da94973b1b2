#include "plot/data_ink.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace stiction::plot {

DataInk::DataInk(const Rect& frame, const CairoFont& font,
                 const std::function<void(Painter&)>& draw)
    : frame_(frame),
      width_(std::max(1, static_cast<int>(std::ceil(frame.width())))),
      height_(std::max(1, static_cast<int>(std::ceil(frame.height())))) {
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_A8, width_, height_), &cairo_surface_destroy);
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()),
                                                        &cairo_destroy);
  cairo_translate(cr.get(), -frame.x0, -frame.y0);
  cairo_rectangle(cr.get(), frame.x0, frame.y0, frame.width(), frame.height());
  cairo_clip(cr.get());
  FigureLayout scratch;
  Painter painter(cr.get(), font, scratch);
  draw(painter);
  cairo_surface_flush(surface.get());
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  sums_.assign(static_cast<std::size_t>(width_ + 1) * (height_ + 1), 0);
  for (int row = 0; row < height_; ++row) {
    long line = 0;
    for (int col = 0; col < width_; ++col) {
      line += data[static_cast<std::size_t>(row) * stride + col] != 0 ? 1 : 0;
      sums_[static_cast<std::size_t>(row + 1) * (width_ + 1) + col + 1] =
          sums_[static_cast<std::size_t>(row) * (width_ + 1) + col + 1] + line;
    }
  }
}

long DataInk::count(const Rect& r) const {
  const auto clamp_x = [&](double x) {
    return std::clamp(static_cast<int>(std::floor(x - frame_.x0)), 0, width_);
  };
  const auto clamp_y = [&](double y) {
    return std::clamp(static_cast<int>(std::floor(y - frame_.y0)), 0, height_);
  };
  const int x0 = clamp_x(r.x0), x1 = clamp_x(std::ceil(r.x1));
  const int y0 = clamp_y(r.y0), y1 = clamp_y(std::ceil(r.y1));
  if (x1 <= x0 || y1 <= y0) return 0;
  auto at = [&](int x, int y) { return sums_[static_cast<std::size_t>(y) * (width_ + 1) + x]; };
  return at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
}

}  // namespace stiction::plot
