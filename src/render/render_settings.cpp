#include "render/render_settings.hpp"

#include <algorithm>
#include <cmath>

#include "render/scene_view.hpp"
#include "render/talk_preset.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

namespace stiction::render {
namespace {

using scene::TableReader;

std::optional<TableReader> table(TableReader& root, std::string_view key) {
  if (root.has(key) && !root.table().get(key)->is_table()) root.fail(key, "expected a table");
  return root.subtable(key);
}

bool matches_signal(const std::string& signal, const std::vector<std::string>& columns) {
  return std::any_of(columns.begin(), columns.end(),
                     [&](const std::string& c) { return c == signal || is_axis_of(c, signal); });
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

void read_render(TableReader& r, RenderSettings& s) {
  if (r.has("size")) {
    const std::vector<double> size = r.numbers("size");
    if (size.size() != 2) r.fail("size", "expected [width, height]");
    for (double v : size) {
      if (v != static_cast<double>(static_cast<long>(v)) || v < 16 || v > 7680 ||
          static_cast<long>(v) % 2 != 0) {
        r.fail("size",
               "width and height must be even whole numbers of pixels in 16..7680 "
               "(H.264 with yuv420p needs even sizes)");
      }
    }
    s.width = static_cast<int>(size[0]);
    s.height = static_cast<int>(size[1]);
  }
  s.fps = r.positive("fps", s.fps);
  if (s.fps < 1.0 || s.fps > 240.0) r.fail("fps", "must be in 1..240");
  const long crf = r.integer("crf", s.crf);
  if (crf < 0 || crf > 51) r.fail("crf", "must be in 0..51");
  s.crf = static_cast<int>(crf);
  s.codec = r.string("codec", s.codec);
  if (s.codec != "h264") r.fail("codec", "unknown codec '" + s.codec + "' (supported: h264)");
  // `preset`: a look (applied before this table is read: read_render_settings) or, as in
  // older scene files, libx264's speed preset, which has its own key `encoder_preset` now.
  static const std::vector<std::string> presets{"ultrafast", "superfast", "veryfast",
                                                "faster",    "fast",      "medium",
                                                "slow",      "slower",    "veryslow"};
  const auto x264 = [&](const std::string& name) {
    return std::find(presets.begin(), presets.end(), name) != presets.end();
  };
  const std::string preset = r.string("preset", "");
  if (r.has("preset") && !is_look_preset(preset)) {
    if (!x264(preset)) {
      r.fail("preset", "unknown preset '" + preset + "' (a look: " + join(look_preset_names()) +
                           "; or libx264's speed, now `encoder_preset`: " + join(presets) + ")");
    }
    if (r.has("encoder_preset")) {
      r.fail("preset",
             "libx264's speed is given twice: keep `encoder_preset` (`preset` takes "
             "a look: " +
                 join(look_preset_names()) + ")");
    }
    s.preset = preset;
  }
  s.preset = r.string("encoder_preset", s.preset);
  if (!x264(s.preset)) {
    r.fail("encoder_preset",
           "unknown libx264 preset '" + s.preset + "' (one of: " + join(presets) + ")");
  }
  s.slow_motion = r.positive("slow_motion", s.slow_motion);
  if (s.slow_motion < 1e-3 || s.slow_motion > 1e3) r.fail("slow_motion", "must be in 0.001..1000");
  if (r.has("slow_motion_around_events")) {
    s.slow_motion_around_events = r.number("slow_motion_around_events", 0.0);
    if (!(s.slow_motion_around_events >= 0.0)) {
      r.fail("slow_motion_around_events", "must be a duration in seconds, >= 0 (0: off)");
    }
  }
  s.event_slow_motion = r.positive("event_slow_motion", s.event_slow_motion);
  if (s.event_slow_motion < 1.0 || s.event_slow_motion > 100.0) {
    r.fail("event_slow_motion", "must be in 1..100 (times slower around events)");
  }
  const long slowed = r.integer("slowed_events", s.slowed_events);
  if (slowed < 0 || slowed > 1000000) {
    r.fail("slowed_events", "must be a count of episodes of events, >= 0 (0: every event)");
  }
  s.slowed_events = static_cast<int>(slowed);
  const long msaa = r.integer("msaa", s.msaa);
  if (msaa != 1 && msaa != 2 && msaa != 4) r.fail("msaa", "must be 1, 2 or 4");
  s.msaa = static_cast<int>(msaa);
  const long shadow = r.integer("shadow_map_size", s.shadow_map_size);
  if (shadow != 0 && (shadow < 256 || shadow > 8192 || (shadow & (shadow - 1)) != 0)) {
    r.fail("shadow_map_size", "must be 0 (no shadows) or a power of two in 256..8192");
  }
  s.shadow_map_size = static_cast<int>(shadow);
  const long taps = r.integer("shadow_taps", s.shadow_taps);
  if (taps != 1 && taps != 4) r.fail("shadow_taps", "must be 1 or 4");
  s.shadow_taps = static_cast<int>(taps);
  const long threads = r.integer("encoder_threads", s.encoder_threads);
  if (threads < 0 || threads > 64) r.fail("encoder_threads", "must be 0 (automatic) or 1..64");
  s.encoder_threads = static_cast<int>(threads);
  r.finish();
}

void read_camera(TableReader& r, CameraSettings& c, const std::vector<std::string>& bodies) {
  if (r.has("position")) c.position = r.vec3("position", core::Vec3::Zero());
  if (r.has("target")) c.target = r.vec3("target", core::Vec3::Zero());
  c.fov_degrees = r.positive("fov", c.fov_degrees);
  if (c.fov_degrees >= 170.0) r.fail("fov", "must be below 170 degrees");
  c.follow = r.string("follow", "");
  if (!c.follow.empty() && !bodies.empty() &&
      std::find(bodies.begin(), bodies.end(), c.follow) == bodies.end()) {
    r.fail("follow", "no body named '" + c.follow + "' (bodies: " + join(bodies) + ")");
  }
  c.follow_vertical = r.boolean("follow_vertical", c.follow_vertical);
  if (c.follow_vertical && c.follow.empty()) {
    r.fail("follow_vertical", "needs `follow` (the body whose motion the camera tracks)");
  }
  c.view = read_camera_view(r);
  if (c.view == CameraView::follow && c.follow_vertical) {
    r.fail("follow_vertical", "the \"follow\" view keeps a fixed height (use view = \"auto\")");
  }
  if (c.position && c.target && (*c.position - *c.target).norm() < 1e-9) {
    r.fail("target", "must differ from position");
  }
  r.finish();
}

void read_overlay(TableReader& r, OverlaySettings& o, const std::vector<std::string>& columns) {
  o.enabled = r.boolean("enabled", o.enabled);
  o.signal = r.string("signal", "");
  if (!o.signal.empty() && !columns.empty() && !matches_signal(o.signal, columns)) {
    std::vector<std::string> names;
    for (const auto& c : columns) {
      if (c != "t") names.push_back(c);
    }
    r.fail("signal", "no signal named '" + o.signal + "' (signals: " + join(names) + ")");
  }
  o.label = r.string("label", o.signal);
  o.unit = r.string("unit", "");
  o.trail = r.boolean("trail", o.trail);
  o.trail_seconds = r.positive("trail_seconds", o.trail_seconds);
  if (r.has("trail_contacts")) {
    o.trail_contacts = r.strings("trail_contacts");
    for (const std::string& c : o.trail_contacts) {
      if (!columns.empty() && !matches_signal(c + ".slip", columns)) {
        r.fail("trail_contacts", "no contact named '" + c + "' with a slip speed (" + c +
                                     ".slip is not a signal of the scene)");
      }
    }
  }
  read_overlay_layers(r, o.layers, columns);
  r.finish();
}

}  // namespace

RenderSettings read_render_settings(const toml::table& document,
                                    const std::vector<std::string>& body_names,
                                    const std::vector<std::string>& signal_columns) {
  RenderSettings s;
  TableReader root(document, "");
  // A look preset first, so that every key the tables give is read over it and wins.
  const std::string look = document["render"]["preset"].value<std::string>().value_or("");
  if (look == "talk") apply_talk_preset(s, signal_columns);
  if (auto r = table(root, "render")) read_render(*r, s);
  if (auto r = table(root, "camera")) read_camera(*r, s.camera, body_names);
  if (auto r = table(root, "overlay")) read_overlay(*r, s.overlay, signal_columns);
  if (auto r = table(root, "inset")) read_inset(*r, s.inset, signal_columns);
  default_title_and_caption(document, s.overlay.layers);
  return s;
}

RenderSettings read_render_settings(const scene::Scene& scene) {
  std::vector<std::string> bodies;
  for (const auto& a : scene.network->admittances()) bodies.push_back(a->name());
  std::vector<std::string> columns = scene.network->signal_columns();
  columns.insert(columns.begin(), "t");
  RenderSettings s = read_render_settings(scene.document, bodies, columns);
  s.overlay.stick_thresholds = scene.run.stick_thresholds;
  s.overlay.default_stick_threshold = scene.run.default_stick_threshold;
  return s;
}

void check_frame_count(const scene::Scene& scene, const RenderSettings& s) {
  // The frame count, in floating point before anything is sized by it.
  const double frames = std::floor(scene.run.duration * s.fps * s.slow_motion) + 1.0;
  if (!(frames <= kMaxFrames)) {
    TableReader root(scene.document, "");
    auto render = root.subtable("render");
    const std::string message = "duration * fps * slow_motion gives " + std::to_string(frames) +
                                " frames, more than the limit of " + std::to_string(kMaxFrames) +
                                " (docs/limits.md)";
    if (render && render->has("slow_motion")) render->fail("slow_motion", message);
    if (render && render->has("fps")) render->fail("fps", message);
    throw scene::InputError("error: " + scene.path.string() + ": " + message +
                            " (lower --duration, or skip the video with --no-video)");
  }
}

}  // namespace stiction::render
