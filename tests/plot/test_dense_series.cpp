// Dense signals are drawn honestly: where a series turns more often than a line can show, it
// is a band between its extremes per pixel column (no moiré, no gaps), whose edges are the
// data's true extremes; sparse series stay polylines, exactly as before.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>

#include "image/png.hpp"
#include "plot/figure.hpp"
#include "plot/series_strokes.hpp"
#include "synthetic.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

const fs::path kOut = fs::path(STICTION_TEST_OUTPUT_DIR) / "dense";

plot::Series sampled(double duration, double rate, double (*f)(double)) {
  plot::Series s;
  for (int i = 0; i * (1.0 / rate) <= duration + 1e-12; ++i) {
    const double t = i / rate;
    s.x.push_back(t);
    s.y.push_back(f(t));
  }
  return s;
}

// Ink of the band: the series' red, tinted or full, over white or the grey grid.
bool red_ink(image::Rgba c) { return c.r > c.g + 20 && c.r > c.b + 20; }

}  // namespace

TEST_CASE("a 100 rad/s sine over 20 s is a band with its true edges and no gaps", "[plot][dense]") {
  fs::create_directories(kOut);
  plot::Figure figure;
  figure.title = "100 rad/s over 20 s";
  plot::Panel& panel = figure.panels.emplace_back();
  panel.label = "Torque";  // one series named by its axis: no legend over the band
  panel.unit = "N m";
  panel.y_min = -1.5;  // a fixed range: the axis positions of +-1 are known
  panel.y_max = 1.5;
  plot::Series s = sampled(20.0, 1000.0, [](double t) { return std::sin(100.0 * t); });
  s.label = "dither";
  s.style = plot::series_style(0);
  s.style->colour = {230, 0, 0, 255};
  panel.series.push_back(s);
  plot::FigureLayout layout;
  const image::Image img = plot::render(figure, &layout);
  image::write_png(kOut / "dither.png", img);
  REQUIRE(layout.panels.size() == 1);
  const plot::Rect& f = layout.panels[0];
  // The frame's rectangle is the axis: y = +1.5 at its top edge, -1.5 at its bottom.
  auto row_of = [&](double v) { return f.y1 - (v + 1.5) / 3.0 * (f.y1 - f.y0); };
  const double top = row_of(1.0), bottom = row_of(-1.0);
  int columns = 0;
  for (int x = static_cast<int>(f.x0) + 10; x < static_cast<int>(f.x1) - 10; ++x) {
    int first = -1, last = -1;
    for (int y = static_cast<int>(f.y0) + 2; y < static_cast<int>(f.y1) - 2; ++y) {
      if (red_ink(img.at(x, y))) {
        if (first < 0) first = y;
        last = y;
      }
    }
    INFO("column " << x << ": ink from " << first << " to " << last << ", expected " << top
                   << " to " << bottom);
    REQUIRE(first >= 0);
    CHECK(std::abs(first - top) <= 1.0);
    CHECK(std::abs(last + 1 - bottom) <= 1.0);
    // Every pixel between is ink: no moiré gaps.
    int gaps = 0;
    for (int y = first; y <= last; ++y) gaps += red_ink(img.at(x, y)) ? 0 : 1;
    CHECK(gaps == 0);
    ++columns;
  }
  CHECK(columns > 1000);
}

TEST_CASE("dense stretches become bands, sparse ones stay the same polyline", "[plot][dense]") {
  // The paper's torques: a ramp (sparse) then 100 rad/s (dense) from 4 s.
  const core::Trajectory run = plot::testing::arm_run(15.0);
  plot::Series torque;
  const int column = *run.find("motor0.tau");
  for (int r = 0; r < run.row_count(); ++r) {
    torque.x.push_back(run.at(r, 0));
    torque.y.push_back(run.at(r, column));
  }
  const plot::Axis x{0.0, 15.0, false, 100.0, 1500.0}, y{0.0, 0.55, false, 900.0, 500.0};
  const std::vector<plot::Point> pixels = plot::to_pixels(torque, x, y);
  const std::vector<plot::SeriesPiece> pieces = plot::split_dense(pixels, plot::dense_spacing(3.2));
  // The ramp, the band, and the last half swing after the last turning point.
  REQUIRE(pieces.size() == 3);
  CHECK(pieces[0].band.empty());
  CHECK(pieces[0].line.front().x == pixels.front().x);
  CHECK(pieces[0].line.back().x == Approx(x.map(4.0)).margin(8.0));
  REQUIRE(!pieces[1].band.empty());
  CHECK(pieces[2].band.empty());
  CHECK(pieces[2].line.front().x == pieces[1].band.back().x1);
  CHECK(pieces[2].line.back().x == pixels.back().x);
  CHECK(pieces[2].line.back().x - pieces[2].line.front().x < plot::dense_spacing(3.2));
  // The band's edges are the torque's extremes: 0.336 +- 0.144.
  double highest = 1e9, lowest = -1e9;
  for (const plot::BandColumn& c : pieces[1].band) {
    highest = std::min(highest, c.top);
    lowest = std::max(lowest, c.bottom);
  }
  CHECK(highest == Approx(y.map(0.48)).margin(0.5));
  CHECK(lowest == Approx(y.map(0.192)).margin(0.5));

  // Sparse series of random shapes, with gaps: one polyline of every point, untouched.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    std::vector<plot::Point> p;
    const double cycles = 1 + 20 * unit(rng), amplitude = 5 + 200 * unit(rng);
    for (int i = 0; i < 3000; ++i) {
      const double px = 100 + 1400.0 * i / 2999;
      p.push_back({px, 500 + amplitude * std::sin(cycles * 6.283 * i / 2999) +
                           0.2 * (unit(rng) - 0.5)});  // noise below the hysteresis
    }
    const std::vector<plot::SeriesPiece> sparse = plot::split_dense(p, plot::dense_spacing(3.2));
    REQUIRE(sparse.size() == 1);
    CHECK(sparse[0].band.empty());
    CHECK(sparse[0].line.size() == p.size());
  }
}
