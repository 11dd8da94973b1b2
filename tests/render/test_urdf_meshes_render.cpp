// URDF robots drawn with their meshes, joint badges and floor (issue 37): golden images of the
// bundled 4-joint mesh arm (scenes/arm4_meshes.toml) from the side, three-quarter and follow
// views with badges and its waist motor's arrow; its meshes at their links in their colours;
// the floor at the pedestal's foot (and under everything for an arm moving below its base);
// and on generated URDF chains (random link lengths, origins, orientations and axes), every
// friction joint's badge dot drawn on the joint's projection in every view, with the time
// panel, inset, title and caption on and no link's picture under any of them. Hand-made
// trajectories (joint angles from closed forms), as the other render tests use.
// Regenerate the goldens after an intended change with
//   STICTION_UPDATE_GOLDEN=1 ./build/tests/render/test_render "[golden]"
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "image/compare.hpp"
#include "image/png.hpp"
#include "overlay_pixels.hpp"
#include "render/camera.hpp"
#include "render/mechanism_items.hpp"
#include "render/regime_badges.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render/tree_items.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;
using testing::nearest;
namespace fs = std::filesystem;

namespace {

const fs::path kSource(STICTION_SOURCE_DIR);

scene::Scene arm4() {
  return scene::load_scene(scene::SceneSource((kSource / "scenes" / "arm4_meshes.toml").string()));
}

// A joint that slips from `from` to `to` and sticks at `stop` s: theta = to - (to - from)
// (1 - t / stop)^2, its rate falling linearly to zero.
struct Slip {
  double from, to, stop;
  double theta(double t) const {
    const double u = std::min(t / stop, 1.0);
    return to - (to - from) * (1.0 - u) * (1.0 - u);
  }
  double omega(double t) const {
    return t < stop ? 2.0 * (to - from) * (1.0 - t / stop) / stop : 0.0;
  }
};

// arm4_meshes's joints (waist, shoulder, elbow, wrist) swinging from its initial pose to about
// where the simulation stops them, sticking one after the other (the wrist from 0.25 s); the
// waist motor's 0.4 s pulse.
core::Trajectory arm4_trajectory() {
  const Slip joints[] = {
      {0.0, 1.14, 0.98}, {-0.3, 0.37, 1.3}, {-0.5, 1.15, 0.86}, {0.35, -0.09, 0.25}};
  const char* names[] = {"waist", "shoulder", "elbow", "wrist"};
  std::vector<std::string> columns{"t"};
  for (const char* n : names) columns.push_back(std::string("arm.theta.") + n);
  for (const char* n : names) columns.push_back(std::string("arm.omega.") + n);
  columns.push_back("waist_motor.tau");
  core::Trajectory tr(columns);
  for (int k = 0; k <= 1500; ++k) {
    const double t = 1e-3 * k;
    std::vector<double> row{t};
    for (const Slip& j : joints) row.push_back(j.theta(t));
    for (const Slip& j : joints) row.push_back(j.omega(t));
    row.push_back(t < 0.4 ? 2.5 : 0.0);
    tr.append(row.data());
  }
  return tr;
}

RenderSettings small(const scene::Scene& s) {
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  return settings;
}

// The camera a FrameRenderer with these settings draws with at t, as view-projection.
glm::mat4 view_projection(const RenderSettings& settings, const Drawing& drawing,
                          const PoseTrack& poses, double t) {
  const float aspect = float(settings.width) / float(settings.height);
  const CameraRig rig(settings.camera, drawing, poses, aspect);
  const Camera camera = rig.at(t);
  return camera.projection(aspect) * camera.view();
}

void save(const image::Image& frame, const std::string& name) {
  const fs::path dir = fs::path(STICTION_TEST_OUTPUT_DIR) / "urdf_meshes";
  fs::create_directories(dir);
  image::write_png(dir / name, frame);
}

glm::vec3 pixel_colour(const image::Image& im, glm::vec2 p) {
  const auto x = static_cast<std::size_t>(p.x), y = static_cast<std::size_t>(p.y);
  const std::size_t i = 4 * (y * static_cast<std::size_t>(im.width) + x);
  return {float(im.pixels[i]), float(im.pixels[i + 1]), float(im.pixels[i + 2])};
}

// Pixels that differ between two frames of the same size.
std::vector<glm::vec2> changed(const image::Image& a, const image::Image& b) {
  return testing::changed_pixels(a, b);
}

}  // namespace

