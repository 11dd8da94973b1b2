#include "scene/components.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "components/admittance/planar_arm.hpp"
#include "components/admittance/point_mass.hpp"
#include "components/admittance/rigid_body.hpp"
#include "components/impedance/dahl.hpp"
#include "components/impedance/kikuuwe_contact.hpp"
#include "components/impedance/kikuuwe_friction.hpp"
#include "components/impedance/line_spring_damper.hpp"
#include "components/impedance/lugre.hpp"
#include "components/impedance/penalty_joint.hpp"
#include "components/impedance/spring_damper.hpp"
#include "components/maps/contact_point_map.hpp"
#include "components/maps/frame_pair_map.hpp"
#include "components/maps/joint_map.hpp"
#include "components/maps/point_map.hpp"
#include "core/safe_normalize.hpp"
#include "scene/friction_keys.hpp"

namespace stiction::scene {

using core::Vec3;

namespace {

const std::vector<std::string> kBodyTypes{"point_mass", "rigid_body", "planar_arm",
                                          "spatial_tree", "urdf"};
const std::vector<std::string> kImpedanceTypes{
    "kikuuwe_contact", "kikuuwe_friction", "lugre",        "dahl",    "spring_damper",
    "penalty_joint",   "torque_source",    "force_source", "external"};

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

}  // namespace

// Why `name` cannot name a component, or empty. Its columns are NAME.SIGNAL[.AXIS] and an
// expression names them the same way: a '.' would make "a.b.p.x" ambiguous (body "a.b" or
// an element "b" of "a"?), and anything beyond letters, digits, '_' and '-' would need
// quoting in the CSV, in --set keys and in expressions.
std::string component_name_problem(const std::string& name) {
  if (name.empty()) return "a component name must not be empty";
  if (name.size() > 200) return "a component name must be at most 200 characters long";
  if (name.find('.') != std::string::npos) {
    return "component names must not contain '.' (the CSV columns are NAME.SIGNAL: a dot "
           "would make them ambiguous)";
  }
  for (const char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) {
      return "component names may use letters, digits, '_' and '-' only (they name CSV columns)";
    }
  }
  return {};
}

std::string signal_name_problem(const std::string& name) {
  if (name.empty()) return "a signal name must not be empty";
  if (name.size() > 200) return "a signal name must be at most 200 characters long";
  if (name.front() == '.' || name.back() == '.' || name.find("..") != std::string::npos) {
    return "a signal name must not start or end with '.' or hold '..'";
  }
  for (const char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) {
      return "signal names may use letters, digits, '_', '-' and '.' only (they name CSV "
             "columns)";
    }
  }
  return {};
}

namespace {

std::string name_of(const TableReader& table) {
  const std::string& p = table.path();
  return p.substr(p.rfind('.') + 1);
}

Vec3 unit(TableReader& table, std::string_view key, const Vec3& fallback) {
  const auto u = core::safe_normalized(table.vec3(key, fallback));
  if (!u) table.fail(key, "must be a non-zero vector");
  return *u;
}

// [w, x, y, z], normalized without overflow (core/safe_normalize.hpp).
core::Quat unit_quaternion(TableReader& table, std::string_view key) {
  const std::vector<double> q = table.numbers(key);
  if (q.size() != 4) table.fail(key, "expected a quaternion [w, x, y, z]");
  const auto u = core::safe_normalized(Eigen::Vector4d(q[0], q[1], q[2], q[3]));
  if (!u) table.fail(key, "must be a non-zero quaternion");
  return core::Quat((*u)[0], (*u)[1], (*u)[2], (*u)[3]);
}

std::string type_of(TableReader& table, const std::vector<std::string>& known) {
  const std::string type = table.required_string("type");
  if (std::find(known.begin(), known.end(), type) == known.end()) {
    table.fail("type", "unknown component type '" + type + "' (expected one of " + join(known) + ")");
  }
  return type;
}

// Components check their own parameters as a last line of defence; report what they
// reject at the table, as any other input error.
template <typename Make>
auto construct(TableReader& table, Make make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    throw InputError::at(table.table().source(), table.path() + ": " + e.what());
  }
}

