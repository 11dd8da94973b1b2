// A point with no finite neighbour makes no line segment; it must still show (as a dot), or a
// study's integrator with one stable step, or a series broken by gaps, loses data silently.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "plot/figure.hpp"
#include "text/font.hpp"

using namespace stiction;

namespace {

bool red(image::Rgba c) { return c.r > 150 && c.g < 90 && c.b < 90; }

// Connected blobs of red pixels (4-neighbours).
int red_blobs(const image::Image& img) {
  std::vector<char> seen(static_cast<std::size_t>(img.width) * img.height, 0);
  int blobs = 0;
  for (int y0 = 0; y0 < img.height; ++y0) {
    for (int x0 = 0; x0 < img.width; ++x0) {
      const auto at = [&](int x, int y) { return static_cast<std::size_t>(y) * img.width + x; };
      if (seen[at(x0, y0)] || !red(img.at(x0, y0))) continue;
      ++blobs;
      std::vector<std::pair<int, int>> stack{{x0, y0}};
      seen[at(x0, y0)] = 1;
      while (!stack.empty()) {
        const auto [x, y] = stack.back();
        stack.pop_back();
        const int dx[] = {1, -1, 0, 0}, dy[] = {0, 0, 1, -1};
        for (int k = 0; k < 4; ++k) {
          const int nx = x + dx[k], ny = y + dy[k];
          if (nx < 0 || ny < 0 || nx >= img.width || ny >= img.height) continue;
          if (seen[at(nx, ny)] || !red(img.at(nx, ny))) continue;
          seen[at(nx, ny)] = 1;
          stack.emplace_back(nx, ny);
        }
      }
    }
  }
  return blobs;
}

}  // namespace

TEST_CASE("isolated points are drawn as dots (one per point)", "[plot]") {
  text::Font font = text::Font::open_default();
  const double gap = std::numeric_limits<double>::quiet_NaN();
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    // A blue line over the panel sets the axes; the red series (left out of the legend by
    // its empty label) is `dots` points, each between gaps, spread apart on both axes.
    const int dots = 1 + trial;
    plot::Figure figure;
    plot::Panel& panel = figure.panels.emplace_back();
    panel.log = trial % 2 == 1;
    plot::Series line, points;
    line.label.assign(4, 'l');
    line.x = {0.0, 10.0};
    line.y = {1.0, 100.0};
    line.style = plot::LineStyle{{0, 0, 255, 255}, {}, 3.0};
    points.style = plot::LineStyle{{220, 0, 0, 255}, {}, 3.0};
    for (int i = 0; i < dots; ++i) {
      points.x.push_back(0.5 + 9.0 * (i + 0.2 * unit(rng)) / dots);
      points.y.push_back(5.0 + 90.0 * (i % 2 == 0 ? unit(rng) * 0.3 : 0.7 + 0.3 * unit(rng)));
      points.x.push_back(gap);
      points.y.push_back(gap);
    }
    panel.series.push_back(line);
    panel.series.push_back(points);
    const image::Image img = plot::render(figure, font);
    INFO("trial " << trial << ", " << dots << " isolated points");
    CHECK(red_blobs(img) == dots);
  }
}
