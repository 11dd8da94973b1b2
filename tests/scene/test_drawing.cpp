// The drawing the scene builder fills beside the network (scene/drawing.hpp): generated scenes
// of every body kind with random sizes, odd orientations and several components; what is
// drawn must match what each table declares and what the network wires, and a cylinder's or
// ring's contact sites must sit on its rim where it touches the plane.
#include <toml++/toml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "core/network.hpp"
#include "scene/scene.hpp"
#include "scene/urdf_loader.hpp"

using namespace stiction;
using core::Quat;
using core::Vec3;

namespace {

scene::Scene build(const std::string& text) {
  return scene::build_scene(toml::parse(std::string_view(text), std::string_view("drawing.toml")),
                            "drawing.toml");
}

std::string vec(const Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

Quat random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
}

// The body the network wires element `name` to (its map's first admittance).
std::string wired_body(const core::Network& network, const std::string& name) {
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    if (network.impedances()[i]->name() != name) continue;
    const auto wired = network.map_of(static_cast<int>(i)).admittances();
    return wired.empty() ? "" : wired.front()->name();
  }
  return "(no element " + name + ")";
}

const scene::ContactSite& site_named(const scene::Drawing& d, const std::string& name) {
  for (const auto& s : d.sites.contacts) {
    if (s.name == name) return s;
  }
  FAIL("no contact site " << name);
  throw std::logic_error("unreachable");
}

}  // namespace