// `joint`: the joint's index, or its name (a string) when the arm names its joints.
long joint_number(TableReader& table, const core::JointSpace& arm) {
  const toml::node* node = table.node("joint");
  if (node == nullptr || !node->is_string()) return table.integer("joint", 0);
  const std::string wanted = node->as_string()->get();
  std::vector<std::string> names;
  for (int i = 0; i < arm.joint_count(); ++i) {
    if (arm.joint_name(i) == wanted) return i;
    if (!arm.joint_name(i).empty()) names.push_back(arm.joint_name(i));
  }
  if (names.empty()) table.fail("joint", "'" + arm.name() + "' numbers its joints: give an index");
  table.fail("joint", "'" + arm.name() + "' has no joint named '" + wanted + "' (joints: " +
                          join(names) + ")");
}

// shape = "cylinder": radius, length, axis (body frame, normalized), hollow (a thin wall).
components::CylinderShape read_cylinder(TableReader& table) {
  components::CylinderShape c;
  c.radius = table.positive("radius", table.required_number("radius"));
  c.length = table.positive("length", table.required_number("length"));
  c.axis = unit(table, "axis", c.axis);
  c.hollow = table.boolean("hollow", false);
  return c;
}

// About the centre of mass, body frame: I_perp Id + (I_axis - I_perp) a a^T, a full matrix
// when the axis is oblique. Solid: I_axis = m r^2 / 2, I_perp = m (3 r^2 + L^2) / 12; thin
// wall (hollow): I_axis = m r^2, I_perp = m r^2 / 2 + m L^2 / 12.
core::Mat3 cylinder_inertia(const components::CylinderShape& c, double m) {
  const double r2 = c.radius * c.radius, l2 = c.length * c.length;
  const double axial = (c.hollow ? 1.0 : 0.5) * m * r2;
  const double perp = c.hollow ? m * r2 / 2.0 + m * l2 / 12.0 : m * (3.0 * r2 + l2) / 12.0;
  return perp * core::Mat3::Identity() + (axial - perp) * c.axis * c.axis.transpose();
}

}  // namespace

std::vector<TableReader> ComponentBuilder::entries(TableReader& section) {
  std::vector<std::pair<const toml::key*, const toml::table*>> found;
  for (const auto& [key, value] : section.table()) {
    const toml::node* node = section.node(key.str());
    // The name is checked here, where the key is still whole: the dotted path built from it
    // below cannot tell `[bodies."a.b"]` from a body `b` (issue 25: "a.b" became "b").
    if (const std::string why = component_name_problem(std::string(key.str())); !why.empty()) {
      throw InputError::at(key.source().path ? key.source() : node->source(),
                           section.path() + ".\"" + std::string(key.str()) + "\": " + why);
    }
    if (!node->is_table()) section.fail(key.str(), "expected a table (a component)");
    found.emplace_back(&key, node->as_table());
  }
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    const auto& sa = a.first->source().begin;
    const auto& sb = b.first->source().begin;
    return sa.line != sb.line ? sa.line < sb.line : sa.column < sb.column;
  });
  std::vector<TableReader> out;
  for (const auto& [key, table] : found) out.emplace_back(*table, section.path() + "." + std::string(key->str()));
  return out;
}

void ComponentBuilder::check_name(TableReader& table) {
  const std::string name = name_of(table);
  const bool plain = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
  if (!plain) {
    throw InputError::at(table.table().source(),
                         table.path() + ": component names may use letters, digits, '_' and '-' only"
                                        " (they name CSV columns)");
  }
  if (bodies_.contains(name) || impedance_types_.contains(name)) {
    throw InputError::at(table.table().source(),
                         table.path() + ": the name '" + name + "' is already used by another component");
  }
}

const ComponentBuilder::BodyInfo& ComponentBuilder::body(TableReader& table, std::string_view key) {
  const std::string name = table.required_string(key);
  const auto it = bodies_.find(name);
  if (it == bodies_.end()) {
    std::vector<std::string> names;
    for (const auto& [n, info] : bodies_) names.push_back(n);
    table.fail(key, "no body named '" + name + "' (bodies: " + join(names) + ")");
  }
  return it->second;
}

const core::Body* ComponentBuilder::pose_body(TableReader& table, std::string_view key) {
  const BodyInfo& info = body(table, key);
  const auto* pose = dynamic_cast<const core::Body*>(info.admittance);
  if (pose == nullptr) {
    table.fail(key, "'" + info.admittance->name() + "' is a " + std::string(info.admittance->type()) +
                        ", not a point_mass or rigid_body");
  }
  return pose;
}

