// draw() with the choice of how text is output: drawn as glyphs by cairo (PNG, PDF), or
// measured, laid out and handed back for an SVG that keeps text as <text> elements.
// Internal to src/plot.
#pragma once

#include <cairo.h>

#include <vector>

#include "plot/figure.hpp"
#include "plot/painter.hpp"

namespace stiction::plot {

// As draw(); with `texts`, no text is drawn: each is appended there, placed as it would be.
FigureLayout draw_figure(const Figure& figure, cairo_t* cr, std::vector<PlacedText>* texts);

}  // namespace stiction::plot
