// The scene file's [render], [camera] and [overlay] tables (the scene loader leaves them to
// the renderer). Every key is checked: an unknown key or a bad value is a
// scene::InputError "FILE:LINE:COL: error: KEY: ..." (exit code 2).
//
//   [render]
//   size = [1280, 720]      # pixels, both even (yuv420p) and in 16..7680
//   fps = 60                # video frames per second of video time
//   crf = 21                # H.264 quality, 0 (lossless) .. 51 (worst); 18-23 look good
//   codec = "h264"          # only "h264" (libx264)
//   preset = "talk"         # a look preset (talk_preset.hpp: 16:9, slow motion around the
//                           # first events, badges, force arrows, trail, inset); any key
//                           # given explicitly wins. An x264 name here (older files) is
//                           # encoder_preset's
//   encoder_preset = "superfast"  # libx264 speed preset (with crf 21: half the encoding time
//                           # of veryfast at crf 20, better SSIM and PSNR, 1.5x the bytes;
//                           # "ultrafast", deblocking kept on: 60% of this CPU, 2.6x bytes)
//   slow_motion = 1.0       # video seconds per simulated second (4 = four times slower)
//   slow_motion_around_events = 0.0  # seconds of simulated time on each side of every
//                           # stick/slip event played `event_slow_motion` times slower
//   event_slow_motion = 8   # how much slower, 1..100 (ramps in and out over half the window)
//   slowed_events = 0       # slow down around the first N episodes of slip/stick changes
//                           # only (time_warp.hpp: slowed_events); 0: around every event
//   msaa = 4                # samples per pixel: 1, 2 or 4
//   shadow_map_size = 2048  # 0 turns shadows off; else a power of two 256..8192: the most
//                           # texels per side; each frame uses what the fitted region needs
//   shadow_taps = 4         # 1 or 4 filtered shadow-map lookups per pixel
//   encoder_threads = 0     # libx264 threads; 0: the cores the renderer leaves (at least 1)
//
//   [camera]                # what each key does under each view: docs/scene_format.md
//   position = [x, y, z]    # default: framed from the bodies over the whole run, beside the
//                           # panels (framing.hpp); given: no automatic framing. Under a
//                           # follow camera: the eye at the start, moving with the body
//   target = [x, y, z]      # likewise, the point at the frame's centre
//   fov = 40                # vertical field of view, degrees; a fixed camera comes as close
//                           # as the bodies allow, a follow camera stands where its body is
//                           # 1/3 of the height at 40 degrees, so there fov zooms
//   follow = "sphere"       # keep this body's horizontal position in view
//   follow_vertical = false # true: follow its height too (needs `follow`); the shadow map is
//                           # then fitted around the body every frame (long descents)
//   view = "auto"           # camera preset (camera_preset.hpp): "auto" (the automatic framing
//                           # above), "side", "top", "three_quarter" (fixed, the whole mechanism
//                           # over the run in view; `follow` ignored) or "follow" (the `follow`
//                           # body, else the first, tracked horizontally at a fixed height)
//
//   [overlay]
//   enabled = true          # draw the time and the signal
//   signal = "contact.slip" # a signal name; a vector signal shows its norm
//   label = "slip speed"    # text shown before the value (default: the signal name)
//   unit = "m/s"
//   trail = true            # the path of each contact point over the last trail_seconds,
//                           # green below the contact's stick_threshold, red above
//   trail_seconds = 0.5
//   trail_contacts = ["ground"]  # contacts with a trail (default: every contact)
//   values, title, caption, forces, force_scale, velocities, velocity_scale, badges:
//                           # see overlay_layers_settings.hpp
//
//   [inset]                 # a live plot in a corner of the video: see inset_settings.hpp
#pragma once

#include <toml++/toml.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "render/camera_preset.hpp"
#include "render/inset_settings.hpp"
#include "render/overlay_layers_settings.hpp"

namespace stiction::scene {
struct Scene;
}

namespace stiction::render {

struct CameraSettings {
  std::optional<core::Vec3> position;
  std::optional<core::Vec3> target;
  double fov_degrees = 40.0;
  std::string follow;                       // body name, empty: fixed camera
  bool follow_vertical = false;             // also follow the body's vertical motion
  CameraView view = CameraView::automatic;  // `view`: a preset (camera_preset.hpp)
};

struct OverlaySettings {
  bool enabled = true;
  std::string signal;  // empty: time only
  std::string label;
  std::string unit;
  bool trail = false;
  double trail_seconds = 0.5;
  std::vector<std::string> trail_contacts;  // empty: every contact
  // Not keys of [overlay]: the run's stick thresholds per contact (scene.run), which colour
  // the trails as the events are detected.
  std::map<std::string, double> stick_thresholds;
  double default_stick_threshold = 1e-3;
  // Several values, title and caption, force/velocity arrows, badges (overlay_layers_settings.hpp).
  OverlayLayers layers;
  // Not a key: false leaves out the time and value panel but keeps the other layers (a tile
  // of `compare --video`, which labels its tiles and shows one shared time line).
  bool panel = true;
};

// Frames of one video at most (about 4.6 hours at 60 fps); see docs/limits.md.
inline constexpr double kMaxFrames = 1e6;

struct RenderSettings {
  int width = 1280;
  int height = 720;
  double fps = 60.0;
  int crf = 21;
  std::string codec = "h264";
  std::string preset = "superfast";  // libx264's speed preset: [render] encoder_preset
  std::string look;                  // [render] preset = "talk": the look applied; "": none
  double slow_motion = 1.0;
  double slow_motion_around_events = 0.0;  // seconds; 0: off
  double event_slow_motion = 8.0;
  int slowed_events = 0;  // episodes of events slowed down, from the first; 0: all
  int msaa = 4;
  int shadow_map_size = 2048;
  int shadow_taps = 4;
  int encoder_threads = 0;  // 0: encoder_threads(); -1 (not a key): libx264's own choice
  CameraSettings camera;
  OverlaySettings overlay;
  InsetSettings inset;  // [inset]: a live plot in a corner of the video (inset_settings.hpp)
};

// Reads the three tables of `document` (each optional). `body_names` are the names a camera
// may follow; `signal_columns` the trajectory columns an overlay signal must match (either
// exactly or as "NAME.<axis>"). Empty lists skip those checks.
RenderSettings read_render_settings(const toml::table& document,
                                    const std::vector<std::string>& body_names = {},
                                    const std::vector<std::string>& signal_columns = {});

// Same, with the names taken from the scene's network. Call before simulating so that a bad
// [render] table fails fast.
RenderSettings read_render_settings(const scene::Scene& scene);

// InputError (at [render] slow_motion or fps when given) when the run's duration gives more
// than kMaxFrames frames. Only for runs that render.
void check_frame_count(const scene::Scene& scene, const RenderSettings& settings);

}  // namespace stiction::render
