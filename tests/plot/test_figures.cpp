// Golden images of the paper figures, drawn from synthetic runs (synthetic.hpp) so that they
// test the plotting alone. Regenerate after an intended change with
//   STICTION_UPDATE_GOLDEN=1 ./build/tests/plot/test_plot "[golden]"
// and look at every changed PNG before committing it (docs/plots.md).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "image/compare.hpp"
#include "image/png.hpp"
#include "plot/plot_spec.hpp"
#include "scene/toml_reader.hpp"
#include "synthetic.hpp"

using namespace stiction;

namespace {

const std::filesystem::path kGolden = std::filesystem::path(STICTION_SOURCE_DIR) / "tests/golden";
const std::filesystem::path kFailures = STICTION_TEST_OUTPUT_DIR;

void check_golden(const std::string& name, const image::Image& actual) {
  const image::CompareResult result =
      image::compare_to_golden(kGolden / (name + ".png"), actual, kFailures);
  INFO(result.message);
  CHECK(result.matches);
}

}  // namespace

TEST_CASE("paper Fig. 4 replica", "[plot][golden]") {
  text::Font font = text::Font::open_default();
  const core::Trajectory run = plot::testing::sphere_run(1.0);
  const double t_stick = plot::testing::sphere_stick_time();
  const plot::Figure figure =
      plot::make_figure(plot::paper_fig4_spec(), run, {{"ground.stick_time", t_stick}});
  const image::Image img = plot::render(figure, font);
  // A one-column journal figure: 88 mm wide, two panels 80 mm high, at 300 dpi.
  REQUIRE(figure.print.has_value());
  CHECK(figure.print->width_mm == 88.0);
  CHECK(figure.print->height_mm == plot::default_height_mm(2));
  CHECK(img.width == static_cast<int>(std::lround(88.0 / 25.4 * 300.0)));
  CHECK(img.height == static_cast<int>(std::lround(plot::default_height_mm(2) / 25.4 * 300.0)));
  check_golden("plot_fig4", img);
}

TEST_CASE("paper Fig. 7 replica", "[plot][golden]") {
  text::Font font = text::Font::open_default();
  const core::Trajectory run = plot::testing::arm_run(15.0);
  const image::Image img = plot::render(
      plot::make_figure(plot::paper_fig7_spec(), run, std::vector<plot::PlotEvent>{}), font);
  check_golden("plot_fig7", img);
}

TEST_CASE("Kikuuwe vs LuGre drift comparison", "[plot][golden]") {
  text::Font font = text::Font::open_default();
  const core::Trajectory a = plot::testing::arm_run(15.0);
  const core::Trajectory b = plot::testing::arm_run(15.0, 0.004);
  const std::vector<plot::Run> runs{{"two_link", &a}, {"two_link_lugre", &b}};
  const image::Image img =
      plot::render(plot::make_comparison_figure(plot::default_comparison_spec(runs), runs), font);
  check_golden("plot_compare_drift", img);
}

TEST_CASE("axes for awkward data: log, tiny, flat, empty, NaN", "[plot][golden]") {
  text::Font font = text::Font::open_default();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> t, decay, tiny, flat, holes;
  for (int i = 0; i <= 200; ++i) {
    const double x = i * 0.05;
    t.push_back(x);
    decay.push_back(std::exp(-2.0 * x) + 1e-9);
    tiny.push_back(3e-12 * std::sin(x));
    flat.push_back(0.336);
    holes.push_back(i % 50 < 5 ? nan : -2e5 * std::cos(x));
  }
  plot::Figure figure;
  figure.title = "Axis cases";
  figure.width = 1200;
  figure.height = 1300;
  figure.panels.push_back({"Decay", "m", true, {{"exp(\u22122t)", t, decay, {}}}, {}, {}, {}});
  figure.panels.push_back({"Tiny", "rad", false, {{"3e\u221212 sin t", t, tiny, {}}}, {}, {}, {}});
  figure.panels.push_back({"Flat", "N\u00B7m", false, {{"0.336", t, flat, {}}}, {}, {}, {}});
  figure.panels.push_back({"Large, with gaps", "N", false, {{"", t, holes, {}}}, {}, {}, {}});
  figure.panels.push_back({"Empty", "", false, {{"nothing", {}, {}, {}}}, {}, {}, {}});
  figure.events.push_back({2.5, "event A"});
  figure.events.push_back({2.6, "event B, close to A"});
  const image::Image img = plot::render(figure, font);
  check_golden("plot_axis_cases", img);
}

TEST_CASE("write_plot writes a PNG of the requested size", "[plot]") {
  const core::Trajectory run = plot::testing::sphere_run(0.5);
  plot::PlotSpec spec = plot::paper_fig4_spec();
  spec.print.reset();  // the legacy pixel size (`size = [800, 500]`)
  spec.width = 800;
  spec.height = 500;
  const std::filesystem::path out = kFailures / "write_plot" / "fig4_small.png";
  std::filesystem::remove(out);
  plot::write_plot(spec, run, {}, out);
  const image::Image img = image::read_png(out);
  CHECK(img.width == 800);
  CHECK(img.height == 500);
  CHECK_THROWS_AS(plot::write_plot(plot::paper_fig7_spec(), run, {}, out), scene::InputError);
}

TEST_CASE("figures of any size and content render without throwing", "[plot]") {
  text::Font font = text::Font::open_default();
  plot::Figure empty;
  CHECK_NOTHROW(plot::render(empty, font));
  empty.width = 100;
  CHECK_THROWS_AS(plot::render(empty, font), std::invalid_argument);
  plot::Figure one;
  one.panels.push_back({"x", "", false, {{"a", {1.0}, {2.0}, {}}}, {}, {}, {}});
  one.events.push_back({std::numeric_limits<double>::quiet_NaN(), "nowhere"});
  const image::Image img = plot::render(one, font);
  CHECK(img.width == 1600);
}
