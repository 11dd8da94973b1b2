// Several overlay values, title and caption, the speed note and values below a stick
// threshold (issue 22): settings parsing and the text the overlay draws.
#include <catch2/catch.hpp>
#include <random>

#include "render/contact_sites.hpp"
#include "render/overlay.hpp"
#include "render/render_settings.hpp"
#include "render/scene_view.hpp"
#include "scene/toml_reader.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

const std::vector<std::string> kColumns{
    "t",          "sphere.p.x",     "sphere.p.y",     "sphere.p.z",     "sphere.q.w",
    "sphere.q.x", "sphere.q.y",     "sphere.q.z",     "sphere.w.x",     "sphere.w.y",
    "sphere.w.z", "contact.slip.x", "contact.slip.y", "contact.slip.z", "contact.n_force"};

RenderSettings read(const std::string& text) {
  return read_render_settings(toml::parse(std::string_view(text), std::string_view("scene.toml")),
                              {"sphere"}, kColumns);
}

// A sphere resting on its contact: position fixed, the given slip and spin at every row.
core::Trajectory resting_sphere(double slip, double spin) {
  core::Trajectory tr(kColumns);
  for (int i = 0; i <= 10; ++i) {
    const double row[] = {0.1 * i, 0.0,  0.0, 0.2,  1.0, 0.0, 0.0, 0.0,
                          0.0,     spin, 0.0, slip, 0.0, 0.0, 3.0};
    tr.append(row);
  }
  return tr;
}

Drawing sphere_scene() {
  Drawing scene;
  BodyVisual b;
  b.name = "sphere";
  b.radius = 0.2;
  scene.bodies.push_back(b);
  return scene;
}

}  // namespace

TEST_CASE("overlay values: an array of tables in either TOML form, signal/label/unit kept",
          "[render][overlay_values]") {
  const RenderSettings inline_form = read(
      "name = \"demo\"\n[overlay]\nsignal = \"contact.slip\"\nlabel = \"slip\"\nunit = \"m/s\"\n"
      "values = [{signal = \"sphere.w.y\", label = \"spin\", unit = \"rad/s\"},"
      " {signal = \"contact.n_force\"}]\n");
  const RenderSettings table_form = read(
      "[overlay]\nsignal = \"contact.slip\"\nlabel = \"slip\"\nunit = \"m/s\"\n"
      "[[overlay.values]]\nsignal = \"sphere.w.y\"\nlabel = \"spin\"\nunit = \"rad/s\"\n"
      "[[overlay.values]]\nsignal = \"contact.n_force\"\n");
  for (const RenderSettings* s : {&inline_form, &table_form}) {
    const std::vector<OverlayValue> v = overlay_values(s->overlay);
    REQUIRE(v.size() == 3);
    CHECK(v[0].signal == "contact.slip");
    CHECK(v[0].label == "slip");
    CHECK(v[1].label == "spin");
    CHECK(v[1].unit == "rad/s");
    CHECK(v[2].label == "contact.n_force");  // the label defaults to the signal
    CHECK(v[2].unit.empty());
  }
}

TEST_CASE("overlay values: title and caption default to the scene's name and description",
          "[render][overlay_values]") {
  const RenderSettings d = read("name = \"tilting_plane\"\ndescription = \"A ball rolls\"\n");
  CHECK(d.overlay.layers.title == "tilting_plane");
  CHECK(d.overlay.layers.caption == "A ball rolls");
  const RenderSettings off =
      read("name = \"n\"\ndescription = \"d\"\n[overlay]\ntitle = \"\"\ncaption = \"\"\n");
  CHECK(off.overlay.layers.title == "");
  CHECK(off.overlay.layers.caption == "");
  const RenderSettings set = read("name = \"n\"\n[overlay]\ntitle = \"Rolling to slip\"\n");
  CHECK(set.overlay.layers.title == "Rolling to slip");
  CHECK(set.overlay.layers.caption == "");
}

