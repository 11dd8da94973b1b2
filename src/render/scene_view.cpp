#include "render/scene_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "components/admittance/planar_arm.hpp"
#include "components/admittance/point_mass.hpp"
#include "components/admittance/rigid_body.hpp"
#include "components/impedance/kikuuwe_contact.hpp"
#include "components/impedance/moving_contact.hpp"
#include "components/impedance/penalty_joint.hpp"
#include "core/admittance.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::render {
namespace {

const toml::table* body_table(const toml::table& document, const std::string& name) {
  const toml::table* bodies = document["bodies"].as_table();
  return bodies ? (*bodies)[name].as_table() : nullptr;
}

core::Vec3 vec3_of(const toml::node_view<const toml::node>& node, const core::Vec3& fallback) {
  const toml::array* a = node.as_array();
  if (!a || a->size() != 3) return fallback;
  core::Vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = (*a)[static_cast<std::size_t>(i)].value<double>().value_or(fallback[i]);
  return v;
}

// Tangent basis of a surface: t1 along x where possible (down the slope of a tilted plane).
void tangents(const core::Vec3& n, core::Vec3& t1, core::Vec3& t2) {
  core::Vec3 a = std::abs(n.x()) < 0.9 ? core::Vec3::UnitX() : core::Vec3::UnitY();
  t1 = (a - a.dot(n) * n).normalized();
  t2 = n.cross(t1);
}

glm::mat4 rotation_from_basis(const core::Vec3& x, const core::Vec3& y, const core::Vec3& z) {
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(to_glm(x), 0.0f);
  m[1] = glm::vec4(to_glm(y), 0.0f);
  m[2] = glm::vec4(to_glm(z), 0.0f);
  return m;
}

glm::mat4 to_glm(const core::Quat& q) {
  return glm::mat4_cast(glm::quat(static_cast<float>(q.w()), static_cast<float>(q.x()),
                                  static_cast<float>(q.y()), static_cast<float>(q.z())));
}

// A round value no larger than `size`: 0.01, 0.02, 0.05, 0.1, ...
double nice_floor(double size) {
  double best = 0.01;
  for (double decade = 0.01; decade <= 100.0; decade *= 10.0) {
    for (double m : {1.0, 2.0, 5.0}) {
      if (m * decade <= size) best = m * decade;
    }
  }
  return best;
}

struct ArmPose {
  std::vector<core::Vec3> joints;  // n + 1 points: joints then the tip
  std::vector<double> phi;         // absolute angle of each link
};

ArmPose arm_pose(const BodyVisual& arm, const PoseTrack& poses, int index, double t) {
  ArmPose pose;
  core::Vec3 p = arm.base;
  double phi = 0.0;
  pose.joints.push_back(p);
  for (std::size_t i = 0; i < arm.lengths.size(); ++i) {
    phi += poses.angle(index, static_cast<int>(i), t);
    p += arm.lengths[i] * (std::cos(phi) * arm.plane_x + std::sin(phi) * arm.plane_y);
    pose.joints.push_back(p);
    pose.phi.push_back(phi);
  }
  return pose;
}

const glm::vec3 kSphereColour{0.90f, 0.30f, 0.03f};
const glm::vec3 kSphereColour2{0.86f, 0.86f, 0.82f};
const glm::vec3 kBoxColour{0.10f, 0.28f, 0.62f};
const glm::vec3 kLinkColour2{0.15f, 0.50f, 0.75f};  // every other link of a chain
const glm::vec3 kJointColour{0.06f, 0.06f, 0.07f};
const glm::vec3 kBlockColour{0.72f, 0.10f, 0.08f};
const glm::vec3 kGroundLight{0.78f, 0.78f, 0.76f};
const glm::vec3 kGroundDark{0.55f, 0.57f, 0.60f};
const glm::vec3 kBeltLight{0.36f, 0.36f, 0.38f};  // moving surfaces: darker, rubber-like
const glm::vec3 kBeltDark{0.16f, 0.16f, 0.18f};

// True if body `index` is a child or a parent of a joint: a link, drawn as an arm's link is.
bool is_link(const SceneDescription& scene, int index) {
  return std::any_of(scene.joints.begin(), scene.joints.end(),
                     [&](const JointVisual& j) { return j.child == index || j.parent == index; });
}

// Rotation taking the unit shapes' z axis to `axis` (unit).
glm::mat4 align_z(const core::Vec3& axis) {
  core::Vec3 t1, t2;
  tangents(axis, t1, t2);
  return rotation_from_basis(t1, t2, axis);
}

// World position of a joint's articulation point and world direction of its axis, both from
// the child's pose (the parent's point differs by the joint's tiny separation).
core::Vec3 joint_point(const JointVisual& j, const PoseTrack& poses, double t) {
  return poses.position(j.child, t) + poses.orientation(j.child, t) * j.point;
}
core::Vec3 joint_axis(const JointVisual& j, const PoseTrack& poses, double t) {
  return (poses.orientation(j.child, t) * j.axis).normalized();
}

// Half-extents of the axis-aligned box around a box of full sides `size` turned by `q`.
glm::vec3 box_half_extent(const core::Vec3& size, const core::Quat& q) {
  const core::Mat3 r = q.toRotationMatrix();
  const core::Vec3 e = r.cwiseAbs() * (0.5 * size);
  return {static_cast<float>(e.x()), static_cast<float>(e.y()), static_cast<float>(e.z())};
}

// Characteristic size of the scene's bodies: sets the checker square.
double body_scale(const SceneDescription& scene) {
  double s = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyVisual& b = scene.bodies[i];
    switch (b.kind) {
      case BodyVisual::Kind::sphere: s = std::min(s, b.radius); break;
      case BodyVisual::Kind::box:
        // A jointed link counts as an arm's link does: half its length.
        s = std::min(s, (is_link(scene, static_cast<int>(i)) ? 0.5 : 1.0) * b.size.maxCoeff());
        break;
      case BodyVisual::Kind::block: s = std::min(s, b.size.maxCoeff()); break;
      case BodyVisual::Kind::arm:
        for (double l : b.lengths) s = std::min(s, 0.5 * l);
        break;
    }
  }
  return std::isfinite(s) ? s : 0.2;
}

