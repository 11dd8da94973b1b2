// Perspective camera, framed automatically from the scene's bounds or set by the scene file
// ([camera] position/target/fov), optionally following one body's horizontal motion.
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

// The camera at every time of a run.
class CameraRig {
 public:
  CameraRig(const CameraSettings& settings, const SceneDescription& scene, const PoseTrack& poses,
            float aspect);
  Camera at(double t) const;

 private:
  const PoseTrack& poses_;
  Camera base_;
  int follow_ = -1;             // body index, -1: fixed
  glm::vec3 follow_origin_{0};  // followed body's position at the start
};

}  // namespace stiction::render
