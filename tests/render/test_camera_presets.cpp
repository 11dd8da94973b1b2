// Camera presets ([camera] view): parsed with errors at the key, and framed so that every
// body and every element of the mechanism (coils, posts, arrows, arcs, rollers, axles) is in
// the picture at every time, for each fixed preset, on generated scenes and on
// belt_oscillator; the follow view keeps its body in the picture (it frames that body at a
// fixed fraction of the height, test_panel_framing.cpp, so the rest may leave the picture).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "generated_mechanism.hpp"
#include "render/camera.hpp"
#include "render/framing.hpp"
#include "render/mechanism_items.hpp"
#include "render/render_settings.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

RenderSettings read(const std::string& text) {
  return read_render_settings(toml::parse(std::string_view(text), std::string_view("scene.toml")),
                              {"sphere"}, {});
}

// Every point drawn at time t: the bodies' and the mechanism's.
std::vector<glm::vec3> drawn_points(const Drawing& scene, const PoseTrack& poses,
                                    const MechanismFrame& frame, double t) {
  std::vector<glm::vec3> points = body_points(scene, poses, t);
  const std::vector<glm::vec3> parts = mechanism_points(scene, poses, frame, t);
  points.insert(points.end(), parts.begin(), parts.end());
  return points;
}

// Largest |x| and |y| over the points in normalized device coordinates (in view: below 1).
float widest_in_picture(const Camera& c, float aspect, const std::vector<glm::vec3>& points) {
  float widest = 0.0f;
  for (const glm::vec3& p : points) {
    const glm::vec4 clip = c.projection(aspect) * c.view() * glm::vec4(p, 1.0f);
    if (!(clip.w > 0.0f)) return 1e9f;  // behind the camera
    widest = std::max({widest, std::abs(clip.x / clip.w), std::abs(clip.y / clip.w)});
  }
  return widest;
}

}  // namespace

TEST_CASE("camera view: the presets by name, errors at the key", "[render][settings]") {
  using Catch::Contains;
  CHECK(read("").camera.view == CameraView::automatic);
  CHECK(read("[camera]\nview = \"side\"\n").camera.view == CameraView::side);
  CHECK(read("[camera]\nview = \"top\"\n").camera.view == CameraView::top);
  CHECK(read("[camera]\nview = \"three_quarter\"\n").camera.view == CameraView::three_quarter);
  CHECK(read("[camera]\nview = \"follow\"\n").camera.view == CameraView::follow);
  CHECK_THROWS_WITH(read("[camera]\nfov = 30\nview = \"diagonal\"\n"),
                    Contains("scene.toml:3:") && Contains("camera.view") &&
                        Contains("unknown view 'diagonal'") && Contains("\"three_quarter\""));
  CHECK_THROWS_AS(read("[camera]\nview = 3\n"), scene::InputError);
  CHECK_THROWS_WITH(
      read("[camera]\nview = \"follow\"\nfollow = \"sphere\"\nfollow_vertical = true\n"),
      Contains("camera.follow_vertical") && Contains("fixed height"));
}

TEST_CASE("every preset keeps every element of generated mechanisms in the picture",
          "[render][framing][mechanism]") {
  std::mt19937 rng(7202612);
  const float aspect = 16.0f / 9.0f;
  for (int trial = 0; trial < 10; ++trial) {
    const testing::Generated g = testing::generated_mechanism(rng);
    const scene::Scene s = testing::make_scene(g.toml, "generated");
    const Drawing scene = s.drawing;
    const PoseTrack poses(g.trajectory, scene);
    const MechanismFrame frame = mechanism_frame(scene, poses);
    for (CameraView view : {CameraView::automatic, CameraView::side, CameraView::top,
                            CameraView::three_quarter, CameraView::follow}) {
      CameraSettings settings;
      settings.view = view;
      const CameraRig rig(settings, scene, poses, aspect);
      INFO("trial " << trial << ", view " << camera_view_names()[static_cast<int>(view)] << ":\n"
                    << g.toml);
      for (int i = 0; i <= 20; ++i) {
        const double t = 0.1 * i;
        if (view == CameraView::follow) {
          std::vector<glm::vec3> followed;
          add_body_points(followed, scene, poses, 0, t);
          CHECK(widest_in_picture(rig.at(t), aspect, followed) < 1.0f);
          continue;
        }
        CHECK(widest_in_picture(rig.at(t), aspect, drawn_points(scene, poses, frame, t)) < 1.0f);
      }
    }
  }
}

TEST_CASE("belt_oscillator: spring, post, block and rollers in view, the camera still",
          "[render][framing][mechanism]") {
  std::ifstream file(std::filesystem::path(STICTION_SOURCE_DIR) / "scenes" /
                     "belt_oscillator.toml");
  std::stringstream text;
  text << file.rdbuf();
  const scene::Scene s = testing::make_scene(text.str(), "belt_oscillator");
  const Drawing scene = s.drawing;
  REQUIRE(scene.springs.size() == 1);
  // The stick-slip oscillation about F/k = 0.0294 m, amplitude 0.02 m, period 0.628 s.
  core::Trajectory tr({"t", "mass.p.x", "mass.p.y", "mass.p.z"});
  for (int i = 0; i <= 500; ++i) {
    const double t = 0.01 * i;
    const double row[] = {t, 0.0294 + 0.02 * std::sin(10.0 * t), 0.0, 0.0};
    tr.append(row);
  }
  const PoseTrack poses(tr, scene);
  const MechanismFrame frame = mechanism_frame(scene, poses);
  const RenderSettings settings = read_render_settings(s);
  REQUIRE(settings.camera.follow == "mass");
  const float aspect = 16.0f / 9.0f;
  for (CameraView view : {CameraView::automatic, CameraView::side, CameraView::top,
                          CameraView::three_quarter, CameraView::follow}) {
    CameraSettings camera = settings.camera;
    camera.view = view;
    const CameraRig rig(camera, scene, poses, aspect);
    INFO("view " << camera_view_names()[static_cast<int>(view)]);
    // The scene's own camera (auto, follow = "mass") stays still: the oscillation is seen
    // against the post and the belt's rollers.
    if (view == CameraView::automatic) CHECK(rig.at(0.0).eye == rig.at(4.0).eye);
    for (int i = 0; i <= 50; ++i) {
      const double t = 0.1 * i;
      const SpringEnds e = spring_ends(scene, poses, frame, 0, t);
      CHECK(e.post);
      // The coil is long enough to read: three block sizes or more between block and post.
      CHECK(glm::length(e.b - e.a) > 0.3f);
      if (view == CameraView::follow) {
        std::vector<glm::vec3> followed;
        add_body_points(followed, scene, poses, 0, t);
        CHECK(widest_in_picture(rig.at(t), aspect, followed) < 1.0f);
        continue;
      }
      CHECK(widest_in_picture(rig.at(t), aspect, drawn_points(scene, poses, frame, t)) < 1.0f);
    }
  }
}
