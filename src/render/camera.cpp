#include "render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "render/framing.hpp"
#include "render/mechanism_items.hpp"
#include "render/scene_geometry.hpp"
#include "render/tree_items.hpp"

namespace stiction::render {

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::mat4 Camera::projection(float aspect) const {
  const glm::mat4 centred =
      glm::perspective(glm::radians(fov_y_degrees), aspect, near_plane, far_plane);
  if (lens_shift == glm::vec2(0.0f)) return centred;
  // Adds lens_shift to the normalized device coordinates (clip x += shift.x w): the picture
  // moves, the depth and the view do not.
  return glm::translate(glm::mat4(1.0f), glm::vec3(lens_shift, 0.0f)) * centred;
}

Camera frame_bounds(const Bounds& bounds, glm::vec3 direction, float fov_y_degrees, float aspect,
                    float margin) {
  Camera camera;
  camera.fov_y_degrees = fov_y_degrees;
  const glm::vec3 f = glm::normalize(direction);
  const glm::vec3 right = glm::normalize(glm::cross(f, camera.up));
  const glm::vec3 up = glm::cross(right, f);
  const float ty = std::tan(glm::radians(fov_y_degrees) * 0.5f) * (1.0f - margin);
  const float tx = ty * aspect;
  const glm::vec3 c = bounds.centre();
  float distance = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x,
                           (i & 2) ? bounds.max.y : bounds.min.y,
                           (i & 4) ? bounds.max.z : bounds.min.z);
    const glm::vec3 o = corner - c;
    // The corner's depth is distance + o.f; it must see |x| and |y| within the half-angles.
    distance = std::max(distance, std::abs(glm::dot(o, right)) / tx - glm::dot(o, f));
    distance = std::max(distance, std::abs(glm::dot(o, up)) / ty - glm::dot(o, f));
  }
  distance = std::max(distance, 1e-3f);
  camera.target = c;
  camera.eye = c - f * distance;
  const float r = std::max(bounds.radius(), 1e-3f);
  camera.near_plane = std::max(1e-3f, 0.05f * (distance - r));
  camera.far_plane = distance + 60.0f * r + 20.0f;
  return camera;
}

namespace {

// The horizontal direction the cameras look along: +y (from the front), or, for a scene
// with an arm swinging in a vertical plane, along its joint axis so the arm is seen face on.
glm::vec3 front_direction(const Drawing& scene) {
  glm::vec3 forward(0.0f, 1.0f, 0.0f);
  for (const BodyVisual& body : scene.bodies) {
    if (body.kind != BodyVisual::Kind::arm) continue;
    const glm::vec3 axis = to_glm(body.axis);
    const glm::vec3 horizontal(axis.x, axis.y, 0.0f);
    if (glm::length(horizontal) > 0.5f) forward = -glm::normalize(horizontal);
    break;
  }
  return forward;
}

// The first body with a pose of its own (a planar arm has none to follow).
int first_followable(const Drawing& scene) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (!jointed(scene.bodies[i])) return static_cast<int>(i);
  }
  return -1;
}

// The links of the scene's kinematic trees (not their bases) at 96 times of the run; empty
// if the scene has no tree.
std::vector<glm::vec3> robot_links(const Drawing& scene, const PoseTrack& poses) {
  std::vector<glm::vec3> points;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyVisual& b = scene.bodies[i];
    if (b.kind != BodyVisual::Kind::tree || b.tree == nullptr) continue;
    const float w = static_cast<float>(*std::max_element(b.widths.begin(), b.widths.end()));
    for (int k = 0; k < 96; ++k) {
      const double t = poses.start_time() + (poses.end_time() - poses.start_time()) * k / 95.0;
      for (const core::Vec3& p : tree_points(b, poses, static_cast<int>(i), t, true)) {
        for (int c = 0; c < 8; ++c) {
          points.push_back(to_glm(p) +
                           glm::vec3((c & 1) ? w : -w, (c & 2) ? w : -w, (c & 4) ? w : -w));
        }
      }
    }
  }
  return points;
}

}  // namespace

glm::vec3 default_view_direction(const Drawing& scene) {
  // A three-quarter view looking down ~28 degrees, slightly from the side: from the front
  // (-y), or, for a scene with an arm swinging in a vertical plane, from in front of that
  // plane (along its joint axis) so that the arm is seen face on, not edge on.
  const glm::vec3 forward = front_direction(scene);
  const glm::vec3 side(-forward.y, forward.x, 0.0f);  // (-1, 0, 0) for the front view
  return glm::normalize(forward + 0.30f * side + glm::vec3(0.0f, 0.0f, -0.55f));
}

