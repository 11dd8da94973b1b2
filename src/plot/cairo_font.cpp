#include "plot/cairo_font.hpp"

#include <cairo-ft.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include "text/font.hpp"

namespace stiction::plot {

// Owned by the cairo face through user data: released when cairo drops its last reference.
struct FreeTypeHandles {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  ~FreeTypeHandles() {
    if (face) FT_Done_Face(face);
    if (library) FT_Done_FreeType(library);
  }
};

namespace {

const cairo_user_data_key_t kHandlesKey{};

void destroy_handles(void* data) { delete static_cast<FreeTypeHandles*>(data); }

}  // namespace

CairoFont::CairoFont(const std::filesystem::path& file) {
  auto* handles = new FreeTypeHandles;
  if (FT_Init_FreeType(&handles->library) != 0) {
    delete handles;
    throw text::FontError("FreeType could not be initialised");
  }
  if (FT_New_Face(handles->library, file.c_str(), 0, &handles->face) != 0) {
    delete handles;
    throw text::FontError(file.string() + ": cannot read the font");
  }
  face_ = cairo_ft_font_face_create_for_ft_face(handles->face, 0);
  if (cairo_font_face_set_user_data(face_, &kHandlesKey, handles, destroy_handles) !=
      CAIRO_STATUS_SUCCESS) {
    cairo_font_face_destroy(face_);
    face_ = nullptr;
    delete handles;
    throw text::FontError("cairo could not use the font " + file.string());
  }
  handles_ = handles;
}

double CairoFont::kerning(unsigned long left_glyph, unsigned long right_glyph) const {
  FT_Face face = handles_->face;
  if (!FT_HAS_KERNING(face) || face->units_per_EM == 0) return 0.0;
  FT_Vector delta{0, 0};
  if (FT_Get_Kerning(face, static_cast<FT_UInt>(left_glyph), static_cast<FT_UInt>(right_glyph),
                     FT_KERNING_UNSCALED, &delta) != 0) {
    return 0.0;
  }
  return static_cast<double>(delta.x) / face->units_per_EM;
}

CairoFont CairoFont::open_default() { return CairoFont(text::default_font_path()); }

CairoFont::~CairoFont() {
  if (face_) cairo_font_face_destroy(face_);
}

}  // namespace stiction::plot
