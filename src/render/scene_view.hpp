// What the renderer draws: the shapes of a scene (from its components and its document) and
// their poses at any time (from the trajectory's signals only: `<body>.p.*`, `<body>.q.*`,
// `<arm>.theta.*`), turned into a list of draw items. Defined in scene_description.cpp
// (describe_scene), pose_track.cpp (PoseTrack), body_bounds.cpp (bounds), draw_items.cpp
// (build_items) and scene_view.cpp (small helpers); scene_geometry.hpp holds their shared maths.
#pragma once

#include <toml++/toml.h>

#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

#include "components/admittance/spatial_tree.hpp"
#include "components/impedance/moving_contact.hpp"
#include "components/impedance/surface_extent.hpp"
#include "core/network.hpp"
#include "core/trajectory.hpp"
#include "core/types.hpp"
#include "scene/urdf_loader.hpp"

namespace stiction::render {

// The trajectory lacks a column the renderer needs, or has no rows (exit code 1).
class RenderError : public std::runtime_error {
 public:
  explicit RenderError(const std::string& message) : std::runtime_error(message) {}
};

struct BodyVisual {
  // tree: a components::SpatialTree (a urdf or spatial_tree body), drawn from its link poses.
  enum class Kind { sphere, box, block, arm, cylinder, tree };
  Kind kind = Kind::sphere;
  std::string name;
  double radius = 0.0;                   // sphere, cylinder
  core::Vec3 size{0.1, 0.1, 0.1};        // box, block: full side lengths; cylinder: its
                                         // body-frame bounding box (bounds, framing, arrows)
  double length = 0.0;                   // cylinder (along `axis`, body frame)
  bool hollow = false;                   // cylinder: a ring (drawn with dark bores)
  core::Vec3 up{0.0, 0.0, 1.0};          // block: normal of the surface it rests on
  core::Vec3 base = core::Vec3::Zero();  // arm
  // arm: its plane of motion, e1 and e2 (theta_0 from e1 towards e2), and the joint axis;
  // cylinder: `axis` is its axis in the body frame
  core::Vec3 plane_x{1.0, 0.0, 0.0}, plane_y{0.0, 1.0, 0.0}, axis{0.0, 0.0, 1.0};
  std::vector<double> lengths, widths;  // arm links; tree: per link, its reach and thickness
  const components::SpatialTree* tree = nullptr;  // tree
  std::vector<scene::UrdfVisual> visuals;         // tree: its URDF's shapes (none: a stick figure)
};

// True for the jointed bodies, which have no pose columns of their own (arm, tree).
inline bool jointed(const BodyVisual& b) {
  return b.kind == BodyVisual::Kind::arm || b.kind == BodyVisual::Kind::tree;
}

// A contact's surface. With an extent only that rectangle (or half-plane, strip) of the plane
// is drawn; a moving surface is drawn at its tilt at time t, its checker carried along by the
// belt (both from the contact component's own law of t).
struct SurfaceVisual {
  core::Vec3 normal{0.0, 0.0, 1.0};
  double offset = 0.0;
  components::SurfaceExtent extent;                   // the whole plane unless bounded()
  const components::MovingContact* moving = nullptr;  // null: fixed
};

// A contact whose touching point can leave a trail (point = p - radius * normal).
struct ContactVisual {
  std::string contact;  // impedance name, for its slip signal
  std::string body;
  double radius = 0.0;
  core::Vec3 normal{0.0, 0.0, 1.0};
  double offset = 0.0;  // its surface's plane n . x = offset (at rest for a moving one)
};

// A revolute joint between two rigid bodies (penalty_joint), drawn like a planar arm's joint:
// a dark cylinder along the joint axis at the articulation point, and a post down to the
// floor when the parent is the ground.
struct JointVisual {
  std::string name;                              // impedance name
  int child = -1;                                // index into SceneDescription::bodies
  int parent = -1;                               // -1: the ground
  core::Vec3 point = core::Vec3::Zero();         // articulation point in the child's frame
  core::Vec3 parent_point = core::Vec3::Zero();  // in the parent's frame (world for the ground)
  core::Vec3 axis{0.0, 0.0, 1.0};                // joint axis in the child's frame (unit)
  double width = 0.02;                           // the child's thickness (as an arm link's width)
};

// A spring-damper between a point of a body and a point of another body or of the world
// (spring_damper wired to points; with `length`, a line spring), drawn as a coil, with a
// damper inside it when its damping is non-zero and a post under a world end.
struct SpringVisual {
  std::string name;                             // impedance name
  int body = -1;                                // the moving side, index into bodies
  core::Vec3 point = core::Vec3::Zero();        // in the body's frame
  int other = -1;                               // -1: the world
  core::Vec3 other_point = core::Vec3::Zero();  // in other's frame (world for the world)
  double damping = 0.0;                         // Ns/m; > 0: a damper is drawn
  double free_length = 0.0;                     // m; 0: a zero-length spring (spring_damper)
};

// A force or torque source, drawn as an arrow scaled by its value at time t (its trajectory
// columns `NAME.f.*` or `NAME.tau`, i.e. the value of its own law at every output row).
struct SourceVisual {
  enum class Kind { force, torque };
  Kind kind = Kind::force;
  std::string name;                       // impedance name: its signal is NAME.f or NAME.tau
  int body = -1;                          // index into bodies
  core::Vec3 point = core::Vec3::Zero();  // force: application point in the body's frame
  bool body_frame = false;                // force: its value is in the body's frame
  core::Vec3 axis{0.0, 0.0, 1.0};         // torque on a rigid body: axis in its frame (unit)
  int joint = -1;                         // torque on a planar arm's joint (axis: the arm's)
};

struct SceneDescription {
  std::vector<BodyVisual> bodies;
  std::vector<SurfaceVisual> surfaces;  // empty: a floor is put under the scene
  std::vector<ContactVisual> contacts;
  std::vector<JointVisual> joints;
  std::vector<SpringVisual> springs;
  std::vector<SourceVisual> sources;
};

// Shapes from the network's components (dynamic_cast) and the body tables of the document
// (shape, radius, size, link widths); surfaces from kikuuwe_contact impedances; joints from
// penalty_joint impedances (bodies from their maps, axes from their params, articulation
// points from the document's `point` and `parent_point`).
// `robot_visuals`: the urdf bodies' shapes by body name (Scene::robot_visuals), if any.
SceneDescription describe_scene(
    const core::Network& network, const toml::table& document,
    const std::map<std::string, std::vector<scene::UrdfVisual>>* robot_visuals = nullptr);

// Index of the body named `name` in scene.bodies, -1 if there is none.
int body_index(const SceneDescription& scene, const std::string& name);

enum class Shape { sphere, box, cylinder, plane, trail, cone };

enum class MaterialKind { plain = 0, checker = 1, sphere_pattern = 2 };

struct Material {
  MaterialKind kind = MaterialKind::plain;
  glm::vec3 colour{0.5f};  // linear RGB
  glm::vec3 colour2{0.5f};
  float shininess = 32.0f;
  float specular = 0.25f;
  float checker_size = 0.2f;     // metres per square (checker)
  float grid_spacing = 1.0f;     // metres between darker grid lines (checker)
  float local_scale = 1.0f;      // unit-shape coordinates -> metres (checker)
  glm::vec2 local_offset{0.0f};  // added after scaling, so squares align with the world
  // Motion blur of the sphere pattern (render/spin_blur.hpp): the rotation during the
  // frame's exposure, about `spin_axis` (object coordinates, unit), `spin_blur` radians.
  glm::vec3 spin_axis{0.0f, 0.0f, 1.0f};
  float spin_blur = 0.0f;
};

struct DrawItem {
  Shape shape = Shape::box;
  glm::mat4 model{1.0f};  // unit shape -> world
  Material material;
  bool casts_shadow = true;
  int body = -1;  // index into SceneDescription::bodies of the body drawn, or -1
};

struct Bounds {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};
  void add(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void add(const Bounds& b) {
    if (!b.empty()) {
      add(b.min);
      add(b.max);
    }
  }
  bool empty() const { return min.x > max.x; }
  glm::vec3 centre() const { return 0.5f * (min + max); }
  float radius() const { return 0.5f * glm::length(max - min); }
};

// Pose lookups with linear interpolation between rows (quaternions: normalized lerp).
class PoseTrack {
 public:
  // Throws RenderError naming a missing column.
  PoseTrack(const core::Trajectory& trajectory, const SceneDescription& scene);

