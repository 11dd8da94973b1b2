#include "render/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/number_format.hpp"

namespace stiction::render {
namespace {

std::string time_number(double t) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.3f", t);
  return buffer;
}

std::string speed_note(double speed) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "  (1/%.0f speed)", 1.0 / speed);
  return buffer;
}

}  // namespace

Overlay::Overlay(const OverlaySettings& settings, int image_height, double end_time, bool time_warp)
    : settings_(settings), font_(text::Font::open_default()) {
  style_.pixel_size = std::max(11.0, image_height / 30.0);
  style_.colour = {20, 22, 26, 255};
  pad_ = 0.6 * style_.pixel_size;
  line_height_ = 1.35 * style_.pixel_size;
  auto width = [&](const std::string& s) { return font_.measure(s, style_).width; };

  time_prefix_ = "t = ";
  // Every digit in every place of the largest time the run reaches.
  const std::string longest_time = time_number(std::max(std::abs(end_time), 1.0));
  for (char d = '0'; d <= '9'; ++d) {
    std::string s = longest_time;
    for (char& c : s) {
      if (c >= '0' && c <= '9') c = d;
    }
    time_number_width_ = std::max(time_number_width_, width(s));
  }
  double time_line = width(time_prefix_) + time_number_width_ + width(" s");
  if (time_warp) time_line += width(speed_note(1.0 / 88.0));
  panel_width_ = time_line;

  if (!settings_.signal.empty()) {
    zero_below_ = -1.0;  // measured on the first frame (the poses are not known here)
    value_prefix_ = settings_.label + " = ";
    for (const std::string& s : widest_number_candidates(settings_.unit)) {
      value_number_width_ = std::max(value_number_width_, width(s));
    }
    for (const std::string& u : possible_units(settings_.unit)) {
      unit_width_ = std::max(unit_width_, width(u.empty() ? u : " " + u));
    }
    value_number_width_ = std::max(value_number_width_, width("n/a"));
    panel_width_ = std::max(panel_width_, width(value_prefix_) + value_number_width_ + unit_width_);
  }
}

PixelBox Overlay::draw(image::Image& frame, const PoseTrack& poses, double t, double speed) {
  if (!settings_.enabled) return {};
  auto width = [&](const std::string& s) { return font_.measure(s, style_).width; };
  const int lines = settings_.signal.empty() ? 1 : 2;
  // Translucent white panel so the text reads on any background; its size is the run's.
  PixelBox box;
  box.x0 = static_cast<int>(pad_);
  box.y0 = static_cast<int>(pad_);
  box.x1 = static_cast<int>(std::ceil(pad_ + panel_width_ + 2 * pad_));
  box.y1 = static_cast<int>(pad_ + lines * line_height_ + pad_);
  for (int y = box.y0; y < std::min(box.y1, frame.height); ++y) {
    for (int x = box.x0; x < std::min(box.x1, frame.width); ++x) {
      frame.blend(x, y, {255, 255, 255, 255}, 0.75f);
    }
  }
  const double left = 2.0 * pad_;
  double baseline = pad_ + pad_ + 0.95 * style_.pixel_size;
  // Numbers right-aligned in their column: the digits stay put as the value changes.
  const double time_x = left + width(time_prefix_);
  const std::string tn = time_number(t);
  font_.draw(frame, time_prefix_, left, baseline, style_);
  font_.draw(frame, tn, time_x + time_number_width_ - width(tn), baseline, style_);
  std::string suffix = " s";
  if (speed < 0.999) suffix += speed_note(speed);
  font_.draw(frame, suffix, time_x + time_number_width_, baseline, style_);
  if (!settings_.signal.empty()) {
    baseline += line_height_;
    if (zero_below_ < 0.0) {  // first frame: the signal's scale over the run
      double largest = 0.0;
      const double t0 = poses.start_time(), t1 = poses.end_time();
      for (int i = 0; i <= 512; ++i) {
        const double v = std::abs(poses.signal(settings_.signal, t0 + (t1 - t0) * i / 512.0));
        if (std::isfinite(v)) largest = std::max(largest, v);
      }
      zero_below_ = 1e-9 * largest;
    }
    const Quantity q =
        format_quantity(poses.signal(settings_.signal, t), settings_.unit, zero_below_);
    const double value_x = left + width(value_prefix_);
    font_.draw(frame, value_prefix_, left, baseline, style_);
    font_.draw(frame, q.number, value_x + value_number_width_ - width(q.number), baseline, style_);
    if (!q.unit.empty())
      font_.draw(frame, " " + q.unit, value_x + value_number_width_, baseline, style_);
  }
  return box;
}

}  // namespace stiction::render
