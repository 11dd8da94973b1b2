#include "render/title_caption.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::render {
namespace {

// The overlay panel's text size (overlay.cpp), so the title matches it.
double text_size(int image_height) { return std::max(11.0, image_height / 30.0); }

}  // namespace

std::unique_ptr<TitleCaption> TitleCaption::create(const OverlaySettings& settings,
                                                   int image_height) {
  const std::string title = settings.layers.title.value_or("");
  const std::string caption = settings.layers.caption.value_or("");
  if (!settings.enabled || (title.empty() && caption.empty())) return nullptr;
  return std::make_unique<TitleCaption>(title, caption, image_height);
}

TitleCaption::TitleCaption(std::string title, std::string caption, int image_height)
    : title_(std::move(title)), caption_(std::move(caption)), font_(text::Font::open_default()) {
  style_.pixel_size = text_size(image_height);
  style_.colour = {20, 22, 26, 255};
  pad_ = 0.6 * style_.pixel_size;
}

int TitleCaption::caption_height(const OverlaySettings& settings, int image_height) {
  if (!settings.enabled || settings.layers.caption.value_or("").empty()) return 0;
  const double size = 0.8 * text_size(image_height);
  // The band (1.35 lines and a pad of 0.6 of its text size) and the margin below it.
  return static_cast<int>(std::ceil(1.95 * size + 0.6 * text_size(image_height)));
}

void TitleCaption::draw(image::Image& frame) {
  if (!title_.empty()) {
    draw_band(frame, band(title_, style_.pixel_size, true, frame.width, frame.height), title_);
  }
  if (!caption_.empty()) {
    draw_band(frame, band(caption_, 0.8 * style_.pixel_size, false, frame.width, frame.height),
              caption_);
  }
}

std::vector<PixelBox> TitleCaption::boxes(int width, int height) {
  std::vector<PixelBox> out;
  if (!title_.empty()) out.push_back(band(title_, style_.pixel_size, true, width, height).box);
  if (!caption_.empty()) {
    out.push_back(band(caption_, 0.8 * style_.pixel_size, false, width, height).box);
  }
  return out;
}

TitleCaption::Band TitleCaption::band(const std::string& text, double pixel_size, bool top_right,
                                      int width, int height) {
  Band b;
  b.style = style_;
  b.style.pixel_size = pixel_size;
  double w = font_.measure(text, b.style).width;
  const double room = width - 4.0 * pad_;
  if (w > room) {
    b.style.pixel_size = std::max(0.6 * pixel_size, pixel_size * room / w);
    w = font_.measure(text, b.style).width;
  }
  const double pad = 0.6 * b.style.pixel_size;
  const double band_height = 1.35 * b.style.pixel_size + pad;
  b.text_x = top_right ? width - pad_ - pad - w : 0.5 * (width - w);
  const double y0 = top_right ? pad_ : height - pad_ - band_height;
  b.baseline = y0 + 0.5 * pad + 1.0 * b.style.pixel_size;
  b.box = {static_cast<int>(b.text_x - pad), static_cast<int>(y0),
           static_cast<int>(std::ceil(b.text_x + w + pad)),
           static_cast<int>(std::ceil(y0 + band_height))};
  return b;
}

void TitleCaption::draw_band(image::Image& frame, const Band& b, const std::string& text) {
  const PixelBox& box = b.box;
  for (int y = std::max(0, box.y0); y < std::min(box.y1, frame.height); ++y) {
    for (int px = std::max(0, box.x0); px < std::min(box.x1, frame.width); ++px) {
      frame.blend(px, y, {255, 255, 255, 255}, 0.75f);
    }
  }
  font_.draw(frame, text, b.text_x, b.baseline, b.style);
}

}  // namespace stiction::render
