// Every vertical axis shows at least two labelled ticks, whatever its range and the figure's
// size: a label that would touch the time axis' first label, or the lowest label of the panel
// above, used to be left out, and a short bottom panel kept one label (issue 21). Tested on
// generated ranges (tiny to huge, negative, offset, log) in figures of random sizes.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "plot/figure.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

const fs::path kOut = fs::path(STICTION_TEST_OUTPUT_DIR) / "axis_labels";

// Labels left of each frame: the vertical axis' tick labels.
std::vector<int> y_labels_per_panel(const plot::FigureLayout& layout) {
  std::vector<int> count(layout.panels.size(), 0);
  for (const plot::TextBox& t : layout.texts) {
    if (t.role != plot::TextRole::tick_label || t.panel < 0) continue;
    const plot::Rect& f = layout.panels[t.panel];
    if (t.box.x1 <= f.x0 + 1 && t.box.y1 > f.y0 - 40 && t.box.y0 < f.y1 + 40) ++count[t.panel];
  }
  return count;
}

plot::Figure random_ranges(std::mt19937& rng, int panels) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  plot::Figure figure;
  if (unit(rng) < 0.35) {
    const double pt = 6 + 4 * unit(rng);
    const double w = std::max(8 * pt, 60 + 120 * unit(rng));
    figure.print =
        plot::Figure::Print{w, std::max(5.5 * pt + 12 * panels, w * (0.5 + 0.6 * unit(rng))), pt,
                            100 + 300 * unit(rng)};
  } else {
    figure.width = 300 + static_cast<int>(2000 * unit(rng));
    figure.height = 220 + static_cast<int>(1200 * unit(rng));
  }
  for (int p = 0; p < panels; ++p) {
    figure.panels.push_back({"y", "m", false, {}, {}, {}, {}});
    plot::Panel& panel = figure.panels.back();
    const double magnitude = std::pow(10.0, -12 + 18 * unit(rng));
    const double offset = unit(rng) < 0.4 ? magnitude * 1000 * (unit(rng) - 0.3) : 0.0;
    const double span = magnitude * (0.01 + unit(rng));
    panel.log = unit(rng) < 0.15;
    plot::Series& s = panel.series.emplace_back();
    for (int i = 0; i <= 100; ++i) {
      s.x.push_back(i * 0.01);
      const double v = offset + span * (unit(rng) < 0.5 ? i / 100.0 : std::sin(0.2 * i));
      s.y.push_back(panel.log ? std::abs(v) + magnitude : v);
    }
    if (unit(rng) < 0.1) {  // a fixed range
      panel.y_min = offset - span;
      panel.y_max = offset + 2 * span;
    }
  }
  return figure;
}

}  // namespace

TEST_CASE("every vertical axis keeps at least two labelled ticks", "[plot][ticks]") {
  std::mt19937 rng(2107);
  fs::create_directories(kOut);
  int figures = 0, written = 0;
  for (int i = 0; i < 300; ++i) {
    const plot::Figure figure = random_ranges(rng, 1 + i % 4);
    plot::FigureLayout layout;
    plot::render(figure, &layout);
    ++figures;
    const std::vector<int> count = y_labels_per_panel(layout);
    for (std::size_t p = 0; p < count.size(); ++p) {
      INFO("figure " << i << " (" << layout.width << " x " << layout.height << "), panel " << p
                     << " of " << count.size());
      CHECK(count[p] >= 2);
      if (count[p] < 2 && written < 5) {
        plot::write_figure(figure, kOut / ("one_label_" + std::to_string(i) + ".png"),
                           plot::Format::png);
        ++written;
      }
    }
    const std::vector<std::string> problems = plot::layout_problems(layout);
    for (const std::string& p : problems) UNSCOPED_INFO(p);
    CHECK(problems.empty());
  }
  CHECK(figures == 300);
}