TEST_CASE("golden: the 4-joint mesh arm with joint badges and its motor's arrow, three views",
          "[render][golden][urdf][meshes]") {
  const scene::Scene s = arm4();
  const core::Trajectory tr = arm4_trajectory();
  for (const auto& [view, name] :
       {std::pair{CameraView::side, "side"}, std::pair{CameraView::three_quarter, "three_quarter"},
        std::pair{CameraView::follow, "follow"}}) {
    INFO(name);
    RenderSettings settings = small(s);
    settings.camera.view = view;
    FrameRenderer renderer(s.drawing, tr, settings);
    const image::Image frame = renderer.render(0.3);
    save(frame, std::string("arm4_") + name + ".png");
    const image::CompareResult r = image::compare_to_golden(
        kSource / "tests" / "golden" / (std::string("render_arm4_meshes_") + name + ".png"), frame,
        fs::path(STICTION_TEST_OUTPUT_DIR) / "failures");
    INFO(r.message);
    CHECK(r.matches);
  }
}

TEST_CASE("the mesh arm: each mesh drawn on its link in its colour, badges at the joints",
          "[render][urdf][meshes][badges]") {
  const scene::Scene s = arm4();
  const core::Trajectory tr = arm4_trajectory();
  RenderSettings settings = small(s);
  settings.camera.view = CameraView::side;
  settings.overlay.panel = false;
  settings.overlay.layers.badges = false;
  settings.overlay.layers.title = "";
  settings.overlay.layers.caption = "";
  const double t = 0.3;
  FrameRenderer renderer(s.drawing, tr, settings);
  const image::Image frame = renderer.render(t);
  const glm::mat4 vp = view_projection(settings, s.drawing, renderer.poses(), t);

  // The three meshes are drawn as mesh items (one part each), at their links.
  const std::vector<DrawItem> items = build_items(s.drawing, renderer.poses(), t);
  const auto meshes = std::count_if(items.begin(), items.end(),
                                    [](const DrawItem& i) { return i.shape == Shape::mesh; });
  CHECK(meshes == 3);
  const BodyVisual& arm = s.drawing.bodies.at(0);
  const std::vector<components::LinkPose> links = tree_poses(arm, renderer.poses(), 0, t);
  // A point inside each mesh, in its link's frame, and the colour it is drawn in: the
  // turret in the URDF's navy, the upper arm in its .mtl's orange, the hand in its DAE green.
  struct Probe {
    int link;
    core::Vec3 local;
    int strongest;  // colour channel
  };
  for (const Probe& p : {Probe{0, {0.0, -0.06, 0.01}, 2}, Probe{1, {0.2, 0.0, 0.0}, 0},
                         Probe{3, {0.05, 0.0, 0.0}, 1}}) {
    INFO("link " << p.link);
    const components::LinkPose& f = links[static_cast<std::size_t>(p.link)];
    glm::vec2 pixel;
    REQUIRE(project(vp, to_glm(f.p + f.q * p.local), 640, 360, pixel));
    const glm::vec3 c = pixel_colour(frame, pixel);
    INFO("pixel " << pixel.x << "," << pixel.y << ": " << c.r << " " << c.g << " " << c.b);
    for (int k = 0; k < 3; ++k) {
      if (k != p.strongest) CHECK(c[p.strongest] > c[k] + 10.0f);
    }
  }

  // Lit, not flat: from the top to the bottom of the upper arm's octagonal beam (its normals
  // computed by the loader: the OBJ has none) the shading varies.
  float darkest = 1e9f, brightest = 0.0f;
  for (double z : {-0.03, -0.015, 0.0, 0.015, 0.03}) {
    const components::LinkPose& f = links[1];
    glm::vec2 pixel;
    REQUIRE(project(vp, to_glm(f.p + f.q * core::Vec3(0.2, 0.0, z)), 640, 360, pixel));
    const glm::vec3 c = pixel_colour(frame, pixel);
    darkest = std::min(darkest, c.r + c.g + c.b);
    brightest = std::max(brightest, c.r + c.g + c.b);
  }
  CHECK(brightest - darkest > 15.0f);

  // A badge per friction joint, at the joint: three slip (waist, shoulder, elbow), one stick.
  RegimeBadges badges(s.drawing, s.drawing.sites, renderer.poses(), 360);
  const std::vector<Badge> all = badges.badges(renderer.poses(), t, vp, 640, 360);
  REQUIRE(all.size() == 4);
  int slipping = 0;
  for (const Badge& b : all) {
    REQUIRE(b.points.size() == 1);
    slipping += b.regime == Regime::slip ? 1 : 0;
    float best = 1e9f;
    for (std::size_t j = 0; j < links.size(); ++j) {
      glm::vec2 joint;
      REQUIRE(project(vp, to_glm(links[j].p), 640, 360, joint));
      best = std::min(best, glm::length(joint - b.points[0]));
    }
    CHECK(best < 0.5f);
  }
  CHECK(slipping == 3);
}

