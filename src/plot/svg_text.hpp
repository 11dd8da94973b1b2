// SVG figures whose text stays text. cairo 1.16 (Debian 12) writes SVG text as glyph
// outlines (<symbol> + <use>), which an editor cannot restyle or a journal re-typeset; so the
// figure is drawn through cairo's SVG surface without its text, and each text is added as an
// SVG <text> element in the bundled font's family ("DejaVu Sans") at the pen origin, size and
// rotation the layout measured through cairo-ft: a viewer with DejaVu Sans shows it as the
// PNG does. Internal to src/plot.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "plot/painter.hpp"

namespace stiction::plot {

// `svg` is cairo's document (without text); returns it with a <g> of <text> elements added
// as its last child (text is drawn last in every figure, over the data and legend boxes).
// With `page_mm` (width, height), the root's width and height say millimetres, the viewBox
// keeps the pixels in which the figure was laid out.
struct PageSize {
  double width_mm = 0.0, height_mm = 0.0;
};
std::string add_svg_text(const std::string& svg, const std::vector<PlacedText>& texts,
                         std::optional<PageSize> page_mm);

}  // namespace stiction::plot
