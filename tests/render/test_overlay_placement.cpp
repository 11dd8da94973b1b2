// Where the overlays land on generated scenes of every body kind with contacts (issue 37,
// "What must be shown"): a sphere, a box, a cylinder and a ring resting at an odd orientation
// on the floor, and body pairs (a sphere on a box, a box on a box, a sphere on a sphere), with
// random sizes, masses and positions, simulated for a few hundredths of a second and drawn
// from a random camera view with every panel on (time panel, inset, arrows' legend, title,
// caption). On every frame:
// - every point where a body touches the floor or another body (found here from the bodies'
//   shapes and poses, not from the renderer's contact sites) has a badge dot drawn on its
//   projection, and every badge's points are such points;
// - every force arrow starts at such a point: its tail is within a shaft or two of it (for a
//   round body, beside it: outside the body, on the camera's side), never inside a body, and
//   every pixel the arrows draw lies on an arrow from such a tail;
// - no body's picture overlaps a panel or leaves the frame.
// test_contact_overlays.cpp follows one wheel in detail, test_panel_framing.cpp the framing
// of moving bodies without contacts, test_urdf_meshes_render.cpp the badges of tree joints.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/simulation.hpp"
#include "generated_mechanism.hpp"
#include "image/png.hpp"
#include "overlay_pixels.hpp"
#include "render/camera.hpp"
#include "render/contact_sites.hpp"
#include "render/force_arrows.hpp"
#include "render/regime_badges.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "scene/scene.hpp"

using namespace stiction;
using namespace stiction::render;
using testing::nearest;
namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 640, kHeight = 360;

// A body as the test knows it: its shape in its own terms, independent of the drawing.
struct TestBody {
  enum class Kind { sphere, box, cylinder };
  std::string name;
  Kind kind = Kind::sphere;
  double radius = 0.0;                    // sphere, cylinder
  core::Vec3 size = core::Vec3::Zero();   // box
  double length = 0.0;                    // cylinder
  core::Vec3 axis = core::Vec3::UnitZ();  // cylinder, body frame
  bool hollow = false;                    // cylinder: a ring
  double mass = 1.0;
  core::Vec3 position = core::Vec3::Zero();
  core::Quat orientation = core::Quat::Identity();

