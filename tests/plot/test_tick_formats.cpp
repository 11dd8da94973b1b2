// One tick rule for every format: the PNG, the SVG and the PDF of a figure show the same tick
// values (the same labels on every axis) and the same text, because the layout measures text
// the same way whatever surface it draws on. Checked on every figure of the bundled scenes
// (their [[plots]] or the default figures, on their own page and on an 88 x 70 mm page) and
// on generated figures of many sizes.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "core/column_info.hpp"
#include "core/simulation.hpp"
#include "plot/plot_spec.hpp"
#include "scene/scene.hpp"
#include "services/plot_outputs.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

const fs::path kOut = fs::path(STICTION_TEST_OUTPUT_DIR) / "tick_formats";

// Every text of the layout with its role and panel, in drawing order: "panel 0 tick 0.5".
std::vector<std::string> texts_of(const plot::FigureLayout& layout, bool ticks_only) {
  std::vector<std::string> out;
  for (const plot::TextBox& t : layout.texts) {
    if (ticks_only && t.role != plot::TextRole::tick_label) continue;
    out.push_back("panel " + std::to_string(t.panel) + " role " +
                  std::to_string(static_cast<int>(t.role)) + " '" + t.text + "'");
  }
  return out;
}

void check_formats(const plot::Figure& figure, const std::string& name) {
  INFO(name);
  fs::create_directories(kOut);
  const plot::FigureLayout png =
      plot::write_figure(figure, kOut / (name + ".png"), plot::Format::png);
  const plot::FigureLayout svg =
      plot::write_figure(figure, kOut / (name + ".svg"), plot::Format::svg);
  const plot::FigureLayout pdf =
      plot::write_figure(figure, kOut / (name + ".pdf"), plot::Format::pdf);
  CHECK(texts_of(png, true) == texts_of(svg, true));
  CHECK(texts_of(png, true) == texts_of(pdf, true));
  // Not only the ticks: every text, and where it is.
  CHECK(texts_of(png, false) == texts_of(svg, false));
  CHECK(texts_of(png, false) == texts_of(pdf, false));
  REQUIRE(png.texts.size() == svg.texts.size());
  for (std::size_t i = 0; i < png.texts.size(); ++i) {
    CHECK(png.texts[i].box.x0 == Approx(svg.texts[i].box.x0).margin(1e-6));
    CHECK(png.texts[i].box.y0 == Approx(svg.texts[i].box.y0).margin(1e-6));
    CHECK(png.texts[i].box.x1 == Approx(svg.texts[i].box.x1).margin(1e-6));
  }
  CHECK(png.panels.size() == svg.panels.size());
  for (std::size_t p = 0; p < std::min(png.panels.size(), svg.panels.size()); ++p) {
    CHECK(png.panels[p].y0 == svg.panels[p].y0);
    CHECK(png.panels[p].y1 == svg.panels[p].y1);
    CHECK(png.panels[p].x0 == svg.panels[p].x0);
  }
}

}  // namespace

TEST_CASE("the PNG, SVG and PDF of a bundled scene's figure show the same ticks",
          "[plot][ticks][formats]") {
  for (const std::string name : {"sphere_roll", "two_link", "belt_oscillator", "box_stack",
                                 "coin_roll", "pendulum_friction"}) {
    scene::Scene scene = scene::load_scene(name);
    scene.run.duration = std::min(scene.run.duration, 3.0);
    const std::vector<core::ColumnInfo> infos = core::column_infos(*scene.network);
    std::vector<plot::PlotSpec> specs =
        plot::read_plot_specs(scene.document, scene.path.string(), infos);
    if (specs.empty()) specs = plot::default_plot_specs(infos);
    const core::RunResult result = core::simulate(*scene.network, scene.run);
    REQUIRE(!result.instability);
    const std::vector<plot::PlotEvent> events = services::plot_events(result);
    for (const plot::PlotSpec& spec : specs) {
      plot::Figure figure = plot::make_figure(spec, result.trajectory, events);
      check_formats(figure, name + "_" + spec.name);
      if (figure.print) {
        figure.print->width_mm = 88.0;
        figure.print->height_mm = 70.0;
        check_formats(figure, name + "_" + spec.name + "_88x70");
      }
    }
  }
}

TEST_CASE("generated figures show the same ticks as PNG, SVG and PDF", "[plot][ticks][formats]") {
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 12; ++k) {
    plot::Figure figure;
    figure.title = k % 2 ? "Generated figure " + std::to_string(k) : "";
    figure.print = plot::Figure::Print{60.0 + 60.0 * unit(rng), 45.0 + 60.0 * unit(rng),
                                       6.0 + 4.0 * unit(rng), k % 3 ? 300.0 : 150.0};
    const int panels = 1 + k % 3;
    for (int p = 0; p < panels; ++p) {
      plot::Panel& panel = figure.panels.emplace_back();
      panel.label = "signal " + std::to_string(p);
      panel.unit = p % 2 ? "m/s" : "N";
      const double scale = std::pow(10.0, -4.0 + 8.0 * unit(rng));
      const double offset = scale * (unit(rng) - 0.5) * 4.0;
      for (int s = 0; s < 1 + (k + p) % 3; ++s) {
        plot::Series series;
        series.label = "series " + std::to_string(s);
        const double f = 0.5 + 3.0 * unit(rng);
        for (int i = 0; i <= 400; ++i) {
          const double t = 0.01 * i * (1.0 + k);
          series.x.push_back(t);
          series.y.push_back(offset + scale * std::sin(f * t + s));
        }
        panel.series.push_back(std::move(series));
      }
    }
    check_formats(figure, "generated_" + std::to_string(k));
  }
}
