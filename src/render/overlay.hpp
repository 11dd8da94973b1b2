// Text drawn over a read-back frame on the CPU: the simulation time and one signal.
#pragma once

#include <string>

#include "image/image.hpp"
#include "render/render_settings.hpp"
#include "render/scene_view.hpp"
#include "text/font.hpp"

namespace stiction::render {

class Overlay {
 public:
  // Opens the bundled font (text::FontError if missing).
  Overlay(const OverlaySettings& settings, int image_height);
  // Draws "t = 1.234 s" and "LABEL = VALUE UNIT" in a translucent panel at the top left.
  void draw(image::Image& frame, const PoseTrack& poses, double t);

 private:
  OverlaySettings settings_;
  text::Font font_;
  double pixel_size_;
};

// "1.23", "0.0123", "1.23e-05": three significant digits, for the overlay.
std::string format_value(double v);

}  // namespace stiction::render