  double size_scale() const {
    return kind == Kind::box ? size.maxCoeff()
                             : 2.0 * std::max(radius, kind == Kind::cylinder ? 0.5 * length : 0.0);
  }
  // How far it reaches below its centre, turned by q: where it stands on a plane.
  double depth_below(const core::Quat& q) const {
    const core::Vec3 down = -core::Vec3::UnitZ();
    switch (kind) {
      case Kind::sphere:
        return radius;
      case Kind::box: {
        const core::Vec3 l = q.conjugate() * down;
        return 0.5 * (std::abs(l.x()) * size.x() + std::abs(l.y()) * size.y() +
                      std::abs(l.z()) * size.z());
      }
      case Kind::cylinder: {
        const double along = std::abs((q * axis).dot(down));
        return 0.5 * length * along + radius * std::sqrt(std::max(0.0, 1.0 - along * along));
      }
    }
    return 0.0;
  }
  // Is world point p strictly inside the body at pose (c, q), by `margin`?
  bool contains(const core::Vec3& c, const core::Quat& q, const core::Vec3& p,
                double margin) const {
    const core::Vec3 l = q.conjugate() * (p - c);
    switch (kind) {
      case Kind::sphere:
        return l.norm() < radius - margin;
      case Kind::box:
        return std::abs(l.x()) < 0.5 * size.x() - margin &&
               std::abs(l.y()) < 0.5 * size.y() - margin &&
               std::abs(l.z()) < 0.5 * size.z() - margin;
      case Kind::cylinder: {
        const double along = l.dot(axis);
        // A ring is drawn as a solid wheel with dark bores: an arrow inside it is hidden too.
        return std::abs(along) < 0.5 * length - margin &&
               (l - along * axis).norm() < radius - margin;
      }
    }
    return false;
  }
  // The points of its surface that can touch a plane below it or a body under it: a
  // sphere's lowest point, a box's corners, each rim's lowest point.
  std::vector<core::Vec3> low_points(const core::Vec3& c, const core::Quat& q) const {
    std::vector<core::Vec3> out;
    switch (kind) {
      case Kind::sphere:
        out.push_back(c - radius * core::Vec3::UnitZ());
        break;
      case Kind::box:
        for (int k = 0; k < 8; ++k) {
          out.push_back(c + q * core::Vec3(((k & 1) ? 0.5 : -0.5) * size.x(),
                                           ((k & 2) ? 0.5 : -0.5) * size.y(),
                                           ((k & 4) ? 0.5 : -0.5) * size.z()));
        }
        break;
      case Kind::cylinder: {
        const core::Vec3 a = q * axis;
        const core::Vec3 down = -core::Vec3::UnitZ() + a.z() * a;  // -z across the axis
        const core::Vec3 u =
            down.norm() > 1e-9 ? core::Vec3(down.normalized()) : core::Vec3::UnitX();
        for (const double side : {-0.5, 0.5}) out.push_back(c + side * length * a + radius * u);
        break;
      }
    }
    return out;
  }
  // Points spread over its surface (its picture's outline is among them).
  std::vector<glm::vec3> surface_points(const core::Vec3& c, const core::Quat& q) const {
    std::vector<glm::vec3> out;
    auto add = [&](const core::Vec3& local) { out.push_back(to_glm(core::Vec3(c + q * local))); };
    switch (kind) {
      case Kind::sphere:
        for (int i = 0; i < 24; ++i) {
          for (int j = 0; j <= 12; ++j) {
            const double a = 2.0 * std::numbers::pi * i / 24.0, e = std::numbers::pi * j / 12.0;
            add(radius *
                core::Vec3(std::cos(a) * std::sin(e), std::sin(a) * std::sin(e), std::cos(e)));
          }
        }
        break;
      case Kind::box:
        for (int k = 0; k < 8; ++k) {
          add(core::Vec3(((k & 1) ? 0.5 : -0.5) * size.x(), ((k & 2) ? 0.5 : -0.5) * size.y(),
                         ((k & 4) ? 0.5 : -0.5) * size.z()));
        }
        break;
      case Kind::cylinder: {
        const core::Vec3 u = axis.unitOrthogonal(), v = axis.cross(u);
        for (int i = 0; i < 48; ++i) {
          const double a = 2.0 * std::numbers::pi * i / 48.0;
          for (const double side : {-0.5, 0.5}) {
            add(side * length * axis + radius * (std::cos(a) * u + std::sin(a) * v));
          }
        }
        break;
      }
    }
    return out;
  }
};

std::string toml_body(const TestBody& b) {
  std::ostringstream s;
  s.precision(12);
  s << "[bodies." << b.name << "]\ntype = \"rigid_body\"\nmass = " << b.mass << "\n";
  switch (b.kind) {
    case TestBody::Kind::sphere:
      s << "shape = \"sphere\"\nradius = " << b.radius << "\n";
      break;
    case TestBody::Kind::box:
      s << "shape = \"box\"\nsize = " << testing::vec(b.size) << "\n";
      break;
    case TestBody::Kind::cylinder:
      s << "shape = \"cylinder\"\nradius = " << b.radius << "\nlength = " << b.length
        << "\naxis = " << testing::vec(b.axis) << "\nhollow = " << (b.hollow ? "true" : "false")
        << "\n";
      break;
  }
  const core::Quat& q = b.orientation;
  s << "position = [" << b.position.x() << ", " << b.position.y() << ", " << b.position.z()
    << "]\norientation = [" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]\n";
  return s.str();
}

struct GeneratedContacts {
  std::string what;
  std::vector<TestBody> bodies;
  // Which pairs touch (indices into bodies): first the one on top (`body`), then `other`.
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> on_floor;
  std::string toml;
};

