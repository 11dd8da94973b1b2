#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "plot/canvas.hpp"

using namespace stiction;
using plot::Point;

namespace {

const image::Rgba kWhite{255, 255, 255, 255};

// Total ink of a black drawing on white, in pixels of full coverage.
double ink(const image::Image& img) {
  double sum = 0.0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) sum += (255 - img.at(x, y).g) / 255.0;
  }
  return sum;
}

}  // namespace

TEST_CASE("a thick line covers its area with soft edges", "[plot][canvas]") {
  image::Image img(200, 50, kWhite);
  plot::Canvas canvas(img);
  canvas.line({20, 25.5}, {180, 25.5}, {{0, 0, 0, 255}, 4.0, {}});
  // 160 x 4 pixels of body plus two round caps of radius 2 (pi * 4).
  CHECK(ink(img) == Approx(160 * 4 + 3.14159 * 4).epsilon(0.03));
  CHECK(img.at(100, 25) == image::Rgba{0, 0, 0, 255});
  CHECK(img.at(100, 23).g < 255);  // edge pixel row: partly covered
  CHECK(img.at(100, 30) == kWhite);
  CHECK(img.at(10, 25) == kWhite);
}

TEST_CASE("joins and overlaps are blended once", "[plot][canvas]") {
  image::Image img(100, 100, kWhite);
  plot::Canvas canvas(img);
  // A zig-zag that folds back on itself many times, drawn half transparent.
  std::vector<Point> zigzag;
  for (int i = 0; i < 20; ++i) zigzag.push_back({i % 2 ? 80.0 : 20.0, 50.0 + (i % 3)});
  canvas.polyline(zigzag, {{0, 0, 0, 128}, 6.0, {}});
  int darkest = 255;
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) darkest = std::min<int>(darkest, img.at(x, y).g);
  }
  // One blend of 50% black over white is 127; overdraw would give far darker pixels.
  CHECK(darkest >= 126);
  CHECK(darkest <= 128);
}

TEST_CASE("dash patterns alternate along the path", "[plot][canvas]") {
  image::Image img(220, 20, kWhite);
  plot::Canvas canvas(img);
  // Butt-like check on the centre row: dashes of 20 with gaps of 10, width 2.
  canvas.line({10, 10}, {210, 10}, {{0, 0, 0, 255}, 2.0, {20, 10}});
  int runs = 0;
  bool inside = false;
  for (int x = 0; x < img.width; ++x) {
    const bool on = img.at(x, 9).g < 128;
    if (on && !inside) ++runs;
    inside = on;
  }
  CHECK(runs == 7);  // 200 px / 30 px per period: 6 full dashes and a seventh from 190 to 210
  // Less ink than solid, more than nothing.
  const double dashed = ink(img);
  image::Image solid_img(220, 20, kWhite);
  plot::Canvas solid(solid_img);
  solid.line({10, 10}, {210, 10}, {{0, 0, 0, 255}, 2.0, {}});
  CHECK(dashed < 0.8 * ink(solid_img));
  CHECK(dashed > 0.55 * ink(solid_img));
}

TEST_CASE("dotted lines made of zero-length dashes give round dots", "[plot][canvas]") {
  image::Image img(120, 20, kWhite);
  plot::Canvas canvas(img);
  canvas.line({10, 10}, {110, 10}, {{0, 0, 0, 255}, 4.0, {0, 10}});
  CHECK(ink(img) == Approx(11 * 3.14159 * 4).epsilon(0.1));  // 11 discs of radius 2
}

TEST_CASE("strokes respect the clip rectangle and break at NaN", "[plot][canvas]") {
  image::Image img(100, 100, kWhite);
  plot::Canvas canvas(img);
  canvas.set_clip({20, 20, 80, 80});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  canvas.polyline({{0, 50}, {45, 50}, {nan, 50}, {55, 50}, {100, 50}}, {{0, 0, 0, 255}, 3.0, {}});
  for (int x = 0; x < 100; ++x) {
    for (int y = 0; y < 100; ++y) {
      if (x < 20 || x >= 80) CHECK(img.at(x, y) == kWhite);
    }
  }
  CHECK(img.at(30, 50).g == 0);
  CHECK(img.at(50, 50) == kWhite);  // the gap left by the NaN point
  canvas.reset_clip();
  canvas.line({0, 10}, {10, 10}, {{0, 0, 0, 255}, 3.0, {}});
  CHECK(img.at(5, 10).g == 0);
}

TEST_CASE("rectangles are filled by area", "[plot][canvas]") {
  image::Image img(40, 40, kWhite);
  plot::Canvas canvas(img);
  canvas.fill_rect({10.5, 10, 20, 20}, {0, 0, 0, 255});
  CHECK(img.at(10, 15).g == 128);  // half covered: 255 - 127.5, rounded
  CHECK(img.at(11, 15).g == 0);
  CHECK(img.at(20, 15) == kWhite);
  CHECK(ink(img) == Approx(95.0).epsilon(0.01));
}
