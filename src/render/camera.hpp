// Perspective camera, framed automatically from the bodies' positions over the run (every
// body stays in view) or set by the scene file ([camera] position/target/fov), optionally
// following one body's horizontal motion (and its height once it leaves a dead zone of half
// the picture's half-height, so a dropping body stays in the frame), or with
// follow_vertical, its motion along all three axes. `view` presets (camera_preset.hpp) pick
// the direction (side, top, three-quarter) or a follow camera at a fixed height; every fixed
// camera frames the mechanism's elements too (mechanism_items.hpp).
#pragma once

#include <glm/glm.hpp>

#include "render/render_settings.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {

struct Camera {
  glm::vec3 eye{0.0f, -3.0f, 1.5f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 0.0f, 1.0f};
  float fov_y_degrees = 40.0f;
  float near_plane = 0.01f;
  float far_plane = 100.0f;

  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
};

// The closest camera looking along `direction` (from the eye towards the target) that shows
// every corner of `bounds` with a margin (fraction of the half-extent of the view left free).
Camera frame_bounds(const Bounds& bounds, glm::vec3 direction, float fov_y_degrees, float aspect,
                    float margin = 0.12f);

// The automatic camera's viewing direction: a three-quarter view from the front (-y), or
// from in front of the plane of the first arm that swings in a vertical plane.
glm::vec3 default_view_direction(const Drawing& scene);

// A preset's viewing direction (`auto` and `follow`: default_view_direction) and the
// picture's up vector (+z, or the front direction for `top`).
glm::vec3 view_direction(CameraView view, const Drawing& scene);
glm::vec3 view_up(CameraView view, const Drawing& scene);

// The camera at every time of a run.
class CameraRig {
 public:
  CameraRig(const CameraSettings& settings, const Drawing& scene, const PoseTrack& poses,
            float aspect);
  Camera at(double t) const;
  // True if the camera follows a body along all three axes.
  bool follows_vertically() const { return follow_ >= 0 && follow_vertical_; }
  // The region framed around the followed body at time t (the body's neighbourhood at the
  // start, moved as the camera is); empty for a fixed camera.
  Bounds follow_bounds(double t) const;

 private:
  glm::vec3 shift(double t) const;

  const PoseTrack& poses_;
  Camera base_;
  int follow_ = -1;  // body index, -1: fixed
  bool follow_vertical_ = false;
  glm::vec3 follow_origin_{0};       // followed body's position at the start
  Bounds follow_region_;             // followed body's neighbourhood at the start
  float vertical_dead_zone_ = 0.0f;  // height change (m) a horizontal follow lets pass
};

}  // namespace stiction::render
