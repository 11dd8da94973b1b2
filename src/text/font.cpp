#include "text/font.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>

#include "sys/data_dirs.hpp"

namespace stiction::text {
namespace {

std::string ft_message(FT_Error error) {
  const char* s = FT_Error_String(error);
  return s ? std::string(s) : "FreeType error " + std::to_string(error);
}

struct LibraryDeleter {
  void operator()(FT_Library library) const { FT_Done_FreeType(library); }
};
struct FaceDeleter {
  void operator()(FT_Face face) const { FT_Done_Face(face); }
};
using LibraryHandle = std::unique_ptr<FT_LibraryRec_, LibraryDeleter>;
using FaceHandle = std::unique_ptr<FT_FaceRec_, FaceDeleter>;

long to_26_6(double pixels) { return std::lround(pixels * 64.0); }

}  // namespace

// The face is declared after the library so that it is destroyed first.
struct Font::Impl {
  LibraryHandle library;
  FaceHandle face;
  long current_size_26_6 = -1;
};

std::filesystem::path default_font_path() {
  const std::filesystem::path relative = std::filesystem::path("assets") / "DejaVuSans.ttf";
  std::string looked;
  for (const std::filesystem::path& dir : sys::data_directories()) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(dir / relative, ec)) return dir / relative;
    looked += (looked.empty() ? "" : ", ") + (dir / relative).string();
  }
  throw FontError("font not found: looked for " + looked);
}

std::u32string decode_utf8(std::string_view s) {
  std::u32string out;
  out.reserve(s.size());
  std::size_t i = 0;
  while (i < s.size()) {
    const auto b0 = static_cast<unsigned char>(s[i]);
    int extra = 0;
    char32_t code = 0;
    if (b0 < 0x80) {
      code = b0;
    } else if ((b0 & 0xE0) == 0xC0) {
      extra = 1;
      code = b0 & 0x1F;
    } else if ((b0 & 0xF0) == 0xE0) {
      extra = 2;
      code = b0 & 0x0F;
    } else if ((b0 & 0xF8) == 0xF0) {
      extra = 3;
      code = b0 & 0x07;
    } else {
      out.push_back(U'\uFFFD');
      ++i;
      continue;
    }
    bool valid = i + static_cast<std::size_t>(extra) < s.size();
    for (int k = 1; valid && k <= extra; ++k) {
      const auto b = static_cast<unsigned char>(s[i + k]);
      if ((b & 0xC0) != 0x80) {
        valid = false;
      } else {
        code = (code << 6) | (b & 0x3F);
      }
    }
    if (valid && (code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF))) valid = false;
    if (!valid) {
      out.push_back(U'\uFFFD');
      ++i;
      continue;
    }
    out.push_back(code);
    i += 1 + extra;
  }
  return out;
}

Font::Font(const std::filesystem::path& file) : impl_(std::make_unique<Impl>()) {
  FT_Library library = nullptr;
  if (FT_Error error = FT_Init_FreeType(&library)) {
    throw FontError("cannot initialise FreeType: " + ft_message(error));
  }
  impl_->library.reset(library);
  FT_Face face = nullptr;
  if (FT_Error error = FT_New_Face(library, file.c_str(), 0, &face)) {
    throw FontError("cannot open font " + file.string() + ": " + ft_message(error));
  }
  impl_->face.reset(face);
  if (!FT_IS_SCALABLE(face)) throw FontError("font " + file.string() + " is not scalable");
}

Font::Font(Font&&) noexcept = default;
Font& Font::operator=(Font&&) noexcept = default;
Font::~Font() = default;

void Font::set_size(long size_26_6) {
  if (impl_->current_size_26_6 == size_26_6) return;
  if (FT_Error error = FT_Set_Char_Size(impl_->face.get(), 0, size_26_6, 72, 72)) {
    throw FontError("cannot set font size: " + ft_message(error));
  }
  impl_->current_size_26_6 = size_26_6;
}

