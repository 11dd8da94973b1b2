// The mechanism's drawing (mechanism_items.hpp) on GENERATED scenes: springs between random
// anchors of randomly turned bodies and the world, random force and torque sources, belts in
// random directions and planes tilting about random axes. Each element must be where the
// scene puts it: coil ends on the anchors, posts under world ends, arrows ending at the
// application point along the force, arcs about the torque's axis with its sign, rollers at
// the belt's ends under its surface, the axle along the tilt axis through the pivot.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "generated_mechanism.hpp"
#include "render/mechanism_items.hpp"
#include "render/scene_geometry.hpp"
#include "render/spring_coil.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;
using namespace stiction::render::testing;

namespace {

float distance_to_segment(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = b - a;
  const float s = glm::clamp(glm::dot(p - a, d) / glm::dot(d, d), 0.0f, 1.0f);
  return glm::length(p - (a + s * d));
}

}  // namespace

TEST_CASE("coils run from anchor to anchor within their radius", "[render][mechanism]") {
  std::mt19937 rng(2026120201);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  for (int trial = 0; trial < 50; ++trial) {
    const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    CoilShape shape;
    shape.coil_radius = 0.01f + 0.05f * std::abs(u(rng));
    shape.turns = 3 + trial % 9;
    const std::vector<glm::vec3> path = coil_path(a, b, shape);
    REQUIRE(path.size() == static_cast<std::size_t>(shape.turns * shape.segments_per_turn + 3));
    CHECK(glm::length(path.front() - a) == 0.0f);
    CHECK(glm::length(path.back() - b) == 0.0f);
    float widest = 0.0f;
    for (const glm::vec3& p : path) {
      const float r = distance_to_segment(p, a, b);
      CHECK(r <= shape.coil_radius * 1.001f + 1e-5f);
      widest = std::max(widest, r);
    }
    CHECK(widest > 0.99f * shape.coil_radius);  // a helix, not a line
    std::vector<DrawItem> items;
    add_tube(items, path, 0.1f * shape.coil_radius, Material{});
    CHECK(items.size() + 1 == path.size());  // one cylinder per segment
  }
}

