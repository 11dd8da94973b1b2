// `stiction compare A B ... --video` (render/compare_video.hpp): the tile grid for generated
// run counts and frame sizes, a decoded compare.mp4 with the expected frame count and size
// whose tiles both show their run, and a golden frame of two arms side by side.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>

#include "image/compare.hpp"
#include "render/compare_video.hpp"
#include "render/render_settings.hpp"
#include "render_fixtures.hpp"
#include "scene/scene.hpp"
#include "video_decode.hpp"

namespace fs = std::filesystem;
using namespace stiction;
using namespace stiction::render;

namespace {

const fs::path kGoldenDir = fs::path(STICTION_SOURCE_DIR) / "tests" / "golden";
const fs::path kFailureDir = fs::path(STICTION_TEST_OUTPUT_DIR) / "failures";

// The two_link arm turning at `rate` times the fixture's speeds (a second run that drifts).
core::Trajectory arm_run(double rate, double duration) {
  core::Trajectory tr({"t", "arm.theta.0", "arm.theta.1", "arm.omega.0", "arm.omega.1"});
  const int rows = static_cast<int>(duration * 1000.0) + 1;
  for (int i = 0; i < rows; ++i) {
    const double t = i * 1e-3;
    const double row[] = {t, 0.3 + 1.2 * rate * t, 0.4 + 0.9 * rate * t, 1.2 * rate, 0.9 * rate};
    tr.append(row);
  }
  return tr;
}

// How much a box of the image varies: the standard deviation of its green channel.
double spread(const image::Image& img, int x0, int y0, int x1, int y1) {
  double sum = 0.0, sum2 = 0.0;
  long n = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const double g = img.data(x, y)[1];
      sum += g;
      sum2 += g * g;
      ++n;
    }
  }
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, sum2 / n - mean * mean));
}

}  // namespace

TEST_CASE("tile grid: tiles are disjoint, even, inside the frame, for generated runs and sizes",
          "[render][compare]") {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const int runs = 1 + trial % 9;
    const int width = 2 * std::uniform_int_distribution<int>(100, 2000)(rng);
    const int height = 2 * std::uniform_int_distribution<int>(100, 1200)(rng);
    const TileGrid g = tile_grid(runs, width, height);
    INFO(runs << " runs in " << width << "x" << height);
    CHECK(g.columns * g.rows >= runs);
    CHECK(g.columns * g.rows - runs < g.columns);  // no empty row
    if (runs == 2) CHECK((g.columns == 2 && g.rows == 1));
    CHECK(g.tile_width % 2 == 0);
    CHECK(g.tile_height % 2 == 0);
    for (int i = 0; i < runs; ++i) {
      const TileGrid::Box a = g.tile(i);
      CHECK(a.x0 >= 0);
      CHECK(a.y0 >= 0);
      CHECK(a.x1 <= width);
      CHECK(a.y1 <= height);
      for (int j = 0; j < i; ++j) {
        const TileGrid::Box b = g.tile(j);
        CHECK_FALSE((a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1));
      }
    }
  }
}

