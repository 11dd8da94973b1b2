#include "render/force_arrows.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "render/arrow.hpp"

namespace stiction::render {
namespace {

core::Vec3 vector_signal(const PoseTrack& poses, const std::string& name, double t) {
  return {poses.signal(name + ".x", t), poses.signal(name + ".y", t), poses.signal(name + ".z", t)};
}

Material arrow_material(const glm::vec3& colour) {
  Material m;
  m.colour = colour;
  m.specular = 0.35f;
  return m;
}

// `v` cut to `max_length` (a spike's arrow would cross the picture).
core::Vec3 capped(const core::Vec3& v, double max_length) {
  const double n = v.norm();
  return n > max_length ? core::Vec3(v * (max_length / n)) : v;
}

// Distance from a body's centre to its surface along the unit direction d.
double support(const BodyVisual& b, const core::Quat& q, const core::Vec3& d) {
  switch (b.kind) {
    case BodyVisual::Kind::sphere:
      return b.radius;
    case BodyVisual::Kind::cylinder:
    case BodyVisual::Kind::box:
    case BodyVisual::Kind::block: {
      const core::Vec3 local = q.conjugate() * d;
      return 0.5 * (std::abs(local.x()) * b.size.x() + std::abs(local.y()) * b.size.y() +
                    std::abs(local.z()) * b.size.z());
    }
    case BodyVisual::Kind::arm:
    case BodyVisual::Kind::tree:
      return 0.0;
  }
  return 0.0;
}

// A contact at a box's corner: the box (its index in the drawing) and the corner in its frame.
struct BoxCorner {
  int body = -1;
  core::Vec3 local = core::Vec3::Zero();
};

std::optional<BoxCorner> box_corner_of(const ContactSite& site) {
  if (site.rule == ContactSite::Rule::pair) {
    if (site.pair.kind != components::PairKind::box_box) return std::nullopt;
    const int i = site.pair.corner;  // 0-7 the first box's corners, 8-15 the second's
    return BoxCorner{i < 8 ? site.body : site.other,
                     components::box_corner(i < 8 ? site.pair.half_a : site.pair.half_b, i % 8)};
  }
  // A point without a radius off the centre along every axis: a box's corner.
  if (site.rule == ContactSite::Rule::point && site.radius == 0.0 &&
      (site.local.array() != 0.0).all()) {
    return BoxCorner{site.body, site.local};
  }
  return std::nullopt;
}

// True if `offset` (world) from the corner leads out of the box: it points out of one of the
// three faces that meet there (exact for offsets small against the box).
bool leaves_corner(const BoxCorner& corner, const core::Quat& q, const core::Vec3& offset) {
  const core::Vec3 o = q.conjugate() * offset;
  for (int i = 0; i < 3; ++i) {
    if (corner.local[i] * o[i] > 0.0) return true;
  }
  return false;
}

}  // namespace

double arrow_body_size(const Drawing& scene) {
  double size = 0.0;
  for (const BodyVisual& b : scene.bodies) {
    switch (b.kind) {
      case BodyVisual::Kind::sphere:
        size = std::max(size, 2.0 * b.radius);
        break;
      case BodyVisual::Kind::cylinder:
      case BodyVisual::Kind::box:
      case BodyVisual::Kind::block:
        size = std::max(size, b.size.maxCoeff());
        break;
      case BodyVisual::Kind::arm:
      case BodyVisual::Kind::tree:
        for (double l : b.lengths) size = std::max(size, l);
        break;
    }
  }
  return size > 0.0 ? size : 0.1;
}

double round_up_125(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * decade >= x * (1.0 - 1e-12)) return m * decade;
  }
  return 10.0 * decade;
}

ContactForce contact_force(const ContactSite& site, const PoseTrack& poses, double t,
                           double exposure) {
  // Samples 0.5 ms apart or closer resolve a 1 kHz trajectory's one-row spikes.
  const int samples = exposure > 0.0 ? std::clamp(static_cast<int>(exposure / 5e-4), 4, 64) : 1;
  core::Vec3 sum = core::Vec3::Zero();
  for (int i = 0; i < samples; ++i) {
    const double s = samples == 1 ? t : t + exposure * ((i + 0.5) / samples - 0.5);
    const core::Vec3 f = vector_signal(poses, site.name + ".f", s);
    if (!f.allFinite()) return {};
    sum += f;
  }
  const core::Vec3 f = sum / samples;
  const core::Vec3 n = surface_plane(site, poses, t).normal;
  ContactForce out;
  out.normal = n.dot(f) * n;
  out.friction = f - out.normal;
  return out;
}

