#include "render/framing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "render/mechanism_items.hpp"
#include "render/scene_geometry.hpp"
#include "render/tree_items.hpp"

namespace stiction::render {
namespace {

void add_cube(std::vector<glm::vec3>& points, glm::vec3 c, glm::vec3 half) {
  for (int i = 0; i < 8; ++i) {
    points.push_back(c + glm::vec3((i & 1) ? half.x : -half.x, (i & 2) ? half.y : -half.y,
                                   (i & 4) ? half.z : -half.z));
  }
}

}  // namespace

void add_body_points(std::vector<glm::vec3>& points, const Drawing& scene, const PoseTrack& poses,
                     int index, double t) {
  const BodyVisual& b = scene.bodies[static_cast<std::size_t>(index)];
  switch (b.kind) {
    case BodyVisual::Kind::arm: {
      // Joints and tip of the planar chain, in its own plane (as scene_view draws it), each
      // with the width of the link that ends there (the base with the first link's).
      const std::vector<core::Vec3> joints = arm_joints(b, poses, index, t);
      for (std::size_t k = 0; k < joints.size(); ++k) {
        const double width = b.widths[k == 0 ? 0 : k - 1];
        add_cube(points, to_glm(joints[k]), glm::vec3(static_cast<float>(width)));
      }
      break;
    }
    case BodyVisual::Kind::tree: {
      const float w = static_cast<float>(*std::max_element(b.widths.begin(), b.widths.end()));
      for (const core::Vec3& p : tree_points(b, poses, index, t))
        add_cube(points, to_glm(p), glm::vec3(w));
      break;
    }
    case BodyVisual::Kind::sphere: {
      // A polyhedron around the ball: 12 meridians, rings every 30 degrees and the poles, its
      // vertices 1 / cos(22.5 deg) = 1.08 radii out so that its faces (whose corners are at
      // most 21 degrees from their centres) stay outside the ball. The cube around it stood
      // out by up to sqrt(3) and framed a ball about 1.5x smaller than the picture allows.
      const glm::vec3 c = to_glm(poses.position(index, t));
      const double r = b.radius / std::cos(std::numbers::pi / 8.0);
      points.push_back(c + glm::vec3(0.0f, 0.0f, static_cast<float>(r)));
      points.push_back(c - glm::vec3(0.0f, 0.0f, static_cast<float>(r)));
      for (int ring = 1; ring < 6; ++ring) {
        const double polar = std::numbers::pi * ring / 6.0;
        for (int k = 0; k < 12; ++k) {
          const double a = 2.0 * std::numbers::pi * k / 12.0;
          points.push_back(c + static_cast<float>(r) *
                                   glm::vec3(static_cast<float>(std::sin(polar) * std::cos(a)),
                                             static_cast<float>(std::sin(polar) * std::sin(a)),
                                             static_cast<float>(std::cos(polar))));
        }
      }
      break;
    }
    case BodyVisual::Kind::cylinder: {
      // Its two rims, as regular 12-gons around them (not its box, whose corners stand out
      // by up to 41% of the radius as the wheel turns, which framed a rolling wheel smaller).
      const core::Vec3 c = poses.position(index, t);
      const core::Quat q = poses.orientation(index, t);
      core::Vec3 u, v;
      tangents(b.axis, u, v);
      const double r = b.radius / std::cos(std::numbers::pi / 12.0);
      for (int k = 0; k < 12; ++k) {
        const double a = 2.0 * std::numbers::pi * k / 12.0;
        const core::Vec3 rim = r * (std::cos(a) * u + std::sin(a) * v);
        for (const double side : {-0.5, 0.5}) {
          points.push_back(to_glm(c + q * (rim + side * b.length * b.axis)));
        }
      }
      break;
    }
    case BodyVisual::Kind::box: {
      const core::Vec3 c = poses.position(index, t);
      const core::Quat q = poses.orientation(index, t);
      for (int k = 0; k < 8; ++k) {
        const core::Vec3 corner(((k & 1) ? 0.5 : -0.5) * b.size.x(),
                                ((k & 2) ? 0.5 : -0.5) * b.size.y(),
                                ((k & 4) ? 0.5 : -0.5) * b.size.z());
        points.push_back(to_glm(c + q * corner));
      }
      break;
    }
    case BodyVisual::Kind::block: {
      // A block sits on its surface: its centre is half its height along the normal.
      const core::Vec3 c = poses.position(index, t) + 0.5 * b.size.z() * b.up;
      add_cube(points, to_glm(c), glm::vec3(static_cast<float>(0.5 * b.size.norm())));
      break;
    }
  }
}

std::vector<glm::vec3> body_points(const Drawing& scene, const PoseTrack& poses, double t) {
  std::vector<glm::vec3> points;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    add_body_points(points, scene, poses, static_cast<int>(i), t);
  }
  for (const JointVisual& j : scene.joints) {
    const core::Vec3 p = poses.position(j.child, t) + poses.orientation(j.child, t) * j.point;
    add_cube(points, to_glm(p), glm::vec3(static_cast<float>(j.width)));
  }
  return points;
}

