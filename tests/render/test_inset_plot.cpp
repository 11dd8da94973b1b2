// The live inset plot of issue 22 ([inset], render/inset_plot.hpp): its keys, the revealed
// curves ending at the cursor x(t) on generated signals and windows, paging, and a golden
// frame of sphere_roll with the slip speed falling to zero at the stick.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "image/compare.hpp"
#include "render/inset_plot.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render_fixtures.hpp"
#include "scene/scene.hpp"

namespace fs = std::filesystem;
using namespace stiction;
using namespace stiction::render;

namespace {

const fs::path kGoldenDir = fs::path(STICTION_SOURCE_DIR) / "tests" / "golden";
const fs::path kFailureDir = fs::path(STICTION_TEST_OUTPUT_DIR) / "failures";
const std::vector<std::string> kColumns{"t", "ground.slip.x", "ground.slip.y", "sphere.w.y"};

InsetSettings read_inset_table(const std::string& text) {
  return read_render_settings(toml::parse(std::string_view(text), std::string_view("scene.toml")),
                              {}, kColumns)
      .inset;
}

std::string error_of(const std::string& text) {
  try {
    read_inset_table(text);
  } catch (const scene::InputError& e) {
    return e.what();
  }
  return "";
}

bool same_pixel(const image::Image& a, const image::Image& b, int x, int y) {
  return std::equal(a.data(x, y), a.data(x, y) + 3, b.data(x, y));
}

std::string signal_name(int i) {
  std::string name = "s";
  name += std::to_string(i);  // (not "s" + ...: GCC 12's -Wrestrict false positive)
  return name;
}

// A run of `signals` random sines (random amplitude, frequency, phase, offset) over `duration`.
core::Trajectory random_run(std::mt19937& rng, int signals, double duration) {
  std::vector<std::string> columns{"t"};
  for (int i = 0; i < signals; ++i) columns.push_back(signal_name(i));
  core::Trajectory tr(columns);
  std::uniform_real_distribution<double> amp(0.1, 50.0), freq(0.2, 5.0), phase(0.0, 6.28),
      offset(-20.0, 20.0);
  std::vector<double> a, f, p, o;
  for (int i = 0; i < signals; ++i) {
    a.push_back(amp(rng));
    f.push_back(freq(rng));
    p.push_back(phase(rng));
    o.push_back(offset(rng));
  }
  const int rows = static_cast<int>(duration * 500.0) + 1;
  std::vector<double> row(columns.size());
  for (int r = 0; r < rows; ++r) {
    row[0] = duration * r / (rows - 1);
    for (int i = 0; i < signals; ++i) {
      const auto k = static_cast<std::size_t>(i);
      row[k + 1] = o[k] + a[k] * std::sin(f[k] * row[0] + p[k]);
    }
    tr.append(row.data());
  }
  return tr;
}

}  // namespace

TEST_CASE("[inset] keys: defaults and values", "[render][inset]") {
  const InsetSettings none = read_inset_table("");
  CHECK_FALSE(none.enabled());
  const InsetSettings s = read_inset_table(R"(
[inset]
signals = ["ground.slip", "sphere.w.y"]
labels = ["slip", "spin"]
units = ["m/s", "rad/s"]
position = "top_left"
size = [400, 220]
window = 0.5
opacity = 0.6
)");
  CHECK(s.enabled());
  CHECK(s.signals == std::vector<std::string>{"ground.slip", "sphere.w.y"});
  CHECK(s.corner == InsetCorner::top_left);
  CHECK(s.in_pixels);
  CHECK(s.width == 400);
  CHECK(s.window == 0.5);
  CHECK(s.opacity == 0.6);
  const InsetSettings f =
      read_inset_table("[inset]\nsignals = [\"ground.slip\"]\nsize = [0.5, 0.3]");
  CHECK_FALSE(f.in_pixels);
  CHECK(f.corner == InsetCorner::bottom_right);
  CHECK_FALSE(f.window.has_value());
}

