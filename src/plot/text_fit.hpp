// The one rule for text that must fit a width: every title, axis title, caption, legend entry
// and event label of every figure (run, compare, study, verify and the video's inset, which
// all draw through plot::draw) goes through fit_text(). In order, the first that fits:
//
//  1. the text at its size, wrapped onto at most `max_lines` lines at word boundaries: spaces
//     first, not inside parentheses ("θ(5 s)") unless the group is longer than a line; a word
//     longer than a line (a long name) also breaks after '_', after a '.' that follows a
//     letter (sphere.v.x; not a decimal point) and after a hyphen between letters. When it
//     wraps, a unit in brackets at the end ("[m/s]") takes a line of its own;
//  2. the same, smaller, in steps of 10%, down to its floor (Metrics::floor: 70% in the pixel
//     design; 75% in print but not below 6 pt, and a text set under 6 pt does not shrink);
//  3. at the floor, shortened: remarks in parentheses are left out first ("Key-signal error
//     (relative)" -> "Key-signal error"), the last first; then whole words or whole name
//     segments from the middle, about a third of those kept from the beginning and two thirds
//     from the end, the first and the last always among them while two are kept
//     ("joint1_friction stop 4.651 s" -> "joint1_… stop 4.651 s"), "…" in their place; at
//     last the last word alone. The unit is never shortened or left out;
//  4. a text whose shortest form (one word or name segment, and its unit) still does not fit
//     is set smaller than the floor, as small as it must be: it is never cut.
//
// So "…" stands only for whole words or whole segments, never inside a word.
// Internal to src/plot.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "plot/painter.hpp"

namespace stiction::plot {

// What a text may do to fit.
struct TextRule {
  double size = 0.0;          // its size, in pixels
  double min_size = 0.0;      // the floor it may shrink to (= size: it keeps its size)
  double max_width = 0.0;     // of every line, in pixels
  std::size_t max_lines = 1;  // lines it may wrap onto
};

struct FittedText {
  std::vector<std::string> lines;  // at least one (possibly empty for an empty text)
  double size = 0.0;               // the size they are set in
  bool shortened = false;          // words left out (step 3)
  bool below_floor = false;        // set smaller than the floor (step 4)
  // The lines joined by spaces (a one-line text is its line).
  std::string joined() const;
};

FittedText fit_text(Painter& painter, const std::string& text, const TextRule& rule);

}  // namespace stiction::plot