// A contact surface as checkered squares: the plane within `half` of the scene's centre,
// cut to the surface's extent (a rectangle in the plane's u, v coordinates, covered by
// squares of its shorter side so the checker keeps square cells), tilted and scrolled as the
// surface moves at time t.
void add_surface(std::vector<DrawItem>& items, const SurfaceVisual& s, const Bounds& around,
                 float half, float checker, double t) {
  const bool bounded = s.extent.bounded();
  core::Vec3 u, v;
  if (bounded) {
    u = s.extent.u;
    v = s.extent.v;
  } else {
    tangents(s.normal, u, v);
  }
  // Everything in the plane at rest, then moved as a whole.
  core::Quat rotation = core::Quat::Identity();
  core::Vec3 pivot = core::Vec3::Zero();
  double travel_u = 0.0, travel_v = 0.0;
  if (s.moving) {
    const components::SurfaceState st = s.moving->surface(t);
    rotation = st.rotation;
    pivot = s.moving->motion().pivot;
    if (s.moving->motion().belt_speed) {
      const double travel = s.moving->belt_travel(t);
      travel_u = travel * s.moving->belt_direction().dot(u);
      travel_v = travel * s.moving->belt_direction().dot(v);
    }
  }
  const core::Vec3 origin = s.offset * s.normal;
  const core::Vec3 c(around.empty() ? 0.0 : around.centre().x,
                     around.empty() ? 0.0 : around.centre().y,
                     around.empty() ? 0.0 : around.centre().z);
  // The scene centre carried back to the plane at rest.
  const core::Vec3 c_rest = pivot + rotation.conjugate() * (c - pivot);
  double a0 = (c_rest - origin).dot(u) - half, a1 = (c_rest - origin).dot(u) + half;
  double b0 = (c_rest - origin).dot(v) - half, b1 = (c_rest - origin).dot(v) + half;
  if (bounded) {
    const double ca = (s.extent.centre - origin).dot(u), cb = (s.extent.centre - origin).dot(v);
    a0 = std::max(a0, ca + s.extent.u_min);
    a1 = std::min(a1, ca + s.extent.u_max);
    b0 = std::max(b0, cb + s.extent.v_min);
    b1 = std::min(b1, cb + s.extent.v_max);
    if (!(a1 > a0) || !(b1 > b0)) return;
  }
  const double side = std::min(a1 - a0, b1 - b0);
  // A long narrow strip (a belt) is drawn over at most 64 of its squares around the scene.
  constexpr int kMost = 64;
  auto shorten = [&](double& lo, double& hi, double centre) {
    if (hi - lo <= kMost * side) return;
    const double from = std::clamp(centre - 0.5 * kMost * side, lo, hi - kMost * side);
    lo = from;
    hi = from + kMost * side;
  };
  shorten(a0, a1, (c_rest - origin).dot(u));
  shorten(b0, b1, (c_rest - origin).dot(v));
  const int na = std::max(1, static_cast<int>(std::ceil((a1 - a0) / side - 1e-9)));
  const int nb = std::max(1, static_cast<int>(std::ceil((b1 - b0) / side - 1e-9)));
  const double grid = 5.0 * checker;
  const double period = 2.0 * grid;
  for (int i = 0; i < na; ++i) {
    for (int j = 0; j < nb; ++j) {
      // Squares from the low corner, the last one flush with the far edge (they overlap).
      const double ma =
          na == 1 ? 0.5 * (a0 + a1) : a0 + 0.5 * side + (a1 - a0 - side) * i / (na - 1);
      const double mb =
          nb == 1 ? 0.5 * (b0 + b1) : b0 + 0.5 * side + (b1 - b0 - side) * j / (nb - 1);
      const core::Vec3 at = pivot + rotation * (origin + ma * u + mb * v - pivot);
      DrawItem item;
      item.shape = Shape::plane;
      item.model = glm::translate(glm::mat4(1.0f), render::to_glm(at)) *
                   rotation_from_basis(rotation * u, rotation * v, rotation * s.normal) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(0.5f * static_cast<float>(side),
                                                         0.5f * static_cast<float>(side), 1.0f));
      item.material.kind = MaterialKind::checker;
      item.material.colour = s.moving ? kBeltLight : kGroundLight;
      item.material.colour2 = s.moving ? kBeltDark : kGroundDark;
      item.material.checker_size = checker;
      item.material.grid_spacing = static_cast<float>(grid);
      item.material.local_scale = 0.5f * static_cast<float>(side);
      // The pattern repeats every 10 checker squares: an offset reduced modulo that keeps
      // the shader's coordinates small, hence precise. A belt shifts it by its travel.
      const double oa = ma - travel_u, ob = mb - travel_v;
      item.material.local_offset =
          glm::vec2(static_cast<float>(oa - period * std::floor(oa / period)),
                    static_cast<float>(ob - period * std::floor(ob / period)));
      item.material.specular = 0.05f;
      item.casts_shadow = false;
      items.push_back(item);
    }
  }
}

}  // namespace

