// SVG figures keep their text as <text> elements (an editor can restyle them), placed where
// the layout measured them, in the bundled font's family; no glyph outlines; well-formed XML;
// and a print figure's SVG says its size in millimetres.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "../app/svg_check.hpp"
#include "image/compare.hpp"
#include "image/png.hpp"
#include "plot/plot_spec.hpp"
#include "synthetic.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

const fs::path kOut = fs::path(STICTION_TEST_OUTPUT_DIR) / "svg_text";

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const std::size_t start = at + key.size();
  return tag.substr(start, tag.find('"', start) - start);
}

struct SvgText {
  std::string tag;   // the opening tag, with its attributes
  std::string text;  // the character data, unescaped
  std::string family;
};

std::string unescaped(std::string s) {
  const std::pair<const char*, const char*> entities[] = {
      {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}, {"&amp;", "&"}};
  for (const auto& [from, to] : entities) {
    for (std::size_t at = 0; (at = s.find(from, at)) != std::string::npos; ++at) {
      s.replace(at, std::string(from).size(), to);
    }
  }
  return s;
}

// Every <text> element and the font family of the <g> around it.
std::vector<SvgText> texts_of(const std::string& svg) {
  std::vector<SvgText> texts;
  std::string family;
  for (std::size_t at = 0; (at = svg.find('<', at)) != std::string::npos; ++at) {
    const std::size_t end = svg.find('>', at);
    const std::string tag = svg.substr(at, end + 1 - at);
    if (tag.rfind("<g ", 0) == 0 && !attribute(tag, "font-family").empty()) {
      family = attribute(tag, "font-family");
    }
    if (tag.rfind("<text", 0) == 0) {
      const std::size_t close = svg.find("</text>", end);
      texts.push_back({tag, unescaped(svg.substr(end + 1, close - end - 1)), family});
    }
  }
  return texts;
}

plot::Figure fig4() {
  plot::Figure figure =
      plot::make_figure(plot::paper_fig4_spec(), plot::testing::sphere_run(1.0),
                        {{"ground.stick_time", plot::testing::sphere_stick_time()}});
  figure.title += " & <friends>";  // characters XML must escape
  figure.print.reset();  // the pixel design: the title on one line, 1 user unit a pixel
  return figure;
}

}  // namespace

TEST_CASE("SVG text is <text> elements at the layout's places, no glyph outlines", "[plot][svg]") {
  fs::create_directories(kOut);
  const plot::Figure figure = fig4();
  const fs::path path = kOut / "fig4.svg";
  const plot::FigureLayout layout = plot::write_figure(figure, path, plot::Format::svg);
  const std::string svg = read_text(path);

  const testing::SvgDocument doc = testing::parse_svg(svg);
  INFO(doc.error);
  REQUIRE(doc.well_formed);
  CHECK(doc.root == "svg");
  CHECK(svg.find("<symbol") == std::string::npos);
  CHECK(svg.find("glyph") == std::string::npos);

  const std::vector<SvgText> texts = texts_of(svg);
  REQUIRE(texts.size() == layout.texts.size());
  std::map<std::string, int> found;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const SvgText& t = texts[i];
    const plot::TextBox& box = layout.texts[i];  // drawn in the same order
    INFO(t.tag << t.text);
    CHECK(t.text == box.text);
    CHECK(t.family.rfind("DejaVu Sans", 0) == 0);
    const double size = std::stod(attribute(t.tag, "font-size"));
    CHECK(size > 0.0);
    if (box.role == plot::TextRole::axis_label && box.panel >= 0) {
      // Rotated: the pen origin is the box's bottom end, at the baseline.
      const std::string transform = attribute(t.tag, "transform");
      REQUIRE(transform.rfind("translate(", 0) == 0);
      CHECK(transform.find("rotate(-90)") != std::string::npos);
      const double x = std::stod(transform.substr(10));
      const double y = std::stod(transform.substr(transform.find(',') + 1));
      CHECK(y == Approx(box.box.y1).margin(0.01));
      CHECK(x > box.box.x0);
      CHECK(x < box.box.x1);
    } else {
      CHECK(std::stod(attribute(t.tag, "x")) == Approx(box.box.x0).margin(0.01));
      const double baseline = std::stod(attribute(t.tag, "y"));
      CHECK(baseline > box.box.y0);
      CHECK(baseline < box.box.y1);
    }
    ++found[plot::TextRole::title == box.role ? "title" : ""];
    if (box.role == plot::TextRole::tick_label) ++found["tick"];
  }
  CHECK(found["title"] == 1);
  CHECK(found["tick"] >= 8);
  CHECK(svg.find("cf. paper Fig. 4) &amp; &lt;friends&gt;</text>") != std::string::npos);

  // Rendered by another program (rsvg, with DejaVu Sans installed), the text lands where
  // the PNG has it: compared at a quarter of the size, as the layout tests compare.
  const fs::path png = kOut / "fig4.svg.png";
  REQUIRE(std::system(("rsvg-convert -b white -o '" + png.string() + "' '" + path.string() + "'")
                          .c_str()) == 0);
  const image::Image converted = image::read_png(png);
  const image::Image drawn = plot::render(figure);
  REQUIRE(converted.width == drawn.width);
  long off = 0;
  for (int y = 0; y + 4 <= drawn.height; y += 4) {
    for (int x = 0; x + 4 <= drawn.width; x += 4) {
      int a = 0, b = 0;
      for (int dy = 0; dy < 4; ++dy) {
        for (int dx = 0; dx < 4; ++dx) {
          a += drawn.at(x + dx, y + dy).g;
          b += converted.at(x + dx, y + dy).g;
        }
      }
      if (std::abs(a - b) > 48 * 16) ++off;
    }
  }
  CHECK(off < drawn.width * drawn.height / 16 / 1000);  // under 0.1% of the blocks
}