glm::vec3 view_direction(CameraView view, const Drawing& scene) {
  const glm::vec3 forward = front_direction(scene);
  const glm::vec3 side(-forward.y, forward.x, 0.0f);
  switch (view) {
    case CameraView::side:  // nearly level: heights read true, the floor a thin strip
      return glm::normalize(forward + glm::vec3(0.0f, 0.0f, -0.08f));
    case CameraView::top:
      return glm::vec3(0.0f, 0.0f, -1.0f);
    case CameraView::three_quarter:  // from a front corner, 35 degrees down
      return glm::normalize(forward + 0.9f * side + glm::vec3(0.0f, 0.0f, -0.95f));
    case CameraView::automatic:
    case CameraView::follow:
      break;
  }
  return default_view_direction(scene);
}

glm::vec3 view_up(CameraView view, const Drawing& scene) {
  // Looking straight down, +z cannot be up: the picture's up is the front direction.
  return view == CameraView::top ? front_direction(scene) : glm::vec3(0.0f, 0.0f, 1.0f);
}

CameraRig::CameraRig(const CameraSettings& settings, const Drawing& scene, const PoseTrack& poses,
                     float aspect)
    : CameraRig(settings, scene, poses,
                FramePanels{static_cast<int>(std::lround(10000.0f * aspect)), 10000, {}}) {}

CameraRig::CameraRig(const CameraSettings& settings, const Drawing& scene, const PoseTrack& poses,
                     const FramePanels& panels)
    : poses_(poses) {
  const CameraView view = settings.view;
  const glm::vec3 direction = view_direction(view, scene);
  const glm::vec3 up = view_up(view, scene);
  const float fov = static_cast<float>(settings.fov_degrees);
  if (view == CameraView::automatic || view == CameraView::follow) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (!settings.follow.empty() && scene.bodies[i].name == settings.follow &&
          !jointed(scene.bodies[i])) {
        follow_ = static_cast<int>(i);
      }
    }
  }
  if (view == CameraView::follow && follow_ < 0) follow_ = first_followable(scene);
  // Every body and every element of the mechanism at every time in view, framed by their
  // own points (an arm fills the picture rather than the box around its sweep), in the part
  // of the frame the panels leave free.
  auto whole_run = [&] {
    std::vector<glm::vec3> points = run_points(scene, poses, direction, 96, up);
    if (points.empty()) points.push_back(glm::vec3(0.0f));
    return frame_points_beside_panels(points, direction, fov, panels, 0.12f, up);
  };
  if (view == CameraView::automatic && follow_ >= 0 && has_world_parts(scene)) {
    // A follow camera would move the posts, rollers and pivots in the picture and hide the
    // body's motion against them (belt_oscillator's oscillation): the camera stays on the
    // whole mechanism while the followed body is still seen at a twelfth of the picture's
    // height or more.
    const Camera fixed = whole_run();
    const float height =
        2.0f * std::tan(glm::radians(fov) * 0.5f) * glm::length(fixed.target - fixed.eye);
    if (piece_size(scene.bodies[static_cast<std::size_t>(follow_)]) >= height / 12.0) follow_ = -1;
  }
  follow_vertical_ = settings.follow_vertical;
  // The follow view keeps its height; `follow` with the automatic view lets the height pass
  // up to a dead zone set below, once the distance is known.
  if (view == CameraView::follow) vertical_dead_zone_ = std::numeric_limits<float>::infinity();
  Bounds bounds;
  if (follow_ >= 0) {
    follow_origin_ = to_glm(poses.position(follow_, poses.start_time()));
    // The followed body's neighbourhood at the start (the ground square of a camera that
    // follows all three axes is centred on it).
    const Bounds b = body_bounds(scene, poses, poses.start_time());
    const glm::vec3 c = b.centre();
    const float h =
        std::max(0.5f * std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z}), 0.02f);
    bounds.add(c - glm::vec3(3.5f * h, 2.0f * h, h));
    bounds.add(c + glm::vec3(3.5f * h, 2.0f * h, h));
    follow_region_ = bounds;
    base_ = frame_followed(scene, direction, up, fov, panels);
  } else if (const std::vector<glm::vec3> links = robot_links(scene, poses);
             view == CameraView::follow && !links.empty()) {
    // Nothing to follow but fixed-base robots: the follow view frames their links over the
    // run (not their pedestals nor the ground around them), so the arm fills the picture
    // where the fixed presets show it whole on its floor.
    bounds = run_bounds(scene, poses);
    base_ = frame_points_beside_panels(links, direction, fov, panels, 0.12f, up);
  } else {
    bounds = run_bounds(scene, poses);
    base_ = whole_run();
  }
  if (bounds.empty()) bounds.add(glm::vec3(0.0f));
  // Following horizontally, the camera still moves vertically once the body is more than
  // this far above or below where it started, so a body that drops stays in the frame.
  if (view != CameraView::follow) {
    vertical_dead_zone_ =
        0.5f * std::tan(glm::radians(fov) * 0.5f) * glm::length(base_.eye - base_.target);
  }
  // An explicit eye or target is the user's camera: no automatic framing, the target at the
  // frame's centre. Under a follow camera both are where they are at the start of the run and
  // move with the body (shift), keeping their offset from it.
  if (settings.target) base_.target = to_glm(*settings.target);
  if (settings.position) base_.eye = to_glm(*settings.position);
  if (settings.position || settings.target) {
    base_.lens_shift = glm::vec2(0.0f);
    const float d = glm::length(base_.eye - base_.target);
    const float r = std::max(bounds.radius(), 1e-3f);
    base_.near_plane = std::max(1e-3f, 0.02f * d);
    base_.far_plane = d + 60.0f * r + 20.0f;
    // A view straight down would make lookAt degenerate: pick another up vector.
    if (glm::length(glm::cross(glm::normalize(base_.target - base_.eye), base_.up)) < 1e-3f) {
      base_.up = glm::vec3(0.0f, 1.0f, 0.0f);
    }
  }
}

