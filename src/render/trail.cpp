#include "render/trail.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::render {
namespace {

const glm::vec3 kStick{0.05f, 0.55f, 0.15f};
const glm::vec3 kSlip{0.85f, 0.05f, 0.05f};

int body_index(const SceneDescription& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

void append_ribbon(std::vector<TrailVertex>& strip, const SceneDescription& scene,
                   const PoseTrack& poses, const ContactVisual& c, int body, double t,
                   double seconds, double threshold) {
  const double t0 = std::max(poses.start_time(), t - seconds);
  const double half = 0.5 * trail_width(scene, c);
  constexpr int kSteps = 96;
  std::vector<TrailVertex> ribbon;
  ribbon.reserve(2 * (kSteps + 1));
  core::Vec3 previous = core::Vec3::Zero();
  for (int i = 0; i <= kSteps; ++i) {
    const double s = t0 + (t - t0) * i / kSteps;
    const core::Vec3 p = poses.position(body, s) - c.radius * c.normal;
    // Project onto the surface plane (slightly above it) so a bounce does not lift the trail.
    core::Vec3 on = p - c.normal * (c.normal.dot(p));
    for (const auto& surface : scene.surfaces) {
      if ((surface.normal - c.normal).norm() < 1e-9) {
        on += (surface.offset + 1e-3) * c.normal;
        break;
      }
    }
    core::Vec3 dir = i == 0 ? core::Vec3(core::Vec3::UnitX()) : core::Vec3(on - previous);
    if (dir.norm() < 1e-9) dir = core::Vec3::UnitX();
    core::Vec3 side = c.normal.cross(dir);
    if (side.norm() < 1e-12) side = c.normal.cross(core::Vec3::UnitY());
    side = side.normalized() * half;
    const double slip = poses.signal(c.contact + ".slip", s);
    const glm::vec3 colour = std::isnan(slip) || sticks(slip, threshold) ? kStick : kSlip;
    ribbon.push_back({to_glm(on - side), colour});
    ribbon.push_back({to_glm(on + side), colour});
    previous = on;
  }
  if (ribbon.empty()) return;
  if (!strip.empty()) {
    // Degenerate triangles join this ribbon to the previous one without drawing anything.
    strip.push_back(strip.back());
    strip.push_back(ribbon.front());
  }
  strip.insert(strip.end(), ribbon.begin(), ribbon.end());
}

}  // namespace

float trail_width(const SceneDescription& scene, const ContactVisual& contact) {
  const int body = body_index(scene, contact.body);
  if (body < 0) return 0.01f;
  const BodyVisual& b = scene.bodies[static_cast<std::size_t>(body)];
  if (b.kind == BodyVisual::Kind::sphere) return static_cast<float>(0.15 * b.radius);
  if (b.kind == BodyVisual::Kind::block) return static_cast<float>(0.3 * b.size.x());
  return static_cast<float>(0.15 * std::max(contact.radius, 0.05 * b.size.maxCoeff()));
}

std::vector<TrailVertex> build_trails(const SceneDescription& scene, const PoseTrack& poses,
                                      double t, const TrailOptions& options) {
  std::vector<TrailVertex> strip;
  for (const ContactVisual& c : scene.contacts) {
    if (!options.contacts.empty() && std::find(options.contacts.begin(), options.contacts.end(),
                                               c.contact) == options.contacts.end()) {
      continue;
    }
    const int body = body_index(scene, c.body);
    if (body < 0) continue;
    const auto it = options.thresholds.find(c.contact);
    const double threshold =
        it != options.thresholds.end() ? it->second : options.default_threshold;
    append_ribbon(strip, scene, poses, c, body, t, options.seconds, threshold);
  }
  return strip;
}

}  // namespace stiction::render
