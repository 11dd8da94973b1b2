// Perspective camera, framed automatically from the bodies' positions over the run (every
// body stays in view) or set by the scene file ([camera] position/target/fov), optionally
// following one body's horizontal motion (and its height once it leaves a dead zone of half
// the picture's half-height, so a dropping body stays in the frame), or with
// follow_vertical, its motion along all three axes. `view` presets (camera_preset.hpp) pick
// the direction (side, top, three-quarter) or a follow camera at a fixed height; every fixed
// camera frames the mechanism's elements too (mechanism_items.hpp). An automatic camera
// frames into the part of the frame the panels (title, caption, time panel, inset) leave
// free, shifting its lens rather than turning (framing.hpp), so no body goes under a panel.
#pragma once

#include <glm/glm.hpp>

#include "render/frame_panels.hpp"
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
  // Where the view's axis (eye to target) meets the picture, in normalized device coordinates
  // (x right, y up, the frame's edges at +-1): (0, 0) is the frame's centre. Off centre, the
  // projection is an off-axis one (a shifted lens, as a view camera's): the picture is moved
  // without turning the camera, so the framing of the free part of the frame beside the
  // panels (framing.hpp) stays exact and verticals stay vertical.
  glm::vec2 lens_shift{0.0f};

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

// A follow camera (view = "follow", or `follow` with the automatic view) stands where the
// followed body's size (a sphere's or cylinder's diameter, a box's largest side: piece_size)
// spans kFollowFraction of the frame's height at a field of view of kFollowReferenceFov
// degrees; the distance is fixed by that, so `fov` zooms: the body spans
// kFollowFraction * tan(kFollowReferenceFov / 2) / tan(fov / 2) of the height. It stands
// farther when the body would otherwise leave the free part of the frame (a narrow fov, a
// bounce under a camera at a fixed height).
inline constexpr float kFollowFraction = 1.0f / 3.0f;
inline constexpr float kFollowReferenceFov = 40.0f;

// The camera at every time of a run.
class CameraRig {
 public:
  // `panels`: the frame's size and the panels drawn over it (frame_panels.hpp); an automatic
  // camera frames the bodies into the part of the frame they leave free.
  CameraRig(const CameraSettings& settings, const Drawing& scene, const PoseTrack& poses,
            const FramePanels& panels);
  // A frame of this aspect ratio without panels.
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
  // The follow camera's base (see kFollowFraction), at the start of the run.
  Camera frame_followed(const Drawing& scene, glm::vec3 direction, glm::vec3 up, float fov,
                        const FramePanels& panels) const;

  const PoseTrack& poses_;
  Camera base_;
  int follow_ = -1;  // body index, -1: fixed
  bool follow_vertical_ = false;
  glm::vec3 follow_origin_{0};       // followed body's position at the start
  Bounds follow_region_;             // followed body's neighbourhood at the start
  float vertical_dead_zone_ = 0.0f;  // height change (m) a horizontal follow lets pass
};

}  // namespace stiction::render
