// [bodies.NAME] type = "spatial_tree": a kinematic tree of revolute and prismatic joints
// (components/admittance/spatial_tree.hpp), read from an array of joint tables in which
// each joint names its parent joint. Frames follow URDF: a joint's `origin` and `rpy` place
// its frame in the parent link's frame (rpy: fixed-axis roll about x, then pitch about y,
// then yaw about z, R = Rz(yaw) Ry(pitch) Rx(roll)); the link's mass properties are in the
// link frame. A link's inertia is `inertia` (principal [Ixx, Iyy, Izz] or the full
// [Ixx, Iyy, Izz, Ixy, Ixz, Iyz], about the com) or `size`, a uniform box centred on `com`.
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "components/admittance/spatial_tree.hpp"
#include "core/safe_normalize.hpp"
#include "scene/components.hpp"

namespace stiction::scene {

using core::Vec3;

namespace {

core::Quat from_rpy(const Vec3& rpy) {
  return core::Quat(Eigen::AngleAxisd(rpy.z(), Vec3::UnitZ()) *
                    Eigen::AngleAxisd(rpy.y(), Vec3::UnitY()) *
                    Eigen::AngleAxisd(rpy.x(), Vec3::UnitX()));
}

core::Mat3 link_inertia(TableReader& link, double mass) {
  if (link.has("inertia") == link.has("size")) {
    link.fail("inertia",
              "give exactly one of `inertia` ([Ixx, Iyy, Izz] or [Ixx, Iyy, Izz, "
              "Ixy, Ixz, Iyz] about the com) and `size` (a uniform box)");
  }
  if (link.has("size")) {
    const Vec3 s = link.vec3("size", Vec3::Zero());
    if (!(s.minCoeff() > 0.0)) link.fail("size", "every side must be > 0");
    const Vec3 d(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                 s.x() * s.x() + s.y() * s.y());
    return (mass / 12.0 * d).asDiagonal();
  }
  const std::vector<double> v = link.numbers("inertia");
  if (v.size() != 3 && v.size() != 6) {
    link.fail("inertia", "expected [Ixx, Iyy, Izz] or [Ixx, Iyy, Izz, Ixy, Ixz, Iyz]");
  }
  if (!(std::min({v[0], v[1], v[2]}) >= 0.0)) link.fail("inertia", "moments must be >= 0");
  core::Mat3 I = Vec3(v[0], v[1], v[2]).asDiagonal();
  if (v.size() == 6) {
    I(0, 1) = I(1, 0) = v[3];
    I(0, 2) = I(2, 0) = v[4];
    I(1, 2) = I(2, 1) = v[5];
  }
  return I;
}

}  // namespace

std::unique_ptr<core::Admittance> ComponentBuilder::add_spatial_tree(TableReader& table,
                                                                     const std::string& name) {
  components::SpatialTreeParams p;
  std::vector<TableReader> joints = table.array_of_tables("joints");
  if (joints.empty()) table.fail("joints", "missing (an array of joint tables is required)");
  std::map<std::string, int> index;  // joints read so far
  for (TableReader& joint : joints) {
    components::SpatialLink l;
    l.joint_name = joint.required_string("name");
    if (const std::string why = component_name_problem(l.joint_name); !why.empty()) {
      joint.fail("name", why);  // it names the columns NAME.theta.JOINT
    }
    if (index.contains(l.joint_name)) {
      joint.fail("name", "'" + l.joint_name + "' names another joint already");
    }
    l.link_name = l.joint_name;
    if (joint.has("parent")) {
      const std::string parent = joint.string("parent", "");
      const auto it = index.find(parent);
      if (it == index.end()) {
        joint.fail("parent", "no earlier joint named '" + parent +
                                 "' (a parent comes before its children; omit for the base)");
      }
      l.parent = it->second;
    }
    const std::string type = joint.string("type", "revolute");
    if (type == "prismatic") {
      l.type = components::SpatialJointType::prismatic;
    } else if (type != "revolute") {
      joint.fail("type", "unknown joint type '" + type + "' (expected revolute or prismatic)");
    }
    const auto axis = core::safe_normalized(joint.vec3("axis", l.axis));
    if (!axis) joint.fail("axis", "must be a non-zero vector");
    l.axis = *axis;
    l.origin = joint.vec3("origin", l.origin);
    l.rotation = from_rpy(joint.vec3("rpy", Vec3::Zero()));
    l.mass = joint.positive("mass", joint.required_number("mass"));
    l.com = joint.vec3("com", l.com);
    l.inertia = link_inertia(joint, l.mass);
    for (const char* key : {"lower", "upper"}) {  // inf allowed: no limit that way
      if (const toml::node* node = joint.node(key)) {
        (std::string_view(key) == "lower" ? l.lower : l.upper) =
            number_or_infinity(*node, joint.path() + "." + key);
      }
    }
    if (!(l.lower <= l.upper)) joint.fail("upper", "must be >= lower");
    joint.finish();
    index.emplace(l.joint_name, static_cast<int>(p.links.size()));
    p.links.push_back(l);
  }
  p.base_position = table.vec3("base", p.base_position);
  p.base_orientation = from_rpy(table.vec3("base_rpy", Vec3::Zero()));
  const auto n = static_cast<std::size_t>(joints.size());
  for (const char* key : {"angles", "rates"}) {
    if (!table.has(key)) continue;
    const std::vector<double> v = table.numbers(key);
    if (v.size() != n) table.fail(key, "expected " + std::to_string(n) + " numbers, one per joint");
    (std::string_view(key) == "angles" ? p.angles : p.rates) =
        Eigen::Map<const core::Vec>(v.data(), static_cast<Eigen::Index>(n));
  }
  p.gravity = gravity_;
  std::unique_ptr<components::SpatialTree> tree;
  try {
    tree = std::make_unique<components::SpatialTree>(name, p);
  } catch (const std::invalid_argument& e) {
    throw InputError::at(table.table().source(), table.path() + ": " + e.what());
  }
  drawing_.bodies.push_back(tree_visual(*tree, {}));  // a stick figure
  return tree;
}

}  // namespace stiction::scene
