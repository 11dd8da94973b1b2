// Video details of issue 11 item 5: fast start, a fixed-width overlay, a trail per contact
// coloured by its own stick threshold, and time-warp around events.
#include <catch2/catch.hpp>
#include <filesystem>
#include <random>
#include <sstream>
#include <thread>

#include "mp4_atoms.hpp"
#include "render/number_format.hpp"
#include "render/overlay.hpp"
#include "render/render_outputs.hpp"
#include "render/time_warp.hpp"
#include "render/trail.hpp"
#include "render/video_encoder.hpp"
#include "render_fixtures.hpp"

namespace fs = std::filesystem;
using namespace stiction;
using namespace stiction::render;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(STICTION_TEST_OUTPUT_DIR) / "video_outputs" / name;
  fs::remove_all(dir);
  return dir;
}

// The smallest box holding every pixel that differs from `background`.
PixelBox changed_region(const image::Image& img, image::Rgba background) {
  PixelBox box{img.width, img.height, 0, 0};
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.pixels.data() + (static_cast<std::size_t>(y) * img.width + x) * 4;
      if (p[0] != background.r || p[1] != background.g || p[2] != background.b) {
        box.x0 = std::min(box.x0, x);
        box.y0 = std::min(box.y0, y);
        box.x1 = std::max(box.x1, x + 1);
        box.y1 = std::max(box.y1, y + 1);
      }
    }
  }
  return box;
}

// `n` spheres of random radii with long names, each rolling along x on its own contact whose
// slip speed falls linearly from v0 to 0 over the run: slip(t) = v0 (1 - t / T).
struct ManySpheres {
  std::string toml;
  core::Trajectory trajectory;
  std::vector<std::string> contacts;
  std::vector<double> v0;
};

ManySpheres many_spheres(int n, double duration, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> radius(0.05, 0.3), speed(0.5, 3.0);
  ManySpheres m;
  std::ostringstream toml;
  toml << "name = \"many\"\n";
  std::vector<std::string> columns{"t"};
  std::vector<double> radii;
  for (int i = 0; i < n; ++i) {
    const std::string body = "a_sphere_with_a_rather_long_descriptive_name_" + std::to_string(i);
    const std::string contact = "contact_of_" + body;
    radii.push_back(radius(rng));
    m.v0.push_back(speed(rng));
    m.contacts.push_back(contact);
    toml << "[bodies." << body
         << "]\ntype = \"rigid_body\"\nshape = \"sphere\"\nradius = " << radii.back()
         << "\nmass = 1.0\nposition = [0.0, " << 1.5 * i << ", " << radii.back()
         << "]\n[impedances." << contact << "]\ntype = \"kikuuwe_contact\"\nbody = \"" << body
         << "\"\nmu = 0.2\nstick_threshold = " << 0.1 * (i + 1) << "\n";
    for (const char* a : {"p.x", "p.y", "p.z", "q.w", "q.x", "q.y", "q.z"})
      columns.push_back(body + "." + a);
    for (const char* a : {"slip.x", "slip.y", "slip.z"}) columns.push_back(contact + "." + a);
  }
  toml << "[overlay]\ntrail = true\n";
  m.toml = toml.str();
  m.trajectory = core::Trajectory(columns);
  for (int k = 0; k <= 1000; ++k) {
    const double t = duration * k / 1000.0;
    std::vector<double> row{t};
    for (int i = 0; i < n; ++i) {
      const double slip = m.v0[i] * (1.0 - t / duration);
      row.insert(row.end(), {m.v0[i] * t, 1.5 * i, radii[i], 1.0, 0.0, 0.0, 0.0, slip, 0.0, 0.0});
    }
    m.trajectory.append(row.data());
  }
  return m;
}

}  // namespace

