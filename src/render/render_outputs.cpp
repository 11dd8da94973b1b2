#include "render/render_outputs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "render/camera.hpp"
#include "render/force_regime_layers.hpp"
#include "render/frame_worker.hpp"
#include "render/gl_context.hpp"
#include "render/inset_plot.hpp"
#include "render/overlay.hpp"
#include "render/renderer.hpp"
#include "render/spin_blur.hpp"
#include "render/time_warp.hpp"
#include "render/title_caption.hpp"
#include "render/trail.hpp"
#include "render/video_encoder.hpp"
#include "scene/scene.hpp"
#include "sys/terminal_text.hpp"

namespace stiction::render {

namespace fs = std::filesystem;

FrameClock frame_clock(double start, double end, double fps, double slow_motion) {
  FrameClock clock;
  clock.start = start;
  clock.step = 1.0 / (fps * slow_motion);
  clock.count = static_cast<int>(std::floor((end - start) / clock.step + 1e-6)) + 1;
  return clock;
}

FrameRenderer::FrameRenderer(Drawing scene, const core::Trajectory& trajectory,
                             const RenderSettings& settings, const FrameAnnotations& annotations)
    : scene_(std::move(scene)),
      settings_(settings),
      joint_rate_thresholds_(joint_rate_thresholds(scene_.sites)),
      poses_(trajectory, scene_) {
  context_ = create_offscreen_context();
  RendererOptions options;
  options.width = settings.width;
  options.height = settings.height;
  options.msaa = settings.msaa;
  options.shadow_map_size = settings.shadow_map_size;
  options.shadow_taps = settings.shadow_taps;
  renderer_ = std::make_unique<Renderer>(options);
  if (settings.overlay.enabled && settings.overlay.panel) {
    overlay_ =
        std::make_unique<Overlay>(settings.overlay, settings.height, poses_.end_time(),
                                  settings.slow_motion_around_events > 0.0, joint_rate_thresholds_);
  }
  if (settings.inset.enabled()) {
    std::vector<InsetEvent> events;
    const auto& times = annotations.event_times;
    const auto& kinds = annotations.event_kinds;
    for (std::size_t i = 0; i < times.size(); ++i)
      events.push_back({times[i], i < kinds.size() ? kinds[i] : ""});
    inset_ = std::make_unique<InsetPlot>(
        settings.inset, trajectory, settings.width, settings.height, std::move(events),
        TitleCaption::caption_height(settings.overlay, settings.height));
  }
  layers_ = ForceRegimeLayers::create(scene_, scene_.sites, poses_, settings);
  titles_ = TitleCaption::create(settings.overlay, settings.height);
  // The camera comes last: it frames the bodies beside the panels above.
  panels_.width = settings.width;
  panels_.height = settings.height;
  if (overlay_) panels_.boxes.push_back(overlay_->box());
  if (inset_) panels_.boxes.push_back(inset_->box());
  if (layers_) {
    const PixelBox legend = layers_->legend_box(settings.height);
    if (!legend.empty()) panels_.boxes.push_back(legend);
  }
  if (titles_) {
    for (const PixelBox& b : titles_->boxes(settings.width, settings.height)) {
      panels_.boxes.push_back(b);
    }
  }
  camera_ = std::make_unique<CameraRig>(settings.camera, scene_, poses_, panels_);
}

Camera FrameRenderer::camera(double t) const { return camera_->at(t); }

std::unique_ptr<FrameRenderer> frame_renderer_for(const scene::Scene& scene,
                                                  const core::Trajectory& trajectory,
                                                  const RenderSettings& settings,
                                                  std::vector<double> event_times,
                                                  std::vector<std::string> event_kinds) {
  FrameAnnotations annotations;
  annotations.event_times = std::move(event_times);
  annotations.event_kinds = std::move(event_kinds);
  return std::make_unique<FrameRenderer>(scene.drawing, trajectory, settings, annotations);
}

double FrameRenderer::stuck_below(const std::string& signal) const {
  const auto joint = joint_rate_thresholds_.find(signal);
  if (joint != joint_rate_thresholds_.end()) return joint->second;
  return threshold_zero(signal, settings_.overlay.stick_thresholds,
                        settings_.overlay.default_stick_threshold);
}

FrameRenderer::~FrameRenderer() {
  // GL objects go before the context, deleted in it.
  context_->make_current();
  renderer_.reset();
}

void FrameRenderer::render(double t, image::Image& out, double speed) {
  // Several FrameRenderers may live at once (tests, benchmarks): draw in our own context.
  context_->make_current();
  const Bounds focus = camera_->follows_vertically() ? camera_->follow_bounds(t) : Bounds{};
  std::vector<DrawItem> items = build_items(scene_, poses_, t, focus);
  // The frame stands for 1 / fps of video, i.e. this much simulated time (open shutter).
  const double exposure = speed / (settings_.fps * settings_.slow_motion);
  apply_spin_blur(items, poses_, t, exposure);
  std::vector<TrailVertex> trail;
  if (settings_.overlay.trail) {
    TrailOptions options;
    options.seconds = settings_.overlay.trail_seconds;
    options.thresholds = settings_.overlay.stick_thresholds;
    options.default_threshold = settings_.overlay.default_stick_threshold;
    options.contacts = settings_.overlay.trail_contacts;
    trail = build_trails(scene_, poses_, t, options);
  }
  const Camera camera = camera_->at(t);
  if (layers_) layers_->add_items(items, t, camera, exposure);
  renderer_->draw(items, camera, trail);
  renderer_->read_back(out);
  if (overlay_) overlay_->draw(out, poses_, t, speed);
  if (inset_) inset_->draw(out, t);
  if (titles_) titles_->draw(out);
  if (layers_) layers_->draw(out, t, camera, exposure);
}

image::Image FrameRenderer::render(double t, double speed) {
  image::Image out;
  render(t, out, speed);
  return out;
}

RenderResult render_outputs(const scene::Scene& scene, const core::Trajectory& trajectory,
                            const RenderSettings& settings, const RenderRequest& request) {
  const auto started = std::chrono::steady_clock::now();
  RenderResult result;
  if (!request.video && !request.frames) return result;

  const std::unique_ptr<FrameRenderer> run_renderer =
      frame_renderer_for(scene, trajectory, settings, request.event_times, request.event_kinds);
  FrameRenderer& renderer = *run_renderer;
  const FrameClock clock = frame_clock(renderer.poses().start_time(), renderer.poses().end_time(),
                                       settings.fps, settings.slow_motion);
  const std::vector<FrameTime> times =
      warped_frame_times(clock.start, renderer.poses().end_time(), clock.step,
                         slowed_events(request.event_times, request.event_kinds,
                                       settings.slow_motion_around_events, settings.slowed_events),
                         settings.slow_motion_around_events, settings.event_slow_motion);
  std::error_code ec;
  fs::create_directories(request.out_dir, ec);
  if (ec) throw VideoError("cannot create " + request.out_dir.string() + ": " + ec.message());
  std::optional<fs::path> frames_dir;
  if (request.frames) {
    frames_dir = request.out_dir / "frames";
    fs::create_directories(*frames_dir, ec);
    if (ec) throw image::ImageError("cannot create " + frames_dir->string() + ": " + ec.message());
  }
  std::unique_ptr<VideoEncoder> encoder;
  if (request.video) {
    encoder =
        std::make_unique<VideoEncoder>(request.out_dir / "video.mp4", video_options(settings));
  }
  render_frame_sequence(
      times, [&](const FrameTime& f, image::Image& frame) { renderer.render(f.t, frame, f.speed); },
      encoder.get(), frames_dir, request.cancel, request.progress, started, result);
  if (encoder) {
    result.video = encoder->finish(result.interrupted ? request.out_dir / "video.partial.mp4"
                                                      : request.out_dir / "video.mp4");
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace stiction::render
