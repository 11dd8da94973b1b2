// Text drawn over a read-back frame on the CPU: the simulation time and the chosen signals, in
// a translucent panel at the top left whose size is fixed for the whole run (numbers are
// right-aligned in a column as wide as the widest value the format can produce), so the box
// never changes width from frame to frame. (The title and caption: title_caption.hpp.)
#pragma once

#include <map>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/frame_panels.hpp"
#include "render/render_settings.hpp"
#include "render/scene_view.hpp"
#include "text/font.hpp"

namespace stiction::render {

// The values an overlay shows: `signal` (the one-value form) first, then `layers.values`.
std::vector<OverlayValue> overlay_values(const OverlaySettings& settings);

// The magnitude below which a signal prints as zero, if the signal has a stick threshold:
// a contact's slip speed "C.slip" (or a component "C.slip.x") uses the contact's own
// threshold, so a rolling ball's 142.5 nm/s of rounding noise reads 0. -1 otherwise.
double threshold_zero(const std::string& signal, const std::map<std::string, double>& thresholds,
                      double default_threshold);

// The playback-speed note of the time line: "  (1/8 speed)", or "" when the speed prints as
// 1/1 (the frames between slow-motion windows).
std::string speed_note(double speed);

class Overlay {
 public:
  // Opens the bundled font (text::FontError if missing). `end_time`: the run's last time
  // (sizes the time column). `time_warp`: reserve room for a playback-speed note.
  // `signal_thresholds`: more signals that print as zero below a threshold (a friction
  // joint's rate "ARM.omega.J" below the joint's stick threshold: joint_rate_thresholds).
  Overlay(const OverlaySettings& settings, int image_height, double end_time = 1.0,
          bool time_warp = false, const std::map<std::string, double>& signal_thresholds = {});
  // Draws "t = 1.234 s" and a "LABEL = VALUE UNIT" line per value. `speed` < 1 (slow motion around
  // an event) adds "(1/8 speed)" to the time line. Returns the panel's box.
  PixelBox draw(image::Image& frame, const PoseTrack& poses, double t, double speed = 1.0);
  // The panel's box (the same at every time; empty when the overlay is off).
  PixelBox box() const;
  // The text of the value lines at time t, as drawn ("slip speed = 0.000 m/s").
  std::vector<std::string> value_lines(const PoseTrack& poses, double t);

 private:
  struct Line {
    OverlayValue value;
    std::string prefix;        // "LABEL = "
    double zero_below = -1.0;  // < 0: measured on the first frame (1e-9 of the largest)
  };
  void measure_zero_levels(const PoseTrack& poses);

  OverlaySettings settings_;
  text::Font font_;
  text::TextStyle style_;
  double pad_, line_height_;
  std::string time_prefix_;  // "t = "
  std::vector<Line> lines_;
  double time_number_width_ = 0;   // widest time number
  double value_x_ = 0;             // numbers column, from the left text edge
  double value_number_width_ = 0;  // widest value number
  double panel_width_ = 0;
  bool zero_levels_known_ = false;
};

}  // namespace stiction::render