glm::vec3 to_glm(const core::Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

bool is_axis_of(const std::string& column, const std::string& signal) {
  if (column.size() <= signal.size() + 1 || column.compare(0, signal.size(), signal) != 0 ||
      column[signal.size()] != '.') {
    return false;
  }
  const std::string axis = column.substr(signal.size() + 1);
  if (axis == "x" || axis == "y" || axis == "z" || axis == "w") return true;
  return std::all_of(axis.begin(), axis.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

SceneDescription describe_scene(const core::Network& network, const toml::table& document) {
  SceneDescription scene;
  for (const auto& a : network.admittances()) {
    BodyVisual b;
    b.name = a->name();
    const toml::table* table = body_table(document, b.name);
    if (const auto* arm = dynamic_cast<const components::PlanarArm*>(a.get())) {
      b.kind = BodyVisual::Kind::arm;
      b.base = arm->params().base;
      b.plane_x = arm->plane_x();
      b.plane_y = arm->plane_y();
      b.axis = arm->params().axis;
      const toml::array* links = table ? (*table)["links"].as_array() : nullptr;
      for (std::size_t i = 0; i < arm->params().links.size(); ++i) {
        const double length = arm->params().links[i].length;
        double width = 0.0;
        if (links && i < links->size()) {
          if (const toml::table* link = (*links)[i].as_table()) {
            width = (*link)["width"].value<double>().value_or(0.0);
          }
        }
        b.lengths.push_back(length);
        b.widths.push_back(width > 0.0 ? width : 0.1 * length);
      }
    } else if (dynamic_cast<const components::RigidBody*>(a.get())) {
      const std::string shape = table ? (*table)["shape"].value_or(std::string()) : "";
      if (shape == "box") {
        b.kind = BodyVisual::Kind::box;
        b.size = vec3_of((*table)["size"], b.size);
      } else {
        b.kind = BodyVisual::Kind::sphere;
        b.radius = table ? (*table)["radius"].value<double>().value_or(0.1) : 0.1;
      }
    } else if (dynamic_cast<const components::PointMass*>(a.get())) {
      b.kind = BodyVisual::Kind::block;
    } else {
      continue;  // an admittance with no pose of its own
    }
    scene.bodies.push_back(std::move(b));
  }
  const toml::table* contact_tables = document["impedances"].as_table();
  std::vector<std::string> drawn;  // contact tables whose surface is drawn already
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const core::Impedance* imp = network.impedances()[i].get();
    const auto* fixed = dynamic_cast<const components::KikuuweContact*>(imp);
    const auto* moving = dynamic_cast<const components::MovingContact*>(imp);
    if (!fixed && !moving) continue;
    const components::KikuuweContactParams& params = fixed ? fixed->params() : moving->params();
    // The element of a contact point "NAME.i" comes from the table NAME.
    std::string table_name = imp->name();
    if (!(contact_tables && (*contact_tables)[table_name].as_table())) {
      table_name = table_name.substr(0, table_name.rfind('.'));
    }
    const bool several = table_name != imp->name();
    SurfaceVisual s{params.normal.normalized(), params.offset, params.extent, moving};
    if (std::find(drawn.begin(), drawn.end(), table_name) == drawn.end()) {
      drawn.push_back(table_name);
      const bool seen =
          !moving && !params.extent.bounded() &&
          std::any_of(scene.surfaces.begin(), scene.surfaces.end(), [&](const auto& o) {
            return !o.moving && !o.extent.bounded() && (o.normal - s.normal).norm() < 1e-9 &&
                   std::abs(o.offset - s.offset) < 1e-9;
          });
      if (!seen) scene.surfaces.push_back(s);
    }
    // The contact's body, from its map; a trail only for a single contact point.
    const auto wired = network.map_of(static_cast<int>(i)).admittances();
    const std::string body = wired.empty() ? "" : wired.front()->name();
    const toml::table* t = contact_tables ? (*contact_tables)[table_name].as_table() : nullptr;
    for (auto& b : scene.bodies) {
      if (b.name != body) continue;
      if (b.kind == BodyVisual::Kind::block) b.up = s.normal;
      if (several) continue;
      ContactVisual c{imp->name(), body, b.kind == BodyVisual::Kind::sphere ? b.radius : 0.0,
                      s.normal};
      if (t && (*t)["radius"].is_number()) c.radius = (*t)["radius"].value<double>().value_or(c.radius);
      scene.contacts.push_back(c);
    }
  }
  auto body_index = [&](const core::Admittance* a) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (a != nullptr && scene.bodies[i].name == a->name()) return static_cast<int>(i);
    }
    return -1;
  };
  const toml::table* imps = document["impedances"].as_table();
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const auto* joint = dynamic_cast<const components::PenaltyJoint*>(network.impedances()[i].get());
    if (!joint) continue;
    // The map lists the child first, then the parent (none: the ground).
    const auto wired = network.map_of(static_cast<int>(i)).admittances();
    JointVisual j;
    j.name = joint->name();
    j.child = wired.empty() ? -1 : body_index(wired[0]);
    j.parent = wired.size() > 1 ? body_index(wired[1]) : -1;
    if (j.child < 0 || (wired.size() > 1 && j.parent < 0)) continue;
    const toml::table* t = imps ? (*imps)[j.name].as_table() : nullptr;
    if (t) {
      j.point = vec3_of((*t)["point"], j.point);
      j.parent_point = vec3_of((*t)["parent_point"], j.parent_point);
    }
    j.axis = joint->params().axis_child.normalized();
    const BodyVisual& c = scene.bodies[static_cast<std::size_t>(j.child)];
    if (c.kind == BodyVisual::Kind::box) j.width = c.size.minCoeff();
    if (c.kind == BodyVisual::Kind::sphere) j.width = c.radius;
    scene.joints.push_back(j);
  }
  return scene;
}