TEST_CASE("springs, posts and source arrows sit where generated scenes put them",
          "[render][mechanism]") {
  std::mt19937 rng(20261202);
  for (int trial = 0; trial < 25; ++trial) {
    const Generated g = generated_mechanism(rng);
    const scene::Scene s = testing::make_scene(g.toml, "generated");
    const Drawing scene = s.drawing;
    const PoseTrack poses(g.trajectory, scene);
    const MechanismFrame frame = mechanism_frame(scene, poses);
    INFO("trial " << trial << ":\n" << g.toml);
    REQUIRE(!scene.springs.empty());
    REQUIRE(scene.sources.size() == 2);
    for (double t : {0.0, 0.7, 2.0}) {
      for (std::size_t i = 0; i < scene.springs.size(); ++i) {
        const SpringVisual& sp = scene.springs[i];
        const BodyVisual& body = scene.bodies[static_cast<std::size_t>(sp.body)];
        const glm::vec3 lift = body.kind == BodyVisual::Kind::block
                                   ? to_glm(0.5 * body.size.z() * body.up)
                                   : glm::vec3(0.0f);
        const SpringEnds e = spring_ends(scene, poses, frame, static_cast<int>(i), t);
        const glm::vec3 anchor =
            to_glm(poses.position(sp.body, t) + poses.orientation(sp.body, t) * sp.point) + lift;
        CHECK(glm::length(e.a - anchor) < 1e-5f);
        if (sp.other >= 0) {
          CHECK_FALSE(e.post);
          const BodyVisual& other = scene.bodies[static_cast<std::size_t>(sp.other)];
          const glm::vec3 other_lift = other.kind == BodyVisual::Kind::block
                                           ? to_glm(0.5 * other.size.z() * other.up)
                                           : glm::vec3(0.0f);
          const glm::vec3 b = to_glm(poses.position(sp.other, t) +
                                     poses.orientation(sp.other, t) * sp.other_point) +
                              other_lift;
          CHECK(glm::length(e.b - b) < 1e-5f);
        } else {
          // A post from the floor straight up to the world end, which is the scene's point
          // (or, for a short zero-length spring, that point set back away from the body).
          CHECK(e.post);
          CHECK(e.post_foot.x == e.b.x);
          CHECK(e.post_foot.y == e.b.y);
          CHECK(e.post_foot.z < e.b.z);
          const glm::vec3 setback = e.b - lift - to_glm(sp.other_point);
          if (sp.free_length > 0.0) CHECK(glm::length(setback) < 1e-5f);
          const float piece = static_cast<float>(piece_size(body));
          CHECK(glm::length(setback) <= 3.5f * piece + 1e-4f);
        }
      }
      for (std::size_t i = 0; i < scene.sources.size(); ++i) {
        const SourceVisual& src = scene.sources[i];
        const double value = 3.0 * t;
        if (src.kind == SourceVisual::Kind::force) {
          const auto arrow = force_arrow(scene, poses, frame, static_cast<int>(i), t);
          if (t == 0.0) {
            CHECK_FALSE(arrow);  // a zero force has no arrow
            continue;
          }
          REQUIRE(arrow);
          const core::Vec3 point =
              poses.position(src.body, t) + poses.orientation(src.body, t) * src.point;
          CHECK(glm::length(arrow->tail + arrow->vector - to_glm(point)) < 1e-5f);
          core::Vec3 f(poses.signal(src.name + ".f.x", t), poses.signal(src.name + ".f.y", t),
                       poses.signal(src.name + ".f.z", t));
          if (src.body_frame) f = poses.orientation(src.body, t) * f;
          CHECK(glm::dot(glm::normalize(arrow->vector), to_glm(f.normalized())) > 0.9999f);
          // In proportion: 2.5 body pieces at the run's peak (6 at t = 2).
          const double piece = piece_size(scene.bodies[static_cast<std::size_t>(src.body)]);
          CHECK(glm::length(arrow->vector) == Approx(2.5 * piece * value / 6.0).epsilon(1e-4));
        } else {
          const auto arc = torque_arc(scene, poses, frame, static_cast<int>(i), t);
          if (t == 0.0) {
            CHECK_FALSE(arc);
            continue;
          }
          REQUIRE(arc);
          const glm::vec3 axis = glm::normalize(to_glm(poses.orientation(src.body, t) * src.axis));
          CHECK(std::abs(glm::dot(arc->axis, axis)) > 0.9999f);
          CHECK(std::abs(glm::dot(arc->start, arc->axis)) < 1e-4f);
          const double tau = poses.signal(src.name + ".tau", t);
          CHECK(arc->sweep == Approx(1.5 * std::numbers::pi * tau / 6.0).epsilon(1e-4));
        }
      }
    }
  }
}

