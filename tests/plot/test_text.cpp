#include <catch2/catch.hpp>

#include "text/font.hpp"

using namespace stiction;

namespace {

struct Box {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
  long inked = 0;
};

// Bounding box of the pixels that differ from white.
Box ink(const image::Image& img) {
  Box b;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      if (img.at(x, y) == image::Rgba{255, 255, 255, 255}) continue;
      b.x0 = std::min(b.x0, x);
      b.y0 = std::min(b.y0, y);
      b.x1 = std::max(b.x1, x);
      b.y1 = std::max(b.y1, y);
      ++b.inked;
    }
  }
  return b;
}

}  // namespace

TEST_CASE("UTF-8 decoding", "[text]") {
  CHECK(text::decode_utf8("a\u00D7\u03B8\u2080") == U"a\u00D7\u03B8\u2080");
  CHECK(text::decode_utf8("\xFF"
                          "a") == U"\uFFFDa");
  CHECK(text::decode_utf8("\xE2\x82") == U"\uFFFD\uFFFD");  // truncated sequence
  CHECK(text::decode_utf8("") == U"");
}

TEST_CASE("the bundled font is found and opens", "[text]") {
  const auto path = text::default_font_path();
  CHECK(std::filesystem::is_regular_file(path));
  CHECK_NOTHROW(text::Font(path));
  CHECK_THROWS_AS(text::Font("/nonexistent/font.ttf"), text::FontError);
}

TEST_CASE("measured extents match the drawn ink", "[text]") {
  text::Font font = text::Font::open_default();
  const text::TextStyle style{32.0, {0, 0, 0, 255}, text::Rotation::none};
  const text::Extent e = font.measure("Height [m]", style);
  CHECK(e.width > 100);
  CHECK(e.width < 200);
  CHECK(e.ascent > 20);
  CHECK(e.ascent <= e.line_ascent + 1);
  CHECK(e.descent > 3);  // the brackets descend
  image::Image img(400, 100, {255, 255, 255, 255});
  const double advance = font.draw(img, "Height [m]", 50, 60, style);
  CHECK(advance == Approx(e.width));
  const Box b = ink(img);
  CHECK(b.x0 >= 50);
  CHECK(b.x1 <= 50 + e.width + 1);
  CHECK(b.y0 >= 60 - e.ascent - 1);
  CHECK(b.y1 <= 60 + e.descent + 1);
  CHECK(b.x1 - b.x0 > 0.9 * e.width);
  // Twice the size: about twice as wide.
  text::TextStyle big = style;
  big.pixel_size = 64.0;
  CHECK(font.measure("Height [m]", big).width == Approx(2 * e.width).epsilon(0.05));
  CHECK(font.measure("", style).width == 0.0);
}

TEST_CASE("text is anti-aliased, coloured and blended", "[text]") {
  text::Font font = text::Font::open_default();
  image::Image img(200, 60, {255, 255, 255, 255});
  font.draw(img, "Sample", 10, 40, {24.0, {255, 0, 0, 255}, text::Rotation::none});
  bool partial = false, full = false, off_line = false;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const image::Rgba c = img.at(x, y);
      // Red over white stays on the red-white line: red channel untouched, g == b.
      if (c.r != 255 || c.g != c.b || c.a != 255) off_line = true;
      if (c.g < 20) full = true;
      if (c.g > 60 && c.g < 200) partial = true;
    }
  }
  CHECK_FALSE(off_line);
  CHECK(full);
  CHECK(partial);
}

TEST_CASE("rotated text reads bottom to top with the same extents", "[text]") {
  text::Font font = text::Font::open_default();
  const text::TextStyle flat{28.0, {0, 0, 0, 255}, text::Rotation::none};
  text::TextStyle up = flat;
  up.rotation = text::Rotation::ccw90;
  const text::Extent e = font.measure("Velocity [m/s]", up);
  CHECK(e.width == Approx(font.measure("Velocity [m/s]", flat).width));
  image::Image img(100, 300, {255, 255, 255, 255});
  font.draw(img, "Velocity [m/s]", 60, 250, up);
  const Box b = ink(img);
  // Runs upwards from y = 250 and stands left of the baseline x = 60.
  CHECK(b.y1 <= 251);
  CHECK(b.y0 >= 250 - e.width - 1);
  CHECK(b.y1 - b.y0 > 0.9 * e.width);
  CHECK(b.x1 <= 60 + e.descent + 1);
  CHECK(b.x0 >= 60 - e.ascent - 1);
  // Same ink as the horizontal rendering, transposed.
  image::Image flat_img(300, 100, {255, 255, 255, 255});
  font.draw(flat_img, "Velocity [m/s]", 50, 60, flat);
  CHECK(ink(flat_img).inked == b.inked);
}

TEST_CASE("drawing is deterministic and clipped at the image border", "[text]") {
  text::Font font = text::Font::open_default();
  image::Image a(120, 40, {255, 255, 255, 255}), b(120, 40, {255, 255, 255, 255});
  font.draw(a, "Clipped text runs off", -10, 30, {30.0, {0, 0, 0, 255}, text::Rotation::none});
  text::Font other = text::Font::open_default();
  other.draw(b, "Clipped text runs off", -10, 30, {30.0, {0, 0, 0, 255}, text::Rotation::none});
  CHECK(a.pixels == b.pixels);
  CHECK(ink(a).inked > 100);
}