TEST_CASE("[inset] errors name the file, line, column and key", "[render][inset]") {
  CHECK_THAT(error_of("[inset]\nsignals = [\"ground.slipp\"]"),
             Catch::Contains("scene.toml:2:") && Catch::Contains("inset.signals") &&
                 Catch::Contains("no signal named 'ground.slipp'"));
  CHECK_THAT(error_of("[inset]\nsignals = [\"ground.slip\"]\nposition = \"middle\""),
             Catch::Contains("scene.toml:3:") && Catch::Contains("inset.position"));
  CHECK_THAT(error_of("[inset]\nsignals = [\"ground.slip\"]\nsize = [100, 50]"),
             Catch::Contains("scene.toml:3:") && Catch::Contains("inset.size"));
  CHECK_THAT(error_of("[inset]\nsignals = [\"ground.slip\"]\nsize = [0.5, 300]"),
             Catch::Contains("inset.size"));
  CHECK_THAT(error_of("[inset]\nsignals = [\"ground.slip\"]\nwindow = -1"),
             Catch::Contains("scene.toml:3:") && Catch::Contains("inset.window"));
  CHECK_THAT(error_of("[inset]\nsignals = [\"ground.slip\"]\nlabels = [\"a\", \"b\"]"),
             Catch::Contains("inset.labels") && Catch::Contains("one entry per signal"));
  CHECK_THAT(error_of("[inset]\nsignals = [\"ground.slip\"]\nopacity = 2"),
             Catch::Contains("inset.opacity"));
  CHECK_THAT(error_of("[inset]\nwindow = 1"), Catch::Contains("inset.signals"));
  CHECK_THAT(error_of("[inset]\nsignals = [\"ground.slip\"]\ncolour = 1"),
             Catch::Contains("scene.toml:3:") && Catch::Contains("colour"));
}

TEST_CASE("generated signals and windows: the curves are revealed up to the cursor at x(t)",
          "[render][inset]") {
  std::mt19937 rng(22);
  for (int trial = 0; trial < 12; ++trial) {
    const int signals = 1 + trial % 4;
    const double duration = std::uniform_real_distribution<double>(0.5, 8.0)(rng);
    const core::Trajectory tr = random_run(rng, signals, duration);
    InsetSettings s;
    for (int i = 0; i < signals; ++i) s.signals.push_back(signal_name(i));
    s.corner = static_cast<InsetCorner>(trial % 4);
    s.width = std::uniform_real_distribution<double>(0.35, 0.9)(rng);
    s.height = std::uniform_real_distribution<double>(0.45, 0.9)(rng);
    if (trial % 2 == 1) s.window = std::uniform_real_distribution<double>(0.2, duration)(rng);
    const double t = std::uniform_real_distribution<double>(0.0, duration)(rng);
    INFO("trial " << trial << ": " << signals << " signals over " << duration << " s, t = " << t
                  << ", window " << (s.window ? *s.window : 0.0));
    const image::Rgba background{40, 60, 80, 255};
    InsetPlot inset(s, tr, 640, 360);
    const auto [t0, t1] = inset.page_range(t);
    CHECK(t0 <= t + 1e-12);
    CHECK(t <= t1 + 1e-12);
    if (s.window && *s.window < duration) CHECK(t1 - t0 == Approx(*s.window));
    image::Image now(640, 360, background), at_start(640, 360, background),
        at_end(640, 360, background);
    inset.draw(now, t);
    inset.draw(at_start, t0);
    inset.draw(at_end, t1 - 1e-9 * (t1 - t0));  // t1 itself starts the next page
    const PixelBox box = inset.box();
    const PixelBox panels = inset.panels_box(t);
    const int cursor = inset.cursor_x(t);
    // The cursor column at x(t) = panel left + (t - t0) / (t1 - t0) * panel width.
    CHECK(std::abs(cursor - (panels.x0 + (t - t0) / (t1 - t0) * (panels.x1 - panels.x0))) <= 1.5);
    const int mid = (panels.y0 + panels.y1) / 2;
    CHECK(now.at(cursor, mid) == image::Rgba{200, 30, 30, 255});
    // Left of the cursor the frame is the fully drawn plot, right of it the empty axes.
    int left_differs = 0, right_differs = 0, revealed = 0;
    for (int y = box.y0; y < box.y1; ++y) {
      for (int x = box.x0; x < box.x1; ++x) {
        if (x < cursor - 1 && x > panels.x0 + 1) {
          left_differs += !same_pixel(now, at_end, x, y);
          revealed += !same_pixel(at_end, at_start, x, y);
        }
        if (x > cursor + 1 && x < panels.x1 - 2) right_differs += !same_pixel(now, at_start, x, y);
      }
    }
    CHECK(left_differs == 0);
    CHECK(right_differs == 0);
    if (cursor - panels.x0 > 8) CHECK(revealed > 0);  // there was a curve to reveal
    // Outside the inset nothing changes.
    for (int y = 0; y < 360; y += 7) {
      for (int x = 0; x < 640; x += 7) {
        if (x >= box.x0 && x < box.x1 && y >= box.y0 && y < box.y1) continue;
        CHECK(now.at(x, y) == background);
      }
    }
  }
}

