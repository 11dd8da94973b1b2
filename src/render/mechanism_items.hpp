// The mechanism around the bodies, drawn so that a viewer sees it without reading the scene:
// springs as coils (a damper inside when damped) with a post under a world end, force
// sources as straight arrows and torque sources as curved ones (both scaled by the source's
// value at time t against its largest over the run), belts between two turning rollers,
// tilting planes on an axle along their tilt axis. Each element's geometry is a function of
// its own, so that tests and the framing use exactly what is drawn.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "render/scene_view.hpp"

namespace stiction::render {

// What the elements' geometry needs from the whole run, computed once per frame list.
struct MechanismFrame {
  double scale = 0.1;    // body_scale: the scene's characteristic piece
  double floor_z = 0.0;  // the floor drawn under a scene without surfaces (under the bodies'
                         // run and the springs' world ends)
  Bounds run;            // the bodies over the run
  // Per spring: offset of its drawn world end (a zero-length spring whose anchor sits inside
  // or next to its body is drawn with its post set back, see spring_ends).
  std::vector<glm::vec3> spring_setback;
  // Per source: its columns NAME.f.x .y .z or NAME.tau (empty if absent) and its largest
  // magnitude over the run (the root of the sum of its columns' largest squares).
  std::vector<std::vector<int>> source_columns;
  std::vector<double> source_peak;
};

// `run`: the bodies' bounds over the run when the caller has them already (build_items).
MechanismFrame mechanism_frame(const Drawing& scene, const PoseTrack& poses,
                               const Bounds* run = nullptr);

struct SpringEnds {
  glm::vec3 a{0.0f};  // on the body (a block's at half its height)
  glm::vec3 b{0.0f};  // on the other body, or the drawn world end
  bool post = false;  // b is held by the world: a post from the floor to b
  glm::vec3 post_foot{0.0f};
  float coil_radius = 0.02f;
};
// A zero-length spring (spring_damper without `length`) whose world anchor is closer to its
// body than three body sizes over the run (belt_oscillator's post is inside the block) is
// drawn with the anchor set back along the spring's mean direction over the run by what it
// lacks: the drawn coil then shows the spring's stretch, and its law along that direction is
// unchanged (K times the displacement from the mean).
SpringEnds spring_ends(const Drawing& scene, const PoseTrack& poses,
                       const MechanismFrame& frame, int spring, double t);

struct ForceArrow {
  glm::vec3 tail{0.0f}, vector{0.0f};  // the head touches the application point
  float shaft_radius = 0.005f;
};
struct TorqueArc {
  glm::vec3 centre{0.0f}, axis{0.0f, 0.0f, 1.0f}, start{1.0f, 0.0f, 0.0f};  // start: unit, _|_ axis
  float radius = 0.1f;
  float sweep = 0.0f;  // radians about axis (right hand), |sweep| = 1.5 pi at the run's peak,
                       // centred on the top of the circle
  float tube_radius = 0.005f;
};
// A source's arrow at time t: length (or sweep) in proportion to its value over its largest
// over the run; nullopt when it is zero or has no column.
std::optional<ForceArrow> force_arrow(const Drawing& scene, const PoseTrack& poses,
                                      const MechanismFrame& frame, int source, double t);
std::optional<TorqueArc> torque_arc(const Drawing& scene, const PoseTrack& poses,
                                    const MechanismFrame& frame, int source, double t);

struct BeltRollers {
  glm::vec3 centre[2];   // roller axes' midpoints, the belt's top tangent to them
  glm::vec3 axis{0.0f};  // along the rollers (across the belt)
  float radius = 0.02f, half_length = 0.1f;
  double span_min = 0.0, span_max = 0.0;  // the belt between them, along its direction from
                                          // the plane's origin (offset * normal)
};
// A belt's rollers (nullopt for a surface that is not a belt): at the ends of its extent
// along its direction, or, for an endless one, 2.5 pieces beyond the bodies' run and the
// springs' anchors.
std::optional<BeltRollers> belt_rollers(const Drawing& scene, const MechanismFrame& frame,
                                        const SurfaceVisual& surface);

struct PivotAxle {
  glm::vec3 a{0.0f}, b{0.0f};  // ends, along the tilt axis just under the plane
  float radius = 0.01f;
};
// A tilting plane's axle at time t (nullopt for a surface that does not tilt).
std::optional<PivotAxle> pivot_axle(const MechanismFrame& frame, const SurfaceVisual& surface,
                                    double t);

// Draw items of every element above at time t.
void add_mechanism_items(std::vector<DrawItem>& items, const Drawing& scene,
                         const PoseTrack& poses, const MechanismFrame& frame, double t);

// Points whose hull holds every element above at time t (coil ends and radius, post feet,
// arrows, arcs, rollers, axle ends), for the framing.
std::vector<glm::vec3> mechanism_points(const Drawing& scene, const PoseTrack& poses,
                                        const MechanismFrame& frame, double t);

// True if the scene has parts held by the world (posts, belt rollers, pivots): a camera
// following a body would make them move in the picture.
bool has_world_parts(const Drawing& scene);

}  // namespace stiction::render
