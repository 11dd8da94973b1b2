// What the renderer draws: the shapes the scene declares (Scene::drawing, scene/drawing.hpp)
// and their poses at any time (from the trajectory's signals only: `<body>.p.*`, `<body>.q.*`,
// `<arm>.theta.*`), turned into a list of draw items. Defined in pose_track.cpp (PoseTrack),
// body_bounds.cpp (bounds), draw_items.cpp (build_items) and scene_view.cpp (small helpers);
// scene_geometry.hpp holds their shared maths.
#pragma once

#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/trajectory.hpp"
#include "core/types.hpp"
#include "scene/drawing.hpp"

namespace stiction::render {

// The trajectory lacks a column the renderer needs, or has no rows (exit code 1).
class RenderError : public std::runtime_error {
 public:
  explicit RenderError(const std::string& message) : std::runtime_error(message) {}
};

// What is drawn comes from the scene (scene/drawing.hpp): the builder fills it as it builds.
using Drawing = scene::Drawing;
using scene::BodyVisual;
using scene::body_index;
using scene::JointVisual;
using scene::jointed;
using scene::SourceVisual;
using scene::SpringVisual;
using scene::SurfaceVisual;

// mesh: a part of a URDF mesh file (DrawItem::mesh), drawn as the unit shapes are: its
// vertices mapped onto [-1, 1]^3 (TriangleMesh::Part::half_extent), so that the model
// matrix takes the unit cube to its bounding box.
enum class Shape { sphere, box, cylinder, plane, trail, cone, mesh };

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
  int body = -1;  // index into Drawing::bodies of the body drawn, or -1
  // Shape::mesh: the scene's mesh and which of its parts.
  std::shared_ptr<const scene::TriangleMesh> mesh;
  std::size_t mesh_part = 0;
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
  PoseTrack(const core::Trajectory& trajectory, const Drawing& scene);

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
std::vector<DrawItem> build_items(const Drawing& scene, const PoseTrack& poses, double t,
                                  const Bounds& focus = Bounds{});

// A planar arm's joints and then its tip at time t, as drawn (in the arm's plane of motion);
// `index` is the arm's index in scene.bodies.
std::vector<core::Vec3> arm_joints(const BodyVisual& arm, const PoseTrack& poses, int index,
                                   double t);
// Axis-aligned bounds of the bodies (not the surfaces) at time t.
Bounds body_bounds(const Drawing& scene, const PoseTrack& poses, double t);
// Union of body_bounds over `samples` times spread over the run.
Bounds run_bounds(const Drawing& scene, const PoseTrack& poses, int samples = 64);

// A vertex of the contact trails (render/trail.hpp builds them).
struct TrailVertex {
  glm::vec3 position;
  glm::vec3 colour;
};

glm::vec3 to_glm(const core::Vec3& v);

// True if `column` is "SIGNAL.AXIS" with AXIS one of x y z w or a joint index (DESIGN 4).
bool is_axis_of(const std::string& column, const std::string& signal);

}  // namespace stiction::render