TEST_CASE("a print figure's SVG is its page in mm, its text and lines in points",
          "[plot][svg][print]") {
  fs::create_directories(kOut);
  plot::Figure figure = fig4();
  figure.print = plot::Figure::Print{88.0, 66.0, 8.0, 300.0};
  const fs::path path = kOut / "fig4_print.svg";
  const plot::FigureLayout layout = plot::write_figure(figure, path, plot::Format::svg);
  const std::string svg = read_text(path);
  const std::size_t root = svg.find("<svg");
  const std::string tag = svg.substr(root, svg.find('>', root) - root);
  CHECK(attribute(tag, "width") == "88mm");
  CHECK(attribute(tag, "height") == "66mm");
  CHECK(attribute(tag, "viewBox") == "0 0 1039 780");
  // User units are pixels at 300 dpi: 8 pt text is 33.33 units, 9 pt the title; a text too
  // long for its place smaller, down to 6 pt (text_fit.hpp), and the SVG says the size the
  // layout measured it at (the height of its box is the font's ascent + descent).
  const std::vector<SvgText> texts = texts_of(svg);
  REQUIRE(texts.size() == layout.texts.size());
  int full = 0;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    INFO(texts[i].text);
    const double points = std::stod(attribute(texts[i].tag, "font-size")) * 72.0 / 300.0;
    const bool title = layout.texts[i].role == plot::TextRole::title;
    CHECK(points <= Approx(title ? 9.0 : 8.0));
    CHECK(points >= Approx(title ? 6.75 : 6.0));
    const bool rotated =
        layout.texts[i].role == plot::TextRole::axis_label && layout.texts[i].panel >= 0;
    const double box = rotated ? layout.texts[i].box.width() : layout.texts[i].box.height();
    CHECK(box / (points * 300.0 / 72.0) == Approx(1.1641).epsilon(0.01));
    if (points == Approx(title ? 9.0 : 8.0)) ++full;
  }
  CHECK(full > static_cast<int>(texts.size()) / 2);  // most text at its size
  // The series are 0.96 pt wide (3.2 line units of 0.3 pt), the frame 0.48 pt.
  const testing::SvgDocument doc = testing::parse_svg(svg);
  REQUIRE(doc.well_formed);
  int series = 0, frames = 0;
  for (const testing::SvgPath& p : doc.paths) {
    if (p.style.find("stroke:rgb(0%,44.705882%,69.803922%)") != std::string::npos) {
      CHECK(p.style.find("stroke-width:4;") != std::string::npos);
      ++series;
    }
    if (p.style.find("stroke-width:2;") != std::string::npos &&
        p.style.find("stroke:rgb(23.529412%,23.529412%,23.529412%)") != std::string::npos) {
      ++frames;
    }
  }
  CHECK(series >= 2);
  CHECK(frames >= 2);
}
