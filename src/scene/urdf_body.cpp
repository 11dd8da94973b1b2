// [bodies.NAME] type = "urdf": a robot read from a URDF file (scene/urdf_loader.hpp) as a
// components::SpatialTree, with the joint elements its URDF asks for: Kikuuwe friction
// (<dynamics friction>), a damper (<dynamics damping>) and a one-sided stop at each end of
// the travel (<limit lower upper>), named NAME.JOINT.friction, .damping and .limit.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <memory>
#include <optional>

#include "components/admittance/spatial_tree.hpp"
#include "components/impedance/joint_limit.hpp"
#include "components/impedance/kikuuwe_friction.hpp"
#include "components/impedance/spring_damper.hpp"
#include "components/maps/joint_map.hpp"
#include "scene/components.hpp"
#include "scene/urdf_loader.hpp"

namespace stiction::scene {

namespace {

// URDF's rpy: fixed-axis roll about x, then pitch about y, then yaw about z.
core::Quat from_rpy(const core::Vec3& rpy) {
  using Eigen::AngleAxisd;
  return core::Quat(AngleAxisd(rpy.z(), core::Vec3::UnitZ()) *
                    AngleAxisd(rpy.y(), core::Vec3::UnitY()) *
                    AngleAxisd(rpy.x(), core::Vec3::UnitX()));
}

// `angles` or `rates`: an array in joint order, or a table {JOINT = value} (other joints 0).
core::Vec joint_values(TableReader& table, std::string_view key,
                       const std::vector<components::SpatialLink>& links) {
  const auto n = static_cast<Eigen::Index>(links.size());
  core::Vec out = core::Vec::Zero(n);
  if (!table.has(key)) return out;
  const toml::node* node = table.node(key);
  if (auto sub = node->is_table() ? table.subtable(key) : std::nullopt) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::string& joint = links[static_cast<std::size_t>(i)].joint_name;
      if (sub->has(joint)) out[i] = sub->number(joint, 0.0);
    }
    sub->finish();  // a name that is no joint: "unknown key"
    return out;
  }
  const std::vector<double> v = table.numbers(key);
  if (static_cast<Eigen::Index>(v.size()) != n) {
    table.fail(key, "expected " + std::to_string(n) +
                        " numbers, one per joint in the URDF's order, or a table {joint = value}");
  }
  return Eigen::Map<const core::Vec>(v.data(), n);
}

// As components.cpp's construct(): a component's own refusal, located at its table.
template <typename Make>
auto construct_here(TableReader& table, Make make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    throw InputError::at(table.table().source(), table.path() + ": " + e.what());
  }
}

}  // namespace

std::unique_ptr<core::Admittance> ComponentBuilder::add_urdf_body(TableReader& table,
                                                                  const std::string& name) {
  const std::string file = table.required_string("file");
  std::filesystem::path path(file);
  if (path.is_relative()) path = directory_ / path;
  // The scene's bound on mesh triangles holds for all its robots together.
  std::size_t used = 0;
  for (const BodyVisual& b : drawing_.bodies) {
    for (const UrdfVisual& v : b.visuals) used += v.triangles ? v.triangles->triangle_count() : 0;
  }
  UrdfRobot robot;
  try {
    robot = load_urdf(path, kMaxSceneTriangles - std::min(used, kMaxSceneTriangles));
  } catch (const UrdfError& e) {
    table.fail("file", e.what());
  }
  // A joint name becomes a column (NAME.JOINT.theta): a comma, quote or newline in it would
  // break trajectory.csv (issue 39), a '.' make the column ambiguous.
  for (const components::SpatialLink& link : robot.links) {
    if (const std::string why = component_name_problem(link.joint_name); !why.empty()) {
      table.fail("file", path.string() + ": joint '" + link.joint_name + "': " + why +
                             " (a URDF joint name names the joint's columns)");
    }
  }

  components::SpatialTreeParams p;
  p.links = robot.links;
  p.base_position = table.vec3("base", p.base_position);
  p.base_orientation = from_rpy(table.vec3("base_rpy", core::Vec3::Zero()));
  p.angles = joint_values(table, "angles", p.links);
  p.rates = joint_values(table, "rates", p.links);
  p.gravity = gravity_;

  // Joint friction: the Kikuuwe element's spring and damper (the paper's Simulation II
  // values, which the step guard accepts at dt = 1e-4 s for links down to ~1e-3 kg m^2).
  components::KikuuweFrictionParams friction;
  friction.stiffness = table.positive("friction_stiffness", 5000.0);
  friction.damping = table.non_negative("friction_damping", 1.0);
  const double stick_threshold = table.positive("stick_threshold", 1e-3);
  components::JointLimitParams limit;
  limit.stiffness = table.positive("limit_stiffness", limit.stiffness);
  limit.damping = table.non_negative("limit_damping", limit.damping);

  auto tree = construct_here(table, [&] { return std::make_unique<components::SpatialTree>(name, p); });
  const components::SpatialTree& t = *tree;
  const int drawn_as = static_cast<int>(drawing_.bodies.size());  // the tree, pushed below
  for (std::size_t i = 0; i < robot.links.size(); ++i) {
    const components::SpatialLink& link = robot.links[i];
    const std::string prefix = name + "." + link.joint_name + ".";
    const int joint = static_cast<int>(i);
    auto element = [&](std::unique_ptr<core::Impedance> impedance, const std::string& type) {
      impedance_types_.emplace(impedance->name(), type);
      add_element(std::move(impedance), std::make_unique<components::JointMap>(t, joint));
    };
    if (robot.dynamics[i].friction > 0.0) {
      components::KikuuweFrictionParams f = friction;
      f.force_limit = robot.dynamics[i].friction;
      stick_thresholds_[prefix + "friction"] = stick_threshold;
      // Its stick/slip badge, at the joint (the tree is body `drawn_as` of the drawing).
      drawing_.sites.joints.push_back(
          {prefix + "friction", name, drawn_as, joint, stick_threshold, link.joint_name});
      element(construct_here(table, [&] {
                return std::make_unique<components::KikuuweFriction>(prefix + "friction", f);
              }),
              "kikuuwe_friction");
    }
    if (robot.dynamics[i].damping > 0.0) {
      components::SpringDamperParams d{.stiffness = 0.0, .damping = robot.dynamics[i].damping,
                                       .dimension = 1, .rest = {}};
      element(construct_here(table, [&] {
                return std::make_unique<components::SpringDamper>(prefix + "damping", d);
              }),
              "spring_damper");
    }
    if (std::isfinite(link.lower) || std::isfinite(link.upper)) {
      components::JointLimitParams l = limit;
      l.lower = link.lower;
      l.upper = link.upper;
      element(construct_here(table, [&] {
                return std::make_unique<components::JointLimit>(prefix + "limit", l);
              }),
              "joint_limit");
    }
  }
  drawing_.bodies.push_back(tree_visual(t, std::move(robot.visuals)));
  return tree;
}

}  // namespace stiction::scene
