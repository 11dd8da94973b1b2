// The default figures of every bundled scene and of three generated ones (a six-link arm
// with many signals, a scene with very long component names, a block sliding from a slope
// onto a floor) laid out as a reader needs them: no text box overlaps another or leaves the
// image, no legend covers another or an event label, every axis label carries a unit, every
// signal of the scene is drawn in some figure; and the SVG and PDF files, turned into PNG by
// rsvg-convert and pdftoppm, match the PNG drawn by the same code within a tolerance.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "../app/generated_scenes.hpp"
#include "core/column_info.hpp"
#include "core/simulation.hpp"
#include "image/compare.hpp"
#include "image/png.hpp"
#include "plot/plot_spec.hpp"
#include "scene/scene.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

// The top-left width x height of an image at least that large (else the image itself).
image::Image crop(const image::Image& in, int width, int height) {
  if (in.width < width || in.height < height || in.width > width + 1 || in.height > height + 1) {
    return in;
  }
  image::Image out(width, height);
  for (int y = 0; y < height; ++y) {
    std::copy_n(in.data(0, y), out.stride(), out.data(0, y));
  }
  return out;
}

const fs::path kOut = fs::path(STICTION_TEST_OUTPUT_DIR) / "layouts";

struct SceneRun {
  std::string name;
  std::vector<core::ColumnInfo> columns;
  core::RunResult result;
};

SceneRun run_scene(const std::string& name_or_path, double max_duration) {
  scene::Scene scene = scene::load_scene(name_or_path);
  scene.run.duration = std::min(scene.run.duration, max_duration);
  SceneRun run{scene.name, core::column_infos(*scene.network), {}};
  run.result = core::simulate(*scene.network, scene.run);
  REQUIRE(!run.result.instability);
  return run;
}

std::vector<plot::PlotEvent> events_of(const core::RunResult& result) {
  std::vector<plot::PlotEvent> events;
  for (const core::SlipHistory& h : result.slip_events) {
    for (const core::SlipEvent& e : h.monitor.events())
      events.push_back({h.component, e.kind, e.time});
  }
  return events;
}

// Mean of every 4x4 block.
image::Image shrink4(const image::Image& in) {
  image::Image out(in.width / 4, in.height / 4);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      int sum[3] = {0, 0, 0};
      for (int dy = 0; dy < 4; ++dy) {
        for (int dx = 0; dx < 4; ++dx) {
          const image::Rgba c = in.at(4 * x + dx, 4 * y + dy);
          sum[0] += c.r;
          sum[1] += c.g;
          sum[2] += c.b;
        }
      }
      out.set(x, y,
              {static_cast<std::uint8_t>(sum[0] / 16), static_cast<std::uint8_t>(sum[1] / 16),
               static_cast<std::uint8_t>(sum[2] / 16), 255});
    }
  }
  return out;
}

// "label [unit]" possibly over several lines: the bracket holds something.
bool has_unit(const std::string& text) {
  const std::size_t open = text.rfind('[');
  const std::size_t close = text.rfind(']');
  return open != std::string::npos && close != std::string::npos && close > open + 1;
}

void check_layout(const plot::FigureLayout& layout, const std::string& figure) {
  INFO(figure);
  const std::vector<std::string> problems = plot::layout_problems(layout);
  for (const std::string& p : problems) UNSCOPED_INFO(p);
  CHECK(problems.empty());
  // Axis labels: the x label, and per panel the (possibly wrapped) y label lines joined.
  std::vector<std::string> y_label(layout.panels.size());
  bool x_label = false;
  for (const plot::TextBox& t : layout.texts) {
    if (t.role != plot::TextRole::axis_label) continue;
    if (t.panel < 0) {
      x_label = true;
      CHECK(has_unit(t.text));
    } else {
      y_label[t.panel] += t.text;
    }
  }
  CHECK(x_label);
  for (std::size_t p = 0; p < y_label.size(); ++p) {
    INFO("panel " << p << ": '" << y_label[p] << "'");
    CHECK(has_unit(y_label[p]));
  }
}