// The size of the bodies' pieces: a sphere's diameter, a free box's or block's largest side,
// a link's width (a chain is framed by its reach, not by its size).
float piece_size(const Drawing& scene) {
  float size = 0.0f;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyVisual& b = scene.bodies[i];
    const bool link =
        std::any_of(scene.joints.begin(), scene.joints.end(), [&](const JointVisual& j) {
          return j.child == static_cast<int>(i) || j.parent == static_cast<int>(i);
        });
    double s = 0.0;
    switch (b.kind) {
      case BodyVisual::Kind::sphere:
        s = 2.0 * b.radius;
        break;
      case BodyVisual::Kind::cylinder:
      case BodyVisual::Kind::box:
        s = link ? b.size.minCoeff() : b.size.maxCoeff();
        break;
      case BodyVisual::Kind::block:
        s = b.size.maxCoeff();
        break;
      case BodyVisual::Kind::arm:
      case BodyVisual::Kind::tree:
        s = *std::max_element(b.widths.begin(), b.widths.end());
        break;
    }
    size = std::max(size, static_cast<float>(s));
  }
  return size;
}

std::vector<glm::vec3> run_points(const Drawing& scene, const PoseTrack& poses, glm::vec3 direction,
                                  int samples, glm::vec3 up_hint,
                                  const std::function<glm::vec3(double)>& moving_frame) {
  std::vector<glm::vec3> points;
  Bounds all;
  const MechanismFrame mechanism = mechanism_frame(scene, poses);
  for (int i = 0; i < samples; ++i) {
    const double t =
        poses.start_time() + (poses.end_time() - poses.start_time()) * i / std::max(1, samples - 1);
    std::vector<glm::vec3> at = body_points(scene, poses, t);
    const std::vector<glm::vec3> parts = mechanism_points(scene, poses, mechanism, t);
    at.insert(at.end(), parts.begin(), parts.end());
    const glm::vec3 offset = moving_frame ? moving_frame(t) : glm::vec3(0.0f);
    for (glm::vec3& p : at) {
      p -= offset;
      all.add(p);
    }
    points.insert(points.end(), at.begin(), at.end());
  }
  // Some ground around bodies that barely move (a block at rest would fill the picture): a
  // rectangle five pieces wide and three high (about a 16:9 frame's shape) around the centre
  // of the run, facing the camera so that it is seen centred. Three pieces high puts a body
  // at rest at about a third of the picture's height, as a follow camera shows its body
  // (kFollowFraction); a square six pieces wide and high showed a wheel or a ball that rolls
  // a metre at a sixth of the height, under a band of sky.
  if (!all.empty()) {
    const glm::vec3 f = glm::normalize(direction);
    const glm::vec3 right = glm::normalize(glm::cross(f, up_hint));
    const glm::vec3 up = glm::cross(right, f);
    const float p = piece_size(scene);
    for (const glm::vec3 d : {2.5f * p * right, -2.5f * p * right, 1.5f * p * up, -1.5f * p * up})
      points.push_back(all.centre() + d);
  }
  return points;
}

