// The camera frames the bodies beside the panels (issue 37 item 3): on generated scenes of
// spheres, boxes and cylinders at random places, sizes and velocities, with the time panel,
// the inset, the arrows' legend, the title and the caption on, no body's picture (sampled
// over the run) touches a panel in any fixed preset, nor does the followed body under a
// follow camera; the follow camera shows its body at the documented fraction of the frame's
// height (kFollowFraction), and `fov` zooms it. The free rectangles themselves are checked on
// random panels.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "generated_mechanism.hpp"
#include "render/camera.hpp"
#include "render/frame_panels.hpp"
#include "render/framing.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

constexpr int kWidth = 640, kHeight = 360;

struct GeneratedBodies {
  std::string toml;
  core::Trajectory trajectory{std::vector<std::string>{"t"}};
};

// 1-4 spheres, boxes and cylinders at random places (up to 3 m apart), random sizes (2 cm to
// 60 cm), random fixed orientations, moving at random constant velocities (`level`: only
// horizontally) for two seconds; the panels' text is long enough to matter.
GeneratedBodies generated_bodies(std::mt19937& rng, bool level) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.02, 0.6);
  const int n = 1 + static_cast<int>(rng() % 4);
  // Written to a stream: GCC 12 warns (-Wrestrict) on "literal" + std::string.
  std::ostringstream toml;
  toml << "name = \"generated bodies\"\ngravity = [0.0, 0.0, 0.0]\n";
  std::vector<std::string> columns{"t"};
  struct Body {
    core::Vec3 p0, v;
    core::Quat q;
  };
  std::vector<Body> bodies;
  for (int i = 0; i < n; ++i) {
    std::ostringstream name;
    name << "body_" << i;
    toml << "[bodies." << name.str() << "]\ntype = \"rigid_body\"\nmass = 1.0\n";
    const int kind = static_cast<int>(rng() % 3);
    if (kind == 0) {
      toml << "shape = \"sphere\"\nradius = " << 0.5 * size(rng) << "\n";
    } else if (kind == 1) {
      toml << "shape = \"box\"\nsize = "
           << testing::vec(core::Vec3(size(rng), size(rng), size(rng))) << "\n";
    } else {
      toml << "shape = \"cylinder\"\nradius = " << 0.5 * size(rng) << "\nlength = " << size(rng)
           << "\naxis = " << testing::vec(testing::random_unit(rng)) << "\n";
    }
    Body b{core::Vec3(1.5 * u(rng), 1.5 * u(rng), 0.6 + 0.5 * u(rng)),
           core::Vec3(0.8 * u(rng), 0.8 * u(rng), level ? 0.0 : 0.3 * u(rng)),
           core::Quat(Eigen::AngleAxisd(3.0 * u(rng), testing::random_unit(rng)))};
    toml << "position = " << testing::vec(b.p0) << "\n";
    for (const char* a :
         {".p.x", ".p.y", ".p.z", ".q.w", ".q.x", ".q.y", ".q.z", ".v.x", ".v.y", ".v.z"}) {
      columns.push_back(name.str() + a);
    }
    bodies.push_back(b);
  }
  GeneratedBodies g;
  g.toml = toml.str();
  g.trajectory = core::Trajectory(columns);
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.02 * k;
    std::vector<double> row{t};
    for (const Body& b : bodies) {
      const core::Vec3 p = b.p0 + t * b.v;
      row.insert(row.end(), {p.x(), p.y(), p.z(), b.q.w(), b.q.x(), b.q.y(), b.q.z(), b.v.x(),
                             b.v.y(), b.v.z()});
    }
    g.trajectory.append(row.data());
  }
  return g;
}

// Every panel on: the time panel with a value, the inset in a random corner, title, caption,
// and the velocity arrows' legend (read from the scene's text, as a user writes them).
RenderSettings panel_settings(const GeneratedBodies& g, std::mt19937& rng, CameraView view,
                              double fov = 40.0) {
  static const char* corners[] = {"top_left", "top_right", "bottom_left", "bottom_right"};
  std::ostringstream text;
  text << g.toml << R"(
[overlay]
signal = "body_0.p.x"
label = "position of the first body"
unit = "m"
title = "Generated bodies framed beside the panels"
caption = "No body goes under the title, the caption, the time panel or the inset"
velocities = true
[inset]
signals = ["body_0.p.x"]
position = ")"
       << corners[rng() % 4] << "\"\n";
  RenderSettings settings = read_render_settings(testing::make_scene(text.str(), "generated"));
  settings.width = kWidth;
  settings.height = kHeight;
  settings.camera.view = view;
  settings.camera.fov_degrees = fov;
  return settings;
}

