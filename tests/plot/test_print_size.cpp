// Figures with a physical size (Figure::print): the page is width_mm x height_mm in every
// format, the text is font_pt on that page whatever its size or resolution, and the layout
// stays clean on pages from a narrow column to a full page.
#include <cairo.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "plot/cairo_font.hpp"
#include "plot/plot_spec.hpp"
#include "synthetic.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

const fs::path kOut = fs::path(STICTION_TEST_OUTPUT_DIR) / "print";

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Height of a text's logical box (ascent + descent) per unit of font size, for the bundled
// font: a box h pixels high holds text of h / ratio pixels.
double line_ratio() {
  const plot::CairoFont font = plot::CairoFont::open_default();
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 4, 4);
  cairo_t* cr = cairo_create(surface);
  cairo_set_font_face(cr, font.face());
  cairo_font_options_t* options = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);  // as figures do
  cairo_set_font_options(cr, options);
  cairo_font_options_destroy(options);
  cairo_set_font_size(cr, 100.0);
  cairo_font_extents_t e;
  cairo_font_extents(cr, &e);
  cairo_destroy(cr);
  cairo_surface_destroy(surface);
  return (e.ascent + e.descent) / 100.0;
}

// The font size in points of every text box of a print layout, by role.
struct TextSizes {
  double title = 0.0;
  double body_min = 1e9, body_max = 0.0;
};
TextSizes text_sizes(const plot::FigureLayout& layout) {
  REQUIRE(layout.dpi > 0.0);
  const double ratio = line_ratio();
  TextSizes sizes;
  for (const plot::TextBox& t : layout.texts) {
    // A rotated axis title is as wide as its line is high.
    const bool rotated = t.role == plot::TextRole::axis_label && t.panel >= 0;
    const double pixels = rotated ? t.box.width() : t.box.height();
    const double points = pixels / ratio * 72.0 / layout.dpi;
    if (t.role == plot::TextRole::title) {
      sizes.title = points;
    } else {
      sizes.body_min = std::min(sizes.body_min, points);
      sizes.body_max = std::max(sizes.body_max, points);
    }
  }
  return sizes;
}

// The least size a text of `pt` points may shrink to in print (Metrics::floor).
double floor_pt(double pt) { return std::max(0.75 * pt, std::min(pt, 6.0)); }

plot::Figure fig4(plot::Figure::Print print) {
  plot::Figure figure =
      plot::make_figure(plot::paper_fig4_spec(), plot::testing::sphere_run(1.0),
                        {{"ground.stick_time", plot::testing::sphere_stick_time()}});
  figure.print = print;
  return figure;
}

plot::Figure fig7(plot::Figure::Print print) {
  plot::Figure figure = plot::make_figure(plot::paper_fig7_spec(), plot::testing::arm_run(15.0),
                                          std::vector<plot::PlotEvent>{});
  figure.print = print;
  return figure;
}

void check_clean(const plot::FigureLayout& layout, const std::string& what) {
  INFO(what);
  const std::vector<std::string> problems = plot::layout_problems(layout);
  for (const std::string& p : problems) UNSCOPED_INFO(p);
  CHECK(problems.empty());
}

}  // namespace

TEST_CASE("a print figure is its page at its dpi, in PNG, PDF and SVG", "[plot][print]") {
  const plot::Figure figure = fig4({88.0, 66.0, 8.0, 300.0});
  // 88 mm at 300 dpi is 1039.4 pixels, 66 mm is 779.5.
  CHECK(plot::pixel_size(figure).width == 1039);
  CHECK(plot::pixel_size(figure).height == 780);
  fs::create_directories(kOut);

  const plot::FigureLayout png =
      plot::write_figure(figure, kOut / "fig4_88mm.png", plot::Format::png, /*dpi ignored*/ 100.0);
  CHECK(png.width == 1039);
  CHECK(png.dpi == 300.0);
  const std::string bytes = read_bytes(kOut / "fig4_88mm.png");
  const std::size_t at = bytes.find("pHYs");
  REQUIRE(at != std::string::npos);
  auto u32 = [&](std::size_t i) {
    return (static_cast<unsigned>(static_cast<unsigned char>(bytes[i])) << 24) |
           (static_cast<unsigned>(static_cast<unsigned char>(bytes[i + 1])) << 16) |
           (static_cast<unsigned>(static_cast<unsigned char>(bytes[i + 2])) << 8) |
           static_cast<unsigned>(static_cast<unsigned char>(bytes[i + 3]));
  };
  CHECK(u32(at + 4) == 11811u);  // 300 dpi in pixels per metre

  // The PDF page is 88 mm x 66 mm: 249.45 x 187.09 pt.
  plot::write_figure(figure, kOut / "fig4_88mm.pdf", plot::Format::pdf, 100.0);
  const std::string pdf = read_bytes(kOut / "fig4_88mm.pdf");
  const std::size_t box = pdf.find("/MediaBox");
  REQUIRE(box != std::string::npos);
  double x0 = -1, y0 = -1, x1 = 0, y1 = 0;
  REQUIRE(std::sscanf(pdf.c_str() + box, "/MediaBox [ %lf %lf %lf %lf", &x0, &y0, &x1, &y1) == 4);
  CHECK(x0 == 0.0);
  CHECK(y0 == 0.0);
  CHECK(x1 == Approx(88.0 / 25.4 * 72.0).margin(0.01));
  CHECK(y1 == Approx(66.0 / 25.4 * 72.0).margin(0.01));
  CHECK(std::abs(x1 - 249.4) < 0.05);
  CHECK(std::abs(y1 - 187.1) < 0.05);
}

