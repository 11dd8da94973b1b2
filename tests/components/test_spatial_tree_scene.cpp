// The spatial_tree scene type: generated scenes that hold a planar_arm and the same arm as
// a spatial_tree (odd axis, base, yawed joint frames, Kikuuwe friction on a joint named by
// index in one and by name in the other) run to the same joint angles; a tree with named
// joints loads, runs and names its CSV columns by its joints; bad input gives located errors.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "components/admittance/planar_arm.hpp"
#include "core/simulation.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

scene::Scene from_text(const std::string& text) {
  return scene::build_scene(toml::parse(std::string_view(text), std::string_view("gen.toml")),
                            "gen.toml");
}

std::string vec(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(17);
  out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

int column(const core::Trajectory& t, const std::string& name) {
  const auto c = t.find(name);
  INFO("column " << name);
  REQUIRE(c.has_value());
  return *c;
}

std::string error_of(const std::string& text) {
  try {
    from_text(text);
  } catch (const scene::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("spatial_tree scene: runs as the same planar_arm, friction on a named joint") {
  std::mt19937 rng(31337);
  auto between = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  for (int n = 1; n <= 4; ++n) {
    Eigen::Vector3d axis(between(-1, 1), between(-1, 1), between(-1, 1));
    axis.normalize();
    Eigen::Vector3d e1, e2;
    components::arm_plane(axis, e1, e2);
    Eigen::Matrix3d plane;
    plane << e1, e2, axis;
    const Eigen::Vector3d ypr = plane.eulerAngles(2, 1, 0);  // R = Rz Ry Rx
    const Eigen::Vector3d base(between(-1, 1), between(-1, 1), between(-1, 1));
    std::ostringstream arm, tree, angles, tree_angles, rates;
    arm.precision(17);
    tree.precision(17);
    angles.precision(17);
    tree_angles.precision(17);
    rates.precision(17);
    double previous_length = 0.0;
    for (int i = 0; i < n; ++i) {
      const double length = between(0.1, 0.4), mass = between(0.2, 2.0),
                   com = between(0.2, 0.8) * length, inertia = between(0.001, 0.01);
      const double yaw = between(-3, 3), theta = between(-2, 2), omega = between(-2, 2);
      arm << "{ length = " << length << ", mass = " << mass << ", com = " << com
          << ", inertia = " << inertia << " },\n";
      tree << "{ name = \"j" << i << "\"" << (i ? ", parent = \"j" + std::to_string(i - 1) + "\"" : "")
           << ", origin = [" << previous_length << ", 0, " << between(-0.1, 0.1) << "]"
           << ", rpy = [0, 0, " << yaw << "], mass = " << mass << ", com = [" << com
           << ", 0, 0], inertia = [0.02, 0.03, " << inertia << "] },\n";
      angles << (i ? ", " : "") << theta;
      tree_angles << (i ? ", " : "") << theta - yaw;
      rates << (i ? ", " : "") << omega;
      previous_length = length;
    }
    const std::string text = "gravity = [0.5, -3.0, -9.8]\n"
                             "[simulation]\ndt = 1e-3\nduration = 0.3\n"
                             "[bodies.arm]\ntype = \"planar_arm\"\naxis = " + vec(axis) +
                             "\nbase = " + vec(base) + "\nangles = [" + angles.str() +
                             "]\nrates = [" + rates.str() + "]\nlinks = [\n" + arm.str() +
                             "]\n[bodies.tree]\ntype = \"spatial_tree\"\nbase = " + vec(base) +
                             "\nbase_rpy = " + vec({ypr[2], ypr[1], ypr[0]}) + "\nangles = [" +
                             tree_angles.str() + "]\nrates = [" + rates.str() + "]\njoints = [\n" +
                             tree.str() + "]\n"
                             "[impedances.arm_friction]\ntype = \"kikuuwe_friction\"\n"
                             "body = \"arm\"\njoint = 0\nstiffness = 100\nforce_limit = 0.3\n"
                             "[impedances.tree_friction]\ntype = \"kikuuwe_friction\"\n"
                             "body = \"tree\"\njoint = \"j0\"\nstiffness = 100\nforce_limit = 0.3\n";
    INFO(text);
    scene::Scene s = from_text(text);
    const core::RunResult result = core::simulate(*s.network, s.run);
    REQUIRE_FALSE(result.instability.has_value());
    const core::Trajectory& t = result.trajectory;
    double worst = 0.0, motion = 0.0;
    for (int i = 0; i < n; ++i) {
      const int a = column(t, "arm.theta." + std::to_string(i));
      const int b = column(t, "tree.theta.j" + std::to_string(i));
      const int w = column(t, "tree.omega.j" + std::to_string(i));
      for (int row = 0; row < t.row_count(); ++row) {
        // The tree's angles read from its yawed joint frames: compare the changes.
        const double change_a = t.at(row, a) - t.at(0, a), change_b = t.at(row, b) - t.at(0, b);
        worst = std::max(worst, std::abs(change_a - change_b));
        motion = std::max(motion, std::abs(t.at(row, w)));
      }
    }
    INFO("n = " << n << ": largest angle difference " << worst << " rad, rates up to "
                << motion);
    CHECK(motion > 0.1);
    CHECK(worst < 1e-12);  // measured: about 1e-14
  }
}

TEST_CASE("spatial_tree scene: named joints, CSV columns, prismatic joints, friction holds") {
  const std::string text = R"(
gravity = [0, 0, -9.8]
[simulation]
dt = 1e-4
duration = 0.5
[bodies.robot]
type = "spatial_tree"
base = [0, 0, 0.5]
angles = [0.3, 0.2, 0.05]
joints = [
  { name = "shoulder", axis = [0, 1, 0], mass = 1.0, com = [0.15, 0, 0], size = [0.3, 0.04, 0.04] },
  { name = "elbow", parent = "shoulder", origin = [0.3, 0, 0], rpy = [0.2, 0, 0], axis = [0, 1, 0], mass = 0.5, com = [0.1, 0, 0], inertia = [1e-4, 2e-3, 2e-3, 0, 1e-5, 0], lower = -2, upper = 2 },
  { name = "slide", parent = "elbow", type = "prismatic", origin = [0.2, 0, 0], axis = [1, 0, 0], mass = 0.2, inertia = [1e-5, 1e-5, 1e-5] },
]
[impedances.hold_shoulder]
type = "kikuuwe_friction"
body = "robot"
joint = "shoulder"
stiffness = 1e4
damping = 10
force_limit = 50
[impedances.elbow_damping]
type = "spring_damper"
body = "robot"
joint = 1
stiffness = 0
damping = 0.01
)";
  scene::Scene s = from_text(text);
  const core::RunResult result = core::simulate(*s.network, s.run);
  REQUIRE_FALSE(result.instability.has_value());
  const core::Trajectory& t = result.trajectory;
  for (const char* name : {"robot.theta.shoulder", "robot.theta.elbow", "robot.theta.slide",
                           "robot.omega.shoulder", "robot.omega.elbow", "robot.omega.slide"}) {
    CHECK(t.find(name).has_value());
  }
  const int shoulder = column(t, "robot.theta.shoulder");
  const int elbow = column(t, "robot.theta.elbow");
  const int slide = column(t, "robot.theta.slide");
  const int last = t.row_count() - 1;
  // The shoulder's friction (50 N m) holds the arm's gravity torque (about 3.5 N m); the
  // elbow swings and the slide slides out.
  CHECK(std::abs(t.at(last, shoulder) - 0.3) < 1e-3);
  CHECK(std::abs(t.at(last, elbow) - 0.2) > 0.05);
  CHECK(std::abs(t.at(last, slide) - 0.05) > 0.01);
}

TEST_CASE("spatial_tree scene: bad input gives located errors") {
  const std::string head = "[bodies.robot]\ntype = \"spatial_tree\"\n";
  const std::string a = "{ name = \"a\", mass = 1, size = [0.1, 0.1, 0.1] }";
  // A misspelt key in the second joint: its line and the key's path.
  std::string e;
  e = error_of(head + "joints = [\n" + a + ",\n{ name = \"b\", parent = \"a\", mass = 1,"
                                                      " size = [0.1, 0.1, 0.1], colour = 1 } ]\n");
  INFO(e);
  CHECK(e.find("gen.toml:5:") != std::string::npos);
  CHECK(e.find("unknown key 'bodies.robot.joints[1].colour'") != std::string::npos);
  e = error_of(head + "joints = [\n" + a + ",\n{ name = \"b\", parent = \"c\", mass = 1,"
                                           " size = [0.1, 0.1, 0.1] } ]\n");
  INFO(e);
  CHECK(e.find("gen.toml:5:") != std::string::npos);
  CHECK(e.find("no earlier joint named 'c'") != std::string::npos);
  e = error_of(head + "joints = [\n" + a + ",\n{ name = \"a\", mass = 1, size = [1, 1, 1] } ]\n");
  CHECK(e.find("joints[1].name") != std::string::npos);
  e = error_of(head + "joints = [\n{ name = \"a\", mass = 1, inertia = [1, 1] } ]\n");
  CHECK(e.find("joints[0].inertia") != std::string::npos);
  e = error_of(head + "joints = [\n{ name = \"a\", mass = 1, inertia = [1, 1, 1, 5, 0, 0] } ]\n");
  CHECK(e.find("positive semi-definite") != std::string::npos);
  e = error_of(head + "joints = [\n{ name = \"a\", type = \"ball\", mass = 1, size = [1, 1, 1] } ]\n");
  CHECK(e.find("joints[0].type") != std::string::npos);
  e = error_of(head + "angles = [1, 2]\njoints = [\n" + a + " ]\n");
  CHECK(e.find("bodies.robot.angles") != std::string::npos);
  // Joint elements: a name the tree does not have, and an element on a body without joints.
  e = error_of(head + "joints = [\n" + a + " ]\n[impedances.f]\ntype = \"kikuuwe_friction\"\n"
                      "body = \"robot\"\njoint = \"elbow\"\n");
  INFO(e);
  CHECK(e.find("gen.toml:8:") != std::string::npos);
  CHECK(e.find("no joint named 'elbow' (joints: a)") != std::string::npos);
  e = error_of("[bodies.m]\ntype = \"point_mass\"\nmass = 1\n[impedances.f]\ntype = \"lugre\"\n"
               "body = \"m\"\n");
  CHECK(e.find("an arm (planar_arm, spatial_tree or urdf)") != std::string::npos);
  e = error_of("[bodies.arm]\ntype = \"planar_arm\"\nlinks = [{ length = 1, mass = 1 }]\n"
               "[impedances.f]\ntype = \"dahl\"\nbody = \"arm\"\njoint = \"shoulder\"\n");
  CHECK(e.find("numbers its joints") != std::string::npos);
}