TEST_CASE("an inset in a frame smaller than a figure is scaled down into it", "[render][inset]") {
  std::mt19937 rng(1);
  const core::Trajectory tr = random_run(rng, 2, 1.0);
  InsetSettings s;
  s.signals = {"s0", "s1"};
  s.width = 0.8;
  s.height = 0.9;
  for (const auto& [w, h] : {std::pair{158, 88}, std::pair{200, 120}, std::pair{90, 300}}) {
    INFO(w << "x" << h);
    const image::Rgba background{40, 60, 80, 255};
    image::Image frame(w, h, background);
    InsetPlot inset(s, tr, w, h);
    const PixelBox box = inset.box();
    CHECK(box.x0 >= 0);
    CHECK(box.y0 >= 0);
    CHECK(box.x1 <= w);
    CHECK(box.y1 <= h);
    inset.draw(frame, 0.5);
    const PixelBox panels = inset.panels_box(0.5);
    CHECK(panels.x0 >= box.x0);
    CHECK(panels.x1 <= box.x1);
    const int cursor = inset.cursor_x(0.5);
    CHECK(std::abs(cursor - 0.5 * (panels.x0 + panels.x1)) <= 1.5);
    CHECK(frame.at(cursor, (panels.y0 + panels.y1) / 2) == image::Rgba{200, 30, 30, 255});
  }
  s.signals = {"nope"};
  CHECK_THROWS_AS(InsetPlot(s, tr, 640, 360), RenderError);
}

TEST_CASE("a bottom inset stays above the caption's band, a top one ignores it",
          "[render][inset]") {
  std::mt19937 rng(7);
  const core::Trajectory tr = random_run(rng, 1, 1.0);
  std::uniform_int_distribution<int> band(0, 80);
  for (int i = 0; i < 20; ++i) {
    InsetSettings s;
    s.signals = {"s0"};
    const int reserved = band(rng);
    s.corner = i % 2 ? InsetCorner::bottom_left : InsetCorner::bottom_right;
    InsetPlot bottom(s, tr, 640, 360, {}, reserved);
    CHECK(bottom.box().y1 <= 360 - reserved);
    CHECK(bottom.box().y0 >= 0);
    s.corner = InsetCorner::top_left;
    InsetPlot top(s, tr, 640, 360, {}, reserved);
    CHECK(top.box().y0 == InsetPlot(s, tr, 640, 360).box().y0);
  }
}

TEST_CASE("golden: sphere_roll with the slip speed inset after the stick",
          "[render][golden][inset]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory();
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  settings.inset.signals = {"contact.slip", "sphere.p.x"};
  settings.inset.labels = {"slip speed", "position"};
  settings.inset.units = {"m/s", "m"};
  settings.inset.width = 0.45;
  settings.inset.height = 0.6;
  const double stick = 2.0 * 2.0 / (7.0 * 0.1 * 9.8);
  FrameRenderer renderer(s.drawing, tr, settings,
                         FrameAnnotations{{stick}, {"stick"}});
  const image::CompareResult r = image::compare_to_golden(
      kGoldenDir / "render_inset_sphere_roll.png", renderer.render(1.2), kFailureDir);
  INFO(r.message);
  CHECK(r.matches);
}
