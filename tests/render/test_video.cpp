#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "image/compare.hpp"
#include "image/png.hpp"
#include "render/render_outputs.hpp"
#include "render/video_encoder.hpp"
#include "render_fixtures.hpp"
#include "video_decode.hpp"

namespace fs = std::filesystem;
using namespace stiction;
using namespace stiction::render;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(STICTION_TEST_OUTPUT_DIR) / "video" / name;
  fs::remove_all(dir);
  return dir;
}

double mean_abs_difference(const image::Image& a, const image::Image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
  }
  return sum / (a.pixels.size() * 3.0 / 4.0);
}

}  // namespace

TEST_CASE("video.mp4: H.264, frame count, size, duration, and frames match the PNGs",
          "[render][video]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory(1.0);
  RenderSettings settings = read_render_settings(s);
  settings.width = 320;
  settings.height = 180;
  settings.fps = 30.0;
  settings.crf = 16;
  const fs::path dir = scratch("full");
  RenderRequest request;
  request.out_dir = dir;
  request.frames = true;
  int progress_calls = 0;
  request.progress = [&](const RenderProgress& p) {
    ++progress_calls;
    CHECK(p.frame_count == 31);
  };
  const RenderResult result = render_outputs(s, tr, settings, request);
  CHECK(result.frames == 31);  // 1 s at 30 fps, both ends included
  CHECK(progress_calls == 31);
  CHECK_FALSE(result.interrupted);
  // The worker thread's CPU: converting and encoding 31 frames is not free.
  CHECK(result.worker_cpu_seconds > 0.0);
  REQUIRE(fs::exists(dir / "video.mp4"));
  CHECK(fs::exists(dir / "frames" / "000000.png"));
  CHECK(fs::exists(dir / "frames" / "000030.png"));
  CHECK_FALSE(fs::exists(dir / "frames" / "000031.png"));
  for (const auto& entry : fs::directory_iterator(dir)) {
    INFO(entry.path());
    CHECK(entry.path().string().find(".tmp.") == std::string::npos);
  }

  const testing::DecodedVideo video = testing::decode_video(dir / "video.mp4");
  CHECK(video.codec == "h264");
  CHECK(video.width == 320);
  CHECK(video.height == 180);
  CHECK(video.frames == 31);
  CHECK(video.fps == Approx(30.0));
  CHECK(video.duration == Approx(31.0 / 30.0).margin(0.04));
  // Frame 12 (t = 0.4 s): the decoded picture matches the PNG of the same time up to the
  // losses of yuv420p (chroma at half resolution smears colour edges) and of the codec.
  REQUIRE(video.images.size() > 12);
  const image::Image png = image::read_png(dir / "frames" / "000012.png");
  const double mad = mean_abs_difference(png, video.images[12]);
  INFO("mean absolute difference " << mad);
  CHECK(mad < 3.0);
  const image::CompareResult r = image::compare_images(png, video.images[12], {48, 0.02});
  INFO(r.message);
  CHECK(r.matches);
  // ... and not the PNG of another time.
  CHECK(mean_abs_difference(image::read_png(dir / "frames" / "000024.png"), video.images[12]) > mad);
}

TEST_CASE("preset ultrafast keeps x264's deblocking filter on, at 1:1", "[render][video]") {
  // libx264 writes its settings into the stream (an SEI message): "deblock=ON:ALPHA:BETA".
  auto encoder_settings = [](const std::string& preset) {
    const fs::path dir = scratch("deblock_" + preset);
    fs::create_directories(dir);
    VideoOptions options;
    options.width = 64;
    options.height = 64;
    options.preset = preset;
    VideoEncoder encoder(dir / "video.mp4", options);
    for (int i = 0; i < 3; ++i) encoder.encode(image::Image(64, 64, {10, 200, 30, 255}));
    encoder.finish();
    std::ifstream in(dir / "video.mp4", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = bytes.find("deblock=");
    return at == std::string::npos ? std::string() : bytes.substr(at, 13);
  };
  CHECK(encoder_settings("ultrafast") == "deblock=1:1:1");
  CHECK(encoder_settings("superfast") == "deblock=1:0:0");
}

TEST_CASE("slow motion stretches video time", "[render][video]") {
  CHECK(frame_clock(0.0, 2.0, 60.0, 1.0).count == 121);
  const FrameClock slow = frame_clock(0.0, 2.0, 60.0, 4.0);
  CHECK(slow.count == 481);
  CHECK(slow.time(480) == Approx(2.0));
  CHECK(slow.time(60) == Approx(0.25));
}

TEST_CASE("a cancelled render is finalized as video.partial.mp4 and plays", "[render][video]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory(1.0);
  RenderSettings settings = read_render_settings(s);
  settings.width = 160;
  settings.height = 90;
  const fs::path dir = scratch("partial");
  std::atomic<bool> cancel{false};
  RenderRequest request;
  request.out_dir = dir;
  request.cancel = &cancel;
  request.progress = [&](const RenderProgress& p) {
    if (p.frames_done == 10) cancel = true;  // as the app's SIGINT handler would
  };
  const RenderResult result = render_outputs(s, tr, settings, request);
  CHECK(result.interrupted);
  CHECK(result.frames == 10);
  CHECK_FALSE(fs::exists(dir / "video.mp4"));
  REQUIRE(fs::exists(dir / "video.partial.mp4"));
  CHECK(testing::decode_video(dir / "video.partial.mp4").frames == 10);
}

TEST_CASE("an unwritable output path is an I/O error and leaves no file", "[render][video]") {
  const fs::path dir = scratch("unwritable");
  fs::create_directories(dir);
  VideoOptions options;
  options.width = 64;
  options.height = 64;
  CHECK_THROWS_AS(VideoEncoder(dir / "missing_dir" / "video.mp4", options), VideoError);
  options.width = 63;
  CHECK_THROWS_WITH(VideoEncoder(dir / "video.mp4", options), Catch::Contains("even"));
  CHECK(fs::is_empty(dir));
}

TEST_CASE("an encoder dropped before finish() removes its temporary file", "[render][video]") {
  const fs::path dir = scratch("dropped");
  fs::create_directories(dir);
  VideoOptions options;
  options.width = 64;
  options.height = 64;
  {
    VideoEncoder encoder(dir / "video.mp4", options);
    encoder.encode(image::Image(64, 64, {10, 200, 30, 255}));
    CHECK(fs::exists(encoder.temporary_path()));
  }
  CHECK(fs::is_empty(dir));
}