PoseTrack::PoseTrack(const core::Trajectory& trajectory, const SceneDescription& scene)
    : trajectory_(trajectory) {
  const auto t_col = trajectory.find("t");
  if (!t_col || trajectory.row_count() == 0) {
    throw RenderError("the trajectory has no rows (nothing to render)");
  }
  t_ = trajectory.column(*t_col);
  auto need = [&](const std::string& name) {
    const auto c = trajectory.find(name);
    if (!c) throw RenderError("the renderer needs the signal '" + name + "', absent from the run");
    return *c;
  };
  for (const auto& b : scene.bodies) {
    Columns c;
    if (b.kind == BodyVisual::Kind::arm) {
      for (std::size_t i = 0; i < b.lengths.size(); ++i) {
        c.theta.push_back(need(b.name + ".theta." + std::to_string(i)));
      }
    } else {
      for (const char* axis : {"x", "y", "z"}) c.p.push_back(need(b.name + ".p." + axis));
      if (b.kind != BodyVisual::Kind::block) {
        for (const char* axis : {"w", "x", "y", "z"}) c.q.push_back(need(b.name + ".q." + axis));
      }
    }
    columns_.push_back(std::move(c));
  }
}

std::pair<int, double> PoseTrack::locate(double t) const {
  if (t <= t_.front() || t_.size() == 1) return {0, 0.0};
  if (t >= t_.back()) return {static_cast<int>(t_.size()) - 2, 1.0};
  const auto it = std::upper_bound(t_.begin(), t_.end(), t);
  const int r = static_cast<int>(it - t_.begin()) - 1;
  const double span = t_[r + 1] - t_[r];
  return {r, span > 0.0 ? (t - t_[r]) / span : 0.0};
}