// The pixel rectangle around the picture of `points` (y down); empty if any is behind the eye.
PixelBox picture_box(const Camera& c, const std::vector<glm::vec3>& points) {
  const glm::mat4 vp = c.projection(float(kWidth) / float(kHeight)) * c.view();
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (const glm::vec3& p : points) {
    const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
    if (!(clip.w > 0.0f)) return {};
    const float x = (clip.x / clip.w + 1.0f) * 0.5f * kWidth;
    const float y = (1.0f - clip.y / clip.w) * 0.5f * kHeight;
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  return {static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0)),
          static_cast<int>(std::ceil(x1)), static_cast<int>(std::ceil(y1))};
}

}  // namespace

TEST_CASE("free rectangles: free of every panel, maximal, covering every free pixel",
          "[render][framing][panels]") {
  std::mt19937 rng(3712026);
  for (int trial = 0; trial < 200; ++trial) {
    FramePanels panels{64 + static_cast<int>(rng() % 64), 48 + static_cast<int>(rng() % 48), {}};
    const int count = static_cast<int>(rng() % 6);
    for (int k = 0; k < count; ++k) {
      const int x0 = static_cast<int>(rng() % panels.width) - 4;
      const int y0 = static_cast<int>(rng() % panels.height) - 4;
      panels.boxes.push_back(
          {x0, y0, x0 + 1 + static_cast<int>(rng() % 40), y0 + 1 + static_cast<int>(rng() % 30)});
    }
    const std::vector<PixelBox> free = free_rectangles(panels);
    INFO("trial " << trial);
    REQUIRE(!free.empty());
    auto covered = [&](int x, int y) {
      const PixelBox pixel{x, y, x + 1, y + 1};
      return std::any_of(panels.boxes.begin(), panels.boxes.end(),
                         [&](const PixelBox& b) { return boxes_overlap(pixel, b); });
    };
    auto is_free = [&](const PixelBox& r) {
      if (r.x0 < 0 || r.y0 < 0 || r.x1 > panels.width || r.y1 > panels.height) return false;
      return std::none_of(panels.boxes.begin(), panels.boxes.end(),
                          [&](const PixelBox& b) { return boxes_overlap(r, b); });
    };
    bool any_free_pixel = false;
    for (int y = 0; y < panels.height; ++y) {
      for (int x = 0; x < panels.width; ++x) any_free_pixel |= !covered(x, y);
    }
    if (!any_free_pixel) continue;  // all covered: the frame is returned as if free
    for (const PixelBox& r : free) {
      CHECK(!r.empty());
      CHECK(is_free(r));
      // Maximal: no side moves out by a pixel and stays free.
      CHECK(!is_free({r.x0 - 1, r.y0, r.x1, r.y1}));
      CHECK(!is_free({r.x0, r.y0 - 1, r.x1, r.y1}));
      CHECK(!is_free({r.x0, r.y0, r.x1 + 1, r.y1}));
      CHECK(!is_free({r.x0, r.y0, r.x1, r.y1 + 1}));
    }
    for (int k = 0; k < 50; ++k) {
      const int x = static_cast<int>(rng() % panels.width);
      const int y = static_cast<int>(rng() % panels.height);
      if (covered(x, y)) continue;
      CHECK(std::any_of(free.begin(), free.end(), [&](const PixelBox& r) {
        return r.x0 <= x && x < r.x1 && r.y0 <= y && y < r.y1;
      }));
    }
  }
}

TEST_CASE("a shifted lens moves the picture without turning the view",
          "[render][framing][panels]") {
  Camera c;
  c.eye = glm::vec3(0.3f, -2.0f, 1.1f);
  c.target = glm::vec3(0.1f, 0.2f, 0.3f);
  const float aspect = 16.0f / 9.0f;
  const glm::vec3 p(0.4f, 0.5f, 0.1f);
  auto ndc = [&](const Camera& cam, glm::vec3 q) {
    const glm::vec4 clip = cam.projection(aspect) * cam.view() * glm::vec4(q, 1.0f);
    return glm::vec3(clip) / clip.w;
  };
  Camera shifted = c;
  shifted.lens_shift = glm::vec2(-0.3f, 0.25f);
  CHECK(glm::length(glm::vec2(ndc(shifted, c.target)) - shifted.lens_shift) < 1e-5f);
  CHECK(glm::length(glm::vec2(ndc(shifted, p) - ndc(c, p)) - shifted.lens_shift) < 1e-5f);
  CHECK(std::abs(ndc(shifted, p).z - ndc(c, p).z) < 1e-6f);  // the same depth
}