TEST_CASE("drawing: generated scenes of every body kind draw what their tables declare",
          "[scene][drawing]") {
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 25; ++trial) {
    const double ball_r = 0.02 + 0.5 * u(rng);
    const Vec3 box_size(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng));
    const Quat box_q = random_rotation(rng);
    const double wheel_r = 0.01 + 0.3 * u(rng), wheel_l = 0.002 + 0.2 * u(rng);
    const Vec3 wheel_axis = random_unit(rng);
    const bool ring = u(rng) < 0.5;
    const Vec3 floor_n = (Vec3(0.0, 0.0, 1.0) + 0.3 * random_unit(rng)).normalized();
    const double floor_offset = u(rng) - 0.5;
    const double link0 = 0.1 + u(rng), link1 = 0.1 + u(rng), width0 = 0.01 + 0.05 * u(rng);
    const Vec3 spring_point(u(rng), u(rng), u(rng));
    const std::string text =
        "name = \"drawing\"\n"
        "[bodies.ball]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"sphere\"\nradius = " +
        num(ball_r) + "\nposition = [0.0, 0.0, " + num(ball_r) +
        "]\n"
        "[bodies.crate]\ntype = \"rigid_body\"\nmass = 2.0\nshape = \"box\"\nsize = " +
        vec(box_size) + "\norientation = [" + num(box_q.w()) + ", " + num(box_q.x()) + ", " +
        num(box_q.y()) + ", " + num(box_q.z()) + "]\nposition = [2.0, 0.0, 1.0]\n" +
        "[bodies.wheel]\ntype = \"rigid_body\"\nmass = 0.5\nshape = \"cylinder\"\nradius = " +
        num(wheel_r) + "\nlength = " + num(wheel_l) + "\naxis = " + vec(wheel_axis) +
        "\nhollow = " + (ring ? "true" : "false") + "\nposition = [-2.0, 0.0, 1.0]\n" +
        "[bodies.puck]\ntype = \"point_mass\"\nmass = 0.1\nposition = [0.0, 3.0, 0.0]\n"
        "[bodies.arm]\ntype = \"planar_arm\"\nbase = [0.0, -3.0, 0.5]\n"
        "links = [{length = " +
        num(link0) + ", mass = 0.2, width = " + num(width0) + "}, {length = " + num(link1) +
        ", mass = 0.2}]\n"
        // Contacts: one floor under four bodies (drawn once), and a pair.
        "[impedances.ball_floor]\ntype = \"kikuuwe_contact\"\nbody = \"ball\"\nnormal = " +
        vec(floor_n) + "\noffset = " + num(floor_offset) +
        "\n"
        "[impedances.crate_floor]\ntype = \"kikuuwe_contact\"\nbody = \"crate\"\nnormal = " +
        vec(floor_n) + "\noffset = " + num(floor_offset) +
        "\n"
        "[impedances.wheel_floor]\ntype = \"kikuuwe_contact\"\nbody = \"wheel\"\nnormal = " +
        vec(floor_n) + "\noffset = " + num(floor_offset) +
        "\n"
        "[impedances.puck_floor]\ntype = \"kikuuwe_contact\"\nbody = \"puck\"\nnormal = " +
        vec(floor_n) + "\noffset = " + num(floor_offset) +
        "\n"
        "[impedances.knock]\ntype = \"kikuuwe_contact\"\nbody = \"ball\"\nother = \"crate\"\n"
        // Joint friction, a spring, sources on a body and on a joint.
        "[impedances.elbow]\ntype = \"kikuuwe_friction\"\nbody = \"arm\"\njoint = 1\n"
        "force_limit = 0.5\nstick_threshold = 0.02\n"
        "[impedances.tether]\ntype = \"spring_damper\"\nbody = \"crate\"\npoint = " +
        vec(spring_point) +
        "\nother = \"ball\"\nstiffness = 10.0\ndamping = 0.5\n"
        "[impedances.drive]\ntype = \"torque_source\"\nbody = \"wheel\"\naxis = " +
        vec(wheel_axis) +
        "\ntorque = \"0.1 * t\"\n"
        "[impedances.motor]\ntype = \"torque_source\"\nbody = \"arm\"\njoint = 0\ntorque = 0.2\n"
        "[impedances.push]\ntype = \"force_source\"\nbody = \"crate\"\npoint = [0.1, 0.0, 0.0]\n"
        "frame = \"body\"\nforce = [1.0, 0.0, 0.0]\n";
    INFO("trial " << trial << "\n" << text);
    const scene::Scene s = build(text);
    const scene::Drawing& d = s.drawing;

    // Bodies, in the network's order, each of its declared kind and size.
    REQUIRE(d.bodies.size() == 5);
    CHECK(d.bodies[0].name == "ball");
    CHECK(d.bodies[0].kind == scene::BodyVisual::Kind::sphere);
    CHECK(d.bodies[0].radius == ball_r);
    CHECK(d.bodies[1].kind == scene::BodyVisual::Kind::box);
    CHECK((d.bodies[1].size - box_size).norm() == 0.0);
    const scene::BodyVisual& wheel = d.bodies[2];
    CHECK(wheel.kind == scene::BodyVisual::Kind::cylinder);
    CHECK(wheel.radius == wheel_r);
    CHECK(wheel.length == wheel_l);
    CHECK(wheel.hollow == ring);
    CHECK((wheel.axis - wheel_axis).norm() < 1e-12);
    CHECK(d.bodies[3].kind == scene::BodyVisual::Kind::block);
    CHECK((d.bodies[3].up - floor_n).norm() < 1e-12);  // a block rests on its surface
    const scene::BodyVisual& arm = d.bodies[4];
    CHECK(arm.kind == scene::BodyVisual::Kind::arm);
    REQUIRE(arm.lengths.size() == 2);
    CHECK(arm.lengths[0] == link0);
    CHECK(arm.lengths[1] == link1);
    CHECK(arm.widths[0] == width0);
    CHECK(arm.widths[1] == Approx(0.1 * link1));  // no width: a tenth of the length
    CHECK((arm.base - Vec3(0.0, -3.0, 0.5)).norm() == 0.0);

    // One floor for the four plane contacts.
    REQUIRE(d.surfaces.size() == 1);
    CHECK((d.surfaces[0].normal - floor_n).norm() < 1e-12);
    CHECK(d.surfaces[0].offset == floor_offset);

    // Contact sites: one per element, each naming the body the network wires it to.
    // ball 1 + crate corners 8 + wheel rim points 6 + puck 1 + the pair 1.
    REQUIRE(d.sites.contacts.size() == 17);
    for (const scene::ContactSite& c : d.sites.contacts) {
      INFO(c.name);
      REQUIRE(c.body >= 0);
      CHECK(d.bodies[static_cast<std::size_t>(c.body)].name == wired_body(*s.network, c.name));
      CHECK(c.name.rfind(c.group, 0) == 0);
    }
    const scene::ContactSite& ball = site_named(d, "ball_floor");
    CHECK(ball.rule == scene::ContactSite::Rule::point);
    CHECK(ball.radius == ball_r);
    CHECK(ball.trail);
    for (int i = 0; i < 8; ++i) {
      const scene::ContactSite& corner = site_named(d, "crate_floor." + std::to_string(i));
      CHECK(corner.rule == scene::ContactSite::Rule::point);
      CHECK(corner.radius == 0.0);
      // A corner of the box: each coordinate half a side.
      CHECK((corner.local.cwiseAbs() - 0.5 * box_size).norm() < 1e-12);
      CHECK_FALSE(corner.trail);
    }
    const scene::ContactSite& pair = site_named(d, "knock");
    CHECK(pair.rule == scene::ContactSite::Rule::pair);
    CHECK(d.bodies[static_cast<std::size_t>(pair.other)].name == "crate");
    CHECK(site_named(d, "puck_floor").body == 3);
    for (int i = 0; i < 6; ++i) {
      const scene::ContactSite& rim = site_named(d, "wheel_floor." + std::to_string(i));
      CHECK(rim.rule == scene::ContactSite::Rule::rim);
      CHECK(rim.trail == (i == 0 || i == 3));  // the nearest point of each cap
      CHECK(rim.stick_threshold == 1e-3);
    }

    // The friction joint, the spring and the sources.
    REQUIRE(d.sites.joints.size() == 1);
    CHECK(d.sites.joints[0].name == "elbow");
    CHECK(d.sites.joints[0].arm == "arm");
    CHECK(d.sites.joints[0].body == 4);
    CHECK(d.sites.joints[0].joint == 1);
    CHECK(d.sites.joints[0].stick_threshold == 0.02);
    REQUIRE(d.springs.size() == 1);
    CHECK(d.springs[0].body == 1);
    CHECK(d.springs[0].other == 0);
    CHECK((d.springs[0].point - spring_point).norm() == 0.0);
    CHECK(d.springs[0].damping == 0.5);
    REQUIRE(d.sources.size() == 3);
    CHECK(d.sources[0].name == "drive");
    CHECK(d.sources[0].kind == scene::SourceVisual::Kind::torque);
    CHECK(d.sources[0].body == 2);
    CHECK((d.sources[0].axis - wheel_axis).norm() < 1e-12);
    CHECK(d.sources[1].joint == 0);
    CHECK(d.sources[1].body == 4);
    CHECK(d.sources[2].kind == scene::SourceVisual::Kind::force);
    CHECK(d.sources[2].body_frame);
    CHECK((d.sources[2].point - Vec3(0.1, 0.0, 0.0)).norm() == 0.0);
  }
}