double PoseTrack::value(int column, double t) const {
  const auto [r, w] = locate(t);
  if (t_.size() == 1) return trajectory_.at(0, column);
  return (1.0 - w) * trajectory_.at(r, column) + w * trajectory_.at(r + 1, column);
}

core::Vec3 PoseTrack::position(int body, double t) const {
  const auto& p = columns_[body].p;
  return {value(p[0], t), value(p[1], t), value(p[2], t)};
}

core::Quat PoseTrack::orientation(int body, double t) const {
  const auto& q = columns_[body].q;
  if (q.empty()) return core::Quat::Identity();
  const auto [r, w] = locate(t);
  auto at = [&](int row) {
    return core::Quat(trajectory_.at(row, q[0]), trajectory_.at(row, q[1]),
                      trajectory_.at(row, q[2]), trajectory_.at(row, q[3]));
  };
  if (t_.size() == 1) return at(0).normalized();
  core::Quat a = at(r), b = at(r + 1);
  if (a.dot(b) < 0.0) b.coeffs() = -b.coeffs();
  core::Quat m;
  m.coeffs() = (1.0 - w) * a.coeffs() + w * b.coeffs();
  return m.normalized();
}

double PoseTrack::angle(int body, int joint, double t) const {
  return value(columns_[body].theta[static_cast<std::size_t>(joint)], t);
}