Camera CameraRig::frame_followed(const Drawing& scene, glm::vec3 direction, glm::vec3 up, float fov,
                                 const FramePanels& panels) const {
  // The followed body as the moving camera sees it over the run (a bounce under a camera at
  // a fixed height moves it in the picture), framed into the free part of the frame: where
  // it goes, and the least distance at which all of it stays there.
  std::vector<glm::vec3> points;
  for (int i = 0; i < 96; ++i) {
    const double t = poses_.start_time() + (poses_.end_time() - poses_.start_time()) * i / 95.0;
    const std::size_t first = points.size();
    add_body_points(points, scene, poses_, follow_, t);
    for (std::size_t k = first; k < points.size(); ++k) points[k] -= shift(t);
  }
  Camera camera = frame_points_beside_panels(points, direction, fov, panels, 0.12f, up);
  // The distance at which the body's size spans kFollowFraction of the frame's height at the
  // reference field of view: a fixed distance, so `fov` zooms.
  const float size =
      static_cast<float>(piece_size(scene.bodies[static_cast<std::size_t>(follow_)]));
  const float at_fraction =
      size / (2.0f * kFollowFraction * std::tan(glm::radians(kFollowReferenceFov) * 0.5f));
  const glm::vec3 f = glm::normalize(camera.target - camera.eye);
  const float distance = std::max(glm::length(camera.target - camera.eye), at_fraction);
  camera.eye = camera.target - f * distance;
  camera.near_plane = std::max(1e-3f, 0.05f * (distance - size));
  camera.far_plane = distance + 60.0f * size + 20.0f;
  return camera;
}

glm::vec3 CameraRig::shift(double t) const {
  if (follow_ < 0) return glm::vec3(0.0f);
  glm::vec3 s = to_glm(poses_.position(follow_, t)) - follow_origin_;
  // By default horizontal motion only, so a bounce does not shake the picture; beyond the
  // dead zone the camera follows the height too (a body falling off an edge stays in view).
  if (!follow_vertical_) s.z -= std::clamp(s.z, -vertical_dead_zone_, vertical_dead_zone_);
  return s;
}

Camera CameraRig::at(double t) const {
  Camera c = base_;
  const glm::vec3 s = shift(t);
  c.eye += s;
  c.target += s;
  return c;
}

Bounds CameraRig::follow_bounds(double t) const {
  if (follow_ < 0) return Bounds{};
  const glm::vec3 s = shift(t);
  Bounds b;
  b.add(follow_region_.min + s);
  b.add(follow_region_.max + s);
  return b;
}

}  // namespace stiction::render
