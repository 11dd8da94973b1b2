// A wheel spinning out under a drive torque, rendered off-screen: its overlays come from the
// contact sites the scene declares, so the stick/slip badge's contact dots sit at the
// projected rim contact points (not at the hub), its force arrows stand clear of the wheel,
// and its trail is drawn on the floor under the rim (issue 37, item 1). Hand-made trajectory
// (poses and contact columns from closed forms), as the other overlay tests use.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>

#include "image/png.hpp"
#include "overlay_pixels.hpp"
#include "render/camera.hpp"
#include "render/contact_sites.hpp"
#include "render/force_arrows.hpp"
#include "render/regime_badges.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;
using testing::nearest;
namespace fs = std::filesystem;

namespace {

constexpr double kRadius = 0.3, kLength = 0.12, kMass = 2.0;

const char* wheel_toml() {
  return R"(
name = "wheel_spin"
[bodies.wheel]
type = "rigid_body"
mass = 2.0
shape = "cylinder"
radius = 0.3
length = 0.12
axis = [0.0, 1.0, 0.0]
position = [0.0, 0.0, 0.3]
[impedances.floor]
type = "kikuuwe_contact"
body = "wheel"
stiffness = 1e6
mu = 0.4
[impedances.drive]
type = "torque_source"
body = "wheel"
axis = [0.0, 1.0, 0.0]
torque = "2.0 * t"
[camera]
position = [0.1, -2.0, 0.9]
target = [0.5, 0.0, 0.25]
[overlay]
badges = true
)";
}

// Rolls along +x with x = 0.8 t^2 while its spin runs ahead (theta = 4 t^2, so the rim slips
// backwards at 0.8 t (1 - 3)): the two nearest rim points (floor.0 and floor.3, one per cap)
// carry the weight and a forward friction force; the other four are in the air.
core::Trajectory spin_out() {
  std::vector<std::string> columns{"t",         "wheel.p.x", "wheel.p.y", "wheel.p.z",
                                   "wheel.q.w", "wheel.q.x", "wheel.q.y", "wheel.q.z",
                                   "wheel.v.x", "wheel.v.y", "wheel.v.z", "drive.tau"};
  for (int i = 0; i < 6; ++i) {
    for (const char* a : {".f.x", ".f.y", ".f.z", ".slip.x", ".slip.y", ".slip.z", ".n_force"}) {
      columns.push_back("floor." + std::to_string(i) + a);
    }
  }
  core::Trajectory tr(columns);
  for (int k = 0; k <= 1000; ++k) {
    const double t = 1e-3 * k;
    const double theta = 4.0 * t * t;
    std::vector<double> row{
        t,       0.8 * t * t, 0.0, kRadius, std::cos(0.5 * theta), 0.0, std::sin(0.5 * theta), 0.0,
        1.6 * t, 0.0,         0.0, 2.0 * t};
    const double n = 0.5 * kMass * 9.8;
    const double slip = 1.6 * t - 8.0 * t * kRadius;
    for (int i = 0; i < 6; ++i) {
      const bool touching = i % 3 == 0;
      row.insert(row.end(), {touching ? 0.4 * n : 0.0, 0.0, touching ? n : 0.0,
                             touching ? slip : 0.0, 0.0, 0.0, touching ? n : 0.0});
    }
    tr.append(row.data());
  }
  return tr;
}

RenderSettings plain_settings(const scene::Scene& s) {
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  settings.overlay.panel = false;
  settings.overlay.trail = false;
  settings.overlay.layers.badges = false;
  settings.overlay.layers.forces = false;
  settings.overlay.layers.velocities = false;
  settings.overlay.layers.title = "";
  settings.overlay.layers.caption = "";
  return settings;
}

// Pixels that differ between two frames of the same size.
std::vector<glm::vec2> changed(const image::Image& a, const image::Image& b) {
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  return testing::changed_pixels(a, b);
}

void save(const image::Image& frame, const std::string& name) {
  const fs::path dir = fs::path(STICTION_TEST_OUTPUT_DIR) / "contact_overlays";
  fs::create_directories(dir);
  image::write_png(dir / name, frame);
}

}  // namespace