TEST_CASE("video.mp4 is fast-start: moov before mdat", "[render][video]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  RenderSettings settings = read_render_settings(s);
  settings.width = 160;
  settings.height = 90;
  settings.fps = 20.0;
  const fs::path dir = scratch("faststart");
  RenderRequest request;
  request.out_dir = dir;
  const RenderResult r = render_outputs(s, testing::sphere_roll_trajectory(0.5), settings, request);
  REQUIRE(fs::exists(r.video));
  const auto boxes = testing::mp4_top_level_boxes(r.video);
  std::string order;
  for (const auto& b : boxes) order += b.type + " ";
  INFO("top-level boxes: " << order);
  const int moov = testing::box_index(boxes, "moov"), mdat = testing::box_index(boxes, "mdat");
  REQUIRE(moov >= 0);
  REQUIRE(mdat >= 0);
  CHECK(moov < mdat);
  CHECK(testing::box_index(boxes, "ftyp") == 0);
}

TEST_CASE("encoder threads: the cores the renderer leaves, at least one", "[render][video]") {
  const int n = encoder_threads();
  CHECK(n >= 1);
  CHECK(n <= std::max(1, static_cast<int>(std::thread::hardware_concurrency())));
}

TEST_CASE("overlay numbers: four digits with an SI prefix, never e-notation", "[render][overlay]") {
  CHECK(format_quantity(1.5906, "m/s").number == "1.591");
  CHECK(format_quantity(1.5906, "m/s").unit == "m/s");
  CHECK(format_quantity(4.71e-06, "m/s").number == "4.710");
  CHECK(format_quantity(4.71e-06, "m/s").unit == "um/s");
  CHECK(format_quantity(0.0044, "m/s").unit == "mm/s");
  CHECK(format_quantity(0.0044, "m/s").number == "4.400");
  CHECK(format_quantity(0.0, "m/s").number == "0.000");
  CHECK(format_quantity(-0.85, "rad").number == "-850.0");
  CHECK(format_quantity(-0.85, "rad").unit == "mrad");
  CHECK(format_quantity(999.96, "N").number == "1.000");  // rounding moves it to kN
  CHECK(format_quantity(999.96, "N").unit == "kN");
  CHECK(format_quantity(12.345, "kg").unit == "kg");  // no prefix on kg
  CHECK(format_quantity(12.345, "kg").number == "12.35");
  CHECK(format_quantity(1.5e-7, "").number == "1.500e-07");
  CHECK(format_quantity(std::nan(""), "m/s").number == "n/a");
  CHECK(takes_si_prefix("N m"));
  CHECK_FALSE(takes_si_prefix("mol"));
  CHECK_FALSE(takes_si_prefix("deg"));
}

TEST_CASE("the overlay box has the same width in every frame of a run", "[render][overlay]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const core::Trajectory tr = testing::sphere_roll_trajectory(2.0);
  const Drawing scene = s.drawing;
  const PoseTrack poses(tr, scene);
  RenderSettings settings = read_render_settings(s);
  for (bool warp : {false, true}) {
    Overlay overlay(settings.overlay, 360, poses.end_time(), warp);
    const image::Rgba grey{90, 90, 90, 255};
    std::optional<PixelBox> first;
    // The slip falls from 2 m/s through mm/s and um/s to exactly 0 (t = 0.583 s).
    for (double t = 0.0; t <= 2.0; t += 0.0125) {
      image::Image frame(640, 360, grey);
      const PixelBox drawn =
          overlay.draw(frame, poses, t, warp && t > 0.5 && t < 0.7 ? 0.125 : 1.0);
      const PixelBox seen = changed_region(frame, grey);
      INFO("t = " << t);
      CHECK(seen == drawn);  // the text stays inside the panel
      if (!first) first = seen;
      CHECK(seen == *first);
    }
  }
}