void check_scene(const SceneRun& run, bool vector_formats) {
  std::vector<std::string> not_drawn;  // groups past the default figures' cap, named by run
  const std::vector<plot::PlotSpec> specs = plot::default_plot_specs(run.columns, &not_drawn);
  REQUIRE(!specs.empty());
  std::set<std::string> drawn;
  std::string captions;
  const std::vector<plot::PlotEvent> events = events_of(run.result);
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const plot::PlotSpec& spec = specs[i];
    CHECK(spec.panels.size() <= static_cast<std::size_t>(plot::kPanelsPerFigure));
    const plot::Figure figure = plot::make_figure(spec, run.result.trajectory, events);
    plot::FigureLayout layout;
    const image::Image png = plot::render(figure, &layout);
    check_layout(layout, run.name + "/" + spec.name);
    drawn.insert(layout.series.begin(), layout.series.end());
    for (const plot::Panel& p : figure.panels) captions += p.caption + "\n";
    const fs::path dir = kOut / run.name;
    fs::create_directories(dir);
    image::write_png(dir / (spec.name + ".png"), png, image::PngSpeed::fast);
    if (!vector_formats || i > 0) continue;
    // The same figure as SVG and PDF, rasterized by other programs at the same size.
    const fs::path svg = dir / (spec.name + ".svg"), pdf = dir / (spec.name + ".pdf");
    check_layout(plot::write_figure(figure, svg, plot::Format::svg), run.name + " svg");
    // A print figure's SVG and PDF pages are in mm: rasterized at its dpi they have its pixels.
    const double dpi = figure.print ? figure.print->dpi : 100.0;
    const std::string dpi_text = std::to_string(static_cast<int>(dpi));
    check_layout(plot::write_figure(figure, pdf, plot::Format::pdf, dpi), run.name + " pdf");
    const fs::path from_svg = dir / (spec.name + ".svg.png");
    REQUIRE(std::system(("rsvg-convert -d " + dpi_text + " -p " + dpi_text + " -b white -o '" +
                         from_svg.string() + "' '" + svg.string() + "'")
                            .c_str()) == 0);
    REQUIRE(std::system(("pdftoppm -r " + dpi_text + " -png -singlefile '" + pdf.string() + "' '" +
                         (dir / (spec.name + ".pdf")).string() + "'")
                            .c_str()) == 0);
    const fs::path pdf_png = dir / (spec.name + ".pdf.png");
    for (const fs::path& other : {from_svg, pdf_png}) {
      INFO(other.string());
      // A page in mm is a fraction of a pixel wider than the PNG's rounded size: rasterizers
      // round it up, the PNG to nearest (88 mm at 300 dpi: 1040 against 1039 pixels).
      const image::Image converted = crop(image::read_png(other), png.width, png.height);
      REQUIRE(converted.width == png.width);
      REQUIRE(converted.height == png.height);
      // Other rasterizers anti-alias differently (poppler snaps thin lines to pixels, glyph
      // edges differ): compared at a quarter of the size, where a line or a glyph in the wrong
      // place or of the wrong colour still shows, but edge shading does not. A print figure's
      // 8 pt glyphs are a larger share of its pixels: their edges differ in up to 1.5%.
      const bool print = figure.print.has_value();
      const image::CompareResult r =
          image::compare_images(shrink4(png), shrink4(converted), {48, print ? 0.02 : 0.01});
      INFO(r.message);
      CHECK(r.matches);
    }
  }
  // Every signal of the scene is in some figure, or zero throughout and said so in a caption,
  // or in a group past the cap (box_stack's 24 corners and pairs), which `run` names.
  const core::Trajectory& rows = run.result.trajectory;
  auto past_cap = [&](const std::string& column) {
    return std::any_of(not_drawn.begin(), not_drawn.end(), [&](const std::string& group) {
      return column.rfind(group + ".", 0) == 0 || column == group;
    });
  };
  for (const core::ColumnInfo& c : run.columns) {
    if (c.name == "t" || drawn.count(c.name) == 1 || past_cap(c.name)) continue;
    INFO(run.name << ": " << c.name);
    const int column = *rows.find(c.name);
    for (int r = 0; r < rows.row_count(); ++r) REQUIRE(rows.at(r, column) == 0.0);
    CHECK(captions.find(" = 0, not drawn)") != std::string::npos);
  }
}

}  // namespace

TEST_CASE("default figures of the bundled scenes: clean layout, units, every signal",
          "[plot][layout]") {
  for (const auto& [name, description] : scene::bundled_scenes()) {
    check_scene(run_scene(name, 2.0), name == "sphere_roll");
  }
}

TEST_CASE("default figures of generated scenes: many signals, long names, slope to floor",
          "[plot][layout]") {
  const fs::path dir = kOut / "scenes";
  fs::create_directories(dir);
  check_scene(
      run_scene(testing::write_scene(dir, "arm6", testing::arm_scene(6, 11, 2.0)).string(), 2.0),
      true);
  check_scene(
      run_scene(testing::write_scene(dir, "long_names", testing::long_names_scene()).string(), 1.0),
      true);
  check_scene(
      run_scene(
          testing::write_scene(dir, "slope_to_floor", testing::slope_to_floor_scene()).string(),
          1.5),
      true);
}

