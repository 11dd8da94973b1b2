// The spin cue of a fast sphere. The octant pattern repeats every half turn about the spin
// axis, so a sphere turning more than a quarter turn per frame aliases (it seems to turn
// slowly, stand still or turn backwards). Like a film camera with an open shutter, each frame
// instead shows the pattern averaged over the rotation during the frame (motion blur): at low
// spin it is sharp; as the spin rises it smears along the direction of turning; past half a
// turn per frame it is a uniform blend in which the dark band around the spin axis stays
// sharp, so the picture shows "fast spin about this axis" and never a false slow rotation.
#pragma once

#include <vector>

#include "render/scene_view.hpp"

namespace stiction::render {

// Rotation of body `body` during [t - exposure / 2, t + exposure / 2] as an angle (radians,
// >= 0) about an axis in the body's frame (angle 0: axis +z). Measured over short
// sub-intervals, so a rotation of many turns per frame is not folded back into one turn.
struct SpinDuringFrame {
  glm::vec3 axis{0.0f, 0.0f, 1.0f};
  float angle = 0.0f;
};
SpinDuringFrame spin_during_frame(const PoseTrack& poses, int body, double t, double exposure);

// The blur (radians) for a frame during which the body turns `turned` radians: none up to
// 0.3 rad, then rising to the whole rotation at half a turn (pi) per frame.
float blur_angle(float turned);

// Sets the blur of every sphere-pattern item that belongs to a body.
void apply_spin_blur(std::vector<DrawItem>& items, const PoseTrack& poses, double t,
                     double exposure);

}  // namespace stiction::render