  double start_time() const { return t_.front(); }
  double end_time() const { return t_.back(); }

  core::Vec3 position(int body, double t) const;
  core::Quat orientation(int body, double t) const;
  double angle(int body, int joint, double t) const;
  // Value of a trajectory column (or the norm of the columns NAME.*) at time t; NaN if absent.
  double signal(const std::string& name, double t) const;
  // Index of a column, -1 if absent; its value at time t; the largest |value| over the run.
  int column(const std::string& name) const;
  double column_value(int column, double t) const { return value(column, t); }
  double column_peak(int column) const;

 private:
  struct Columns {
    std::vector<int> p;      // x y z
    std::vector<int> q;      // w x y z
    std::vector<int> theta;  // arm joints
  };
  // Row index r and weight w with value = (1 - w) row[r] + w row[r + 1].
  std::pair<int, double> locate(double t) const;
  double value(int column, double t) const;

  const core::Trajectory& trajectory_;
  std::vector<double> t_;
  std::vector<Columns> columns_;
  // column_peak's results. A PoseTrack belongs to one FrameRenderer, used from one thread.
  mutable std::map<int, double> peaks_;
};

// Everything to draw at time t: surfaces, bodies (arms as boxes plus joint cylinders; box
// links of penalty joints likewise, with their joints' cylinders and the base post).
// `focus`, if not empty, is the region a camera following a body along all three axes shows:
// the ground square is then centred on it (not on the whole run, which may span kilometres
// and would leave the checker without float precision near the body).
std::vector<DrawItem> build_items(const SceneDescription& scene, const PoseTrack& poses, double t,
                                  const Bounds& focus = Bounds{});

// A planar arm's joints and then its tip at time t, as drawn (in the arm's plane of motion);
// `index` is the arm's index in scene.bodies.
std::vector<core::Vec3> arm_joints(const BodyVisual& arm, const PoseTrack& poses, int index,
                                   double t);
// Axis-aligned bounds of the bodies (not the surfaces) at time t.
Bounds body_bounds(const SceneDescription& scene, const PoseTrack& poses, double t);
// Union of body_bounds over `samples` times spread over the run.
Bounds run_bounds(const SceneDescription& scene, const PoseTrack& poses, int samples = 64);

// A vertex of the contact trails (render/trail.hpp builds them).
struct TrailVertex {
  glm::vec3 position;
  glm::vec3 colour;
};

glm::vec3 to_glm(const core::Vec3& v);

// True if `column` is "SIGNAL.AXIS" with AXIS one of x y z w or a joint index (DESIGN 4).
bool is_axis_of(const std::string& column, const std::string& signal);

}  // namespace stiction::render