TEST_CASE("compare video: frame count and size, both tiles in the decoded frames",
          "[render][compare][video]") {
  const scene::Scene s = testing::make_scene(testing::two_link_toml(), "two_link");
  const core::Trajectory fast = arm_run(1.0, 1.0), slow = arm_run(0.3, 0.8);
  RenderSettings settings = read_render_settings(s);
  settings.width = 320;
  settings.height = 180;
  settings.fps = 15;
  settings.msaa = 1;
  std::vector<CompareRun> runs(2);
  runs[0] = {"two_link", &s, &fast, settings, {}, {}};
  runs[1] = {"two_link_lugre", &s, &slow, settings, {0.5}, {"stick"}};
  runs[1].settings.slow_motion_around_events = 0.1;  // one scene asks for slow motion
  const fs::path dir = fs::path(STICTION_TEST_OUTPUT_DIR) / "compare_video";
  fs::remove_all(dir);
  CompareVideoRequest request;
  request.out_dir = dir;
  const RenderResult r = render_compare_video(runs, request);
  const std::size_t expected = CompareFrames(runs).frame_times().size();
  // 1 s at 15 fps is 16 frames; the slow motion around t = 0.5 s adds more.
  CHECK(expected > 16);
  CHECK(r.frames == static_cast<int>(expected));
  CHECK(r.video == dir / "compare.mp4");
  const testing::DecodedVideo video = testing::decode_video(dir / "compare.mp4");
  CHECK(video.width == 320);
  CHECK(video.height == 180);
  CHECK(video.frames == static_cast<int>(expected));
  const TileGrid g = tile_grid(2, 320, 180);
  for (const image::Image& frame : {video.images.front(), video.images.back()}) {
    for (int i = 0; i < 2; ++i) {
      const TileGrid::Box b = g.tile(i);
      // A rendered scene (floor, arm, label), not the gap colour.
      CHECK(spread(frame, b.x0, b.y0, b.x1, b.y1) > 5.0);
    }
  }
  // The two arms turn at different rates: the tiles differ at the end.
  const image::Image& last = video.images.back();
  const TileGrid::Box left = g.tile(0), right = g.tile(1);
  long differing = 0;
  for (int y = 40; y < left.y1; ++y) {
    for (int x = 0; x < g.tile_width; ++x) {
      differing +=
          std::abs(int(last.data(left.x0 + x, y)[1]) - int(last.data(right.x0 + x, y)[1])) > 30;
    }
  }
  CHECK(differing > 100);
}

TEST_CASE("golden: two arms side by side in a compare tile frame", "[render][golden][compare]") {
  const scene::Scene s = testing::make_scene(testing::two_link_toml(), "two_link");
  const core::Trajectory fast = arm_run(1.0, 1.0), slow = arm_run(0.4, 1.0);
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  std::vector<CompareRun> runs(2);
  runs[0] = {"two_link", &s, &fast, settings, {}, {}};
  runs[1] = {"two_link_lugre", &s, &slow, settings, {}, {}};
  CompareFrames frames(runs);
  const image::CompareResult r = image::compare_to_golden(kGoldenDir / "render_compare_tiles.png",
                                                          frames.render(0.8), kFailureDir);
  INFO(r.message);
  CHECK(r.matches);
}

TEST_CASE("compare video: runs that do not fit the frame, or too many frames, are refused",
          "[render][compare]") {
  const scene::Scene s = testing::make_scene(testing::two_link_toml(), "two_link");
  const core::Trajectory run = arm_run(1.0, 0.2);
  RenderSettings settings = read_render_settings(s);
  settings.msaa = 1;
  std::mt19937 rng(9);
  for (int trial = 0; trial < 20; ++trial) {
    // Tiles of at least 16 pixels with 2-pixel gaps: n runs in a row need 18 n - 2 pixels.
    const int runs_count = 2 + trial % 7;
    const int columns = runs_count <= 2 ? runs_count : int(std::ceil(std::sqrt(runs_count)));
    settings.width = 2 * std::uniform_int_distribution<int>(8, (18 * columns - 4) / 2)(rng);
    settings.height = 180;
    std::vector<CompareRun> runs(static_cast<std::size_t>(runs_count),
                                 CompareRun{"arm", &s, &run, settings, {}, {}});
    INFO(runs_count << " runs in " << settings.width << " px");
    CHECK_THROWS_AS(CompareFrames(runs), RenderError);
  }
  settings.width = 320;
  settings.fps = 240;
  settings.slow_motion = 1e5;  // 0.2 s at 2.4e7 frames per simulated second
  std::vector<CompareRun> runs(2, CompareRun{"arm", &s, &run, settings, {}, {}});
  CHECK_THROWS_AS(CompareFrames(runs), RenderError);
}
