// [render] preset = "talk" (issue 37 item 6, render/talk_preset.hpp): what it sets, that
// every key given explicitly wins over it, that libx264's speed presets keep working under
// `preset` and under `encoder_preset`, and which events its slow motion keeps.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "render/render_settings.hpp"
#include "render/talk_preset.hpp"
#include "render/time_warp.hpp"
#include "scene/toml_reader.hpp"

using namespace stiction;
using namespace stiction::render;
using Catch::Contains;

namespace {

// The columns of a sphere rolling on the ground (sphere_roll's).
const std::vector<std::string>& sphere_columns() {
  static const std::vector<std::string> columns{
      "t",          "sphere.p.x",    "sphere.p.y",    "sphere.p.z",   "sphere.v.x", "sphere.v.y",
      "sphere.v.z", "sphere.w.x",    "sphere.w.y",    "sphere.w.z",   "ground.f.x", "ground.f.y",
      "ground.f.z", "ground.slip.x", "ground.slip.y", "ground.slip.z"};
  return columns;
}

RenderSettings read(const std::string& text,
                    const std::vector<std::string>& columns = sphere_columns()) {
  return read_render_settings(toml::parse(std::string_view(text), std::string_view("scene.toml")),
                              {"sphere"}, columns);
}

}  // namespace

TEST_CASE("talk preset: a 16:9 frame, slow motion at the first events, layers, inset",
          "[render][settings][talk]") {
  const RenderSettings plain = read("");
  const RenderSettings talk = read("[render]\npreset = \"talk\"\n");
  CHECK(plain.look.empty());
  CHECK(talk.look == "talk");
  CHECK(talk.width * 9 == talk.height * 16);
  CHECK(talk.width == 1280);
  CHECK(talk.slow_motion_around_events > 0.0);
  CHECK(plain.slow_motion_around_events == 0.0);
  CHECK(talk.slowed_events == 3);
  CHECK(plain.slowed_events == 0);
  CHECK(talk.overlay.layers.badges);
  CHECK(talk.overlay.layers.forces);
  CHECK(talk.overlay.trail);
  CHECK_FALSE(plain.overlay.layers.badges);
  CHECK_FALSE(plain.overlay.trail);
  // The signals that matter here: the contact's slip speed, then the ball's speed.
  CHECK(talk.inset.signals == std::vector<std::string>{"ground.slip", "sphere.v"});
  CHECK(talk.inset.labels == std::vector<std::string>{"slip speed", "speed"});
  CHECK(talk.inset.units == std::vector<std::string>{"m/s", "m/s"});
  CHECK_FALSE(plain.inset.enabled());
  CHECK(talk.preset == plain.preset);  // the encoder's speed is untouched
  // An arm without contacts: its first joint's rate.
  const RenderSettings arm =
      read("[render]\npreset = \"talk\"\n",
           {"t", "arm.theta.0", "arm.theta.1", "arm.omega.0", "arm.omega.1"});
  CHECK(arm.inset.signals == std::vector<std::string>{"arm.omega.0"});
  CHECK(arm.inset.units == std::vector<std::string>{"rad/s"});
}

TEST_CASE("talk preset: every key given explicitly wins", "[render][settings][talk]") {
  const RenderSettings s = read(R"(
[render]
preset = "talk"
size = [640, 480]
slow_motion_around_events = 0.0
slowed_events = 0
encoder_preset = "veryfast"
[overlay]
badges = false
trail = false
[inset]
signals = ["sphere.w"]
)");
  CHECK(s.look == "talk");
  CHECK(s.width == 640);
  CHECK(s.height == 480);
  CHECK(s.slow_motion_around_events == 0.0);
  CHECK(s.slowed_events == 0);
  CHECK(s.preset == "veryfast");
  CHECK_FALSE(s.overlay.layers.badges);
  CHECK_FALSE(s.overlay.trail);
  CHECK(s.overlay.layers.forces);  // not given: the preset's
  CHECK(s.inset.signals == std::vector<std::string>{"sphere.w"});
  CHECK(s.inset.labels.empty());  // the preset's labels went with its signals
  // An [inset] that only moves the plot keeps the preset's signals.
  const RenderSettings moved =
      read("[render]\npreset = \"talk\"\n[inset]\nposition = \"top_left\"\n");
  CHECK(moved.inset.signals == std::vector<std::string>{"ground.slip", "sphere.v"});
  CHECK(moved.inset.corner == InsetCorner::top_left);
}