double PoseTrack::signal(const std::string& name, double t) const {
  if (const auto c = trajectory_.find(name)) return value(*c, t);
  double sum = 0.0;
  bool any = false;
  for (int c = 0; c < trajectory_.column_count(); ++c) {
    const std::string& column = trajectory_.columns()[c];
    if (is_axis_of(column, name)) {
      const double v = value(c, t);
      sum += v * v;
      any = true;
    }
  }
  return any ? std::sqrt(sum) : std::numeric_limits<double>::quiet_NaN();
}

std::vector<core::Vec3> arm_joints(const BodyVisual& arm, const PoseTrack& poses, int index,
                                   double t) {
  return arm_pose(arm, poses, index, t).joints;
}

Bounds body_bounds(const SceneDescription& scene, const PoseTrack& poses, double t) {
  Bounds bounds;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyVisual& b = scene.bodies[i];
    const int index = static_cast<int>(i);
    if (b.kind == BodyVisual::Kind::arm) {
      const double w = *std::max_element(b.widths.begin(), b.widths.end());
      for (const auto& p : arm_pose(b, poses, index, t).joints) {
        bounds.add(to_glm(p) - glm::vec3(float(w)));
        bounds.add(to_glm(p) + glm::vec3(float(w)));
      }
      continue;
    }
    const glm::vec3 p = to_glm(poses.position(index, t));
    glm::vec3 r(0.0f);
    switch (b.kind) {
      case BodyVisual::Kind::sphere: r = glm::vec3(static_cast<float>(b.radius)); break;
      case BodyVisual::Kind::box: r = box_half_extent(b.size, poses.orientation(index, t)); break;
      default: r = glm::vec3(static_cast<float>(b.size.norm())); break;
    }
    bounds.add(p - r);
    bounds.add(p + r);
  }
  // Joint cylinders, as an arm's joints.
  for (const auto& j : scene.joints) {
    const glm::vec3 p = to_glm(joint_point(j, poses, t));
    bounds.add(p - glm::vec3(static_cast<float>(j.width)));
    bounds.add(p + glm::vec3(static_cast<float>(j.width)));
  }
  return bounds;
}

Bounds run_bounds(const SceneDescription& scene, const PoseTrack& poses, int samples) {
  Bounds bounds;
  for (int i = 0; i < samples; ++i) {
    const double t = poses.start_time() +
                     (poses.end_time() - poses.start_time()) * i / std::max(1, samples - 1);
    bounds.add(body_bounds(scene, poses, t));
  }
  return bounds;
}