ArrowScales choose_arrow_scales(const Drawing& scene, const ContactSites& sites,
                                const PoseTrack& poses, const OverlayLayers& layers,
                                double exposure) {
  ArrowScales scales;
  const double size = arrow_body_size(scene);
  scales.shaft_radius = static_cast<float>(0.025 * size);
  scales.max_length = 1.5 * size;
  std::vector<double> largest_forces;  // per sample time, over the contact points
  double largest_speed = 0.0;
  constexpr int kSamples = 128;
  const double t0 = poses.start_time(), t1 = poses.end_time();
  for (int i = 0; i <= kSamples; ++i) {
    const double t = t0 + (t1 - t0) * i / kSamples;
    if (layers.forces && layers.force_scale <= 0.0) {
      double largest = 0.0;
      for (const ContactSite& s : sites.contacts) {
        const ContactForce f = contact_force(s, poses, t, exposure);
        largest = std::max({largest, f.normal.norm(), f.friction.norm()});
      }
      if (largest > 0.0) largest_forces.push_back(largest);
    }
    if (layers.velocities && layers.velocity_scale <= 0.0) {
      for (const BodyVisual& b : scene.bodies) {
        const double v = poses.signal(b.name + ".v", t);
        if (std::isfinite(v)) largest_speed = std::max(largest_speed, v);
      }
    }
  }
  // The 90th percentile of the per-time largest force rather than the largest: the impact
  // spikes of a stiff contact (a bouncing ball's hundreds of newtons for a fraction of a
  // millisecond) would otherwise shrink the steady forces to nothing.
  double largest_force = 0.0;
  if (!largest_forces.empty()) {
    const auto at =
        largest_forces.begin() +
        static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(largest_forces.size() - 1));
    std::nth_element(largest_forces.begin(), at, largest_forces.end());
    largest_force = *at;
  }
  // Not rounded: the legend's bar is a round value at whatever scale.
  scales.force = layers.force_scale > 0.0
                     ? layers.force_scale
                     : (largest_force > 0.0 ? largest_force / (0.6 * size) : 1.0);
  scales.velocity = layers.velocity_scale > 0.0
                        ? layers.velocity_scale
                        : (largest_speed > 0.0 ? largest_speed / (0.8 * size) : 1.0);
  return scales;
}

core::Vec3 force_arrow_tail(const ContactSite& site, const PoseTrack& poses, double t,
                            const ArrowScales& scales, const glm::vec3& eye) {
  const core::Vec3 n = surface_plane(site, poses, t).normal;
  core::Vec3 tail = contact_point(site, poses, t) + scales.shaft_radius * n;
  core::Vec3 toward = core::Vec3(eye.x, eye.y, eye.z) - tail;
  toward -= n.dot(toward) * n;
  if (toward.norm() > 1e-9) {
    // Beside a ball; off a box's edge by a shaft's width, so the arrow is not half inside;
    // clear of a wheel's near face (its normal force points up through the wheel).
    const core::Vec3 d = toward.normalized();
    // A pair's normal force points through its first body: beside it when that is a ball.
    const bool ball_first = site.rule == ContactSite::Rule::pair &&
                            (site.pair.kind == components::PairKind::sphere_sphere ||
                             site.pair.kind == components::PairKind::sphere_box);
    const double round = ball_first ? site.pair.radius_a : site.radius;
    double aside =
        round > 0.0 ? 1.1 * round + 2.0 * scales.shaft_radius : 1.5 * scales.shaft_radius;
    if (site.rule == ContactSite::Rule::rim) {
      const core::Vec3 centre = poses.position(site.body, t);
      aside = site.rim.reach(poses.orientation(site.body, t), d) - d.dot(tail - centre) +
              2.0 * scales.shaft_radius;
    }
    tail += aside * d;
    // A box's corner whose side towards the camera is the box itself (a back corner): the
    // arrow would start inside the box, so it starts off the corner outwards instead, beside
    // the edge the viewer sees end there (or behind the box, hidden as the corner is).
    if (const std::optional<BoxCorner> corner = box_corner_of(site)) {
      const core::Quat q = poses.orientation(corner->body, t);
      const core::Vec3 lift = scales.shaft_radius * n;
      if (!leaves_corner(*corner, q, tail - contact_point(site, poses, t))) {
        core::Vec3 out = q * corner->local;
        out -= n.dot(out) * n;
        if (out.norm() > 1e-12) {
          const core::Vec3 moved = lift + 1.5 * scales.shaft_radius * out.normalized();
          if (leaves_corner(*corner, q, moved)) tail = contact_point(site, poses, t) + moved;
        }
      }
    }
  }
  return tail;
}

std::vector<ArrowSegment> force_arrow_segments(const ContactSites& sites, const PoseTrack& poses,
                                               double t, const ArrowScales& scales,
                                               const glm::vec3& eye, double exposure) {
  std::vector<ArrowSegment> out;
  for (const ContactSite& s : sites.contacts) {
    const ContactForce f = contact_force(s, poses, t, exposure);
    if (f.normal.isZero(0.0) && f.friction.isZero(0.0)) continue;
    const core::Vec3 tail = force_arrow_tail(s, poses, t, scales, eye);
    out.push_back({tail, tail + capped(f.normal / scales.force, scales.max_length), true});
    out.push_back({tail, tail + capped(f.friction / scales.force, scales.max_length), false});
  }
  return out;
}

void add_force_arrows(std::vector<DrawItem>& items, const ContactSites& sites,
                      const PoseTrack& poses, double t, const ArrowScales& scales,
                      const glm::vec3& eye, double exposure) {
  ArrowStyle style;
  style.shaft_radius = scales.shaft_radius;
  for (const ArrowSegment& a : force_arrow_segments(sites, poses, t, scales, eye, exposure)) {
    add_arrow(items, to_glm(a.tail), to_glm(core::Vec3(a.tip - a.tail)),
              arrow_material(a.normal ? kNormalForceColour : kFrictionColour), style);
  }
}

void add_velocity_arrows(std::vector<DrawItem>& items, const Drawing& scene, const PoseTrack& poses,
                         double t, const ArrowScales& scales) {
  ArrowStyle style;
  style.shaft_radius = scales.shaft_radius;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyVisual& b = scene.bodies[i];
    if (jointed(b)) continue;
    const core::Vec3 v = vector_signal(poses, b.name + ".v", t);
    if (!v.allFinite() || v.norm() <= 0.0) continue;
    const int index = static_cast<int>(i);
    const core::Vec3 d = v.normalized();
    const core::Vec3 tail =
        poses.position(index, t) + support(b, poses.orientation(index, t), d) * d;
    add_arrow(items, to_glm(tail), to_glm(capped(v / scales.velocity, scales.max_length)),
              arrow_material(kVelocityColour), style);
  }
}

}  // namespace stiction::render