TEST_CASE("the floor under a fixed-base robot is at its base, unless a link goes below it",
          "[render][urdf][floor]") {
  const scene::Scene s = arm4();
  const core::Trajectory tr = arm4_trajectory();
  const PoseTrack poses(tr, s.drawing);
  // The pedestal's plate stands on z = 0: the floor is there, not under the arm's reach.
  const std::optional<double> base = tree_base_floor(s.drawing, poses);
  REQUIRE(base);
  CHECK(std::abs(*base) < 1e-12);
  CHECK(mechanism_frame(s.drawing, poses).floor_z == Approx(*base).margin(1e-12));

  // The same arm hung from a ceiling (base_rpy = [pi, 0, 0]): its links reach below the
  // pedestal's far end, so the floor goes under everything, as for any hanging arm.
  const scene::Scene hung = testing::make_scene(
      "name = \"hung\"\n[bodies.arm]\ntype = \"urdf\"\nfile = \"" +
          (kSource / "assets" / "robots" / "arm4.urdf").string() +
          "\"\nbase = [0.0, 0.0, 2.0]\nbase_rpy = [3.141592653589793, 0.0, 0.0]\n",
      "hung");
  const PoseTrack hung_poses(tr, hung.drawing);
  CHECK_FALSE(tree_base_floor(hung.drawing, hung_poses));
  const MechanismFrame hung_frame = mechanism_frame(hung.drawing, hung_poses);
  CHECK(hung_frame.floor_z < hung_frame.run.min.z);

  // A scene with other bodies than robots keeps the usual floor.
  const scene::Scene two = testing::make_scene(testing::two_link_toml(), "two_link");
  CHECK_FALSE(tree_base_floor(two.drawing, PoseTrack(testing::two_link_trajectory(), two.drawing)));
}

