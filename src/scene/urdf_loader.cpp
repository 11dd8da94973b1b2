#include "scene/urdf_loader.hpp"

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <mutex>
#include <optional>

#include "core/safe_normalize.hpp"
#include "scene/mesh_path.hpp"
#include "scene/urdf_numbers.hpp"
#include "sys/read_file.hpp"

namespace stiction::scene {

using components::SpatialLink;
using core::Mat3;
using core::Quat;
using core::Vec3;

namespace {

// urdfdom reports what it refuses through console_bridge, a process-wide logger: collect
// its errors while one parse runs (one at a time) instead of letting it print them.
class ErrorCollector final : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
           int /*line*/) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) messages += (messages.empty() ? "" : "; ") + text;
  }
  std::string messages;
};

std::mutex parse_mutex;

// A rigid frame: x_parent = p + q x_child.
struct Frame {
  Vec3 p = Vec3::Zero();
  Quat q = Quat::Identity();
  Frame operator*(const Frame& o) const { return {p + q * o.p, q * o.q}; }
};

Frame frame_of(const urdf::Pose& pose) {
  const auto& r = pose.rotation;
  Quat q(r.w, r.x, r.y, r.z);
  q.normalize();
  return {Vec3(pose.position.x, pose.position.y, pose.position.z), q};
}

// Mass, centre of mass and inertia about it, all in one frame.
struct MassProps {
  double mass = 0.0;
  Vec3 com = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
};

// Inertia of a point mass m at d about the origin (parallel-axis term).
Mat3 shift(double m, const Vec3& d) {
  return m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
}

MassProps combine(const MassProps& a, const MassProps& b) {
  MassProps out;
  out.mass = a.mass + b.mass;
  if (!(out.mass > 0.0)) return out;
  out.com = (a.mass * a.com + b.mass * b.com) / out.mass;
  out.inertia = a.inertia + shift(a.mass, a.com - out.com) + b.inertia +
                shift(b.mass, b.com - out.com);
  return out;
}

// A link's inertial in the frame `in` (the frame of the moving link it belongs to).
MassProps mass_props(const urdf::Link& link, const Frame& in) {
  MassProps m;
  if (!link.inertial) return m;
  const urdf::Inertial& i = *link.inertial;
  const Frame c = in * frame_of(i.origin);
  Mat3 local;
  local << i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz;
  const Mat3 R = c.q.toRotationMatrix();
  m.mass = i.mass;
  m.com = c.p;
  m.inertia = R * local * R.transpose();
  return m;
}

