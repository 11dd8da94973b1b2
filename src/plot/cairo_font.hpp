// The bundled font (assets/DejaVuSans.ttf) as a cairo font face, loaded through FreeType
// (cairo-ft), so figures look the same on every machine whatever fonts it has installed.
// Owns the FreeType library and face; the cairo face keeps them alive as long as cairo
// needs them (a surface may outlive this object while it is being finished).
#pragma once

#include <cairo.h>

#include <filesystem>

namespace stiction::plot {

class CairoFont {
 public:
  // Throws text::FontError if the file cannot be read.
  explicit CairoFont(const std::filesystem::path& file);
  static CairoFont open_default();
  ~CairoFont();
  CairoFont(const CairoFont&) = delete;
  CairoFont& operator=(const CairoFont&) = delete;

  cairo_font_face_t* face() const { return face_; }

 private:
  cairo_font_face_t* face_ = nullptr;
};

}  // namespace stiction::plot
