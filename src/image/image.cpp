#include "image/image.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::image {

Image::Image(int w, int h, Rgba fill_colour) : width(w), height(h) {
  if (w < 0 || h < 0) throw ImageError("image size must not be negative");
  pixels.resize(static_cast<std::size_t>(w) * h * 4);
  fill(fill_colour);
}

Rgba Image::at(int x, int y) const {
  const std::uint8_t* p = data(x, y);
  return {p[0], p[1], p[2], p[3]};
}

void Image::set(int x, int y, Rgba c) {
  std::uint8_t* p = data(x, y);
  p[0] = c.r;
  p[1] = c.g;
  p[2] = c.b;
  p[3] = c.a;
}

void Image::blend(int x, int y, Rgba c, float coverage) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  const float a = std::clamp(coverage, 0.0f, 1.0f) * (c.a / 255.0f);
  if (a <= 0.0f) return;
  std::uint8_t* p = data(x, y);
  const std::uint8_t src[3] = {c.r, c.g, c.b};
  for (int i = 0; i < 3; ++i) {
    p[i] = static_cast<std::uint8_t>(std::lround(p[i] + (src[i] - p[i]) * a));
  }
  p[3] = static_cast<std::uint8_t>(std::lround(p[3] + (255 - p[3]) * a));
}

void Image::fill(Rgba c) {
  for (std::size_t i = 0; i + 3 < pixels.size(); i += 4) {
    pixels[i] = c.r;
    pixels[i + 1] = c.g;
    pixels[i + 2] = c.b;
    pixels[i + 3] = c.a;
  }
}

void Image::flip_vertical() {
  const std::size_t row = stride();
  for (int y = 0; y < height / 2; ++y) {
    std::swap_ranges(pixels.begin() + y * row, pixels.begin() + (y + 1) * row,
                     pixels.begin() + (height - 1 - y) * row);
  }
}

}  // namespace stiction::image
