// The video's title (top right) and caption (bottom centre), each on a translucent band,
// from [overlay] title and caption (defaults: the scene's name and description). A line
// wider than the picture is drawn smaller, down to 60% of its size.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/frame_panels.hpp"
#include "render/render_settings.hpp"
#include "text/font.hpp"

namespace stiction::render {

class TitleCaption {
 public:
  // Null when the overlay is off or both texts are empty.
  static std::unique_ptr<TitleCaption> create(const OverlaySettings& settings, int image_height);
  TitleCaption(std::string title, std::string caption, int image_height);
  void draw(image::Image& frame);
  // The bands' boxes on a frame `width` x `height` (the one drawn on: the size of a band
  // depends on its text), for the camera to keep the bodies clear of them.
  std::vector<PixelBox> boxes(int width, int height);

  // Pixels the caption's band takes at the bottom of a picture `image_height` high (with
  // its margin), for layers placed above it; 0 without a caption.
  static int caption_height(const OverlaySettings& settings, int image_height);

 private:
  // Where a band goes and the size its text is drawn at (shrunk when too wide).
  struct Band {
    PixelBox box;
    text::TextStyle style;
    double text_x = 0.0, baseline = 0.0;
  };
  Band band(const std::string& text, double pixel_size, bool top_right, int width, int height);
  void draw_band(image::Image& frame, const Band& b, const std::string& text);

  std::string title_, caption_;
  text::Font font_;
  text::TextStyle style_;
  double pad_;
};

}  // namespace stiction::render
