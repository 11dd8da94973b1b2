// Text that must fit a width: shortened in the middle with "…" or wrapped onto lines.
// Internal to src/plot.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "plot/painter.hpp"

namespace stiction::plot {

// The text itself if it fits in max_width, else its beginning and end around "…", as long as
// fits (a third from the beginning, two thirds from the end: long names differ at either end,
// a component and a signal, a run and its axis, and more often at the end).
std::string fit(Painter& painter, const std::string& text, double size, double max_width);

// Splits text into lines no longer than max_width, breaking at spaces; the bracketed unit
// part moves to its own line first. A word longer than a line is shortened with "…".
std::vector<std::string> wrap(Painter& painter, const std::string& text, double max_width,
                              double size, std::size_t max_lines);

}  // namespace stiction::plot