class Builder {
 public:
  Builder(const std::string& origin, UrdfRobot& robot) : origin_(origin), robot_(robot) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw UrdfError(origin_ + ": " + message);
  }

  // Adds `root` and everything below it, depth first, each moving link after its parent
  // (SpatialTreeParams needs parents first). An explicit stack, not recursion: a URDF chain
  // of many thousand joints (a megabyte of XML) must not overflow the call stack.
  void walk(const urdf::Link& root) {
    struct Pending {
      const urdf::Link* link;
      int owner;                        // the moving link it belongs to (-1: the base)
      Frame in;                         // its frame in the owner's
      const urdf::Joint* joint = nullptr;  // set: a moving joint that makes it a new link
    };
    std::vector<Pending> stack{{&root, -1, Frame{}}};
    while (!stack.empty()) {
      Pending p = stack.back();
      stack.pop_back();
      if (p.joint != nullptr) {
        p.owner = add_joint(*p.joint, *p.link, p.owner, p.in);
        p.in = Frame{};
      }
      add_visuals(*p.link, p.owner, p.in);
      if (p.owner >= 0) mass_[p.owner] = combine(mass_[p.owner], mass_props(*p.link, p.in));
      // Children pushed last to first, so that they are taken in the document's order.
      const auto& joints = p.link->child_joints;
      for (auto it = joints.rbegin(); it != joints.rend(); ++it) {
        const urdf::Joint& joint = **it;
        const urdf::LinkSharedPtr child = find_child(*p.link, joint.child_link_name);
        const Frame at = p.in * frame_of(joint.parent_to_joint_origin_transform);
        switch (joint.type) {
          case urdf::Joint::FIXED:
            stack.push_back({child.get(), p.owner, at});
            break;
          case urdf::Joint::REVOLUTE:
          case urdf::Joint::CONTINUOUS:
          case urdf::Joint::PRISMATIC:
            stack.push_back({child.get(), p.owner, at, &joint});
            break;
          case urdf::Joint::FLOATING:
          case urdf::Joint::PLANAR:
            fail("joint '" + joint.name + "' is " +
                 (joint.type == urdf::Joint::FLOATING ? "floating" : "planar") +
                 ": only revolute, continuous, prismatic and fixed joints are supported");
          default:
            fail("joint '" + joint.name + "' has an unknown type");
        }
      }
    }
  }

  void finish() {
    for (std::size_t i = 0; i < robot_.links.size(); ++i) {
      robot_.links[i].mass = mass_[i].mass;
      robot_.links[i].com = mass_[i].com;
      robot_.links[i].inertia = mass_[i].inertia;
    }
  }

 private:
  urdf::LinkSharedPtr find_child(const urdf::Link& link, const std::string& name) const {
    for (const auto& c : link.child_links)
      if (c && c->name == name) return c;
    fail("link '" + name + "' not found under '" + link.name + "'");
  }

  // The moving link that `joint` makes of `child`; returns its index.
  int add_joint(const urdf::Joint& joint, const urdf::Link& child, int owner, const Frame& at) {
    SpatialLink l;
    l.joint_name = joint.name;
    l.link_name = child.name;
    l.parent = owner;
    l.type = joint.type == urdf::Joint::PRISMATIC ? components::SpatialJointType::prismatic
                                                  : components::SpatialJointType::revolute;
    const Vec3 axis(joint.axis.x, joint.axis.y, joint.axis.z);
    const std::optional<Vec3> unit_axis = core::safe_normalized(axis);
    if (!unit_axis) fail("joint '" + joint.name + "' has a zero or non-finite axis");
    l.axis = *unit_axis;
    l.origin = at.p;
    l.rotation = at.q;
    // URDF's revolute and prismatic joints must have <limit>; lower == upper (both 0 when
    // the attributes are left out) means no travel limit is given.
    if (joint.type != urdf::Joint::CONTINUOUS && joint.limits &&
        joint.limits->lower < joint.limits->upper) {
      l.lower = joint.limits->lower;
      l.upper = joint.limits->upper;
    }
    UrdfJointDynamics d;
    if (joint.dynamics) {
      d.friction = joint.dynamics->friction;
      d.damping = joint.dynamics->damping;
      if (!(d.friction >= 0.0) || !(d.damping >= 0.0)) {
        fail("joint '" + joint.name + "': <dynamics> friction and damping must be >= 0");
      }
    }
    const int index = static_cast<int>(robot_.links.size());
    robot_.links.push_back(l);
    robot_.dynamics.push_back(d);
    mass_.emplace_back();
    return index;
  }

  void add_visuals(const urdf::Link& link, int owner, const Frame& in) {
    for (const auto& v : link.visual_array) {
      if (!v || !v->geometry) continue;
      UrdfVisual out;
      out.link = owner;
      out.link_name = link.name;
      const Frame f = in * frame_of(v->origin);
      out.origin = f.p;
      out.rotation = f.q;
      if (v->material) {
        const auto& c = v->material->color;
        out.rgba = Eigen::Vector4d(c.r, c.g, c.b, c.a);
        out.rgba_given = true;
      }
      const urdf::Geometry& g = *v->geometry;
      switch (g.type) {
        case urdf::Geometry::BOX: {
          const auto& d = static_cast<const urdf::Box&>(g).dim;
          out.shape = UrdfVisual::Shape::box;
          out.size = Vec3(d.x, d.y, d.z);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& c = static_cast<const urdf::Cylinder&>(g);
          out.shape = UrdfVisual::Shape::cylinder;
          out.size = Vec3(c.radius, c.radius, c.length);
          break;
        }
        case urdf::Geometry::SPHERE: {
          const double r = static_cast<const urdf::Sphere&>(g).radius;
          out.shape = UrdfVisual::Shape::sphere;
          out.size = Vec3(r, r, r);
          break;
        }
        case urdf::Geometry::MESH: {
          const auto& m = static_cast<const urdf::Mesh&>(g);
          out.shape = UrdfVisual::Shape::mesh;
          out.mesh = m.filename;
          out.size = Vec3(m.scale.x, m.scale.y, m.scale.z);
          break;
        }
      }
      robot_.visuals.push_back(out);
    }
  }

  const std::string& origin_;
  UrdfRobot& robot_;
  std::vector<MassProps> mass_;
};

}  // namespace

UrdfRobot parse_urdf(const std::string& text, const std::string& origin) {
  // XML syntax first, for the line and column tinyxml knows (urdfdom's message has none).
  {
    TiXmlDocument xml;
    xml.Parse(text.c_str());
    if (xml.Error()) {
      throw UrdfError(origin + ":" + std::to_string(xml.ErrorRow()) + ":" +
                      std::to_string(xml.ErrorCol()) + ": malformed XML: " + xml.ErrorDesc());
    }
    check_urdf_numbers(xml, origin);
  }
  urdf::ModelInterfaceSharedPtr model;
  std::string messages;
  {
    const std::lock_guard lock(parse_mutex);
    ErrorCollector collector;
    console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
    console_bridge::useOutputHandler(&collector);
    try {
      model = urdf::parseURDF(text);
    } catch (const std::exception& e) {
      collector.messages += (collector.messages.empty() ? "" : "; ") + std::string(e.what());
    }
    console_bridge::useOutputHandler(previous);
    messages = collector.messages;
  }
  if (!model) {
    throw UrdfError(origin + ": not a valid URDF robot" + (messages.empty() ? "" : ": " + messages));
  }
  const urdf::LinkConstSharedPtr root = model->getRoot();
  if (!root) throw UrdfError(origin + ": the robot has no root link");
  UrdfRobot robot;
  robot.name = model->getName();
  Builder builder(origin, robot);
  builder.walk(*root);
  builder.finish();
  if (robot.links.empty()) {
    throw UrdfError(origin + ": the robot has no moving joint (revolute, continuous or prismatic)");
  }
  return robot;
}

UrdfRobot load_urdf(const std::filesystem::path& file, std::size_t max_triangles) {
  std::string text;
  try {
    text = sys::read_regular_file(file);
  } catch (const sys::FileRefused& e) {
    throw UrdfError(file.string() + ": cannot read the URDF file: " + std::string(e.what()));
  }
  UrdfRobot robot = parse_urdf(text, file.string());
  read_urdf_meshes(robot, file, package_search_path(), max_triangles);
  return robot;
}

}  // namespace stiction::scene