// Kinds of scene: 0 sphere, 1 box, 2 cylinder, 3 ring on the floor; 4 a sphere on a box,
// 5 a box on a box, 6 a sphere on a sphere.
GeneratedContacts generate(std::mt19937& rng, int kind) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto random_q = [&] {
    return core::Quat(
        Eigen::AngleAxisd(std::numbers::pi * (2.0 * u(rng) - 1.0), testing::random_unit(rng)));
  };
  auto yaw = [&] { return core::Quat(Eigen::AngleAxisd(6.0 * u(rng), core::Vec3::UnitZ())); };
  auto scale = [&] { return 0.05 + 0.35 * u(rng); };  // 5 to 40 cm
  GeneratedContacts g;
  TestBody first;
  first.name = "first";
  first.mass = 0.3 + 3.0 * u(rng);
  if (kind == 0 || kind == 6) {
    first.kind = TestBody::Kind::sphere;
    first.radius = 0.5 * scale();
  } else if (kind == 1 || kind == 4 || kind == 5) {
    first.kind = TestBody::Kind::box;
    first.size = core::Vec3(scale(), scale(), scale());
  } else {
    first.kind = TestBody::Kind::cylinder;
    first.radius = 0.5 * scale();
    first.length = 0.3 * scale();
    first.axis = testing::random_unit(rng);
    first.hollow = kind == 3;
  }
  // On the floor at an odd orientation (pairs: a box lies flat, turned about the vertical,
  // so the body on it rests).
  first.orientation = kind >= 4 && first.kind == TestBody::Kind::box ? yaw() : random_q();
  first.position = core::Vec3(u(rng) - 0.5, u(rng) - 0.5, first.depth_below(first.orientation));
  g.bodies.push_back(first);
  g.on_floor.push_back(0);
  const char* names[] = {"a sphere",          "a box",          "a cylinder",          "a ring",
                         "a sphere on a box", "a box on a box", "a sphere on a sphere"};
  g.what = names[kind];
  if (kind >= 4) {
    TestBody second;
    second.name = "second";
    second.mass = 0.2 + 1.0 * u(rng);
    second.orientation = random_q();
    const double top = first.position.z() + first.depth_below(first.orientation);
    core::Vec3 at = first.position;
    if (kind == 5) {
      second.kind = TestBody::Kind::box;
      second.orientation = yaw();
      // Smaller than the box under it and within its top face.
      second.size = core::Vec3(0.5 + 0.4 * u(rng), 0.5 + 0.4 * u(rng), 0.5 + 1.0 * u(rng))
                        .cwiseProduct(core::Vec3(first.size.minCoeff(), first.size.minCoeff(),
                                                 first.size.z()));
    } else {
      second.kind = TestBody::Kind::sphere;
      second.radius = 0.5 * scale();
      if (kind == 4) {
        // Anywhere over the box's top face.
        at += first.orientation * core::Vec3((u(rng) - 0.5) * 0.8 * first.size.x(),
                                             (u(rng) - 0.5) * 0.8 * first.size.y(), 0.0);
      } else {
        // On the lower sphere, off its top by up to 30 degrees.
        const double tilt = 0.5 * u(rng), turn = 6.0 * u(rng);
        const core::Vec3 n(std::sin(tilt) * std::cos(turn), std::sin(tilt) * std::sin(turn),
                           std::cos(tilt));
        second.position = first.position + (first.radius + second.radius) * n;
      }
    }
    if (kind != 6)
      second.position = core::Vec3(at.x(), at.y(), top + second.depth_below(second.orientation));
    g.bodies.push_back(second);
    g.pairs.emplace_back(1, 0);
  }
  std::ostringstream toml;
  toml << "name = \"generated contacts\"\ndescription = \"" << g.what << "\"\n"
       << "[simulation]\nintegrator = \"rk4\"\ndt = 5e-5\nduration = 0.04\noutput_rate = 4000.0\n";
  for (const TestBody& b : g.bodies) toml << toml_body(b);
  toml << "[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"first\"\nstiffness = 1e6\n"
          "damping = 200.0\nmu = 0.5\n";
  if (!g.pairs.empty()) {
    toml << "[impedances.touch]\ntype = \"kikuuwe_contact\"\nbody = \"second\"\nother = \"first\"\n"
            "stiffness = 1e6\ndamping = 200.0\nmu = 0.5\n";
  }
  toml << R"([overlay]
signal = "first.p.z"
label = "height of the first body"
unit = "m"
title = "Generated contacts: badges and arrows at the contact points"
caption = "Every badge dot and force arrow sits where a body touches"
forces = true
[inset]
signals = ["first.p.z"]
position = ")"
       << std::vector<std::string>{"top_left", "top_right", "bottom_left",
                                   "bottom_right"}[rng() % 4]
       << "\"\n";
  g.toml = toml.str();
  return g;
}