TEST_CASE("PNG figures carry their resolution", "[plot][layout]") {
  plot::Figure figure;
  figure.panels.push_back({"v", "m/s", false, {{"a", {0.0, 1.0}, {0.0, 1.0}, {}}}, {}, {}, {}});
  const fs::path png = kOut / "dpi.png";
  fs::create_directories(kOut);
  plot::write_figure(figure, png, plot::Format::png, 300.0);
  std::ifstream in(png, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = bytes.find("pHYs");
  REQUIRE(at != std::string::npos);
  auto u32 = [&](std::size_t i) {
    return (static_cast<unsigned char>(bytes[i]) << 24) |
           (static_cast<unsigned char>(bytes[i + 1]) << 16) |
           (static_cast<unsigned char>(bytes[i + 2]) << 8) |
           static_cast<unsigned char>(bytes[i + 3]);
  };
  CHECK(u32(at + 4) == 11811u);  // 300 dpi in pixels per metre
  CHECK(u32(at + 8) == 11811u);
  CHECK(bytes[at + 12] == 1);  // unit: metre
}

TEST_CASE("comparison figures of many runs keep their legends inside the image", "[plot][layout]") {
  const fs::path dir = kOut / "scenes";
  fs::create_directories(dir);
  std::vector<SceneRun> runs;
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    runs.push_back(run_scene(
        testing::write_scene(dir, "arm" + std::to_string(seed), testing::arm_scene(3, seed, 0.5))
            .string(),
        0.5));
  }
  std::vector<plot::Run> plot_runs;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    plot_runs.push_back({"arm with a long descriptive label, seed " + std::to_string(i + 1),
                         &runs[i].result.trajectory});
  }
  for (const plot::PlotSpec& spec :
       {plot::comparison_spec(plot_runs, {"arm.theta", "motor0.tau", "joint1_friction"},
                              runs[0].columns),
        plot::default_comparison_spec(plot_runs)}) {
    plot::FigureLayout layout;
    const image::Image png = plot::render(plot::make_comparison_figure(spec, plot_runs), &layout);
    image::write_png(dir / ("compare_" + spec.name + ".png"), png, image::PngSpeed::fast);
    check_layout(layout, "compare " + spec.name);
    CHECK(!layout.legends.empty());
  }
}

namespace {

// A synthetic run (no physics: the goldens test the layout) with the columns of a scene with
// `links` joints, a long-named contact and stick/slip events; units as components declare.
struct SyntheticScene {
  core::Trajectory trajectory;
  std::vector<core::ColumnInfo> columns;
  std::vector<plot::PlotEvent> events;
};

SyntheticScene synthetic_scene(int links, const std::string& contact) {
  SyntheticScene s;
  s.columns.push_back({"t", "s", "", "time"});
  for (int j = 0; j < links; ++j) {
    s.columns.push_back({"arm.theta." + std::to_string(j), "rad", "joint", "joint angle"});
  }
  for (int j = 0; j < links; ++j) {
    s.columns.push_back({"arm.omega." + std::to_string(j), "rad/s", "joint", "joint rate"});
  }
  for (int j = 0; j < links; ++j) {
    const std::string f = "joint" + std::to_string(j) + "_friction";
    s.columns.push_back({f + ".tau", "N·m", "joint", "friction torque on the driven side"});
    s.columns.push_back(
        {"motor" + std::to_string(j) + ".tau", "N·m", "joint", "prescribed torque"});
  }
  for (const char* axis : {"x", "y", "z"}) {
    s.columns.push_back({contact + ".f." + axis, "N", "world", "contact force on the body"});
  }
  for (const char* axis : {"x", "y", "z"}) {
    s.columns.push_back({contact + ".slip." + axis, "m/s", "world", "contact-point velocity"});
  }
  std::vector<std::string> names;
  for (const core::ColumnInfo& c : s.columns) names.push_back(c.name);
  s.trajectory = core::Trajectory(names);
  std::vector<double> row(names.size());
  for (int i = 0; i <= 2000; ++i) {
    const double t = i * 1e-3;
    row[0] = t;
    for (std::size_t c = 1; c < row.size(); ++c) {
      const double k = static_cast<double>(c);
      row[c] = std::sin((1.0 + 0.37 * k) * t + 0.5 * k) * (1.0 + 0.1 * k) +
               (c % 3 == 0 ? 0.5 * std::floor(4 * t) : 0.0);
    }
    s.trajectory.append(row.data());
  }
  for (int k = 0; k < 7; ++k) {
    s.events.push_back({contact, k % 2 ? "stick" : "slip", 0.05 + 0.27 * k});
    s.events.push_back({"joint0_friction", k % 2 ? "slip" : "stick", 0.11 + 0.29 * k});
  }
  return s;
}

void check_golden(const std::string& name, const image::Image& actual) {
  const image::CompareResult result = image::compare_to_golden(
      fs::path(STICTION_SOURCE_DIR) / "tests/golden" / (name + ".png"), actual, kOut);
  INFO(result.message);
  CHECK(result.matches);
}

}  // namespace

TEST_CASE("golden default figures of generated scenes: many signals, long names",
          "[plot][layout][golden]") {
  const SyntheticScene arm = synthetic_scene(6, "ground");
  const auto arm_specs = plot::default_plot_specs(arm.columns);
  REQUIRE(arm_specs.size() == 4);  // 2 + 12 + 2 groups over figures of at most 4 panels
  plot::FigureLayout layout;
  image::Image img =
      plot::render(plot::make_figure(arm_specs[0], arm.trajectory, arm.events), &layout);
  check_layout(layout, "six links");
  check_golden("plot_generated_six_links", img);

  const std::string contact = "the_ground_contact_element_whose_name_goes_on_and_on_forever";
  const SyntheticScene longer = synthetic_scene(1, contact);
  const auto specs = plot::default_plot_specs(longer.columns);
  const plot::PlotSpec& last = specs.back();  // the contact's force and slip
  img = plot::render(plot::make_figure(last, longer.trajectory, longer.events), &layout);
  check_layout(layout, "long names");
  check_golden("plot_generated_long_names", img);
}
