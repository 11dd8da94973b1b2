#include "render/arrow_legend.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "render/number_format.hpp"

namespace stiction::render {
namespace {

// Linear RGB -> sRGB bytes, so the legend's swatch is the arrow's lit colour's hue.
image::Rgba srgb(const glm::vec3& c) {
  auto channel = [](float v) {
    const float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return static_cast<std::uint8_t>(std::lround(std::clamp(s, 0.0f, 1.0f) * 255.0f));
  };
  return {channel(c.r), channel(c.g), channel(c.b), 255};
}

void fill(image::Image& frame, int x0, int y0, int x1, int y1, image::Rgba c, float coverage) {
  for (int y = std::max(0, y0); y < std::min(y1, frame.height); ++y) {
    for (int x = std::max(0, x0); x < std::min(x1, frame.width); ++x)
      frame.blend(x, y, c, coverage);
  }
}

std::string bar_label(double value, const std::string& unit) {
  const Quantity q = format_quantity(value, unit);
  // Round values: drop the trailing zeros format_quantity keeps for its fixed width.
  std::string n = q.number;
  if (n.find('.') != std::string::npos && n.find('e') == std::string::npos) {
    while (n.back() == '0') n.pop_back();
    if (n.back() == '.') n.pop_back();
  }
  return ": " + n + " " + q.unit;
}

}  // namespace

LegendBar legend_bar(double units_per_metre, double pixels_per_metre, double target_pixels) {
  // The value whose bar is target_pixels long, rounded down to 1, 2 or 5 times a power of ten
  // (so the bar is 0.4 to 1 times the target).
  const double exact = target_pixels / pixels_per_metre * units_per_metre;
  const double decade = std::pow(10.0, std::floor(std::log10(exact)));
  const double m = exact / decade;
  const double value = (m >= 5.0 ? 5.0 : m >= 2.0 ? 2.0 : 1.0) * decade;
  return {value, value / units_per_metre * pixels_per_metre};
}

double pixels_per_metre(const Camera& camera, int height) {
  const double distance = glm::length(camera.eye - camera.target);
  const double half = std::tan(0.5 * glm::radians(static_cast<double>(camera.fov_y_degrees)));
  return height / (2.0 * distance * half);
}

ArrowLegend::ArrowLegend(bool forces, bool velocities, const ArrowScales& scales, int image_height)
    : forces_(forces), velocities_(velocities), scales_(scales), font_(text::Font::open_default()) {
  style_.pixel_size = std::max(10.0, image_height / 36.0);
  style_.colour = {20, 22, 26, 255};
}

PixelBox ArrowLegend::bound(int bottom) {
  const double px = style_.pixel_size, pad = 0.6 * px, line = 1.4 * px;
  std::vector<std::pair<std::string, std::string>> rows;  // name, unit
  if (forces_) rows.insert(rows.end(), {{"normal force", "N"}, {"friction", "N"}});
  if (velocities_) rows.emplace_back("velocity", "m/s");
  if (rows.empty()) return {};
  double width = 0.0;
  for (const auto& [name, unit] : rows) {
    for (const char* prefix : {"", "m", "\u00b5", "k", "M"}) {
      const std::string label = " " + name + ": 500 " + prefix + unit;
      width = std::max(width, 4.0 * px + font_.measure(label, style_).width);
    }
  }
  const double height = rows.size() * line + 2.0 * pad;
  const int x0 = static_cast<int>(pad);
  return {x0, static_cast<int>(bottom - height),
          static_cast<int>(std::ceil(x0 + width + 2.0 * pad)), bottom};
}

void ArrowLegend::draw(image::Image& frame, const Camera& camera, int bottom) {
  const double px = style_.pixel_size, pad = 0.6 * px, line = 1.4 * px;
  const double ppm = pixels_per_metre(camera, frame.height);
  struct Row {
    image::Rgba colour;
    std::string name;
    LegendBar bar;
    std::string unit;
  };
  std::vector<Row> rows;
  if (forces_) {
    const LegendBar bar = legend_bar(scales_.force, ppm, 4.0 * px);
    rows.push_back({srgb(kNormalForceColour), "normal force", bar, "N"});
    rows.push_back({srgb(kFrictionColour), "friction", bar, "N"});
  }
  if (velocities_) {
    rows.push_back(
        {srgb(kVelocityColour), "velocity", legend_bar(scales_.velocity, ppm, 4.0 * px), "m/s"});
  }
  if (rows.empty()) return;
  // Each row: a bar in the arrow's colour as long as an arrow of a round value, then
  // "normal force: 10 N" (that value).
  double width = 0.0;
  for (const Row& r : rows) {
    width = std::max(
        width,
        r.bar.pixels + font_.measure(" " + r.name + bar_label(r.bar.value, r.unit), style_).width);
  }
  const double height = rows.size() * line + 2.0 * pad;
  const int x0 = static_cast<int>(pad), y0 = static_cast<int>(bottom - height);
  fill(frame, x0, y0, static_cast<int>(std::ceil(x0 + width + 2.0 * pad)), bottom,
       {255, 255, 255, 255}, 0.75f);
  double baseline = y0 + pad + 1.0 * px;
  for (const Row& r : rows) {
    const double bx = x0 + pad;
    const int thickness = std::max(3, static_cast<int>(0.3 * px));
    const int mid = static_cast<int>(baseline - 0.35 * px);
    fill(frame, static_cast<int>(bx), mid - thickness / 2, static_cast<int>(bx + r.bar.pixels),
         mid - thickness / 2 + thickness, r.colour, 1.0f);
    // End ticks mark the bar's length exactly.
    fill(frame, static_cast<int>(bx), mid - thickness, static_cast<int>(bx) + 2, mid + thickness,
         r.colour, 1.0f);
    fill(frame, static_cast<int>(bx + r.bar.pixels) - 2, mid - thickness,
         static_cast<int>(bx + r.bar.pixels), mid + thickness, r.colour, 1.0f);
    font_.draw(frame, " " + r.name + bar_label(r.bar.value, r.unit), bx + r.bar.pixels, baseline,
               style_);
    baseline += line;
  }
}

}  // namespace stiction::render