std::vector<DrawItem> build_items(const SceneDescription& scene, const PoseTrack& poses, double t,
                                  const Bounds& focus) {
  std::vector<DrawItem> items;
  const Bounds all = run_bounds(scene, poses, 16);
  const double scale = body_scale(scene);
  const float checker = static_cast<float>(nice_floor(scale));

  // Surfaces: the contacts' planes, or a floor under the scene.
  std::vector<SurfaceVisual> surfaces = scene.surfaces;
  double floor_z = 0.0;
  if (surfaces.empty()) {
    double gap = 0.5 * scale;
    // Arms and jointed rigid bodies: three link widths below the lowest joint.
    double link_width = 0.0;
    for (const auto& b : scene.bodies) {
      if (b.kind == BodyVisual::Kind::arm) {
        link_width = std::max(link_width, *std::max_element(b.widths.begin(), b.widths.end()));
      }
    }
    for (const auto& j : scene.joints) link_width = std::max(link_width, j.width);
    if (link_width > 0.0) gap = 3.0 * link_width;
    floor_z = (all.empty() ? 0.0 : all.min.z) - gap;
    surfaces.push_back({core::Vec3::UnitZ(), floor_z, {}, nullptr});
  }
  const Bounds& around = focus.empty() ? all : focus;
  const float half = std::max(20.0f, 8.0f * (around.empty() ? 1.0f : around.radius()));
  for (const auto& s : surfaces) add_surface(items, s, around, half, checker, t);

  int links = 0;  // jointed rigid bodies so far: their colours alternate as an arm's links
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyVisual& b = scene.bodies[i];
    const int index = static_cast<int>(i);
    DrawItem item;
    switch (b.kind) {
      case BodyVisual::Kind::sphere: {
        item.shape = Shape::sphere;
        item.model = glm::translate(glm::mat4(1.0f), to_glm(poses.position(index, t))) *
                     to_glm(poses.orientation(index, t)) *
                     glm::scale(glm::mat4(1.0f), glm::vec3(static_cast<float>(b.radius)));
        item.material.kind = MaterialKind::sphere_pattern;
        item.body = index;
        item.material.colour = kSphereColour;
        item.material.colour2 = kSphereColour2;
        item.material.shininess = 48.0f;
        item.material.specular = 0.35f;
        items.push_back(item);
        break;
      }
      case BodyVisual::Kind::box: {
        item.shape = Shape::box;
        item.model = glm::translate(glm::mat4(1.0f), to_glm(poses.position(index, t))) *
                     to_glm(poses.orientation(index, t)) *
                     glm::scale(glm::mat4(1.0f), 0.5f * to_glm(b.size));
        item.material.colour = kBoxColour;
        if (is_link(scene, index) && links++ % 2 == 1) item.material.colour = kLinkColour2;
        items.push_back(item);
        break;
      }
      case BodyVisual::Kind::block: {
        core::Vec3 t1, t2;
        tangents(b.up, t1, t2);
        const core::Vec3 centre_point = poses.position(index, t) + 0.5 * b.size.z() * b.up;
        item.shape = Shape::box;
        item.model = glm::translate(glm::mat4(1.0f), to_glm(centre_point)) *
                     rotation_from_basis(t1, t2, b.up) *
                     glm::scale(glm::mat4(1.0f), 0.5f * to_glm(b.size));
        item.material.colour = kBlockColour;
        items.push_back(item);
        break;
      }
      case BodyVisual::Kind::arm: {
        const ArmPose pose = arm_pose(b, poses, index, t);
        const float w0 = static_cast<float>(b.widths.front());
        // A post from the floor to the base joint.
        // An arm in a tilted plane (a pendulum) would swing through a post under its base:
        // the post stands beside the plane, on the far side from the default camera (+y),
        // and an axle along the joint axis joins it to the base.
        const bool upright = std::abs(b.axis.z()) > 0.9;
        const core::Vec3 side = (b.axis.y() >= 0.0 ? 1.0 : -1.0) * b.axis;
        const core::Vec3 post_at =
            upright ? b.base : core::Vec3(b.base + 2.5 * b.widths.front() * side);
        if (!upright) {
          DrawItem axle;
          axle.shape = Shape::cylinder;
          core::Vec3 t1, t2;
          tangents(side, t1, t2);
          axle.model = glm::translate(glm::mat4(1.0f), to_glm(0.5 * (b.base + post_at))) *
                       rotation_from_basis(t1, t2, side) *
                       glm::scale(glm::mat4(1.0f),
                                  glm::vec3(0.35f * w0, 0.35f * w0,
                                            0.5f * static_cast<float>((post_at - b.base).norm())));
          axle.material.colour = glm::vec3(0.35f);
          items.push_back(axle);
        }
        if (scene.surfaces.empty()) {
          const float z0 = static_cast<float>(floor_z), z1 = static_cast<float>(b.base.z());
          DrawItem post;
          post.shape = Shape::cylinder;
          post.model =
              glm::translate(glm::mat4(1.0f),
                             glm::vec3(to_glm(post_at).x, to_glm(post_at).y, 0.5f * (z0 + z1))) *
              glm::scale(glm::mat4(1.0f), glm::vec3(0.7f * w0, 0.7f * w0, 0.5f * (z1 - z0)));
          post.material.colour = glm::vec3(0.35f);
          items.push_back(post);
        }
        for (std::size_t k = 0; k < b.lengths.size(); ++k) {
          const float w = static_cast<float>(b.widths[k]);
          const core::Vec3 mid = 0.5 * (pose.joints[k] + pose.joints[k + 1]);
          DrawItem link;
          link.shape = Shape::box;
          const core::Vec3 along =
              std::cos(pose.phi[k]) * b.plane_x + std::sin(pose.phi[k]) * b.plane_y;
          link.model =
              glm::translate(glm::mat4(1.0f), to_glm(mid)) *
              rotation_from_basis(along, b.axis.cross(along), b.axis) *
              glm::scale(glm::mat4(1.0f),
                         glm::vec3(0.5f * static_cast<float>(b.lengths[k]), 0.5f * w, 0.5f * w));
          link.material.colour = k % 2 == 0 ? kBoxColour : kLinkColour2;
          items.push_back(link);
          DrawItem joint;
          joint.shape = Shape::cylinder;
          joint.model = glm::translate(glm::mat4(1.0f), to_glm(pose.joints[k])) *
                        rotation_from_basis(b.plane_x, b.plane_y, b.axis) *
                        glm::scale(glm::mat4(1.0f), glm::vec3(0.95f * w, 0.95f * w, 0.85f * w));
          joint.material.colour = kJointColour;
          joint.material.specular = 0.5f;
          items.push_back(joint);
        }
        // The tip: a small sphere, so the end of the chain reads clearly.
        DrawItem tip;
        tip.shape = Shape::sphere;
        tip.model = glm::translate(glm::mat4(1.0f), to_glm(pose.joints.back())) *
                    glm::scale(glm::mat4(1.0f), glm::vec3(0.6f * static_cast<float>(b.widths.back())));
        tip.material.colour = kJointColour;
        items.push_back(tip);
        break;
      }
    }
  }

  // Penalty joints, drawn as an arm's: a dark cylinder along the joint axis at the
  // articulation point, a post from the floor to a joint held by the ground, and a small
  // sphere at the free end of a chain's last link.
  for (const auto& j : scene.joints) {
    const float w = static_cast<float>(j.width);
    if (j.parent < 0 && scene.surfaces.empty()) {
      const float z0 = static_cast<float>(floor_z), z1 = static_cast<float>(j.parent_point.z());
      const glm::vec3 base = to_glm(j.parent_point);
      DrawItem post;
      post.shape = Shape::cylinder;
      post.model = glm::translate(glm::mat4(1.0f), glm::vec3(base.x, base.y, 0.5f * (z0 + z1))) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(0.7f * w, 0.7f * w, 0.5f * (z1 - z0)));
      post.material.colour = glm::vec3(0.35f);
      items.push_back(post);
    }
    DrawItem joint;
    joint.shape = Shape::cylinder;
    joint.model = glm::translate(glm::mat4(1.0f), to_glm(joint_point(j, poses, t))) *
                  align_z(joint_axis(j, poses, t)) *
                  glm::scale(glm::mat4(1.0f), glm::vec3(0.95f * w, 0.95f * w, 0.85f * w));
    joint.material.colour = kJointColour;
    joint.material.specular = 0.5f;
    items.push_back(joint);
    // The tip: the child's point mirrored through its centre, if the child is a box jointed
    // near one end and carries no further joint.
    const BodyVisual& child = scene.bodies[static_cast<std::size_t>(j.child)];
    const bool parent_of_another = std::any_of(scene.joints.begin(), scene.joints.end(),
                                               [&](const JointVisual& o) { return o.parent == j.child; });
    if (child.kind == BodyVisual::Kind::box && !parent_of_another &&
        j.point.norm() > 0.25 * child.size.maxCoeff()) {
      const core::Vec3 end = poses.position(j.child, t) - poses.orientation(j.child, t) * j.point;
      DrawItem tip;
      tip.shape = Shape::sphere;
      tip.model = glm::translate(glm::mat4(1.0f), to_glm(end)) *
                  glm::scale(glm::mat4(1.0f), glm::vec3(0.6f * w));
      tip.material.colour = kJointColour;
      items.push_back(tip);
    }
  }
  return items;
}

}  // namespace stiction::render