Camera frame_points(const std::vector<glm::vec3>& points, glm::vec3 direction, float fov_y_degrees,
                    float aspect, float margin, glm::vec3 up_hint) {
  Camera camera;
  camera.fov_y_degrees = fov_y_degrees;
  camera.up = up_hint;
  if (points.empty()) return camera;
  const glm::vec3 f = glm::normalize(direction);
  const glm::vec3 right = glm::normalize(glm::cross(f, camera.up));
  const glm::vec3 up = glm::cross(right, f);
  const float ty = std::tan(glm::radians(fov_y_degrees) * 0.5f) * (1.0f - margin);
  const float tx = ty * aspect;
  glm::vec3 c0(0.0f);
  for (const glm::vec3& p : points) c0 += p;
  c0 /= static_cast<float>(points.size());
  // With the eye at c0 + cx right + cy up - d f, point i (coordinates x, y, z along right,
  // up, f) is in view if |x - cx| <= tx (d + z) and |y - cy| <= ty (d + z). For each axis,
  // cx + tx d >= max(x - tx z) =: A and tx d - cx >= max(-x - tx z) =: B; the least d is
  // (A + B) / (2 tx), with cx = (A - B) / 2.
  float ax = -1e30f, bx = -1e30f, ay = -1e30f, by = -1e30f, radius = 0.0f;
  for (const glm::vec3& p : points) {
    const glm::vec3 o = p - c0;
    const float x = glm::dot(o, right), y = glm::dot(o, up), z = glm::dot(o, f);
    ax = std::max(ax, x - tx * z);
    bx = std::max(bx, -x - tx * z);
    ay = std::max(ay, y - ty * z);
    by = std::max(by, -y - ty * z);
    radius = std::max(radius, glm::length(o));
  }
  const float d = std::max({(ax + bx) / (2.0f * tx), (ay + by) / (2.0f * ty), 1e-3f});
  const glm::vec3 target = c0 + 0.5f * (ax - bx) * right + 0.5f * (ay - by) * up;
  camera.target = target;
  camera.eye = target - f * d;
  const float r = std::max(radius, 1e-3f);
  camera.near_plane = std::max(1e-3f, 0.05f * (d - r));
  camera.far_plane = d + 60.0f * r + 20.0f;
  return camera;
}

Camera frame_points_beside_panels(const std::vector<glm::vec3>& points, glm::vec3 direction,
                                  float fov_y_degrees, const FramePanels& panels, float margin,
                                  glm::vec3 up, PixelBox* free) {
  const float half = std::tan(glm::radians(fov_y_degrees) * 0.5f);
  Camera best;
  float best_distance = std::numeric_limits<float>::infinity();
  for (const PixelBox& r : free_rectangles(panels)) {
    // The rectangle seen from the eye is a frustum of its own, centred on the view's axis once
    // the lens is shifted: its half-height is `half` times its share of the frame's height.
    const float h = static_cast<float>(r.height()) / static_cast<float>(panels.height);
    const float w = static_cast<float>(r.width()) / static_cast<float>(panels.width);
    const float fov = 2.0f * glm::degrees(std::atan(half * h));
    Camera c = frame_points(points, direction, fov, panels.aspect() * w / h, margin, up);
    const float distance = glm::length(c.target - c.eye);
    if (distance < best_distance) {
      best_distance = distance;
      c.fov_y_degrees = fov_y_degrees;
      c.lens_shift =
          glm::vec2(static_cast<float>(r.x0 + r.x1) / static_cast<float>(panels.width) - 1.0f,
                    1.0f - static_cast<float>(r.y0 + r.y1) / static_cast<float>(panels.height));
      best = c;
      if (free) *free = r;
    }
  }
  return best;
}

}  // namespace stiction::render
