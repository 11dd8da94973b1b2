// The legend of the arrows, at the bottom left of the CPU overlay: what each colour means and
// the scale as a bar as long as an arrow of a round value ("[bar] normal force: 10 N"), measured at
// the camera's target (perspective makes nearer arrows longer).
#pragma once

#include "image/image.hpp"
#include "render/camera.hpp"
#include "render/force_arrows.hpp"
#include "text/font.hpp"

namespace stiction::render {

// A legend bar: `value` (a round 1-2-5 number of the scale's unit) drawn `pixels` long.
struct LegendBar {
  double value = 0.0;
  double pixels = 0.0;
};
// The 1-2-5 value whose bar is at most `target_pixels` long (and at least 0.4 of it), given the
// scale (units per metre) and the pixels per metre at the camera's target.
LegendBar legend_bar(double units_per_metre, double pixels_per_metre, double target_pixels);

// Pixels per metre of a picture `height` pixels high at the camera's target distance.
double pixels_per_metre(const Camera& camera, int height);

class ArrowLegend {
 public:
  ArrowLegend(bool forces, bool velocities, const ArrowScales& scales, int image_height);
  // Draws the legend; `bottom`: the lowest pixel row it may use (above the caption).
  void draw(image::Image& frame, const Camera& camera, int bottom);
  // The most of the frame the legend can cover, whatever the camera (its bars at their
  // longest, each value with three digits and a prefix): a panel the camera keeps the
  // bodies clear of, known before the camera is.
  PixelBox bound(int bottom);

 private:
  bool forces_, velocities_;
  ArrowScales scales_;
  text::Font font_;
  text::TextStyle style_;
};

}  // namespace stiction::render
