// Render + read-back speed at 1280x720 (the figure of merit), with the speed levers
// one at a time, and the end-to-end sphere_roll demo video (2 s at 60 fps = 121 frames,
// rendering overlapped with H.264 encoding on a worker thread).
//   ./build/bench/render/bench_render --benchmark_counters_tabular=true
// BM_VideoPipeline measures, interleaved in one run (so machine load hits all alike):
//   render_only   the 121 frames rendered and read back, nothing else;
//   video         the same frames through render_outputs (encode overlapped, default settings);
//   before        the same with the encoder as before issue 13 (veryfast, crf 20, libx264's
//                 own thread count);
// and reports video_over_render = video time / render-only time (goal <= 1.1),
// encoder_speedup = before time / video time, and for both encoder settings the mean PSNR
// of the decoded video against the rendered frames (every 8th) and the file size. The
// speed-up over the whole pipeline before issue 13 needs the old binary:
// bench/video_speedup.sh.
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <filesystem>

#include "render/render_outputs.hpp"
#include "render_fixtures.hpp"
#include "video_decode.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

void render_frames(benchmark::State& state, int msaa, int shadow_map_size, int taps, bool overlay) {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory();
  RenderSettings settings = read_render_settings(s);
  settings.msaa = msaa;
  settings.shadow_map_size = shadow_map_size;
  settings.shadow_taps = taps;
  settings.overlay.enabled = overlay;
  FrameRenderer renderer(describe_scene(*s.network, s.document), tr, settings);
  image::Image frame;
  renderer.render(0.0, frame);  // shader JIT happens on the first frame
  double t = 0.0;
  timespec c0{}, c1{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
  for (auto _ : state) {
    renderer.render(t, frame);
    benchmark::DoNotOptimize(frame.pixels.data());
    t += 1.0 / 60.0;
    if (t > 2.0) t = 0.0;
  }
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
  // CPU of all threads (llvmpipe's included) per frame: steadier than wall time on a
  // shared machine.
  state.counters["cpu_ms"] =
      ((c1.tv_sec - c0.tv_sec) * 1e3 + (c1.tv_nsec - c0.tv_nsec) * 1e-6) / state.iterations();
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Render720p_Default(benchmark::State& s) { render_frames(s, 4, 2048, 4, true); }
void BM_Render720p_OneShadowTap(benchmark::State& s) { render_frames(s, 4, 2048, 1, true); }
void BM_Render720p_NoMsaa(benchmark::State& s) { render_frames(s, 1, 2048, 4, true); }
void BM_Render720p_Shadow1024(benchmark::State& s) { render_frames(s, 4, 1024, 4, true); }
void BM_Render720p_Shadow512(benchmark::State& s) { render_frames(s, 4, 512, 4, true); }
void BM_Render720p_NoShadows(benchmark::State& s) { render_frames(s, 4, 0, 1, true); }
void BM_Render720p_Fastest(benchmark::State& s) { render_frames(s, 1, 0, 1, false); }

void BM_SphereRollVideo(benchmark::State& state) {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory(2.0);
  const RenderSettings settings = read_render_settings(s);
  const auto dir = std::filesystem::temp_directory_path() / "stiction_bench_render";
  RenderRequest request;
  request.out_dir = dir;
  int frames = 0;
  for (auto _ : state) {
    frames = render_outputs(s, tr, settings, request).frames;
  }
  state.counters["frames"] = frames;
  state.counters["fps"] = benchmark::Counter(static_cast<double>(frames) * state.iterations(),
                                             benchmark::Counter::kIsRate);
  std::filesystem::remove_all(dir);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_VideoPipeline(benchmark::State& state) {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory(2.0);
  const RenderSettings settings = read_render_settings(s);
  // The encoder as it was before issue 13: veryfast at crf 20, libx264's own thread count.
  RenderSettings before = settings;
  before.preset = "veryfast";
  before.crf = 20;
  before.encoder_threads = -1;
  const auto dir = std::filesystem::temp_directory_path() / "stiction_bench_pipeline";
  RenderRequest now_request, before_request;
  now_request.out_dir = dir / "now";
  before_request.out_dir = dir / "before";
  const FrameClock clock = frame_clock(0.0, 2.0, settings.fps, settings.slow_motion);
  double render_only = 0.0, video = 0.0, video_before = 0.0;
  std::vector<image::Image> sampled;  // every 8th rendered frame, for the quality figures
  for (auto _ : state) {
    {
      sampled.clear();
      const auto start = std::chrono::steady_clock::now();
      FrameRenderer renderer(describe_scene(*s.network, s.document), tr, settings);
      image::Image frame;
      for (int i = 0; i < clock.count; ++i) {
        renderer.render(clock.time(i), frame);
        benchmark::DoNotOptimize(frame.pixels.data());
        if (i % 8 == 0) sampled.push_back(frame);
      }
      render_only += seconds_since(start);
    }
    auto start = std::chrono::steady_clock::now();
    render_outputs(s, tr, settings, now_request);
    video += seconds_since(start);
    start = std::chrono::steady_clock::now();
    render_outputs(s, tr, before, before_request);
    video_before += seconds_since(start);
  }
  const double n = static_cast<double>(state.iterations()) * clock.count;
  state.counters["render_only_fps"] = n / render_only;
  state.counters["video_fps"] = n / video;
  state.counters["video_over_render"] = video / render_only;
  state.counters["encoder_speedup"] = video_before / video;
  // Equal quality: the mean PSNR of the decoded video against the rendered frames (yuv420p
  // and the codec's losses), and the file size, for both encoder settings.
  auto quality = [&](const std::filesystem::path& file, const std::string& name) {
    const testing::DecodedVideo decoded = testing::decode_video(file);
    double sum = 0.0;
    for (std::size_t k = 0; k < sampled.size(); ++k) {
      sum += testing::psnr_rgb(sampled[k], decoded.images.at(8 * k));
    }
    state.counters[name + "_psnr_db"] = sum / static_cast<double>(sampled.size());
    state.counters[name + "_kB"] = static_cast<double>(std::filesystem::file_size(file)) / 1e3;
  };
  quality(dir / "now" / "video.mp4", "video");
  quality(dir / "before" / "video.mp4", "before");
  std::filesystem::remove_all(dir);
}

}  // namespace

BENCHMARK(BM_Render720p_Default)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_Render720p_OneShadowTap)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_Render720p_NoMsaa)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_Render720p_Shadow1024)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_Render720p_Shadow512)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_Render720p_NoShadows)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_Render720p_Fastest)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_SphereRollVideo)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_VideoPipeline)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);

BENCHMARK_MAIN();
