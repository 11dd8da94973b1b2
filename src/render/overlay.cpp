#include "render/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stiction::render {

std::string format_value(double v) {
  char buffer[32];
  if (std::isnan(v)) return "n/a";
  const double a = std::abs(v);
  if (a != 0.0 && (a < 1e-3 || a >= 1e5)) {
    std::snprintf(buffer, sizeof buffer, "%.2e", v);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.4f", v);
  }
  return buffer;
}

Overlay::Overlay(const OverlaySettings& settings, int image_height)
    : settings_(settings),
      font_(text::Font::open_default()),
      pixel_size_(std::max(11.0, image_height / 30.0)) {}

void Overlay::draw(image::Image& frame, const PoseTrack& poses, double t) {
  if (!settings_.enabled) return;
  char time_text[48];
  std::snprintf(time_text, sizeof time_text, "t = %.3f s", t);
  std::vector<std::string> lines{time_text};
  if (!settings_.signal.empty()) {
    std::string line = settings_.label + " = " + format_value(poses.signal(settings_.signal, t));
    if (!settings_.unit.empty()) line += " " + settings_.unit;
    lines.push_back(line);
  }
  text::TextStyle style;
  style.pixel_size = pixel_size_;
  style.colour = {20, 22, 26, 255};
  const double pad = 0.6 * pixel_size_;
  const double line_height = 1.35 * pixel_size_;
  double width = 0.0;
  for (const auto& l : lines) width = std::max(width, font_.measure(l, style).width);
  // Translucent white panel so the text reads on any background.
  const int x0 = static_cast<int>(pad), y0 = static_cast<int>(pad);
  const int x1 = static_cast<int>(pad + width + 2 * pad);
  const int y1 = static_cast<int>(pad + lines.size() * line_height + pad);
  for (int y = y0; y < std::min(y1, frame.height); ++y) {
    for (int x = x0; x < std::min(x1, frame.width); ++x) frame.blend(x, y, {255, 255, 255, 255}, 0.75f);
  }
  double baseline = pad + pad + 0.95 * pixel_size_;
  for (const auto& l : lines) {
    font_.draw(frame, l, 2.0 * pad, baseline, style);
    baseline += line_height;
  }
}

}  // namespace stiction::render