// Pixels that differ between two frames of the same size, outside the panels.
std::vector<glm::vec2> changed(const image::Image& a, const image::Image& b,
                               const FramePanels& panels) {
  return testing::changed_pixels(a, b, [&](int x, int y) {
    const PixelBox pixel{x, y, x + 1, y + 1};
    return std::any_of(panels.boxes.begin(), panels.boxes.end(),
                       [&](const PixelBox& p) { return boxes_overlap(pixel, p); });
  });
}

float segment_distance(const glm::vec2& p, const glm::vec2& a, const glm::vec2& b) {
  const glm::vec2 ab = b - a;
  const float l2 = glm::dot(ab, ab);
  const float s = l2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / l2, 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + s * ab));
}

// The trajectory with every contact force column zeroed (its arrows vanish, nothing else).
core::Trajectory without_forces(const core::Trajectory& tr, const ContactSites& sites) {
  std::vector<int> zero;
  for (const ContactSite& s : sites.contacts) {
    for (const char* a : {".f.x", ".f.y", ".f.z"}) {
      if (const auto c = tr.find(s.name + a)) zero.push_back(*c);
    }
  }
  core::Trajectory out(tr.columns());
  std::vector<double> row(static_cast<std::size_t>(tr.column_count()));
  for (int r = 0; r < tr.row_count(); ++r) {
    std::copy(tr.row(r), tr.row(r) + tr.column_count(), row.begin());
    for (int c : zero) row[static_cast<std::size_t>(c)] = 0.0;
    out.append(row.data());
  }
  return out;
}

void save(const image::Image& frame, const std::string& name) {
  const fs::path dir = fs::path(STICTION_TEST_OUTPUT_DIR) / "overlay_placement";
  fs::create_directories(dir);
  image::write_png(dir / name, frame);
}

}  // namespace