TEST_CASE(
    "generated URDF chains: every friction joint's badge dot is on its projection, no "
    "link under a panel",
    "[render][urdf][badges]") {
  std::mt19937 rng(3712);
  std::uniform_real_distribution<double> length(0.08, 0.35), angle(-3.0, 3.0), unit(-1.0, 1.0);
  const fs::path dir =
      fs::temp_directory_path() / ("stiction_test_urdf_badges_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (int trial = 0; trial < 4; ++trial) {
    const int n = 2 + trial % 3;
    std::ostringstream urdf;
    urdf << "<?xml version=\"1.0\"?><robot name=\"g\"><link name=\"l0\"><visual><geometry>"
            "<box size=\"0.1 0.1 0.04\"/></geometry></visual></link>\n";
    std::vector<std::string> joints;
    std::vector<double> reach;  // each moving link's box, along its x from its joint
    for (int i = 1; i <= n; ++i) {
      const double l = length(rng);
      reach.push_back(l);
      core::Vec3 axis(unit(rng), unit(rng), unit(rng));
      if (axis.norm() < 0.2) axis = core::Vec3::UnitZ();
      const std::string name = "j" + std::to_string(i);
      joints.push_back(name);
      urdf << "<link name=\"l" << i << "\"><inertial><origin xyz=\"" << 0.5 * l
           << " 0 0\"/><mass value=\"0.3\"/><inertia ixx=\"1e-3\" ixy=\"0\" ixz=\"0\" iyy=\"1e-3\""
              " iyz=\"0\" izz=\"1e-3\"/></inertial><visual><origin xyz=\""
           << 0.5 * l << " 0 0\"/><geometry><box size=\"" << l
           << " 0.03 0.03\"/></geometry></visual></link>\n"
           << "<joint name=\"" << name << "\" type=\"revolute\"><parent link=\"l" << i - 1
           << "\"/><child link=\"l" << i << "\"/><origin xyz=\"" << (i == 1 ? 0.0 : length(rng))
           << " " << 0.1 * unit(rng) << " " << 0.1 * unit(rng) << "\" rpy=\"" << angle(rng) << " "
           << angle(rng) << " " << angle(rng) << "\"/><axis xyz=\"" << axis.x() << " " << axis.y()
           << " " << axis.z()
           << "\"/><limit lower=\"-3\" upper=\"3\" effort=\"1\" velocity=\"1\"/>"
              "<dynamics friction=\"0.5\"/></joint>\n";
    }
    urdf << "</robot>\n";
    std::ofstream(dir / "g.urdf") << urdf.str();
    std::ofstream(dir / "g.toml")
        << "name = \"g\"\n[bodies.arm]\ntype = \"urdf\"\nfile = "
           "\"g.urdf\"\nbase = [0.0, 0.0, 0.5]\n[overlay]\nbadges = true\n"
           "signal = \"arm.theta.j1\"\nlabel = \"first joint\"\nunit = \"rad\"\n"
           "title = \"A generated chain framed beside the panels\"\n"
           "caption = \"Badges at the joints, no link under a panel\"\n"
           "[inset]\nsignals = [\"arm.theta.j1\"]\n";
    const scene::Scene s = scene::load_scene(scene::SceneSource((dir / "g.toml").string()));
    REQUIRE(static_cast<int>(s.drawing.sites.joints.size()) == n);
    // Joint i turns at rate w_i (odd joints stuck) from a random start.
    std::vector<std::string> columns{"t"};
    for (const std::string& j : joints) columns.push_back("arm.theta." + j);
    for (const std::string& j : joints) columns.push_back("arm.omega." + j);
    std::vector<double> start, rate;
    for (int i = 0; i < n; ++i) {
      start.push_back(angle(rng));
      rate.push_back(i % 2 == 1 ? 0.0 : 0.8 * unit(rng) + 1.0);
    }
    core::Trajectory tr(columns);
    for (int k = 0; k <= 200; ++k) {
      const double t = 0.005 * k;
      std::vector<double> row{t};
      for (int i = 0; i < n; ++i) row.push_back(start[i] + rate[i] * t);
      for (int i = 0; i < n; ++i) row.push_back(rate[i]);
      tr.append(row.data());
    }
    for (CameraView view : {CameraView::side, CameraView::three_quarter, CameraView::follow}) {
      INFO("trial " << trial << ", view " << camera_view_names()[static_cast<int>(view)]);
      RenderSettings plain = read_render_settings(s);
      plain.width = 640;
      plain.height = 360;
      plain.camera.view = view;
      plain.overlay.layers.badges = false;
      RenderSettings badged = plain;
      badged.overlay.layers.badges = true;
      const double t = 0.6;
      FrameRenderer without(s.drawing, tr, plain);
      FrameRenderer with(s.drawing, tr, badged);
      const image::Image shown = with.render(t);
      const std::vector<glm::vec2> drawn = changed(shown, without.render(t));
      if (trial == 0)
        save(shown,
             std::string("generated_") + camera_view_names()[static_cast<int>(view)] + ".png");
      const Camera camera = with.camera(t);  // framed beside the panels
      const glm::mat4 vp = camera.projection(640.0f / 360.0f) * camera.view();
      // The joints from the tree's kinematics at the trajectory's angles.
      core::Vec q(n);
      for (int i = 0; i < n; ++i) q[i] = start[i] + rate[i] * t;
      const std::vector<components::LinkPose> links = s.drawing.bodies[0].tree->link_poses(q);
      RegimeBadges badges(s.drawing, s.drawing.sites, with.poses(), 360);
      const std::vector<Badge> all = badges.badges(with.poses(), t, vp, 640, 360);
      REQUIRE(static_cast<int>(all.size()) == n);
      for (int i = 0; i < n; ++i) {
        glm::vec2 joint;
        REQUIRE(project(vp, to_glm(links[static_cast<std::size_t>(i)].p), 640, 360, joint));
        INFO("joint " << i << " at " << joint.x << "," << joint.y);
        if (joint.x < 4 || joint.y < 4 || joint.x > 636 || joint.y > 356) continue;  // at the edge
        CHECK(nearest(drawn, joint) < 2.0f);  // its dot is drawn there
        // and a badge has that point, in its joint's regime.
        bool found = false;
        for (const Badge& b : all) {
          if (glm::length(b.points.at(0) - joint) < 0.5f) {
            found = true;
            CHECK(b.regime ==
                  (rate[static_cast<std::size_t>(i)] == 0.0 ? Regime::stick : Regime::slip));
          }
        }
        CHECK(found);
      }
      // Every link (and, but under the follow view, which frames the links alone, the base)
      // in the frame and clear of the panels: the corners of its box from the chain's own
      // kinematics.
      const FramePanels& panels = with.panels();
      REQUIRE(panels.boxes.size() == 4);  // time panel, inset, title, caption
      for (int i = view == CameraView::follow ? 0 : -1; i < n; ++i) {
        components::LinkPose f;
        core::Vec3 centre, half;
        if (i < 0) {
          f.p = core::Vec3(0.0, 0.0, 0.5);
          centre = core::Vec3::Zero();
          half = core::Vec3(0.05, 0.05, 0.02);
        } else {
          f = links[static_cast<std::size_t>(i)];
          centre = core::Vec3(0.5 * reach[static_cast<std::size_t>(i)], 0.0, 0.0);
          half = core::Vec3(0.5 * reach[static_cast<std::size_t>(i)], 0.015, 0.015);
        }
        float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
        for (int k = 0; k < 8; ++k) {
          const core::Vec3 corner =
              f.p + f.q * (centre + core::Vec3((k & 1) ? half.x() : -half.x(),
                                               (k & 2) ? half.y() : -half.y(),
                                               (k & 4) ? half.z() : -half.z()));
          glm::vec2 px;
          REQUIRE(project(vp, to_glm(corner), 640, 360, px));
          x0 = std::min(x0, px.x), x1 = std::max(x1, px.x), y0 = std::min(y0, px.y),
          y1 = std::max(y1, px.y);
        }
        const PixelBox box{static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0)),
                           static_cast<int>(std::ceil(x1)), static_cast<int>(std::ceil(y1))};
        INFO("link " << i << " at [" << box.x0 << ", " << box.x1 << ") x [" << box.y0 << ", "
                     << box.y1 << ")");
        CHECK(box.x0 >= 0);
        CHECK(box.y0 >= 0);
        CHECK(box.x1 <= 640);
        CHECK(box.y1 <= 360);
        for (const PixelBox& panel : panels.boxes) CHECK_FALSE(boxes_overlap(box, panel));
      }
    }
  }
}
