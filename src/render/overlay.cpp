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

}  // namespace

std::vector<OverlayValue> overlay_values(const OverlaySettings& settings) {
  std::vector<OverlayValue> values;
  if (!settings.signal.empty()) values.push_back({settings.signal, settings.label, settings.unit});
  values.insert(values.end(), settings.layers.values.begin(), settings.layers.values.end());
  return values;
}

double threshold_zero(const std::string& signal, const std::map<std::string, double>& thresholds,
                      double default_threshold) {
  std::string contact;
  const std::size_t at = signal.rfind(".slip");
  if (at == std::string::npos || at == 0) return -1.0;
  const std::string rest = signal.substr(at + 5);
  if (!(rest.empty() || rest == ".x" || rest == ".y" || rest == ".z")) return -1.0;
  contact = signal.substr(0, at);
  const auto it = thresholds.find(contact);
  if (it != thresholds.end()) return it->second;
  // A contact the run gave no threshold of its own (a hand-written trajectory in tests).
  return thresholds.empty() ? default_threshold : -1.0;
}

std::string speed_note(double speed) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.0f", 1.0 / speed);
  if (std::string(buffer) == "1") return "";
  return std::string("  (1/") + buffer + " speed)";
}

Overlay::Overlay(const OverlaySettings& settings, int image_height, double end_time, bool time_warp,
                 const std::map<std::string, double>& signal_thresholds)
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

  // Left-aligned labels and one number column for every value, so their digits line up.
  double unit_width = 0.0;
  for (const OverlayValue& v : overlay_values(settings_)) {
    const auto given = signal_thresholds.find(v.signal);
    Line line{v, v.label + " = ",
              given != signal_thresholds.end()
                  ? given->second
                  : threshold_zero(v.signal, settings_.stick_thresholds,
                                   settings_.default_stick_threshold)};
    value_x_ = std::max(value_x_, width(line.prefix));
    for (const std::string& s : widest_number_candidates(v.unit)) {
      value_number_width_ = std::max(value_number_width_, width(s));
    }
    for (const std::string& u : possible_units(v.unit)) {
      unit_width = std::max(unit_width, width(u.empty() ? u : " " + u));
    }
    lines_.push_back(std::move(line));
  }
  if (!lines_.empty()) {
    value_number_width_ = std::max(value_number_width_, width("n/a"));
    panel_width_ = std::max(panel_width_, value_x_ + value_number_width_ + unit_width);
  }
}

void Overlay::measure_zero_levels(const PoseTrack& poses) {
  // The signal's scale over the run: magnitudes below 1e-9 of it are rounding noise.
  for (Line& line : lines_) {
    if (line.zero_below >= 0.0) continue;
    double largest = 0.0;
    const double t0 = poses.start_time(), t1 = poses.end_time();
    for (int i = 0; i <= 512; ++i) {
      const double v = std::abs(poses.signal(line.value.signal, t0 + (t1 - t0) * i / 512.0));
      if (std::isfinite(v)) largest = std::max(largest, v);
    }
    line.zero_below = 1e-9 * largest;
  }
  zero_levels_known_ = true;
}

std::vector<std::string> Overlay::value_lines(const PoseTrack& poses, double t) {
  if (!zero_levels_known_) measure_zero_levels(poses);
  std::vector<std::string> out;
  for (const Line& line : lines_) {
    const Quantity q =
        format_quantity(poses.signal(line.value.signal, t), line.value.unit, line.zero_below);
    out.push_back(line.prefix + q.number + (q.unit.empty() ? "" : " " + q.unit));
  }
  return out;
}

PixelBox Overlay::box() const {
  if (!settings_.enabled) return {};
  const int lines = 1 + static_cast<int>(lines_.size());
  PixelBox box;
  box.x0 = static_cast<int>(pad_);
  box.y0 = static_cast<int>(pad_);
  box.x1 = static_cast<int>(std::ceil(pad_ + panel_width_ + 2 * pad_));
  box.y1 = static_cast<int>(pad_ + lines * line_height_ + pad_);
  return box;
}

PixelBox Overlay::draw(image::Image& frame, const PoseTrack& poses, double t, double speed) {
  if (!settings_.enabled) return {};
  auto width = [&](const std::string& s) { return font_.measure(s, style_).width; };
  // Translucent white panel so the text reads on any background; its size is the run's.
  const PixelBox box = this->box();
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
  font_.draw(frame, " s" + speed_note(speed), time_x + time_number_width_, baseline, style_);
  if (!lines_.empty() && !zero_levels_known_) measure_zero_levels(poses);
  for (const Line& line : lines_) {
    baseline += line_height_;
    const Quantity q =
        format_quantity(poses.signal(line.value.signal, t), line.value.unit, line.zero_below);
    const double value_x = left + value_x_;
    font_.draw(frame, line.prefix, left, baseline, style_);
    font_.draw(frame, q.number, value_x + value_number_width_ - width(q.number), baseline, style_);
    if (!q.unit.empty())
      font_.draw(frame, " " + q.unit, value_x + value_number_width_, baseline, style_);
  }
  return box;
}

}  // namespace stiction::render