TEST_CASE(
    "contact overlays: a spinning-out wheel's badge dots sit at its rim contact, not its "
    "hub",
    "[render][overlays][badges]") {
  const scene::Scene s = testing::make_scene(wheel_toml(), "wheel_spin");
  const core::Trajectory tr = spin_out();
  const RenderSettings plain = plain_settings(s);
  RenderSettings badged = plain;
  badged.overlay.layers.badges = true;

  const double t = 0.8;
  FrameRenderer without(s.drawing, tr, plain);
  FrameRenderer with(s.drawing, tr, badged);
  const image::Image bare = without.render(t);
  const image::Image shown = with.render(t);
  save(shown, "wheel_badges.png");

  // The camera the frames were drawn with, and the contact and hub projections.
  const float aspect = 640.0f / 360.0f;
  const CameraRig rig(badged.camera, s.drawing, with.poses(), aspect);
  const Camera camera = rig.at(t);
  const glm::mat4 vp = camera.projection(aspect) * camera.view();
  std::vector<glm::vec2> rim;
  for (const ContactSite& site : s.drawing.sites.contacts) {
    if (site.name != "floor.0" && site.name != "floor.3") continue;
    REQUIRE(site.rule == ContactSite::Rule::rim);
    const core::Vec3 p = contact_point(site, with.poses(), t);
    CHECK(std::abs(p.z()) < 1e-9);  // on the floor, under the hub
    CHECK(std::abs(p.x() - 0.8 * t * t) < 1e-9);
    glm::vec2 pixel;
    REQUIRE(project(vp, to_glm(p), 640, 360, pixel));
    rim.push_back(pixel);
  }
  REQUIRE(rim.size() == 2);
  glm::vec2 hub;
  REQUIRE(project(vp, to_glm(with.poses().position(0, t)), 640, 360, hub));
  // The test tells the two apart: the hub is well above the contact in the picture.
  REQUIRE(hub.y < std::min(rim[0].y, rim[1].y) - 30.0f);

  const std::vector<glm::vec2> badge = changed(shown, bare);
  REQUIRE(badge.size() > 50);  // a badge with text and two dots
  // Every dot and the badge (drawn to the lower right of the dots' mean) start at the dots:
  // nothing is drawn above or left of the rim contacts, so nothing at the hub.
  float min_x = 1e9f, min_y = 1e9f;
  for (const glm::vec2& p : badge) {
    min_x = std::min(min_x, p.x);
    min_y = std::min(min_y, p.y);
  }
  const float dot = 0.22f * 10.0f;  // regime_badges: 0.22 of the 10 px text size at 360 px
  CHECK(std::abs(min_x - (std::min(rim[0].x, rim[1].x) - dot)) < 3.0f);
  CHECK(std::abs(min_y - (std::min(rim[0].y, rim[1].y) - dot)) < 3.0f);
  CHECK(nearest(badge, hub) > 25.0f);
  for (const glm::vec2& r : rim) CHECK(nearest(badge, r) < 1.5f);  // a dot on each contact

  // The badge says the wheel slips, for both of its rim contacts.
  RegimeBadges badges(s.drawing, s.drawing.sites, with.poses(), 360);
  const std::vector<Badge> all = badges.badges(with.poses(), t, vp, 640, 360);
  REQUIRE(all.size() == 1);
  CHECK(all[0].text() == "slip \u00d72");
}

TEST_CASE(
    "contact overlays: a wheel's force arrows stand clear of it and its trail is on the "
    "floor under its rim",
    "[render][overlays][trail]") {
  const scene::Scene s = testing::make_scene(wheel_toml(), "wheel_spin");
  const core::Trajectory tr = spin_out();
  const RenderSettings plain = plain_settings(s);
  const double t = 0.8;
  FrameRenderer without(s.drawing, tr, plain);
  const float aspect = 640.0f / 360.0f;
  const CameraRig rig(plain.camera, s.drawing, without.poses(), aspect);
  const Camera camera = rig.at(t);
  const glm::mat4 vp = camera.projection(aspect) * camera.view();

  // Arrows: their tails are outside the wheel (the normal force points up through it), on
  // the camera's side, within a shaft or two of its near face.
  ArrowScales scales;
  scales.shaft_radius = 0.01f;
  for (const ContactSite& site : s.drawing.sites.contacts) {
    if (site.name != "floor.0" && site.name != "floor.3") continue;
    const core::Vec3 tail = force_arrow_tail(site, without.poses(), t, scales, camera.eye);
    const core::Vec3 hub = without.poses().position(0, t);
    const core::Vec3 local = without.poses().orientation(0, t).conjugate() * (tail - hub);
    INFO(site.name << " tail " << tail.transpose());
    const bool inside =
        std::abs(local.y()) <= 0.5 * kLength && std::hypot(local.x(), local.z()) <= kRadius;
    CHECK_FALSE(inside);
    // Beside the wheel, not far off: within its size of the contact, on the camera's side.
    const core::Vec3 contact = contact_point(site, without.poses(), t);
    CHECK((tail - contact).norm() < kRadius + kLength);
    CHECK((tail.y() < 0.0) == (camera.eye.y < 0.0f));
  }

  // Trail: drawn under the rim points, where the near cap's contact was 0.25 s ago.
  RenderSettings trailed = plain;
  trailed.overlay.trail = true;
  FrameRenderer with(s.drawing, tr, trailed);
  const image::Image shown = with.render(t);
  save(shown, "wheel_trail.png");
  const std::vector<glm::vec2> trail = changed(shown, without.render(t));
  REQUIRE(trail.size() > 50);
  for (const ContactSite& site : s.drawing.sites.contacts) {
    if (site.name != "floor.3") continue;  // the -y cap: the one nearer the camera
    const core::Vec3 before = contact_point(site, with.poses(), t - 0.25);
    glm::vec2 pixel;
    REQUIRE(project(vp, to_glm(before), 640, 360, pixel));
    CHECK(nearest(trail, pixel) < 4.0f);
  }
  glm::vec2 hub;
  REQUIRE(project(vp, to_glm(with.poses().position(0, t)), 640, 360, hub));
  CHECK(nearest(trail, hub) > 25.0f);
}
