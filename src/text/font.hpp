// Anti-aliased UTF-8 text drawn into an image::Image with FreeType.
//
//   text::Font font = text::Font::open_default();          // assets/DejaVuSans.ttf
//   text::TextStyle style{.pixel_size = 24, .colour = {0, 0, 0, 255}};
//   text::Extent e = font.measure("Time t [s]", style);     // width, ascent, descent
//   font.draw(image, "Time t [s]", x, baseline_y, style);   // horizontal, left origin
//   style.rotation = text::Rotation::ccw90;                  // reads bottom to top
//   font.draw(image, "Velocity [m/s]", baseline_x, y, style);
//
// Coordinates are pixels, x right and y down, origin at the image's top-left corner. The
// anchor of draw() is the pen origin: the left end of the baseline for horizontal text; for
// ccw90 text the bottom end of the (now vertical) baseline, the glyphs standing to its left.
// Glyphs are rendered with FreeType's grey-scale anti-aliasing (light hinting, so stems land
// on pixels and results are identical from run to run) and blended source-over with
// image::Image::blend. Positions may be fractional; each glyph's origin is rounded to the
// nearest pixel, advances and kerning are accumulated in 1/64 pixel.
//
// A Font owns its FreeType library and face (RAII) and a cache of rendered glyphs; it is
// movable, not copyable, and not thread-safe (use one Font per thread).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "image/image.hpp"

namespace stiction::text {

// The font file is missing or unreadable, or FreeType failed (exit code 1 in the app).
class FontError : public std::runtime_error {
 public:
  explicit FontError(const std::string& message) : std::runtime_error(message) {}
};

enum class Rotation {
  none,   // left to right
  ccw90,  // rotated 90 degrees counter-clockwise: reads bottom to top (y-axis labels)
};

struct TextStyle {
  double pixel_size = 16.0;  // em size in pixels (the font's nominal height)
  image::Rgba colour{0, 0, 0, 255};
  Rotation rotation = Rotation::none;
};

// Extents of a string along its own baseline, independent of rotation: `width` is the
// advance of the whole string, `ascent` (>= 0) reaches above the baseline and `descent`
// (>= 0) below it, both for the glyphs actually present. `line_ascent`/`line_descent` are
// the font's values for this size, useful to align strings with different glyphs.
struct Extent {
  double width = 0.0;
  double ascent = 0.0;
  double descent = 0.0;
  double line_ascent = 0.0;
  double line_descent = 0.0;
};

// Where the bundled font lives: assets/DejaVuSans.ttf in the first data directory that has it
// (sys/data_dirs.hpp: next to an installed binary, wherever its prefix was moved, then the
// configured prefix, then the source tree). Throws FontError naming every place tried.
std::filesystem::path default_font_path();

// Decodes UTF-8 into code points; an invalid byte becomes U+FFFD.
std::u32string decode_utf8(std::string_view utf8);

class Font {
 public:
  // Opens a TrueType/OpenType file. Throws FontError on failure.
  explicit Font(const std::filesystem::path& file);
  static Font open_default() { return Font(default_font_path()); }

  Font(Font&&) noexcept;
  Font& operator=(Font&&) noexcept;
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;
  ~Font();

  Extent measure(std::string_view utf8, const TextStyle& style);
  // Draws at the pen origin (x, y); returns the advance (pixels along the baseline).
  double draw(image::Image& image, std::string_view utf8, double x, double y,
              const TextStyle& style);

 private:
  struct Glyph {
    int left = 0, top = 0;  // bitmap offset from the pen origin (top: up is positive)
    int width = 0, rows = 0;
    long advance_26_6 = 0;
    unsigned index = 0;  // glyph index, for kerning
    std::vector<std::uint8_t> coverage;
  };
  struct Impl;

  const Glyph& glyph(char32_t code, long size_26_6);
  long kerning(unsigned left, unsigned right, long size_26_6);
  void set_size(long size_26_6);

  std::unique_ptr<Impl> impl_;
  std::map<std::pair<char32_t, long>, Glyph> cache_;
};

}  // namespace stiction::text
