// Automatic framing from the bodies' own extreme points (not the corners of their bounding
// box): an arm sweeping a quarter circle is framed by where its links actually are, so it
// fills the picture instead of sitting in a corner of an empty box.
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "render/camera.hpp"
#include "render/frame_panels.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {

// Points whose convex hull holds every body (and penalty joint) at time t.
std::vector<glm::vec3> body_points(const Drawing& scene, const PoseTrack& poses, double t);
// The points of body `index` alone (a sphere's: the corners of its cube).
void add_body_points(std::vector<glm::vec3>& points, const Drawing& scene, const PoseTrack& poses,
                     int index, double t);

// body_points and the mechanism's points (springs, posts, sources' arrows, rollers, pivots:
// mechanism_items.hpp) at `samples` times spread over the run, and a rectangle five of the
// bodies' pieces wide and three high facing a camera looking along `direction` with `up` (a
// view straight down needs another up than +z), centred on them (ground around a body at
// rest, which it shows at about a third of the picture's height).
// `moving_frame`, if given, is subtracted from the points at each time: the points as seen
// by a camera that moves by it (a follow camera).
std::vector<glm::vec3> run_points(const Drawing& scene, const PoseTrack& poses, glm::vec3 direction,
                                  int samples = 96, glm::vec3 up = glm::vec3(0.0f, 0.0f, 1.0f),
                                  const std::function<glm::vec3(double)>& moving_frame = {});

// The closest camera looking along `direction` that shows every point with `margin` (the
// fraction of the half-width and half-height of the view left free on the tightest side).
// The camera is shifted sideways so the points' picture is centred; exact for perspective.
Camera frame_points(const std::vector<glm::vec3>& points, glm::vec3 direction, float fov_y_degrees,
                    float aspect, float margin = 0.12f, glm::vec3 up = glm::vec3(0.0f, 0.0f, 1.0f));

// frame_points into the part of the frame the panels leave free: for each free rectangle
// (free_rectangles), the closest camera that shows every point inside that rectangle with
// `margin` (of the rectangle's half-sizes), its lens shifted (Camera::lens_shift) so the
// rectangle's centre is on the view's axis; of those, the closest, which shows the points
// largest. `free`, if given, receives the rectangle chosen. Without panels: frame_points.
Camera frame_points_beside_panels(const std::vector<glm::vec3>& points, glm::vec3 direction,
                                  float fov_y_degrees, const FramePanels& panels,
                                  float margin = 0.12f, glm::vec3 up = glm::vec3(0.0f, 0.0f, 1.0f),
                                  PixelBox* free = nullptr);

}  // namespace stiction::render