TEST_CASE("belts get rollers at their ends and tilting planes an axle through the pivot",
          "[render][mechanism]") {
  std::mt19937 rng(1202);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    // A belt in a random direction of a random (mostly upward) plane, bounded or endless
    // along it; a board tilting about a random in-plane axis through a random pivot.
    const core::Vec3 n = (core::Vec3::UnitZ() + 0.3 * random_unit(rng)).normalized();
    const double offset = 0.2 * u(rng);
    const core::Vec3 r0 = random_unit(rng);
    const core::Vec3 dir = (r0 - r0.dot(n) * n).normalized();
    const core::Vec3 across = n.cross(dir);
    const core::Vec3 along_rest = (dir - dir.dot(n) * n).normalized();
    const bool bounded = trial % 2 == 0;
    const double half = 0.5 + (u(rng) + 1.0);
    const core::Vec3 pivot(u(rng), u(rng), 0.0);
    const core::Vec3 tilt_axis =
        (core::Vec3(u(rng), u(rng), 0.0) + 0.1 * core::Vec3::UnitY()).normalized();
    std::string toml =
        "name = \"surfaces\"\n[bodies.ball]\ntype = \"rigid_body\"\nshape = "
        "\"sphere\"\nradius = 0.1\nmass = 1.0\nposition = [0.0, 0.0, 0.5]\n";
    toml += "[impedances.belt]\ntype = \"kikuuwe_contact\"\nbody = \"ball\"\nnormal = " + vec(n) +
            "\noffset = " + std::to_string(offset) +
            "\nbelt_speed = 0.3\nbelt_direction = " + vec(dir) +
            "\nextent = { axis = " + vec(along_rest) + ", min = [" +
            (bounded ? std::to_string(-half) : std::string("-inf")) + ", -0.2], max = [" +
            (bounded ? std::to_string(half) : std::string("inf")) + ", 0.2] }\n";
    toml +=
        "[impedances.board]\ntype = \"kikuuwe_contact\"\nbody = \"ball\"\noffset = -0.6\n"
        "tilt = \"0.2*t\"\ntilt_axis = " +
        vec(tilt_axis) + "\ntilt_pivot = " + vec(pivot + core::Vec3(0.0, 0.0, -0.6)) +
        "\nextent = { axis = [1.0, 0.0, 0.0], min = [-1.0, -0.7], max = [1.0, 0.7] }\n";
    INFO("trial " << trial << ":\n" << toml);
    const scene::Scene s = testing::make_scene(toml, "surfaces");
    const Drawing scene = s.drawing;
    core::Trajectory tr(
        {"t", "ball.p.x", "ball.p.y", "ball.p.z", "ball.q.w", "ball.q.x", "ball.q.y", "ball.q.z"});
    for (int i = 0; i <= 20; ++i) {
      const double row[] = {0.1 * i, 0.02 * i, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0};
      tr.append(row);
    }
    const PoseTrack poses(tr, scene);
    const MechanismFrame frame = mechanism_frame(scene, poses);
    REQUIRE(scene.surfaces.size() == 2);
    const SurfaceVisual& belt = scene.surfaces[0];
    const SurfaceVisual& board = scene.surfaces[1];
    CHECK_FALSE(pivot_axle(frame, belt, 1.0));
    CHECK_FALSE(belt_rollers(scene, frame, board));
    const auto r = belt_rollers(scene, frame, belt);
    REQUIRE(r);
    const core::Vec3 d = belt.moving->belt_direction();
    CHECK(std::abs(glm::dot(r->axis, to_glm(d))) < 1e-4f);
    CHECK(std::abs(glm::dot(r->axis, to_glm(n))) < 1e-4f);
    const glm::vec3 origin = to_glm(offset * n);
    for (int k = 0; k < 2; ++k) {
      // Tangent under the surface, at the belt's ends: its extent's, or around the scene.
      CHECK(glm::dot(r->centre[k] - origin, to_glm(n)) == Approx(-r->radius).margin(1e-4));
      CHECK(glm::dot(r->centre[k] - origin, to_glm(d)) ==
            Approx(k == 0 ? r->span_min : r->span_max).margin(1e-4));
    }
    CHECK(r->span_max > r->span_min);
    if (bounded) {
      CHECK(r->span_max - r->span_min == Approx(2.0 * half).margin(1e-4));
    } else {
      // Endless: the ball's whole run lies between the rollers.
      for (const glm::vec3& c : {frame.run.min, frame.run.max}) {
        const float x = glm::dot(c - origin, to_glm(d));
        CHECK(x > r->span_min);
        CHECK(x < r->span_max);
      }
    }
    CHECK(std::abs(glm::dot(to_glm(across), r->axis)) > 0.9999f);
    for (double t : {0.0, 1.0, 2.0}) {
      const auto axle = pivot_axle(frame, board, t);
      REQUIRE(axle);
      const glm::vec3 along = glm::normalize(axle->b - axle->a);
      CHECK(std::abs(glm::dot(along, to_glm(tilt_axis))) > 0.9999f);
      // Through the pivot line, one axle radius under the tilted board.
      const glm::vec3 p = to_glm(board.moving->motion().pivot);
      const glm::vec3 off = axle->a - p - glm::dot(axle->a - p, along) * along;
      CHECK(glm::length(off) == Approx(axle->radius).epsilon(1e-3));
      const core::Vec3 normal = board.moving->surface(t).rotation * board.normal;
      CHECK(glm::dot(glm::normalize(off), to_glm(normal)) < -0.999f);
      // As long as the board is wide along its axis.
      CHECK(glm::length(axle->b - axle->a) >= 1.4f * 0.99f);
    }
  }
}
