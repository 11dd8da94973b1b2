// The bundled font (assets/DejaVuSans.ttf) as a cairo font face, loaded through FreeType
// (cairo-ft), so figures look the same on every machine whatever fonts it has installed.
// Owns the FreeType library and face; the cairo face keeps them alive as long as cairo
// needs them (a surface may outlive this object while it is being finished). Also gives the
// font's kerning, which cairo's text API leaves out (SVG viewers apply it: figures do too).
#pragma once

#include <cairo.h>

#include <filesystem>

namespace stiction::plot {

struct FreeTypeHandles;

class CairoFont {
 public:
  // Throws text::FontError if the file cannot be read.
  explicit CairoFont(const std::filesystem::path& file);
  static CairoFont open_default();
  ~CairoFont();
  CairoFont(const CairoFont&) = delete;
  CairoFont& operator=(const CairoFont&) = delete;

  cairo_font_face_t* face() const { return face_; }

  // The kerning between two glyphs (by index), in ems: add it times the font size to the
  // position of the right glyph. 0 for a font without a kerning table.
  double kerning(unsigned long left_glyph, unsigned long right_glyph) const;

 private:
  cairo_font_face_t* face_ = nullptr;
  FreeTypeHandles* handles_ = nullptr;  // owned by face_'s user data
};

}  // namespace stiction::plot
