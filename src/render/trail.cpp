#include "render/trail.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/contact_sites.hpp"

namespace stiction::render {
namespace {

const glm::vec3 kStick{0.05f, 0.55f, 0.15f};
const glm::vec3 kSlip{0.85f, 0.05f, 0.05f};

// Appends a ribbon of at least two vertex pairs to the strip and empties it.
void flush_ribbon(std::vector<TrailVertex>& strip, std::vector<TrailVertex>& ribbon) {
  if (ribbon.size() >= 4) {
    if (!strip.empty()) {
      // Degenerate triangles join this ribbon to the previous one without drawing anything.
      strip.push_back(strip.back());
      strip.push_back(ribbon.front());
    }
    strip.insert(strip.end(), ribbon.begin(), ribbon.end());
  }
  ribbon.clear();
}

void append_ribbon(std::vector<TrailVertex>& strip, const Drawing& scene, const PoseTrack& poses,
                   const ContactSite& c, double t, double seconds, double threshold) {
  const double t0 = std::max(poses.start_time(), t - seconds);
  const double half = 0.5 * trail_width(scene, c);
  constexpr int kSteps = 96;
  std::vector<TrailVertex> ribbon;
  ribbon.reserve(2 * (kSteps + 1));
  // A moving surface carries its trail: each point is kept in the surface's frame at its time
  // and drawn where that surface point is now (on the board as it tilts, moving with a belt).
  const components::MovingContact* moving = c.moving;
  core::Vec3 normal = c.normal;
  double travel_now = 0.0, travel = 0.0;
  if (moving != nullptr) {
    normal = moving->surface(t).frame.n;
    travel_now = moving->belt_travel(t);
    travel = moving->belt_travel(t0);
  }
  // The contact's own plane: another surface with the same normal (a floor under a
  // platform) is at another height.
  const double fixed_offset = c.offset;
  core::Vec3 previous = core::Vec3::Zero();
  double previous_s = t0;
  for (int i = 0; i <= kSteps; ++i) {
    const double s = t0 + (t - t0) * i / kSteps;
    core::Vec3 on;
    double height = 0.0;  // of the contact point above the surface at s
    if (moving != nullptr) {
      const components::SurfaceState surface = moving->surface(s);
      const core::Vec3 p = contact_point(c, poses, s);
      height = surface.frame.n.dot(p - surface.origin);
      // Beyond a bounded board's edge the plane goes on only in the maths: no trail there.
      const components::SurfaceExtent& extent = moving->params().extent;
      const core::Vec3& pivot = moving->motion().pivot;
      if (extent.bounded() &&
          !extent.contains(pivot + surface.rotation.conjugate() * (p - pivot) - extent.centre)) {
        height = std::numeric_limits<double>::infinity();
      }
      if (moving->motion().belt_speed && i > 0) {
        // Simpson over the step: belt_travel(s) from 0 for every vertex would cost O(s).
        const auto& v = moving->motion().belt_speed;
        travel += (s - previous_s) / 6.0 * (v(previous_s) + 4.0 * v(0.5 * (previous_s + s)) + v(s));
      }
      on = carry_with_surface(*moving, p, s, travel, t, travel_now) + 1e-3 * normal;
    } else {
      const core::Vec3 p = contact_point(c, poses, s);
      height = c.normal.dot(p) - fixed_offset;
      // Onto the surface plane (slightly above it) so a bounce does not lift the trail.
      on = p - c.normal * (c.normal.dot(p)) + (fixed_offset + 1e-3) * c.normal;
    }
    core::Vec3 dir = i == 0 ? core::Vec3(core::Vec3::UnitX()) : core::Vec3(on - previous);
    if (dir.norm() < 1e-9) dir = core::Vec3::UnitX();
    core::Vec3 side = normal.cross(dir);
    if (side.norm() < 1e-12) side = normal.cross(core::Vec3::UnitY());
    side = side.normalized() * half;
    previous = on;
    previous_s = s;
    // No trail where the contact point is off its surface (or outside its extent) by more than
    // the ribbon's width: a ball off a board leaves none on the floor below it, while the
    // micrometre hops of a stiff contact (open in the events, for a fraction of a millisecond) do
    // not cut it.
    if (std::abs(height) > 2.0 * half) {
      flush_ribbon(strip, ribbon);
      continue;
    }
    const double slip = poses.signal(c.name + ".slip", s);
    const glm::vec3 colour = std::isnan(slip) || sticks(slip, threshold) ? kStick : kSlip;
    ribbon.push_back({to_glm(on - side), colour});
    ribbon.push_back({to_glm(on + side), colour});
  }
  flush_ribbon(strip, ribbon);
}

}  // namespace

float trail_width(const Drawing& scene, const ContactSite& contact) {
  const int body = contact.body;
  if (body < 0) return 0.01f;
  const BodyVisual& b = scene.bodies[static_cast<std::size_t>(body)];
  if (b.kind == BodyVisual::Kind::sphere) return static_cast<float>(0.15 * b.radius);
  if (b.kind == BodyVisual::Kind::block) return static_cast<float>(0.3 * b.size.x());
  // A wheel's two tracks, each narrower than the wheel is long.
  if (contact.rule == ContactSite::Rule::rim) {
    return static_cast<float>(0.15 * std::min(b.radius, b.length));
  }
  return static_cast<float>(0.15 * std::max(contact.radius, 0.05 * b.size.maxCoeff()));
}

std::vector<TrailVertex> build_trails(const Drawing& scene, const PoseTrack& poses, double t,
                                      const TrailOptions& options) {
  std::vector<TrailVertex> strip;
  for (const ContactSite& c : scene.sites.contacts) {
    if (!c.trail || c.body < 0) continue;
    // A table names its contact points: "wheel_floor" chooses the tracks of "wheel_floor.0"
    // and "wheel_floor.3".
    if (!options.contacts.empty() &&
        std::find(options.contacts.begin(), options.contacts.end(), c.name) ==
            options.contacts.end() &&
        std::find(options.contacts.begin(), options.contacts.end(), c.group) ==
            options.contacts.end()) {
      continue;
    }
    const auto it = options.thresholds.find(c.name);
    const double threshold =
        it != options.thresholds.end() ? it->second : options.default_threshold;
    append_ribbon(strip, scene, poses, c, t, options.seconds, threshold);
  }
  return strip;
}

}  // namespace stiction::render