TEST_CASE("print figures have text of font_pt on the page at any size and resolution",
          "[plot][print]") {
  // Every text is font_pt (the title one point more), whether the page is a narrow column
  // (3.5 in, where the pixel design gave 4 pt text) or a full page, at 72 to 600 dpi; a text
  // that does not fit may be smaller, down to its floor (text_fit.hpp: 75%, not below 6 pt),
  // never further on these pages.
  for (const double dpi : {72.0, 150.0, 300.0, 600.0}) {
    for (const auto& [width_mm, height_mm] :
         {std::pair{88.9, 66.0}, std::pair{70.0, 60.0}, std::pair{180.0, 110.0}}) {
      for (const double font_pt : {7.0, 8.0, 10.0}) {
        // 10 pt text needs a taller page than 60 mm for a title, two panels and legends.
        if (height_mm < 7 * font_pt) continue;
        for (int which = 0; which < 2; ++which) {
          const plot::Figure::Print print{width_mm, height_mm, font_pt, dpi};
          const plot::Figure figure = which == 0 ? fig4(print) : fig7(print);
          if (plot::pixel_size(figure).width < 200 || plot::pixel_size(figure).height < 150)
            continue;
          plot::FigureLayout layout;
          plot::render(figure, &layout);
          const std::string what = (which ? "fig7 " : "fig4 ") + std::to_string(width_mm) + " x " +
                                   std::to_string(height_mm) + " mm, " + std::to_string(font_pt) +
                                   " pt at " + std::to_string(dpi) + " dpi";
          INFO(what);
          const TextSizes sizes = text_sizes(layout);
          CHECK(sizes.body_min >= Approx(floor_pt(font_pt)).epsilon(1e-3));
          CHECK(sizes.body_max == Approx(font_pt).epsilon(1e-3));
          CHECK(sizes.title <= Approx(font_pt + 1.0).epsilon(1e-3));
          CHECK(sizes.title >= Approx(floor_pt(font_pt + 1.0)).epsilon(1e-3));
          check_clean(layout, what);
        }
      }
    }
  }
}

TEST_CASE("print figures of random pages keep a clean layout", "[plot][print]") {
  std::mt19937 rng(2112);
  std::uniform_real_distribution<double> width(55.0, 190.0), aspect(0.45, 1.1), font(6.0, 11.0),
      dpi(90.0, 400.0);
  const core::Trajectory sphere = plot::testing::sphere_run(1.0);
  for (int i = 0; i < 24; ++i) {
    // Pages that can hold a title, two panels and their legends: at least 9 times the type
    // size in mm wide, 7 times high (8 pt: 72 x 56 mm).
    const double pt = font(rng);
    const double w = std::max(width(rng), 9 * pt);
    const plot::Figure::Print print{w, std::max(w * aspect(rng), 7 * pt), pt, dpi(rng)};
    plot::Figure figure = i % 2 ? fig7(print) : fig4(print);
    if (plot::pixel_size(figure).height < 150) continue;
    plot::FigureLayout layout;
    plot::render(figure, &layout);
    if (i < 4)
      plot::write_figure(figure, kOut / ("random_" + std::to_string(i) + ".png"),
                         plot::Format::png);
    check_clean(layout, "random page " + std::to_string(i));
    const TextSizes sizes = text_sizes(layout);
    CHECK(sizes.body_min >= Approx(floor_pt(print.font_pt)).epsilon(1e-3));
    CHECK(sizes.body_max == Approx(print.font_pt).epsilon(1e-3));
  }
}

TEST_CASE("a page too small for its legend says so", "[plot][print]") {
  // 50 x 40 mm with 10 pt text: the title, two panels and Fig. 7's legends cannot all fit;
  // the layout reports the legend it left out instead of drawing it over the axes.
  plot::FigureLayout layout;
  plot::render(fig7({50.0, 40.0, 10.0, 300.0}), &layout);
  const std::vector<std::string> problems = plot::layout_problems(layout);
  CHECK(!layout.legends_left_out.empty());
  CHECK(std::any_of(problems.begin(), problems.end(), [](const std::string& p) {
    return p.find("has no room") != std::string::npos;
  }));
}