void ComponentBuilder::add_body(TableReader& table) {
  check_name(table);
  const std::string name = name_of(table);
  const std::string type = type_of(table, kBodyTypes);
  BodyInfo info;
  std::unique_ptr<core::Admittance> admittance;
  BodyVisual visual;  // what is drawn (a urdf or spatial_tree body adds its own)
  visual.name = name;

  if (type == "urdf") {
    admittance = add_urdf_body(table, name);  // urdf_body.cpp
  } else if (type == "point_mass") {
    components::PointMassParams p;
    p.mass = table.positive("mass", table.required_number("mass"));
    p.position = table.vec3("position", p.position);
    p.velocity = table.vec3("velocity", p.velocity);
    p.gravity = gravity_;
    admittance = construct(table, [&] { return std::make_unique<components::PointMass>(name, p); });
    visual.kind = BodyVisual::Kind::block;
  } else if (type == "rigid_body") {
    components::RigidBodyParams p;
    p.mass = table.positive("mass", table.required_number("mass"));
    const std::string shape = table.string("shape", "");
    Vec3 diagonal = Vec3::Zero();
    if (shape == "sphere" || shape == "hollow_sphere") {
      const double r = table.positive("radius", table.required_number("radius"));
      diagonal.setConstant((shape == "sphere" ? 2.0 / 5.0 : 2.0 / 3.0) * p.mass * r * r);
      info.sphere_radius = r;
      visual.radius = r;
    } else if (shape == "box") {
      if (!table.has("size")) table.fail("size", "missing (a box needs size = [lx, ly, lz])");
      const Vec3 s = table.vec3("size", Vec3::Zero());
      if (!(s.minCoeff() > 0.0)) table.fail("size", "every side must be > 0");
      diagonal << s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
          s.x() * s.x() + s.y() * s.y();
      diagonal *= p.mass / 12.0;
      info.box_size = s;
      visual.kind = BodyVisual::Kind::box;
      visual.size = s;
    } else if (shape == "cylinder") {
      info.cylinder = read_cylinder(table);
      visual = cylinder_visual(name, info.cylinder->radius, info.cylinder->length,
                               info.cylinder->axis, info.cylinder->hollow);
    } else if (!shape.empty()) {
      table.fail("shape",
                 "unknown shape '" + shape + "' (expected sphere, hollow_sphere, box or cylinder)");
    }
    if (shape != "cylinder") {
      for (const char* key : {"length", "axis", "hollow"}) {
        if (table.has(key)) table.fail(key, "only a shape = \"cylinder\" has this key");
      }
    }
    p.inertia = info.cylinder ? cylinder_inertia(*info.cylinder, p.mass)
                              : core::Mat3(diagonal.asDiagonal());
    if (table.has("inertia")) {
      diagonal = table.vec3("inertia", Vec3::Zero());
      if (!(diagonal.minCoeff() > 0.0)) table.fail("inertia", "every principal moment must be > 0");
      p.inertia = diagonal.asDiagonal();
    } else if (shape.empty()) {
      table.fail("inertia", "missing (give `shape` or `inertia = [Jxx, Jyy, Jzz]`)");
    }
    if (shape.empty()) visual.radius = 0.1;  // no shape of its own: a small ball
    p.position = table.vec3("position", p.position);
    p.velocity = table.vec3("velocity", p.velocity);
    if (table.has("orientation")) {
      p.orientation = unit_quaternion(table, "orientation");
    }
    p.angular_velocity = table.vec3("angular_velocity", p.angular_velocity);
    p.gravity = gravity_;
    admittance = construct(table, [&] { return std::make_unique<components::RigidBody>(name, p); });
  } else if (type == "spatial_tree") {
    admittance = add_spatial_tree(table, name);
  } else {  // planar_arm
    components::PlanarArmParams p;
    std::vector<double> lengths, widths;  // as drawn
    std::vector<TableReader> links = table.array_of_tables("links");
    if (links.empty()) table.fail("links", "missing (an array of link tables is required)");
    for (TableReader& link : links) {
      const double length = link.positive("length", link.required_number("length"));
      const double mass = link.positive("mass", link.required_number("mass"));
      const double width = link.non_negative("width", 0.0);
      components::ArmLink l = components::box_link(length, width, mass);
      l.com = link.number("com", l.com);
      l.inertia = link.non_negative("inertia", l.inertia);
      link.finish();
      p.links.push_back(l);
      lengths.push_back(length);
      widths.push_back(width);
    }
    p.base = table.vec3("base", p.base);
    const auto n = static_cast<std::size_t>(links.size());
    for (const char* key : {"angles", "rates"}) {
      if (!table.has(key)) continue;
      const std::vector<double> v = table.numbers(key);
      if (v.size() != n) table.fail(key, "expected " + std::to_string(n) + " numbers, one per link");
      (std::string_view(key) == "angles" ? p.angles : p.rates) =
          Eigen::Map<const core::Vec>(v.data(), static_cast<Eigen::Index>(n));
    }
    // The joint axis: vertical by default (a horizontal arm, on which gravity does no work);
    // any other direction tilts the plane of motion, and gravity's part in it drives the arm.
    p.axis = unit(table, "axis", p.axis);
    p.gravity = gravity_;
    auto arm = construct(table, [&] { return std::make_unique<components::PlanarArm>(name, p); });
    visual = arm_visual(name, arm->params().base, arm->plane_x(), arm->plane_y(),
                        arm->params().axis, lengths, widths);
    admittance = std::move(arm);
  }
  table.finish();
  info.admittance = admittance.get();
  bodies_.emplace(name, info);
  if (type != "urdf" && type != "spatial_tree") drawing_.bodies.push_back(std::move(visual));
  network_.add_admittance(std::move(admittance));
}

