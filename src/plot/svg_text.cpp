#include "plot/svg_text.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "text/xml_escape.hpp"

namespace stiction::plot {
namespace {

// A coordinate with at most three decimals (a thousandth of a pixel), "." whatever the locale.
std::string number(double value) {
  if (!std::isfinite(value)) value = 0.0;
  char buffer[64];
  const auto [end, ec] =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, 3);
  std::string s(buffer, ec == std::errc() ? end : buffer);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s == "-0" ? "0" : s;
}

std::string colour(image::Rgba c) {
  return "rgb(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

// Replaces the value of attribute `name` in the tag that starts at `tag_start`.
void set_attribute(std::string& svg, std::size_t tag_start, const std::string& name,
                   const std::string& value) {
  const std::size_t tag_end = svg.find('>', tag_start);
  const std::string key = " " + name + "=\"";
  const std::size_t at = svg.find(key, tag_start);
  if (at == std::string::npos || at > tag_end) {
    throw std::runtime_error("cairo's SVG has no " + name + " attribute on its root");
  }
  const std::size_t start = at + key.size();
  const std::size_t end = svg.find('"', start);
  svg.replace(start, end - start, value);
}

}  // namespace

std::string add_svg_text(const std::string& svg, const std::vector<PlacedText>& texts,
                         std::optional<PageSize> page_mm) {
  std::string out = svg;
  const std::size_t root = out.find("<svg");
  const std::size_t close = out.rfind("</svg>");
  if (root == std::string::npos || close == std::string::npos || close < root) {
    throw std::runtime_error("cairo's SVG has no <svg> root");
  }
  // Pen origins are the start of the baseline: anchor "start", baseline "alphabetic" (SVG's
  // defaults, written out so that an editor keeps them). Viewers kern, as the layout did.
  std::string group =
      "<g font-family=\"DejaVu Sans, sans-serif\" font-style=\"normal\" font-weight=\"normal\" "
      "text-anchor=\"start\" dominant-baseline=\"alphabetic\">\n";
  // Appended piece by piece (GCC 12 warns falsely on chains of "literal" + std::string).
  auto attribute = [&](const char* name, const std::string& value) {
    group += ' ';
    group += name;
    group += "=\"";
    group += value;
    group += '"';
  };
  for (const PlacedText& t : texts) {
    group += "  <text";
    if (t.rotated) {
      attribute("transform",
                "translate(" + number(t.x) + "," + number(t.baseline) + ") rotate(-90)");
      attribute("x", "0");
      attribute("y", "0");
    } else {
      attribute("x", number(t.x));
      attribute("y", number(t.baseline));
    }
    attribute("font-size", number(t.size));
    attribute("fill", colour(t.colour));
    if (t.colour.a != 255) attribute("fill-opacity", number(t.colour.a / 255.0));
    group += '>';
    group += text::xml_escaped(t.text);
    group += "</text>\n";
  }
  group += "</g>\n";
  out.insert(close, group);
  if (page_mm) {
    set_attribute(out, root, "width", number(page_mm->width_mm) + "mm");
    set_attribute(out, root, "height", number(page_mm->height_mm) + "mm");
  }
  return out;
}

}  // namespace stiction::plot
