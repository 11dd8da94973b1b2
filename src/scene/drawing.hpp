// What a scene draws: a plain description of its bodies with their shapes, the surfaces,
// the contact sites (which body, which columns, the body point each contact acts at), the
// joints, springs and sources. The scene builder fills it as it builds each element, beside
// the network (MuJoCo's model carries its geoms, Box2D its shape definitions); the renderer
// and the figures read only this and the trajectory's signals, never the scene's TOML and
// never a concrete component class (DESIGN.md section 2).
// Poses are not here: they come from the signals (`<body>.p.*`, `<body>.q.*`,
// `<arm>.theta.*`); what is here is what stays fixed over a run.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "components/admittance/spatial_tree.hpp"
#include "components/impedance/moving_contact.hpp"
#include "components/impedance/surface_extent.hpp"
#include "components/maps/pair_contact_map.hpp"
#include "core/rim_point.hpp"
#include "core/types.hpp"
#include "scene/triangle_mesh.hpp"

namespace stiction::scene {

// A visual of a URDF link (<visual>): drawn on the link's pose.
struct UrdfVisual {
  enum class Shape { box, cylinder, sphere, mesh };
  Shape shape = Shape::box;
  int link = -1;                  // index into the tree's links, -1: the fixed base
  std::string link_name;          // the URDF link it is written in (messages)
  core::Vec3 size = core::Vec3::Zero();  // box: sides; cylinder: (radius, radius, length)
                                         // along its z axis; sphere: (r, r, r); mesh: scale
  core::Vec3 origin = core::Vec3::Zero();        // in the link frame
  core::Quat rotation = core::Quat::Identity();  // in the link frame
  Eigen::Vector4d rgba{0.6, 0.6, 0.62, 1.0};     // <material><color>, grey if none
  bool rgba_given = false;                       // the URDF gave a <material><color>
  std::string mesh;                              // mesh: its file name as written
  // mesh: the file it names (scene/mesh_path.hpp) and its triangles, read when the scene is
  // loaded (scene/mesh_file.hpp); a part without the URDF's colour takes the file's own.
  std::filesystem::path mesh_file;
  std::shared_ptr<const TriangleMesh> triangles;
};

struct BodyVisual {
  // block: a point mass; arm: a planar arm; tree: a spatial tree (a urdf or spatial_tree
  // body), drawn from its link poses.
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
  const components::SpatialTree* tree = nullptr;  // tree: its kinematics (link poses)
  std::vector<UrdfVisual> visuals;                // tree: its URDF's shapes (none: a stick figure)
};

// True for the jointed bodies, which have no pose columns of their own (arm, tree).
inline bool jointed(const BodyVisual& b) {
  return b.kind == BodyVisual::Kind::arm || b.kind == BodyVisual::Kind::tree;
}

// A contact's surface. With an extent only that rectangle (or half-plane, strip) of the plane
// is drawn; a moving surface is drawn at its tilt at time t, its checker carried along by the
// belt (both from the contact element's own law of t).
struct SurfaceVisual {
  core::Vec3 normal{0.0, 0.0, 1.0};
  double offset = 0.0;
  components::SurfaceExtent extent;                   // the whole plane unless bounded()
  const components::MovingContact* moving = nullptr;  // null: fixed
};

// Where a contact element acts, so that its overlays (stick/slip badge, contact dot, force
// arrows, trail) sit where the force does: its columns are NAME.f.*, NAME.slip.*, NAME.n_force.
struct ContactSite {
  // How the touching point follows the body:
  //   point: body point `local`, less `radius` along the surface normal (a sphere's lowest
  //          point, a box's corner, a listed point);
  //   rim:   a cylinder's or ring's rim point nearest the surface (`rim`, core/rim_point.hpp);
  //   pair:  a contact between two bodies, its point from both poses (`pair`, probe_pair).
  enum class Rule { point, rim, pair };
  Rule rule = Rule::point;
  std::string name;   // element name
  std::string group;  // the contact table ("floor" for "floor.3")
  int body = -1;      // index into Drawing::bodies
  core::Vec3 local = core::Vec3::Zero();  // point: body-frame point the contact sits about
  double radius = 0.0;                    // point: round shape about `local`
  core::RimPoint rim{};                   // rim: the leg of the cylinder's rim tripods
  core::Vec3 normal{0.0, 0.0, 1.0};       // surface normal at rest (unit)
  double offset = 0.0;                    // surface plane n . x = offset at rest
  const components::MovingContact* moving = nullptr;  // null: fixed surface
  double stick_threshold = 1e-3;                      // m/s, the element's (its events')
  // pair: the second body's index and the pair's shapes.
  int other = -1;
  components::PairShape pair{};
  // Draws a trail: a single-point contact, or a cylinder's nearest rim point on each cap.
  bool trail = false;
};

// A friction element on a joint of a planar arm or a kinematic tree (a urdf or spatial_tree
// body): its slip speed is |ARM.omega.AXIS| (rate_column), its badge sits at the joint.
struct JointSite {
  std::string name;  // the friction element (its column NAME.tau)
  std::string arm;   // the arm's or tree's name: its columns ARM.omega.AXIS
  int body = -1;     // the arm's or tree's index into Drawing::bodies
  int joint = 0;     // the joint's index (a tree's: its link's)
  double stick_threshold = 1e-3;  // rad/s
  std::string axis{};  // a tree's joint name, which names its columns; empty: an arm's index
};

// The column of the joint's rate: ARM.omega.1 on an arm, TREE.omega.elbow on a tree.
inline std::string rate_column(const JointSite& site) {
  return site.arm + ".omega." + (site.axis.empty() ? std::to_string(site.joint) : site.axis);
}

// Every contact point (one per element "NAME" or "NAME.i" of a kikuuwe_contact table: box
// corners, rim points and listed points included) and every friction joint of an arm or tree.
struct ContactSites {
  std::vector<ContactSite> contacts;
  std::vector<JointSite> joints;
};

// A revolute joint between two rigid bodies (penalty_joint), drawn like a planar arm's joint:
// a dark cylinder along the joint axis at the articulation point, and a post down to the
// floor when the parent is the ground.
struct JointVisual {
  std::string name;                              // impedance name
  int child = -1;                                // index into Drawing::bodies
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
  int joint = -1;                         // torque on an arm's joint (axis: the arm's)
};

struct Drawing {
  std::vector<BodyVisual> bodies;       // in the network's order of admittances
  std::vector<SurfaceVisual> surfaces;  // empty: a floor is put under the scene
  ContactSites sites;
  std::vector<JointVisual> joints;
  std::vector<SpringVisual> springs;
  std::vector<SourceVisual> sources;
};

// Index of the body named `name` in drawing.bodies, -1 if there is none.
int body_index(const Drawing& drawing, const std::string& name);

// What the builder knows of a body, as drawn: its shape and sizes (from its own table).
// A planar arm's link widths default to a tenth of their length.
BodyVisual arm_visual(const std::string& name, const core::Vec3& base, const core::Vec3& plane_x,
                      const core::Vec3& plane_y, const core::Vec3& axis,
                      const std::vector<double>& lengths, const std::vector<double>& widths);
// A cylinder of `radius` and `length` along the body-frame `axis` (hollow: a ring).
BodyVisual cylinder_visual(const std::string& name, double radius, double length,
                           const core::Vec3& axis, bool hollow);
// A spatial tree's stick figure: each link's reach (the farthest of its children's joints and
// its centre of mass, at least 2 cm) and a thickness a tenth of it; `visuals` its URDF shapes.
BodyVisual tree_visual(const components::SpatialTree& tree, std::vector<UrdfVisual> visuals);

// Adds a contact's surface unless the same table's is drawn already, or (fixed, unbounded)
// the same plane is.
void add_surface(Drawing& drawing, const SurfaceVisual& surface);

}  // namespace stiction::scene