const Font::Glyph& Font::glyph(char32_t code, long size_26_6) {
  const auto key = std::make_pair(code, size_26_6);
  if (auto it = cache_.find(key); it != cache_.end()) return it->second;
  set_size(size_26_6);
  FT_Face face = impl_->face.get();
  FT_UInt index = FT_Get_Char_Index(face, code);
  if (index == 0 && code != U'\uFFFD') index = FT_Get_Char_Index(face, U'\uFFFD');
  if (FT_Error error = FT_Load_Glyph(face, index, FT_LOAD_RENDER | FT_LOAD_TARGET_LIGHT)) {
    throw FontError("cannot render glyph U+" + std::to_string(static_cast<unsigned>(code)) + ": " +
                    ft_message(error));
  }
  const FT_GlyphSlot slot = face->glyph;
  const FT_Bitmap& bitmap = slot->bitmap;
  if (bitmap.pixel_mode != FT_PIXEL_MODE_GRAY && bitmap.rows > 0) {
    throw FontError("unexpected glyph bitmap format");
  }
  Glyph g;
  g.left = slot->bitmap_left;
  g.top = slot->bitmap_top;
  g.width = static_cast<int>(bitmap.width);
  g.rows = static_cast<int>(bitmap.rows);
  g.advance_26_6 = slot->advance.x;
  g.index = index;
  g.coverage.resize(static_cast<std::size_t>(g.width) * g.rows);
  for (int r = 0; r < g.rows; ++r) {
    const unsigned char* src = bitmap.buffer + static_cast<std::ptrdiff_t>(r) * bitmap.pitch;
    std::copy(src, src + g.width, g.coverage.begin() + static_cast<std::ptrdiff_t>(r) * g.width);
  }
  return cache_.emplace(key, std::move(g)).first->second;
}

long Font::kerning(unsigned left, unsigned right, long size_26_6) {
  FT_Face face = impl_->face.get();
  if (!FT_HAS_KERNING(face) || left == 0 || right == 0) return 0;
  set_size(size_26_6);
  FT_Vector delta{0, 0};
  if (FT_Get_Kerning(face, left, right, FT_KERNING_DEFAULT, &delta) != 0) return 0;
  return delta.x;
}

Extent Font::measure(std::string_view utf8, const TextStyle& style) {
  const long size = to_26_6(style.pixel_size);
  set_size(size);
  const FT_Size_Metrics& metrics = impl_->face->size->metrics;
  Extent extent;
  extent.line_ascent = metrics.ascender / 64.0;
  extent.line_descent = -metrics.descender / 64.0;
  long pen = 0;
  unsigned previous = 0;
  for (char32_t code : decode_utf8(utf8)) {
    const Glyph& g = glyph(code, size);
    pen += kerning(previous, g.index, size);
    if (g.rows > 0) {
      extent.ascent = std::max(extent.ascent, static_cast<double>(g.top));
      extent.descent = std::max(extent.descent, static_cast<double>(g.rows - g.top));
    }
    pen += g.advance_26_6;
    previous = g.index;
  }
  extent.width = pen / 64.0;
  return extent;
}

double Font::draw(image::Image& image, std::string_view utf8, double x, double y,
                  const TextStyle& style) {
  const long size = to_26_6(style.pixel_size);
  const bool rotated = style.rotation == Rotation::ccw90;
  long pen = 0;
  unsigned previous = 0;
  for (char32_t code : decode_utf8(utf8)) {
    const Glyph& g = glyph(code, size);
    pen += kerning(previous, g.index, size);
    previous = g.index;
    const double along = pen / 64.0;
    pen += g.advance_26_6;
    if (g.rows == 0 || g.width == 0) continue;
    // Glyph origin in image pixels, rounded so that hinted stems stay on pixels.
    const long ox = std::lround(rotated ? x : x + along);
    const long oy = std::lround(rotated ? y - along : y);
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.width; ++c) {
        const std::uint8_t cov = g.coverage[static_cast<std::size_t>(r) * g.width + c];
        if (cov == 0) continue;
        // Offsets in the text's own frame: u along the baseline, w downwards from it.
        const long u = g.left + c;
        const long w = r - g.top;
        // ccw90 maps the text frame (u, w) to the image offset (w, -u).
        const long px = rotated ? ox + w : ox + u;
        const long py = rotated ? oy - u : oy + w;
        image.blend(static_cast<int>(px), static_cast<int>(py), style.colour, cov / 255.0f);
      }
    }
  }
  return pen / 64.0;
}

}  // namespace stiction::text