TEST_CASE(
    "drawing: a cylinder's and a ring's contact sites sit on the rim where it touches "
    "the plane",
    "[scene][drawing]") {
  std::mt19937 rng(2037);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const double r = 0.005 + 0.4 * u(rng), length = 0.001 + 0.3 * u(rng);
    const Vec3 axis = random_unit(rng);  // body frame
    const Vec3 n = (Vec3(0.0, 0.0, 1.0) + 0.5 * random_unit(rng)).normalized();
    const double offset = 2.0 * u(rng) - 1.0;
    Quat q = random_rotation(rng);
    // Odd orientations, but not lying flat: the caps' tilt stays beyond the lean's blend.
    while (std::abs((q * axis).dot(n)) > 0.98) q = random_rotation(rng);
    const Vec3 a = q * axis;

    // Where the cylinder touches the plane, found by brute force over both rim circles.
    Vec3 e1 = a.unitOrthogonal(), e2 = a.cross(e1);
    auto lowest_on_cap = [&](const Vec3& centre, double sign) {
      Vec3 best = Vec3::Zero();
      double lowest = 1e300;
      for (int k = 0; k < 7200; ++k) {
        const double phi = 2.0 * std::numbers::pi * k / 7200.0;
        const Vec3 x =
            centre + sign * 0.5 * length * a + r * (std::cos(phi) * e1 + std::sin(phi) * e2);
        if (n.dot(x) < lowest) {
          lowest = n.dot(x);
          best = x;
        }
      }
      return best;
    };
    // Put the body so that its lowest point is on the plane.
    const Vec3 probe_lo = lowest_on_cap(Vec3::Zero(), 1.0),
               probe_lo2 = lowest_on_cap(Vec3::Zero(), -1.0);
    const double depth = std::min(n.dot(probe_lo), n.dot(probe_lo2));
    const Vec3 lateral(u(rng), u(rng), 0.0);
    const Vec3 p = (offset - depth) * n + lateral - n.dot(lateral) * n;  // along the plane

    const bool ring = u(rng) < 0.5;
    const std::string text =
        "name = \"wheel\"\n[bodies.wheel]\ntype = \"rigid_body\"\nmass = 1.0\nshape = "
        "\"cylinder\"\nradius = " +
        num(r) + "\nlength = " + num(length) + "\naxis = " + vec(axis) +
        "\nhollow = " + (ring ? "true" : "false") + "\nposition = " + vec(p) + "\norientation = [" +
        num(q.w()) + ", " + num(q.x()) + ", " + num(q.y()) + ", " + num(q.z()) + "]\n" +
        "[impedances.ground]\ntype = \"kikuuwe_contact\"\nbody = \"wheel\"\nnormal = " + vec(n) +
        "\noffset = " + num(offset) + "\n";
    INFO("trial " << trial << "\n" << text);
    const scene::Scene s = build(text);
    const scene::Drawing& d = s.drawing;
    REQUIRE(d.sites.contacts.size() == 6);
    const Quat q_built = q.normalized();
    double touching = 1e300;
    for (int i = 0; i < 6; ++i) {
      const scene::ContactSite& site = d.sites.contacts[static_cast<std::size_t>(i)];
      INFO("site " << site.name);
      CHECK(d.bodies[static_cast<std::size_t>(site.body)].name == "wheel");
      const Vec3 x = p + site.rim.lever(q_built, site.normal);
      // On the rim: on one cap's plane, at the radius from the axis.
      const Vec3 local = q_built.conjugate() * (x - p);
      const double along = local.dot(axis);
      CHECK(std::abs(std::abs(along) - 0.5 * length) < 1e-9 * (1.0 + length));
      CHECK((local - along * axis).norm() == Approx(r).epsilon(1e-9));
      CHECK((i < 3) == (along > 0.0));  // legs 0-2 on the +axis cap
      if (i % 3 == 0) {
        // The nearest point of its cap: the brute-force lowest point of that rim circle.
        const Vec3 best = lowest_on_cap(p, i < 3 ? 1.0 : -1.0);
        CHECK((x - best).norm() < 2e-3 * r);
        CHECK(n.dot(x) <= n.dot(best) + 1e-12 * (1.0 + std::abs(offset)));
        touching = std::min(touching, n.dot(x) - offset);
      }
    }
    // And the lower cap's nearest point touches the plane (the body was placed so).
    CHECK(std::abs(touching) < 1e-6 * (1.0 + r));
  }
}