TEST_CASE("overlay values: bad entries are input errors at their key", "[render][overlay_values]") {
  CHECK_THROWS_WITH(read("[overlay]\nvalues = [{signal = \"nope\"}]\n"),
                    Catch::Contains("no signal named 'nope'") && Catch::Contains("scene.toml:2"));
  CHECK_THROWS_WITH(read("[overlay]\nvalues = [{label = \"x\"}]\n"), Catch::Contains("signal"));
  CHECK_THROWS_WITH(read("[overlay]\nvalues = [{signal = \"contact.slip\", colour = 1}]\n"),
                    Catch::Contains("colour"));
  CHECK_THROWS_WITH(read("[overlay]\nvalues = [3]\n"), Catch::Contains("expected a table"));
  CHECK_THROWS_WITH(read("[overlay]\nforce_scale = -1\n"), Catch::Contains("force_scale"));
  CHECK_THROWS_WITH(read("[overlay]\nbadges = 1\n"), Catch::Contains("badges"));
  const RenderSettings on =
      read("[overlay]\nforces = true\nforce_scale = 20\nvelocities = true\nbadges = true\n");
  CHECK(on.overlay.layers.forces);
  CHECK(on.overlay.layers.force_scale == 20.0);
  CHECK(on.overlay.layers.velocities);
  CHECK(on.overlay.layers.velocity_scale == 0.0);
  CHECK(on.overlay.layers.badges);
  const RenderSettings off = read("");
  CHECK_FALSE(off.overlay.layers.forces);
  CHECK_FALSE(off.overlay.layers.velocities);
  CHECK_FALSE(off.overlay.layers.badges);
}

TEST_CASE("overlay: no speed note when the speed prints as 1/1", "[render][overlay_values]") {
  CHECK(speed_note(1.0) == "");
  CHECK(speed_note(0.98) == "");  // between slow-motion windows, ramping back
  CHECK(speed_note(0.7) == "");   // 1/1.43 prints as 1/1
  CHECK(speed_note(0.6) == "  (1/2 speed)");
  CHECK(speed_note(0.125) == "  (1/8 speed)");
}

TEST_CASE("overlay: a slip speed below the contact's stick threshold prints as zero",
          "[render][overlay_values]") {
  const std::map<std::string, double> thresholds{{"contact", 1e-3}, {"wheel", 0.05}};
  CHECK(threshold_zero("contact.slip", thresholds, 1e-3) == 1e-3);
  CHECK(threshold_zero("contact.slip.x", thresholds, 1e-3) == 1e-3);
  CHECK(threshold_zero("wheel.slip", thresholds, 1e-3) == 0.05);
  CHECK(threshold_zero("contact.slipper", thresholds, 1e-3) < 0.0);
  CHECK(threshold_zero("sphere.w", thresholds, 1e-3) < 0.0);
  CHECK(threshold_zero("other.slip", thresholds, 1e-3) < 0.0);

  // Random slips on either side of a random threshold, printed as the overlay prints them.
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> log_threshold(-5.0, -1.0), factor(0.01, 0.98);
  const Drawing scene = sphere_scene();
  for (int i = 0; i < 6; ++i) {
    const double threshold = std::pow(10.0, log_threshold(rng));
    const double below = factor(rng) * threshold, above = threshold / factor(rng);
    OverlaySettings o;
    o.signal = "contact.slip";
    o.label = "slip speed";
    o.unit = "m/s";
    o.stick_thresholds = {{"contact", threshold}};
    Overlay overlay(o, 360);
    const core::Trajectory stuck = resting_sphere(below, 0.0);
    const PoseTrack stuck_poses(stuck, scene);
    CHECK(overlay.value_lines(stuck_poses, 0.5) ==
          std::vector<std::string>{"slip speed = 0.000 m/s"});
    Overlay overlay2(o, 360);
    const core::Trajectory sliding = resting_sphere(above, 0.0);
    const PoseTrack sliding_poses(sliding, scene);
    CHECK(overlay2.value_lines(sliding_poses, 0.5).front() != "slip speed = 0.000 m/s");
  }
  // The rolling ball: 142.5 nm/s of rounding noise under a 1 mm/s threshold.
  OverlaySettings o;
  o.signal = "contact.slip";
  o.label = "slip speed";
  o.unit = "m/s";
  o.stick_thresholds = {{"contact", 1e-3}};
  Overlay overlay(o, 360);
  const core::Trajectory rolling = resting_sphere(142.5e-9, 0.0);
  CHECK(overlay.value_lines(PoseTrack(rolling, scene), 0.3).front() == "slip speed = 0.000 m/s");
}

