// PNG files through libpng. Writes are atomic: the data goes to a temporary (sys/temporaries.hpp) first and is
// renamed over NAME only once complete, so a reader never sees a half-written file.
#pragma once

#include <filesystem>

#include "image/image.hpp"

namespace stiction::image {

enum class PngSpeed {
  fast,   // zlib level 1, SUB filter: ~4x faster, for video frames
  small,  // zlib level 6, adaptive filters: smaller files, for goldens and figures
};

// Throws ImageError (with the path and the reason) on any failure. A positive `dpi` is
// written as the image's resolution (pHYs chunk, pixels per metre), so that a figure of
// 1600 pixels at 300 dpi is placed 5.33 inches wide by a word processor or LaTeX.
void write_png(const std::filesystem::path& path, const Image& image,
               PngSpeed speed = PngSpeed::fast, double dpi = 0.0);
// Reads any PNG (grey, palette, 16-bit, with or without alpha) as RGBA8.
Image read_png(const std::filesystem::path& path);

}  // namespace stiction::image