TEST_CASE("drawing: a URDF robot is a tree with its file's visuals", "[scene][drawing]") {
  const scene::Scene s =
      scene::load_scene(std::string(STICTION_SOURCE_DIR) + "/scenes/two_link_urdf.toml");
  const scene::UrdfRobot robot =
      scene::load_urdf(std::string(STICTION_SOURCE_DIR) + "/assets/robots/two_link.urdf");
  REQUIRE(s.drawing.bodies.size() == 1);
  const scene::BodyVisual& arm = s.drawing.bodies[0];
  CHECK(arm.kind == scene::BodyVisual::Kind::tree);
  CHECK(arm.name == "arm");
  REQUIRE(arm.tree != nullptr);
  CHECK(arm.tree->joint_count() == 2);
  CHECK(arm.lengths.size() == 2);
  REQUIRE(arm.visuals.size() == robot.visuals.size());
  REQUIRE_FALSE(arm.visuals.empty());
  for (std::size_t i = 0; i < arm.visuals.size(); ++i) {
    CHECK(arm.visuals[i].link == robot.visuals[i].link);
    CHECK((arm.visuals[i].size - robot.visuals[i].size).norm() == 0.0);
  }
  // Each joint's friction (<dynamics friction="0.5">) is a badge site at its joint, judged on
  // the tree's rate column of that joint; the torque sources on its joints are drawn on them.
  REQUIRE(s.drawing.sites.joints.size() == 2);
  for (std::size_t j = 0; j < 2; ++j) {
    const scene::JointSite& site = s.drawing.sites.joints[j];
    const std::string joint = robot.links[j].joint_name;
    CHECK(site.name == "arm." + joint + ".friction");
    CHECK(site.body == 0);
    CHECK(site.joint == static_cast<int>(j));
    CHECK(scene::rate_column(site) == "arm.omega." + joint);
    CHECK(site.stick_threshold == 0.02);  // the scene's stick_threshold
  }
  for (const scene::SourceVisual& src : s.drawing.sources) {
    CHECK(src.body == 0);
    CHECK(src.joint >= 0);
  }
}

TEST_CASE("drawing: friction on a spatial_tree's joint is a badge site at that joint",
          "[scene][drawing]") {
  const scene::Scene s = scene::load_scene(scene::SceneSource::from_text(R"(
name = "tree_friction"
[bodies.robot]
type = "spatial_tree"
joints = [
  { name = "shoulder", axis = [0, 1, 0], mass = 1.0, com = [0.15, 0, 0], size = [0.3, 0.04, 0.04] },
  { name = "elbow", parent = "shoulder", origin = [0.3, 0, 0], axis = [0, 1, 0], mass = 0.5, com = [0.1, 0, 0], inertia = [1e-4, 2e-3, 2e-3] },
]
[impedances.elbow_friction]
type = "kikuuwe_friction"
body = "robot"
joint = "elbow"
force_limit = 0.3
stick_threshold = 0.05
)",
                                                                          "tree_friction.toml"));
  REQUIRE(s.drawing.sites.joints.size() == 1);
  const scene::JointSite& site = s.drawing.sites.joints[0];
  CHECK(site.name == "elbow_friction");
  CHECK(site.body == 0);
  CHECK(site.joint == 1);
  CHECK(scene::rate_column(site) == "robot.omega.elbow");
  CHECK(site.stick_threshold == 0.05);
}