TEST_CASE("preset: libx264's names still work, the two keys never clash",
          "[render][settings][talk]") {
  CHECK(read("[render]\npreset = \"ultrafast\"\n").preset == "ultrafast");
  CHECK(read("[render]\npreset = \"ultrafast\"\n").look.empty());
  CHECK(read("[render]\nencoder_preset = \"ultrafast\"\n").preset == "ultrafast");
  CHECK(read("[render]\npreset = \"talk\"\nencoder_preset = \"slow\"\n").preset == "slow");
  CHECK_THROWS_WITH(
      read("[render]\npreset = \"ultrafast\"\nencoder_preset = \"fast\"\n"),
      Contains("scene.toml:2:") && Contains("render.preset") && Contains("given twice"));
  CHECK_THROWS_WITH(read("[render]\npreset = \"poster\"\n"),
                    Contains("render.preset") && Contains("unknown preset 'poster'") &&
                        Contains("talk") && Contains("superfast"));
  CHECK_THROWS_WITH(read("[render]\npreset = \"\"\n"), Contains("unknown preset ''"));
  CHECK_THROWS_WITH(read("[render]\nencoder_preset = \"talk\"\n"),
                    Contains("render.encoder_preset") && Contains("unknown libx264 preset"));
  CHECK_THROWS_WITH(read("[render]\nslowed_events = -1\n"), Contains("render.slowed_events"));
  // No look name is an x264 name: `preset` is never ambiguous.
  for (const std::string& name : look_preset_names()) {
    std::string text = "[render]\nencoder_preset = \"";  // appended: GCC 12's -Wrestrict
    text += name;
    text += "\"\n";
    CHECK_THROWS(read(text));
  }
}

TEST_CASE("slowed_events keeps the first episodes of events, whole", "[render][talk][time_warp]") {
  // A chattering touch-down (three events within a window) is one episode; the transition
  // after it is the second.
  const std::vector<double> events{1.2, 0.003, 0.001, 0.58, 0.002, 1.9};
  CHECK(first_episodes(events, 0.1, 2) == std::vector<double>{0.001, 0.002, 0.003, 0.58});
  CHECK(first_episodes(events, 0.1, 0).size() == events.size());
  std::mt19937 rng(6372026);
  std::uniform_real_distribution<double> u(0.0, 5.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> all(1 + rng() % 30);
    for (double& e : all) e = u(rng);
    const double window = 0.02 + 0.3 * u(rng) / 5.0;
    const int episodes = 1 + static_cast<int>(rng() % 5);
    const std::vector<double> kept = first_episodes(all, window, episodes);
    std::vector<double> sorted = all;
    std::sort(sorted.begin(), sorted.end());
    INFO("trial " << trial);
    REQUIRE(!kept.empty());
    REQUIRE(kept.size() <= sorted.size());
    CHECK(std::equal(kept.begin(), kept.end(), sorted.begin()));  // a prefix in time
    int count = 1;
    for (std::size_t i = 1; i < kept.size(); ++i) count += kept[i] - kept[i - 1] >= 2.0 * window;
    CHECK(count <= episodes);
    // What is left out starts a new episode beyond the last one kept.
    if (kept.size() < sorted.size()) {
      CHECK(count == episodes);
      CHECK(sorted[kept.size()] - kept.back() >= 2.0 * window);
    }
  }
}

TEST_CASE("slowed_events: the first changes between slip and stick, not the chatter",
          "[render][talk][time_warp]") {
  // sphere_roll's events: it slips and lifts off (micro-bounces) every 40 ms, sticks at
  // 0.583 s and keeps bouncing while rolling: "slip", "open", ..., "stick", "open", ...
  std::vector<double> times;
  std::vector<std::string> kinds;
  for (int k = 0; k < 50; ++k) {
    const double t = 0.0203 + 0.04 * k;
    const bool rolling = t > 0.583;
    times.insert(times.end(), {t, t + 0.0005});
    kinds.insert(kinds.end(), {rolling ? "stick" : "slip", "open"});
  }
  times.push_back(0.583);
  kinds.push_back("stick");
  const std::vector<double> slowed = slowed_events(times, kinds, 0.1, 3);
  CHECK(slowed == std::vector<double>{0.0203, 0.583});
  // Every event, as given, without slowed_events; all events count without their kinds.
  CHECK(slowed_events(times, kinds, 0.1, 0) == times);
  CHECK(slowed_events(times, {}, 0.1, 3).size() > 50);  // chained: one long episode
  // The video: 1/8 speed at the stick, full speed halfway between the two slowed events.
  const std::vector<FrameTime> frames = warped_frame_times(0.0, 2.0, 1.0 / 60.0, slowed, 0.1, 8.0);
  for (const FrameTime& f : frames) {
    if (std::abs(f.t - 0.583) < 0.09) CHECK(f.speed == Approx(1.0 / 8.0));
    if (f.t > 0.75) CHECK(f.speed == 1.0);
  }
}
