// A CPU image: 8-bit RGBA, rows top to bottom, no padding. What the renderer reads back,
// what text is drawn into, what PNG files hold.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace stiction::image {

// Failure to read or write an image file (exit code 1 in the app).
class ImageError : public std::runtime_error {
 public:
  explicit ImageError(const std::string& message) : std::runtime_error(message) {}
};

struct Rgba {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Rgba&) const = default;
};

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4 bytes, RGBA, top row first

  Image() = default;
  Image(int w, int h, Rgba fill = {0, 0, 0, 255});

  bool empty() const { return width == 0 || height == 0; }
  std::size_t stride() const { return static_cast<std::size_t>(width) * 4; }
  std::uint8_t* data(int x, int y) { return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
  const std::uint8_t* data(int x, int y) const {
    return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 4;
  }
  Rgba at(int x, int y) const;
  void set(int x, int y, Rgba c);
  // Source-over blend of colour c with coverage in [0, 1] (c.a scales it further).
  void blend(int x, int y, Rgba c, float coverage);
  void fill(Rgba c);
  // Mirror rows in place (OpenGL read-back comes bottom row first).
  void flip_vertical();
};

}  // namespace stiction::image
