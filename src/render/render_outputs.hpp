// The renderer's entry points.
//
//   render::RenderSettings settings = render::read_render_settings(scene);  // before simulating
//   render::RenderRequest request{.out_dir = dir, .video = true, .frames = with_frames,
//                                 .progress = show_bar, .cancel = &interrupted};
//   render::RenderResult r = render::render_outputs(scene, trajectory, settings, request);
//
// writes OUT/video.mp4 (H.264) and with `frames` OUT/frames/NNNNNN.png. Frame i shows the
// simulated time t0 + i / (fps * slow_motion). Rendering runs on the calling thread,
// encoding and PNG writing on a worker thread. When *cancel becomes true (Ctrl-C), what was
// rendered so far is finalized as OUT/video.partial.mp4 and r.interrupted is set.
// Errors: scene::InputError (bad settings: exit 2), GlError / VideoError / RenderError /
// image::ImageError / text::FontError (exit 1).
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/trajectory.hpp"
#include "image/image.hpp"
#include "render/camera.hpp"
#include "render/contact_sites.hpp"
#include "render/frame_panels.hpp"
#include "render/render_settings.hpp"
#include "render/scene_view.hpp"

namespace stiction::scene {
struct Scene;
}

namespace stiction::render {

struct RenderProgress {
  int frames_done = 0;
  int frame_count = 0;
  double elapsed_seconds = 0.0;
  double frames_per_second = 0.0;
  double eta_seconds = 0.0;
};

struct RenderRequest {
  std::filesystem::path out_dir;
  bool video = true;                                    // OUT/video.mp4
  bool frames = false;                                  // OUT/frames/NNNNNN.png
  std::function<void(const RenderProgress&)> progress;  // called after each frame
  const std::atomic<bool>* cancel = nullptr;
  // Stick/slip event times of the run: the video slows down around them when the settings'
  // slow_motion_around_events is positive.
  std::vector<double> event_times;
  // The kind of each event ("stick", "slip", ...), parallel to event_times; may be empty.
  // The inset plot ([inset]) marks the events with them.
  std::vector<std::string> event_kinds;
};

struct RenderResult {
  int frames = 0;
  bool interrupted = false;
  std::filesystem::path video;  // empty if no video was written
  double wall_seconds = 0.0;
  // CPU time of the thread that converts, encodes and writes the frames (libx264 runs on it
  // when it has one thread, the default beside the renderer; threads it starts itself are
  // not counted).
  double worker_cpu_seconds = 0.0;
};

// Frame times of a run: count and time of frame i.
struct FrameClock {
  double start = 0.0;
  double step = 1.0 / 60.0;  // simulated seconds per frame
  int count = 1;
  double time(int i) const { return start + step * i; }
};
FrameClock frame_clock(double start, double end, double fps, double slow_motion);

class GlContext;
class Renderer;
class CameraRig;
class Overlay;
class InsetPlot;
class ForceRegimeLayers;
class TitleCaption;

// Renders single frames of one run (also used by the tests and the benchmark). Creates its
// own GL context; use it from one thread.
// What a run adds to its frames beyond its drawing and poses: the run's events, which the
// inset plot marks (parallel lists; kinds may be empty). The contact points and friction
// joints that carry force arrows, badges and trails are the drawing's (Drawing::sites).
struct FrameAnnotations {
  std::vector<double> event_times;
  std::vector<std::string> event_kinds;
};

class FrameRenderer {
 public:
  FrameRenderer(Drawing scene, const core::Trajectory& trajectory, const RenderSettings& settings,
                const FrameAnnotations& annotations = {});
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  // The frame at simulated time t, overlay included. `speed` < 1: the frame is in a
  // time-warped stretch (slow motion around an event); the overlay says so.
  void render(double t, image::Image& out, double speed = 1.0);
  image::Image render(double t, double speed = 1.0);

  const PoseTrack& poses() const { return poses_; }
  const RenderSettings& settings() const { return settings_; }
  // The panels drawn over the frames (time panel, inset, arrows' legend, title and caption),
  // which the camera keeps the bodies clear of, and the camera at time t.
  const FramePanels& panels() const { return panels_; }
  Camera camera(double t) const;
  // The magnitude below which `signal` prints as zero because the run judges it stuck (a
  // contact's slip speed, a friction joint's rate: their stick thresholds); -1 for a signal
  // without a stick threshold.
  double stuck_below(const std::string& signal) const;

 private:
  Drawing scene_;
  RenderSettings settings_;
  std::map<std::string, double> joint_rate_thresholds_;
  PoseTrack poses_;
  std::unique_ptr<GlContext> context_;
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<CameraRig> camera_;
  std::unique_ptr<Overlay> overlay_;
  std::unique_ptr<InsetPlot> inset_;
  std::unique_ptr<ForceRegimeLayers> layers_;  // null: forces, velocities, badges off
  std::unique_ptr<TitleCaption> titles_;       // null: no title and no caption
  FramePanels panels_;
};

// The renderer of a run of `scene` as the video draws it: its description, its contact sites
// and the given events. Every path that renders a run's frames (the video, `verify`'s single
// frames, the tiles of `compare --video`) goes through here, so they show the same layers.
std::unique_ptr<FrameRenderer> frame_renderer_for(const scene::Scene& scene,
                                                  const core::Trajectory& trajectory,
                                                  const RenderSettings& settings,
                                                  std::vector<double> event_times = {},
                                                  std::vector<std::string> event_kinds = {});

RenderResult render_outputs(const scene::Scene& scene, const core::Trajectory& trajectory,
                            const RenderSettings& settings, const RenderRequest& request);

}  // namespace stiction::render