TEST_CASE("a trail per contact, coloured by each contact's own stick threshold",
          "[render][trail]") {
  const ManySpheres m = many_spheres(5, 1.0, 7);
  const scene::Scene s = testing::make_scene(m.toml, "many");
  const Drawing scene = s.drawing;
  REQUIRE(scene.sites.contacts.size() == 5);
  const PoseTrack poses(m.trajectory, scene);
  const RenderSettings settings = read_render_settings(s);
  REQUIRE(settings.overlay.stick_thresholds.size() == 5);
  TrailOptions options;
  options.seconds = 1.0;
  options.thresholds = settings.overlay.stick_thresholds;
  const std::vector<TrailVertex> strip = build_trails(scene, poses, 1.0, options);
  // Five ribbons of 97 vertex pairs joined by two degenerate vertices each.
  constexpr std::size_t kRibbon = 2 * 97;
  REQUIRE(strip.size() == 5 * kRibbon + 2 * 4);
  const glm::vec3 green{0.05f, 0.55f, 0.15f};
  for (int i = 0; i < 5; ++i) {
    const double threshold = 0.1 * (i + 1);
    // Sticks from t* = T (1 - threshold / v0) on (the slip falls below its threshold).
    const double t_stick = 1.0 - threshold / m.v0[i];
    const std::size_t first = static_cast<std::size_t>(i) * (kRibbon + 2);
    for (int k = 0; k <= 96; ++k) {
      const double t = k / 96.0;
      if (std::abs(t - t_stick) < 0.011) continue;  // the sample that straddles the crossing
      const TrailVertex& v = strip[first + 2 * static_cast<std::size_t>(k)];
      INFO("contact " << i << " at t = " << t << ", sticks from " << t_stick);
      CHECK((v.colour == green) == (t > t_stick));
      // The ribbon lies under its sphere's path: y = 1.5 i.
      CHECK(std::abs(v.position.y - 1.5f * i) < 0.1f);
    }
  }
  // Only the chosen contacts.
  options.contacts = {m.contacts[2], m.contacts[4]};
  CHECK(build_trails(scene, poses, 1.0, options).size() == 2 * kRibbon + 2);
}

TEST_CASE("[overlay] trail_contacts must name contacts with a slip speed", "[render][trail]") {
  const std::string base = testing::sphere_roll_toml();
  const scene::Scene good = testing::make_scene(base + "trail_contacts = [\"contact\"]\n", "ok");
  CHECK(read_render_settings(good).overlay.trail_contacts == std::vector<std::string>{"contact"});
  const scene::Scene bad = testing::make_scene(base + "trail_contacts = [\"sphere\"]\n", "bad");
  CHECK_THROWS_WITH(read_render_settings(bad),
                    Catch::Contains("trail_contacts") && Catch::Contains("sphere"));
}

TEST_CASE("time-warp: slow motion around events, normal speed elsewhere", "[render][video]") {
  const double step = 1.0 / 60.0, event = 0.583;
  const auto plain = warped_frame_times(0.0, 2.0, step, {}, 0.2, 8.0);
  CHECK(plain.size() == 121);
  const auto frames = warped_frame_times(0.0, 2.0, step, {event}, 0.2, 8.0);
  // Inside the window frames come 8 times as often: a frame every step / 8.
  int inside = 0;
  for (const FrameTime& f : frames) {
    if (std::abs(f.t - event) < 0.2 - step) {
      ++inside;
      CHECK(f.speed == Approx(0.125));
    }
    if (std::abs(f.t - event) > 0.3 + step) CHECK(f.speed == 1.0);
  }
  CHECK(inside == Approx((0.4 - 2 * step) / (step / 8.0)).margin(2));
  CHECK(frames.front().t == 0.0);
  CHECK(frames.back().t <= 2.0);
  CHECK(frames.back().t > 2.0 - step);
  for (std::size_t i = 1; i < frames.size(); ++i) CHECK(frames[i].t > frames[i - 1].t);
  // Video time gained: 0.4 s shown 8x slower plus the ramps.
  CHECK(frames.size() > 121 + 7 * 24);
}

TEST_CASE("bad time-warp settings are input errors", "[render][video]") {
  const std::string base = testing::sphere_roll_toml();
  const scene::Scene ok =
      testing::make_scene(base + "[render]\nslow_motion_around_events = 0.2\n", "ok");
  CHECK(read_render_settings(ok).slow_motion_around_events == 0.2);
  const scene::Scene bad =
      testing::make_scene(base + "[render]\nslow_motion_around_events = -1\n", "bad");
  CHECK_THROWS_WITH(read_render_settings(bad), Catch::Contains("slow_motion_around_events"));
  const scene::Scene bad2 =
      testing::make_scene(base + "[render]\nevent_slow_motion = 0.5\n", "bad2");
  CHECK_THROWS_WITH(read_render_settings(bad2), Catch::Contains("event_slow_motion"));
}
