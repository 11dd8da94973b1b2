// The scene file's [inset] table: a live plot inside the video (issue 22 item 4). A corner
// of every frame shows the chosen signals drawn up to the frame's time, a cursor at that
// time and the run's stick/slip events, so a transition is seen in the motion and in the
// curve at once. GL-free (checked before simulating, like [render]); drawn by inset_plot.
//
//   [inset]
//   signals = ["ground.slip", "sphere.w"]  # one panel each, stacked (a vector signal shows
//                                          # its norm, as the overlay does); none: no inset
//   position = "bottom_right"  # top_left, top_right, bottom_left or bottom_right
//   size = [0.4, 0.4]          # fractions of the frame (both <= 1) or pixels (at least
//                              # [200, 150]); an inset below 200 x 150 pixels (a compare
//                              # tile) is drawn at that size and scaled down
//   window = 2.0               # seconds shown; default: the whole run. A shorter window
//                              # pages: the plot shows [k w, (k + 1) w) and turns to the next
//                              # page when t passes its end
//   opacity = 0.8              # of the white background (0..1); curves stay opaque
//   labels = ["slip", "spin"]  # panel labels (default: the signal names)
//   units = ["m/s", "rad/s"]   # panel units (default: none)
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/toml_reader.hpp"

namespace stiction::render {

enum class InsetCorner { top_left, top_right, bottom_left, bottom_right };

struct InsetSettings {
  std::vector<std::string> signals;  // empty: no inset
  std::vector<std::string> labels;   // per signal; empty: the signal names
  std::vector<std::string> units;    // per signal; empty: none
  InsetCorner corner = InsetCorner::bottom_right;
  double width = 0.4, height = 0.4;  // fractions of the frame, or pixels when `in_pixels`
  bool in_pixels = false;
  std::optional<double> window;  // seconds; none: the whole run
  double opacity = 0.8;
  bool enabled() const { return !signals.empty(); }
};

// Reads [inset] (every key checked; errors are scene::InputError FILE:LINE:COL, exit 2).
// `columns`: the trajectory's columns a signal must match (exactly or as NAME.<axis>); empty
// skips that check.
void read_inset(scene::TableReader& table, InsetSettings& inset,
                const std::vector<std::string>& columns);

}  // namespace stiction::render