TEST_CASE("overlay: several values, each with its unit and SI prefix, and the 1e-9 rule",
          "[render][overlay_values]") {
  const Drawing scene = sphere_scene();
  OverlaySettings o;
  o.signal = "contact.slip";
  o.label = "slip";
  o.unit = "m/s";
  o.stick_thresholds = {{"contact", 1e-3}};
  o.layers.values = {{"sphere.w.y", "spin", "rad/s"}, {"contact.n_force", "normal", "N"}};
  Overlay overlay(o, 360);
  const core::Trajectory tr = resting_sphere(0.0044, 0.0123);
  const std::vector<std::string> lines = overlay.value_lines(PoseTrack(tr, scene), 0.5);
  CHECK(lines ==
        std::vector<std::string>{"slip = 4.400 mm/s", "spin = 12.30 mrad/s", "normal = 3.000 N"});
  // The panel grows by a line per value.
  image::Image one(640, 360, {0, 0, 0, 255}), three(640, 360, {0, 0, 0, 255});
  OverlaySettings single = o;
  single.layers.values.clear();
  Overlay overlay_one(single, 360);
  const PixelBox b1 = overlay_one.draw(one, PoseTrack(tr, scene), 0.5);
  const PixelBox b3 = overlay.draw(three, PoseTrack(tr, scene), 0.5);
  CHECK(b3.y1 - b3.y0 > b1.y1 - b1.y0 + 20);
}

TEST_CASE("overlay: a friction joint's rate below the joint's stick threshold prints as zero",
          "[render][overlay_values]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 5; ++i) {
    ContactSites sites;
    const double threshold = 0.001 + 0.05 * u(rng);
    sites.joints.push_back({"joint1_friction", "arm", 0, 1, threshold});
    const std::map<std::string, double> rates = joint_rate_thresholds(sites);
    REQUIRE(rates.size() == 1);
    CHECK(rates.at("arm.omega.1") == threshold);
    core::Trajectory tr({"t", "arm.theta.0", "arm.theta.1", "arm.omega.0", "arm.omega.1"});
    const double stuck = -0.9 * threshold * u(rng), moving = threshold * (1.0 + u(rng));
    for (double t : {0.0, 1.0}) {
      const double row[] = {t, 0.0, 0.0, moving, stuck};
      tr.append(row);
    }
    Drawing scene;
    BodyVisual arm;
    arm.kind = BodyVisual::Kind::arm;
    arm.name = "arm";
    arm.lengths = {0.2, 0.2};
    arm.widths = {0.02, 0.02};
    scene.bodies.push_back(arm);
    OverlaySettings o;
    o.signal = "arm.omega.1";
    o.label = "joint 1";
    o.unit = "rad/s";
    o.layers.values = {{"arm.omega.0", "joint 0", "rad/s"}};
    Overlay overlay(o, 360, 1.0, false, rates);
    const std::vector<std::string> lines = overlay.value_lines(PoseTrack(tr, scene), 0.5);
    REQUIRE(lines.size() == 2);
    CHECK(lines[0] == "joint 1 = 0.000 rad/s");
    CHECK(lines[1] != "joint 0 = 0.000 rad/s");  // joint 0 has no friction element here
  }
}