TEST_CASE(
    "generated bodies of every kind: badges and force arrows at the contact points, no "
    "body under a panel",
    "[render][overlays][badges][forces][panels]") {
  std::mt19937 rng(37370);
  const CameraView views[] = {CameraView::automatic, CameraView::side, CameraView::three_quarter,
                              CameraView::follow, CameraView::top};
  for (int trial = 0; trial < 14; ++trial) {
    const int kind = trial % 7;
    const GeneratedContacts g = generate(rng, kind);
    const CameraView view = views[rng() % 5];
    INFO("trial " << trial << ": " << g.what << ", view "
                  << camera_view_names()[static_cast<int>(view)] << "\n"
                  << g.toml);
    scene::Scene s = scene::load_scene(scene::SceneSource::from_text(g.toml, "generated.toml"));
    const core::RunResult run = core::simulate(*s.network, s.run);
    REQUIRE_FALSE(run.instability);
    const core::Trajectory& tr = run.trajectory;
    const double t = 0.03;

    RenderSettings settings = read_render_settings(s);
    settings.width = kWidth;
    settings.height = kHeight;
    settings.camera.view = view;
    settings.slow_motion = 20.0;  // a frame stands for 1.7 ms: the poses of time t
    settings.overlay.layers.badges = false;
    // One force scale for the frames with and without forces (same arrows' legend and so the
    // same panels and camera): the largest force at t is 0.5 body sizes.
    double largest = 0.0, size = 0.0;
    for (const TestBody& b : g.bodies) size = std::max(size, b.size_scale());
    {
      const PoseTrack poses(tr, s.drawing);
      for (const ContactSite& c : s.drawing.sites.contacts) {
        const ContactForce f = contact_force(c, poses, t);
        largest = std::max({largest, f.normal.norm(), f.friction.norm()});
      }
    }
    REQUIRE(largest > 0.0);
    settings.overlay.layers.force_scale = largest / (0.5 * size);
    RenderSettings badged = settings;
    badged.overlay.layers.badges = true;

    const core::Trajectory unforced = without_forces(tr, s.drawing.sites);
    FrameRenderer plain(s.drawing, tr, settings);
    FrameRenderer bare(s.drawing, unforced, settings);
    FrameRenderer with_badges(s.drawing, tr, badged);
    const image::Image arrows_frame = plain.render(t);
    const image::Image badges_frame = with_badges.render(t);
    const image::Image bare_frame = bare.render(t);
    if (trial < 7) save(badges_frame, "trial_" + std::to_string(trial) + ".png");
    const FramePanels& panels = plain.panels();
    REQUIRE(panels.boxes.size() == 5);  // time panel, inset, legend, title, caption
    const Camera camera = plain.camera(t);
    const glm::mat4 vp = camera.projection(float(kWidth) / float(kHeight)) * camera.view();
    // The same camera in every frame (the panels are the same).
    const Camera other = with_badges.camera(t);
    REQUIRE(glm::length(other.eye - camera.eye) < 1e-5f);

    // Where the bodies touch, from their shapes and poses at t: their low points that are on
    // the floor or on the body under them (within 0.1% of the body's size).
    auto pose = [&](int i) {
      return std::pair{plain.poses().position(i, t), plain.poses().orientation(i, t)};
    };
    std::vector<core::Vec3> touching;
    for (int i : g.on_floor) {
      const auto [c, q] = pose(i);
      const TestBody& b = g.bodies[static_cast<std::size_t>(i)];
      for (const core::Vec3& p : b.low_points(c, q)) {
        if (p.z() < 1e-3 * b.size_scale()) touching.push_back(p);
      }
    }
    for (const auto& [upper, lower] : g.pairs) {
      const auto [cu, qu] = pose(upper);
      const auto [cl, ql] = pose(lower);
      const TestBody& bu = g.bodies[static_cast<std::size_t>(upper)];
      const TestBody& bl = g.bodies[static_cast<std::size_t>(lower)];
      if (bl.kind == TestBody::Kind::sphere) {  // a sphere on a sphere: on the line of centres
        const core::Vec3 n = (cu - cl).normalized();
        if ((cu - cl).norm() < bu.radius + bl.radius + 1e-3 * bu.size_scale())
          touching.push_back(cl + bl.radius * n);
        continue;
      }
      // On a box lying flat: the upper body's low points at the box's top.
      const double top = cl.z() + 0.5 * bl.size.z();
      for (const core::Vec3& p : bu.low_points(cu, qu)) {
        const double gap = p.z() - top;  // below 0: pressed into it
        if (gap < 1e-3 * bu.size_scale() && gap > -0.05 * bu.size_scale()) touching.push_back(p);
      }
    }
    REQUIRE(!touching.empty());
    auto pixel_of = [&](const core::Vec3& p) {
      glm::vec2 px;
      REQUIRE(project(vp, to_glm(p), kWidth, kHeight, px));
      return px;
    };
    auto in_frame = [&](glm::vec2 p) {
      return p.x > 3.0f && p.y > 3.0f && p.x < kWidth - 3.0f && p.y < kHeight - 3.0f;
    };

    // Badges: a dot on every touching point, and only there.
    RegimeBadges badges(s.drawing, s.drawing.sites, with_badges.poses(), kHeight);
    const std::vector<Badge> all =
        badges.badges(with_badges.poses(), t, vp, kWidth, kHeight, 1.0 / (30.0 * 20.0));
    const std::vector<glm::vec2> badge_pixels = changed(badges_frame, arrows_frame, panels);
    for (const Badge& b : all) {
      for (const glm::vec2& p : b.points) {
        float best = std::numeric_limits<float>::infinity();
        for (const core::Vec3& e : touching) best = std::min(best, glm::length(pixel_of(e) - p));
        INFO("badge '" << b.text() << "' point at " << p.x << "," << p.y);
        CHECK(best < 2.0f);
      }
    }
    for (const core::Vec3& e : touching) {
      const glm::vec2 px = pixel_of(e);
      INFO("touching point " << e.transpose() << " at pixel " << px.x << "," << px.y);
      bool in_badge = false;
      for (const Badge& b : all) {
        for (const glm::vec2& p : b.points) in_badge |= glm::length(p - px) < 2.0f;
      }
      CHECK(in_badge);
      if (in_frame(px)) CHECK(nearest(badge_pixels, px) < 2.0f);  // its dot is drawn
    }

    // Arrows: each starts by a touching point, outside every body; every arrow pixel lies on
    // one of them.
    ArrowScales scales = choose_arrow_scales(s.drawing, s.drawing.sites, plain.poses(),
                                             settings.overlay.layers, 1.0 / (30.0 * 20.0));
    struct Drawn {
      glm::vec2 tail, tip;
      float half_width;  // pixels: the head's radius
    };
    std::vector<Drawn> arrows;
    for (const ContactSite& c : s.drawing.sites.contacts) {
      const ContactForce f = contact_force(c, plain.poses(), t, 1.0 / (30.0 * 20.0));
      if (f.normal.isZero(0.0) && f.friction.isZero(0.0)) continue;
      const core::Vec3 tail = force_arrow_tail(c, plain.poses(), t, scales, camera.eye);
      INFO("arrow of " << c.name << " from " << tail.transpose());
      double from_contact = std::numeric_limits<double>::infinity();
      for (const core::Vec3& e : touching) from_contact = std::min(from_contact, (tail - e).norm());
      // Beside its point: off a corner by a couple of shafts, beside a ball by its radius, off
      // a wheel's face by at most its size.
      double allowed = 4.0 * scales.shaft_radius;
      const TestBody& body = g.bodies[static_cast<std::size_t>(c.body)];
      const TestBody* other = c.other >= 0 ? &g.bodies[static_cast<std::size_t>(c.other)] : nullptr;
      for (const TestBody* b : {&body, other}) {
        if (b == nullptr) continue;
        if (b->kind == TestBody::Kind::sphere)
          allowed = std::max(allowed, 1.1 * b->radius + 4.0 * scales.shaft_radius);
        if (b->kind == TestBody::Kind::cylinder)
          allowed = std::max(allowed, 2.0 * b->radius + b->length + 4.0 * scales.shaft_radius);
      }
      CHECK(from_contact < allowed);
      for (int i = 0; i < static_cast<int>(g.bodies.size()); ++i) {
        const auto [bc, bq] = pose(i);
        INFO("inside body " << g.bodies[static_cast<std::size_t>(i)].name);
        CHECK_FALSE(g.bodies[static_cast<std::size_t>(i)].contains(bc, bq, tail,
                                                                   0.5 * scales.shaft_radius));
      }
      const glm::vec4 at_tail = camera.view() * glm::vec4(to_glm(tail), 1.0f);
      const float pixels_per_metre =
          kHeight / (2.0f * std::tan(glm::radians(camera.fov_y_degrees) * 0.5f) * -at_tail.z);
      for (const core::Vec3& v : {f.normal, f.friction}) {
        if (v.isZero(0.0)) continue;
        core::Vec3 arrow = v / scales.force;
        if (arrow.norm() > scales.max_length) arrow *= scales.max_length / arrow.norm();
        arrows.push_back({pixel_of(tail), pixel_of(tail + arrow),
                          2.2f * scales.shaft_radius * pixels_per_metre});
      }
    }
    const std::vector<glm::vec2> arrow_pixels = changed(arrows_frame, bare_frame, panels);
    CHECK(!arrow_pixels.empty());
    int stray = 0;
    for (const glm::vec2& p : arrow_pixels) {
      bool on_arrow = false;
      for (const Drawn& a : arrows)
        on_arrow |= segment_distance(p, a.tail, a.tip) < a.half_width + 2.5f;
      stray += on_arrow ? 0 : 1;
    }
    CHECK(stray == 0);

    // No body under a panel, none out of the frame (the follow view answers for its body).
    const int checked = view == CameraView::follow ? 1 : static_cast<int>(g.bodies.size());
    for (int i = 0; i < checked; ++i) {
      const auto [c, q] = pose(i);
      float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
      for (const glm::vec3& p : g.bodies[static_cast<std::size_t>(i)].surface_points(c, q)) {
        glm::vec2 px;
        REQUIRE(project(vp, p, kWidth, kHeight, px));
        x0 = std::min(x0, px.x), x1 = std::max(x1, px.x), y0 = std::min(y0, px.y),
        y1 = std::max(y1, px.y);
      }
      const PixelBox box{static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0)),
                         static_cast<int>(std::ceil(x1)), static_cast<int>(std::ceil(y1))};
      INFO("body " << i << " at [" << box.x0 << ", " << box.x1 << ") x [" << box.y0 << ", "
                   << box.y1 << ")");
      CHECK(box.x0 >= 0);
      CHECK(box.y0 >= 0);
      CHECK(box.x1 <= kWidth);
      CHECK(box.y1 <= kHeight);
      for (const PixelBox& panel : panels.boxes) CHECK(!boxes_overlap(box, panel));
    }
  }
}