TEST_CASE("no body of a generated scene goes under a panel, in every preset",
          "[render][framing][panels]") {
  std::mt19937 rng(37032026);
  for (int trial = 0; trial < 8; ++trial) {
    const GeneratedBodies g = generated_bodies(rng, false);
    const scene::Scene s = testing::make_scene(g.toml, "generated");
    for (CameraView view : {CameraView::automatic, CameraView::side, CameraView::top,
                            CameraView::three_quarter, CameraView::follow}) {
      const RenderSettings settings = panel_settings(g, rng, view);
      const FrameRenderer renderer(s.drawing, g.trajectory, settings);
      const FramePanels& panels = renderer.panels();
      INFO("trial " << trial << ", view " << camera_view_names()[static_cast<int>(view)] << ":\n"
                    << g.toml);
      REQUIRE(panels.boxes.size() == 5);  // time panel, inset, legend, title, caption
      // The follow view answers for the followed body (the first) only: the others pass
      // through a moving picture.
      const int checked =
          view == CameraView::follow ? 1 : static_cast<int>(s.drawing.bodies.size());
      for (int k = 0; k <= 40; ++k) {
        const double t = 0.05 * k;
        const Camera camera = renderer.camera(t);
        for (int b = 0; b < checked; ++b) {
          std::vector<glm::vec3> points;
          add_body_points(points, s.drawing, renderer.poses(), b, t);
          const PixelBox body = picture_box(camera, points);
          INFO("t = " << t << ", body " << b << " at [" << body.x0 << ", " << body.x1 << ") x ["
                      << body.y0 << ", " << body.y1 << ")");
          REQUIRE(!body.empty());
          CHECK(body.x0 >= 0);
          CHECK(body.y0 >= 0);
          CHECK(body.x1 <= kWidth);
          CHECK(body.y1 <= kHeight);
          for (const PixelBox& panel : panels.boxes) CHECK(!boxes_overlap(body, panel));
        }
      }
    }
  }
}

TEST_CASE("follow shows its body at the documented fraction of the height, fov zooms it",
          "[render][framing][panels]") {
  std::mt19937 rng(20261207);
  int spheres = 0;
  for (int trial = 0; trial < 40 && spheres < 6; ++trial) {
    const GeneratedBodies g = generated_bodies(rng, true);
    const scene::Scene s = testing::make_scene(g.toml, "generated");
    const BodyVisual& body = s.drawing.bodies[0];
    if (body.kind != BodyVisual::Kind::sphere) continue;
    ++spheres;
    // The sphere's outline: its height in the picture is its diameter's.
    auto picture_height = [&](const FrameRenderer& r, double t) {
      std::vector<glm::vec3> surface;
      const glm::vec3 c = to_glm(r.poses().position(0, t));
      for (int i = 0; i < 48; ++i) {
        for (int j = 0; j <= 24; ++j) {
          const double a = 2.0 * std::numbers::pi * i / 48.0, e = std::numbers::pi * j / 24.0;
          surface.push_back(
              c + static_cast<float>(body.radius) *
                      glm::vec3(std::cos(a) * std::sin(e), std::sin(a) * std::sin(e), std::cos(e)));
        }
      }
      const PixelBox box = picture_box(r.camera(t), surface);
      return static_cast<double>(box.height()) / kHeight;
    };
    std::vector<double> at_fov;
    for (const double fov : {40.0, 34.0}) {
      const RenderSettings settings = panel_settings(g, rng, CameraView::follow, fov);
      const FrameRenderer renderer(s.drawing, g.trajectory, settings);
      const double expected = kFollowFraction * std::tan(glm::radians(kFollowReferenceFov) / 2.0) /
                              std::tan(glm::radians(fov) / 2.0);
      INFO("trial " << trial << ", fov " << fov << ", radius " << body.radius);
      for (const double t : {0.0, 1.0, 2.0}) {
        const double h = picture_height(renderer, t);
        // Pixel rounding and the stretch of a sphere seen off the lens's axis: a few percent.
        CHECK(h == Approx(expected).epsilon(0.06));
      }
      at_fov.push_back(picture_height(renderer, 0.0));
    }
    CHECK(at_fov[1] > 1.12 * at_fov[0]);  // tan(20) / tan(17) = 1.19
  }
  CHECK(spheres >= 3);
}
