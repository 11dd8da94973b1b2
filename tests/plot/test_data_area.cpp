// How much of a figure its data gets: the panels' frames as a share of the page, for every
// figure `stiction run SCENE --no-video` writes for the bundled scenes (the scene's [[plots]],
// else the default figures), at their own size and laid out on an 88 x 70 mm page, and for
// the default `stiction compare` of two runs. A measurement, not a test: hidden from the
// default run; its table is in docs/plots.md. Run it with
//   ./build/tests/plot/test_plot_kinds "[.data-area]"
// (STICTION_DATA_AREA_SCENES=sphere_roll,two_link limits the scenes.)
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/column_info.hpp"
#include "core/simulation.hpp"
#include "image/png.hpp"
#include "plot/plot_spec.hpp"
#include "scene/scene.hpp"
#include "services/plot_outputs.hpp"

using namespace stiction;

namespace {

struct Area {
  double data = 0.0;  // the panels' frames over the page
  int legends_outside = 0;
  int legends = 0;
};

const std::filesystem::path kOut = std::filesystem::path(STICTION_TEST_OUTPUT_DIR) / "data_area";

// The share of the page in the panels; the figure is written to kOut / (name + ".png") to be
// looked at.
Area measure(const plot::Figure& figure, const std::string& name) {
  plot::FigureLayout layout;
  const image::Image img = plot::render(figure, &layout);
  std::filesystem::create_directories(kOut);
  image::write_png(kOut / (name + ".png"), img, image::PngSpeed::fast);
  Area a;
  for (const plot::Rect& r : layout.panels) a.data += r.width() * r.height();
  a.data /= static_cast<double>(layout.width) * layout.height;
  a.legends = static_cast<int>(layout.legends.size());
  for (bool outside : layout.legend_outside) a.legends_outside += outside ? 1 : 0;
  return a;
}

// The figure on an 88 x 70 mm page (8 pt, 300 dpi), whatever size its spec asks for.
plot::Figure on_88_by_70(plot::Figure figure) {
  figure.print = plot::Figure::Print{88.0, 70.0, 8.0, 300.0};
  return figure;
}

bool wanted(const std::string& scene) {
  const char* only = std::getenv("STICTION_DATA_AREA_SCENES");
  if (!only || !*only) return true;
  std::stringstream list(only);
  for (std::string name; std::getline(list, name, ',');) {
    if (name == scene) return true;
  }
  return false;
}

std::string percent(double fraction) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.0f%%", 100.0 * fraction);
  return buffer;
}

std::string legends(const Area& a) {
  return std::to_string(a.legends - a.legends_outside) + " in, " +
         std::to_string(a.legends_outside) + " out";
}

}  // namespace

TEST_CASE("data area of the bundled scenes' figures (a measurement)", "[.data-area]") {
  std::printf("| scene | figure | own size | data | legends | 88 x 70 mm data | legends |\n");
  std::printf("|---|---|---|---:|---|---:|---|\n");
  double sum_own = 0.0, sum_88 = 0.0;
  int count = 0;
  std::vector<core::RunResult> kept;  // two_link and two_link_lugre, for the comparison
  std::vector<std::string> kept_names;
  for (const auto& [name, description] : scene::bundled_scenes()) {
    if (!wanted(name)) continue;
    scene::Scene scene = scene::load_scene(name);
    const std::vector<core::ColumnInfo> infos = core::column_infos(*scene.network);
    std::vector<plot::PlotSpec> specs =
        plot::read_plot_specs(scene.document, scene.path.string(), infos);
    if (specs.empty()) specs = plot::default_plot_specs(infos);
    core::RunResult result = core::simulate(*scene.network, scene.run);
    REQUIRE(!result.instability);
    const std::vector<plot::PlotEvent> events = services::plot_events(result);
    for (const plot::PlotSpec& spec : specs) {
      const plot::Figure figure = plot::make_figure(spec, result.trajectory, events);
      const Area own = measure(figure, name + "_" + spec.name);
      const Area page = measure(on_88_by_70(figure), name + "_" + spec.name + "_88x70");
      const plot::PixelSize size = plot::pixel_size(figure);
      const std::string own_size =
          figure.print ? std::to_string(static_cast<int>(figure.print->width_mm)) + " x " +
                             std::to_string(static_cast<int>(figure.print->height_mm)) + " mm"
                       : std::to_string(size.width) + " x " + std::to_string(size.height) + " px";
      std::printf("| %s | %s | %s | %s | %s | %s | %s |\n", name.c_str(), spec.name.c_str(),
                  own_size.c_str(), percent(own.data).c_str(), legends(own).c_str(),
                  percent(page.data).c_str(), legends(page).c_str());
      std::fflush(stdout);
      sum_own += own.data;
      sum_88 += page.data;
      ++count;
    }
    if (name == "two_link" || name == "two_link_lugre" || name == "sphere_roll" ||
        name == "roll_to_slip") {
      kept.push_back(std::move(result));
      kept_names.push_back(name);
    }
  }
  if (count > 0) {
    std::printf("| mean of %d figures | | | %s | | %s | |\n", count,
                percent(sum_own / count).c_str(), percent(sum_88 / count).c_str());
  }
  // `stiction compare A B` without --signals: the default comparison of each pair kept.
  for (std::size_t i = 0; i + 1 < kept.size(); i += 2) {
    const std::vector<plot::Run> runs{{kept_names[i], &kept[i].trajectory},
                                      {kept_names[i + 1], &kept[i + 1].trajectory}};
    const plot::Figure figure =
        plot::make_comparison_figure(plot::default_comparison_spec(runs), runs);
    const std::string stem = "compare_" + kept_names[i] + "_" + kept_names[i + 1];
    const Area own = measure(figure, stem);
    const Area page = measure(on_88_by_70(figure), stem + "_88x70");
    std::printf("| compare %s %s | compare | %d x %d mm | %s | %s | %s | %s |\n",
                kept_names[i].c_str(), kept_names[i + 1].c_str(),
                static_cast<int>(figure.print->width_mm), static_cast<int>(figure.print->height_mm),
                percent(own.data).c_str(), legends(own).c_str(), percent(page.data).c_str(),
                legends(page).c_str());
  }
  SUCCEED();
}