void ComponentBuilder::add_impedance(TableReader& table) {
  check_name(table);
  const std::string name = name_of(table);
  const std::string type = type_of(table, kImpedanceTypes);
  std::unique_ptr<core::Impedance> impedance;
  std::unique_ptr<core::CoordinateMap> map;

  // What the wiring joins, for the drawing: the joint of an arm, or two points.
  int wired_joint = -1;
  std::string wired_other;
  Vec3 wired_point = Vec3::Zero(), wired_other_point = Vec3::Zero();
  // Wiring of a 1-D element on joint `joint` of an arm; nullptr if `body` is not an arm.
  auto joint_map = [&]() -> std::unique_ptr<core::CoordinateMap> {
    const BodyInfo& info = body(table, "body");
    const auto* arm = dynamic_cast<const core::JointSpace*>(info.admittance);
    if (arm == nullptr) {
      if (table.has("joint")) table.fail("joint", "'" + info.admittance->name() + "' has no joints");
      return nullptr;
    }
    if (!table.has("joint")) table.fail("joint", "missing (which joint of '" + arm->name() + "')");
    const long joint = joint_number(table, *arm);
    if (joint < 0 || joint >= arm->joint_count()) {
      table.fail("joint", "must be in 0.." + std::to_string(arm->joint_count() - 1));
    }
    wired_joint = static_cast<int>(joint);
    return std::make_unique<components::JointMap>(*arm, static_cast<int>(joint));
  };
  // Wiring of a 3-D element between a point of `body` and a point of `other` (or the world).
  auto point_map = [&]() -> std::unique_ptr<core::CoordinateMap> {
    const core::Body* a = pose_body(table, "body");
    const Vec3 point = table.vec3("point", Vec3::Zero());
    const core::Body* b = table.has("other") ? pose_body(table, "other") : nullptr;
    if (b == a) table.fail("other", "must differ from `body`");
    const Vec3 other_point = table.vec3("other_point", Vec3::Zero());
    wired_point = point;
    wired_other = b != nullptr ? b->name() : "";
    wired_other_point = other_point;
    return std::make_unique<components::PointMap>(*a, point, b, other_point);
  };
  auto joint_only = [&]() {
    auto m = joint_map();
    if (!m) {
      table.fail("body", "a " + type +
                             " element acts on a joint: `body` must be an arm (planar_arm, "
                             "spatial_tree or urdf)");
    }
    return m;
  };

  if (type == "kikuuwe_contact") {
    add_contact(table, name);  // one element per contact point: contact_builder.cpp
    return;
  }
  if (type == "external") {
    add_external(table, name, joint_map());  // supplied in code: external_elements.cpp
    return;
  }
  if (type == "kikuuwe_friction") {
    components::KikuuweFrictionParams p;
    map = joint_map();
    if (!map) map = point_map();
    p.dimension = map->force_size();
    p.stiffness = table.positive("stiffness", p.stiffness);
    p.damping = table.non_negative("damping", p.damping);
    const FrictionKeys levels = read_joint_friction(table, p.force_limit);
    p.force_limit = levels.kinetic;
    p.static_limit = levels.static_level;
    p.stribeck_velocity = levels.stribeck_velocity;
    p.viscous = levels.viscous;
    core::Vec initial_e;
    if (const toml::node* e = table.node("initial_e")) {
      std::vector<double> v;
      if (e->is_number())
        v.push_back(table.number("initial_e", 0.0));
      else
        v = table.numbers("initial_e");
      if (static_cast<int>(v.size()) != p.dimension) {
        table.fail("initial_e",
                   "expected " + std::to_string(p.dimension) + " number(s), one per axis");
      }
      initial_e = Eigen::Map<const core::Vec>(v.data(), static_cast<Eigen::Index>(v.size()));
    }
    auto friction =
        construct(table, [&] { return std::make_unique<components::KikuuweFriction>(name, p); });
    friction->set_initial_e(initial_e);
    impedance = std::move(friction);
    add_joint_site(table, name, wired_joint);
  } else if (type == "lugre") {
    components::LuGreParams p;
    map = joint_only();
    p.stiffness = table.positive("stiffness", p.stiffness);
    p.damping = table.non_negative("damping", p.damping);
    p.viscous = table.non_negative("viscous", p.viscous);
    p.force_limit = table.positive("force_limit", p.force_limit);
    p.static_limit = table.non_negative("static_limit", p.static_limit);
    p.stribeck_velocity = table.non_negative("stribeck_velocity", p.stribeck_velocity);
    if (p.stribeck_velocity > 0.0 && !table.has("static_limit")) {
      table.fail("static_limit", "missing (the Stribeck effect needs the static level too)");
    }
    p.initial_e = table.number("initial_e", p.initial_e);
    impedance = construct(table, [&] { return std::make_unique<components::LuGre>(name, p); });
    add_joint_site(table, name, wired_joint);
  } else if (type == "dahl") {
    components::DahlParams p;
    map = joint_only();
    p.stiffness = table.positive("stiffness", p.stiffness);
    p.force_limit = table.positive("force_limit", p.force_limit);
    p.initial_e = table.number("initial_e", p.initial_e);
    impedance = construct(table, [&] { return std::make_unique<components::Dahl>(name, p); });
    add_joint_site(table, name, wired_joint);
  } else if (type == "spring_damper") {
    components::SpringDamperParams p;
    map = joint_map();
    if (!map) map = point_map();
    p.dimension = map->force_size();
    p.stiffness = table.non_negative("stiffness", p.stiffness);
    p.damping = table.non_negative("damping", p.damping);
    if (table.has("rest")) {
      const toml::node* rest = table.node("rest");
      std::vector<double> v;
      if (rest->is_number()) v.push_back(finite_number(*rest, table.path() + ".rest"));
      else v = table.numbers("rest");
      if (static_cast<int>(v.size()) != p.dimension) {
        table.fail("rest", "expected " + std::to_string(p.dimension) + " number(s)");
      }
      p.rest = Eigen::Map<const core::Vec>(v.data(), static_cast<Eigen::Index>(v.size()));
    }
    if (table.has("length")) {
      // A spring along the line between the two points, with a free length (Drake's
      // LinearSpringDamper): point wiring only, and `rest` has no meaning then.
      if (p.dimension != 3)
        table.fail("length", "a free length needs point wiring (a joint spring has `rest`)");
      if (table.has("rest"))
        table.fail("length", "give either `length` (along the line) or `rest`, not both");
      components::LineSpringDamperParams line{p.stiffness, p.damping,
                                              table.non_negative("length", 0.0)};
      impedance = construct(
          table, [&] { return std::make_unique<components::LineSpringDamper>(name, line); });
    } else {
      impedance =
          construct(table, [&] { return std::make_unique<components::SpringDamper>(name, p); });
    }
    if (wired_joint < 0) {  // between two points (a joint spring has no coil to draw)
      SpringVisual spring;
      spring.name = name;
      spring.body = body_index(drawing_, table.required_string("body"));
      spring.point = wired_point;
      spring.other = wired_other.empty() ? -1 : body_index(drawing_, wired_other);
      spring.other_point = wired_other_point;
      spring.damping = p.damping;
      spring.free_length = table.has("length") ? table.non_negative("length", 0.0) : 0.0;
      drawing_.springs.push_back(spring);
    }
  } else if (type == "penalty_joint") {
    components::PenaltyJointParams p;
    const core::Body* child = pose_body(table, "body");
    const core::Body* parent = table.has("parent") ? pose_body(table, "parent") : nullptr;
    if (!child->can_rotate() || (parent != nullptr && !parent->can_rotate())) {
      table.fail("body", "a penalty joint connects rigid bodies (or a rigid body and the ground)");
    }
    if (parent == child) table.fail("parent", "must differ from `body`");
    const Vec3 point = table.vec3("point", Vec3::Zero());
    const Vec3 parent_point = table.vec3("parent_point", Vec3::Zero());
    p.axis_child = unit(table, "axis", p.axis_child);
    p.axis_parent = unit(table, "parent_axis", p.axis_parent);
    p.separation_stiffness = table.positive("separation_stiffness", p.separation_stiffness);
    p.separation_damping = table.non_negative("separation_damping", p.separation_damping);
    p.bending_stiffness = table.positive("bending_stiffness", p.bending_stiffness);
    p.bending_damping = table.non_negative("bending_damping", p.bending_damping);
    p.friction_stiffness = table.positive("friction_stiffness", p.friction_stiffness);
    p.friction_damping = table.non_negative("friction_damping", p.friction_damping);
    p.friction_limit = table.non_negative("friction_limit", p.friction_limit);
    if (table.has("reference")) {
      p.reference = unit_quaternion(table, "reference");
    }
    p.angle_offset = table.number("angle_offset", p.angle_offset);
    p.initial_e = table.number("initial_e", p.initial_e);
    impedance = construct(table, [&] { return std::make_unique<components::PenaltyJoint>(name, p); });
    map = std::make_unique<components::FramePairMap>(parent, parent_point, *child, point);
    JointVisual joint;
    joint.name = name;
    joint.child = body_index(drawing_, child->name());
    joint.parent = parent != nullptr ? body_index(drawing_, parent->name()) : -1;
    joint.point = point;
    joint.parent_point = parent_point;
    joint.axis = p.axis_child.normalized();
    const BodyVisual& drawn = drawing_.bodies[static_cast<std::size_t>(joint.child)];
    if (drawn.kind == BodyVisual::Kind::box) joint.width = drawn.size.minCoeff();
    if (drawn.kind == BodyVisual::Kind::sphere) joint.width = drawn.radius;
    drawing_.joints.push_back(joint);
  } else {  // torque_source, force_source: built in finish() (sources.cpp)
    add_source(table, type, type == "torque_source" ? joint_map() : nullptr);
    SourceVisual source;
    source.name = name;
    source.body = body_index(drawing_, table.required_string("body"));
    if (type == "force_source") {
      source.kind = SourceVisual::Kind::force;
      source.point = table.vec3("point", Vec3::Zero());
      source.body_frame = table.string("frame", "world") == "body";
    } else {
      source.kind = SourceVisual::Kind::torque;
      source.joint = wired_joint;
      if (wired_joint < 0) source.axis = unit(table, "axis", Vec3::UnitZ());
    }
    drawing_.sources.push_back(source);
    table.finish();
    impedance_types_.emplace(name, type);
    return;
  }
  // Elements with a slip speed (contacts, joint friction) get stick/slip events.
  if (core::capabilities_of(*impedance).slip != nullptr) {
    stick_thresholds_[name] = table.positive("stick_threshold", 1e-3);
  }
  table.finish();
  impedance_types_.emplace(name, type);
  add_element(std::move(impedance), std::move(map));
}

void ComponentBuilder::add_joint_site(TableReader& table, const std::string& name, int joint) {
  const int arm = body_index(drawing_, table.required_string("body"));
  if (joint < 0 || arm < 0) return;  // on a point: no joint
  const BodyVisual& b = drawing_.bodies[static_cast<std::size_t>(arm)];
  if (b.kind == BodyVisual::Kind::arm) {
    drawing_.sites.joints.push_back({name, b.name, arm, joint});
  } else if (b.kind == BodyVisual::Kind::tree && b.tree != nullptr) {
    // A tree's columns are named by its joints' names.
    drawing_.sites.joints.push_back(
        {name, b.name, arm, joint, 1e-3,
         b.tree->params().links[static_cast<std::size_t>(joint)].joint_name});
  }
}

void ComponentBuilder::add_element(std::unique_ptr<core::Impedance> impedance,
                                   std::unique_ptr<core::CoordinateMap> map) {
  pending_.push_back({std::move(impedance), std::move(map), nullptr});
}

}  // namespace stiction::scene
