// Text drawn over a read-back frame on the CPU: the simulation time and one signal, in a
// translucent panel at the top left whose size is fixed for the whole run (numbers are
// right-aligned in a column as wide as the widest value the format can produce), so the box
// never changes width from frame to frame.
#pragma once

#include <string>

#include "image/image.hpp"
#include "render/render_settings.hpp"
#include "render/scene_view.hpp"
#include "text/font.hpp"

namespace stiction::render {

struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  bool operator==(const PixelBox&) const = default;
};

class Overlay {
 public:
  // Opens the bundled font (text::FontError if missing). `end_time`: the run's last time
  // (sizes the time column). `time_warp`: reserve room for a playback-speed note.
  Overlay(const OverlaySettings& settings, int image_height, double end_time = 1.0,
          bool time_warp = false);
  // Draws "t = 1.234 s" and "LABEL = VALUE UNIT". `speed` < 1 (slow motion around an event)
  // adds "(1/8 speed)" to the time line. Returns the panel's box.
  PixelBox draw(image::Image& frame, const PoseTrack& poses, double t, double speed = 1.0);

 private:
  OverlaySettings settings_;
  text::Font font_;
  text::TextStyle style_;
  double pad_, line_height_;
  std::string time_prefix_;        // "t = "
  std::string value_prefix_;       // "LABEL = "
  double time_number_width_ = 0;   // widest time number
  double value_number_width_ = 0;  // widest value number
  double unit_width_ = 0;          // widest unit (with prefix)
  double panel_width_ = 0;
  double zero_below_ = 0;  // 1e-9 of the signal's largest magnitude over the run
};

}  // namespace stiction::render
