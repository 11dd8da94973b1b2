// Render + read-back speed at 1280x720 (the figure of merit), with the speed levers
// one at a time, and the end-to-end sphere_roll demo video (2 s at 60 fps = 121 frames,
// rendering overlapped with H.264 encoding on a worker thread).
//   ./build/bench/render/bench_render --benchmark_counters_tabular=true
// BM_VideoPipeline measures, interleaved in one run (so machine load hits all alike):
//   render_only   the 121 frames rendered and read back, nothing else;
//   video         the same frames through render_outputs (encode overlapped, default settings);
//   video_x264_threads  the same with libx264's own thread count (1.5 per core, as before
//                 issue 13) instead of the cores the renderer leaves;
// and reports video_over_render = video time / render-only time (goal <= 1.1) and
// threads_speedup = video fps / video_x264_threads fps. The speed-up over the pipeline
// before issue 13 (whole-run 2048^2 shadow map too) needs the old binary: docs/rendering.md.
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <filesystem>

#include "render/render_outputs.hpp"
#include "render_fixtures.hpp"

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
  RenderSettings before = settings;
  before.encoder_threads = -1;
  const auto dir = std::filesystem::temp_directory_path() / "stiction_bench_pipeline";
  RenderRequest request;
  request.out_dir = dir;
  const FrameClock clock = frame_clock(0.0, 2.0, settings.fps, settings.slow_motion);
  double render_only = 0.0, video = 0.0, video_before = 0.0;
  for (auto _ : state) {
    {
      const auto start = std::chrono::steady_clock::now();
      FrameRenderer renderer(describe_scene(*s.network, s.document), tr, settings);
      image::Image frame;
      for (int i = 0; i < clock.count; ++i) {
        renderer.render(clock.time(i), frame);
        benchmark::DoNotOptimize(frame.pixels.data());
      }
      render_only += seconds_since(start);
    }
    auto start = std::chrono::steady_clock::now();
    render_outputs(s, tr, settings, request);
    video += seconds_since(start);
    start = std::chrono::steady_clock::now();
    render_outputs(s, tr, before, request);
    video_before += seconds_since(start);
  }
  const double n = static_cast<double>(state.iterations()) * clock.count;
  state.counters["render_only_fps"] = n / render_only;
  state.counters["video_fps"] = n / video;
  state.counters["video_x264_threads_fps"] = n / video_before;
  state.counters["video_over_render"] = video / render_only;
  state.counters["threads_speedup"] = video_before / video;
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
