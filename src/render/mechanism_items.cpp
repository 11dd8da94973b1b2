#include "render/mechanism_items.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "render/arrow.hpp"
#include "render/scene_geometry.hpp"
#include "render/spring_coil.hpp"
#include "render/tree_items.hpp"

namespace stiction::render {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
const glm::vec3 kSpringColour{0.72f, 0.74f, 0.78f};  // steel
const glm::vec3 kDamperColour{0.18f, 0.18f, 0.20f};
const glm::vec3 kPostColour{0.25f, 0.25f, 0.27f};
const glm::vec3 kSourceColour{0.50f, 0.10f, 0.62f};  // applied loads: purple, apart from the
                                                     // contact forces' and the trail's colours
const glm::vec3 kRollerColour{0.45f, 0.46f, 0.48f};
const glm::vec3 kRollerStripe{0.95f, 0.75f, 0.10f};  // shows the roller turning

Material plain(const glm::vec3& colour, float specular = 0.25f, float shininess = 32.0f) {
  Material m;
  m.colour = colour;
  m.specular = specular;
  m.shininess = shininess;
  return m;
}

// A body's point (in its frame) in the world at time t; a block's is lifted to half its
// height (what holds a block pulls at its middle, not at its underside).
glm::vec3 anchor(const Drawing& scene, const PoseTrack& poses, int body, const core::Vec3& local,
                 double t) {
  const BodyVisual& b = scene.bodies[static_cast<std::size_t>(body)];
  core::Vec3 p = poses.position(body, t) + poses.orientation(body, t) * local;
  if (b.kind == BodyVisual::Kind::block) p += 0.5 * b.size.z() * b.up;
  return to_glm(p);
}

glm::vec3 lift(const BodyVisual& b) {
  return b.kind == BodyVisual::Kind::block ? to_glm(0.5 * b.size.z() * b.up) : glm::vec3(0.0f);
}

// Height of what a post under `p` stands on: the highest fixed, roughly horizontal surface
// below p (a belt or a tilting board moves: not those), else the floor under the scene.
float floor_under(const Drawing& scene, const MechanismFrame& frame, const glm::vec3& p) {
  if (scene.surfaces.empty()) return static_cast<float>(frame.floor_z);
  float best = -1e30f;
  for (const SurfaceVisual& s : scene.surfaces) {
    if (s.moving || s.normal.z() < 0.5) continue;
    const float z =
        static_cast<float>((s.offset - s.normal.x() * p.x - s.normal.y() * p.y) / s.normal.z());
    if (z < p.z && z > best) best = z;
  }
  if (best > -1e29f) return best;
  return std::min(p.z, frame.run.empty() ? p.z : frame.run.min.z) - static_cast<float>(frame.scale);
}

void add_cylinder(std::vector<DrawItem>& items, const glm::vec3& a, const glm::vec3& b,
                  float radius, const Material& material, bool casts_shadow = true) {
  add_tube(items, {a, b}, radius, material, casts_shadow);
}

void add_box_points(std::vector<glm::vec3>& points, const glm::vec3& c, float h) {
  for (int i = 0; i < 8; ++i) {
    points.push_back(c + glm::vec3((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h));
  }
}

}  // namespace

MechanismFrame mechanism_frame(const Drawing& scene, const PoseTrack& poses, const Bounds* run) {
  MechanismFrame f;
  f.run = run ? *run : run_bounds(scene, poses, 16);
  f.scale = body_scale(scene);
  for (const SpringVisual& s : scene.springs) {
    glm::vec3 setback(0.0f);
    if (s.other < 0 && s.free_length <= 0.0) {
      constexpr int kSamples = 16;
      core::Vec3 mean = core::Vec3::Zero();
      for (int i = 0; i < kSamples; ++i) {
        const double t =
            poses.start_time() + (poses.end_time() - poses.start_time()) * i / (kSamples - 1);
        mean += poses.position(s.body, t) + poses.orientation(s.body, t) * s.point - s.other_point;
      }
      mean /= kSamples;
      const double piece = piece_size(scene.bodies[static_cast<std::size_t>(s.body)]);
      const double wanted = 3.5 * piece;  // three pieces of coil clear of the body's half
      const double length = mean.norm();
      if (length < wanted) {
        const core::Vec3 direction =
            length > 1e-6 * piece ? core::Vec3(mean / length) : core::Vec3::UnitX();
        setback = to_glm(-(wanted - length) * direction);
      }
    }
    f.spring_setback.push_back(setback);
  }
  // The floor is under the springs' world ends too, so that their posts stand on it.
  Bounds ground = f.run;
  for (std::size_t i = 0; i < scene.springs.size(); ++i) {
    const SpringVisual& s = scene.springs[i];
    if (s.other >= 0) continue;
    ground.add(to_glm(s.other_point) + f.spring_setback[i] +
               lift(scene.bodies[static_cast<std::size_t>(s.body)]));
  }
  f.floor_z = floor_height(scene, ground, f.scale);
  // Fixed-base robots stand on the floor (at their bases) rather than above one put under
  // their reach, as long as no link goes beneath it.
  if (const std::optional<double> base = tree_base_floor(scene, poses)) f.floor_z = *base;
  for (const SourceVisual& s : scene.sources) {
    std::vector<int> columns;
    const std::vector<std::string> names =
        s.kind == SourceVisual::Kind::force
            ? std::vector<std::string>{s.name + ".f.x", s.name + ".f.y", s.name + ".f.z"}
            : std::vector<std::string>{s.name + ".tau"};
    double sum = 0.0;
    for (const std::string& n : names) {
      const int c = poses.column(n);
      if (c < 0) {
        columns.clear();
        break;
      }
      columns.push_back(c);
      const double peak = poses.column_peak(c);
      sum += peak * peak;
    }
    f.source_columns.push_back(columns);
    f.source_peak.push_back(columns.empty() ? 0.0 : std::sqrt(sum));
  }
  return f;
}

SpringEnds spring_ends(const Drawing& scene, const PoseTrack& poses, const MechanismFrame& frame,
                       int spring, double t) {
  const SpringVisual& s = scene.springs[static_cast<std::size_t>(spring)];
  const BodyVisual& body = scene.bodies[static_cast<std::size_t>(s.body)];
  SpringEnds e;
  e.a = anchor(scene, poses, s.body, s.point, t);
  if (s.other >= 0) {
    e.b = anchor(scene, poses, s.other, s.other_point, t);
  } else {
    e.b =
        to_glm(s.other_point) + frame.spring_setback[static_cast<std::size_t>(spring)] + lift(body);
    e.post = true;
    e.post_foot = glm::vec3(e.b.x, e.b.y, floor_under(scene, frame, e.b));
  }
  e.coil_radius = static_cast<float>(0.18 * piece_size(body));
  return e;
}

std::optional<ForceArrow> force_arrow(const Drawing& scene, const PoseTrack& poses,
                                      const MechanismFrame& frame, int source, double t) {
  const SourceVisual& s = scene.sources[static_cast<std::size_t>(source)];
  const auto& columns = frame.source_columns[static_cast<std::size_t>(source)];
  const double peak = frame.source_peak[static_cast<std::size_t>(source)];
  if (s.kind != SourceVisual::Kind::force || columns.size() != 3 || !(peak > 0.0)) {
    return std::nullopt;
  }
  core::Vec3 f(poses.column_value(columns[0], t), poses.column_value(columns[1], t),
               poses.column_value(columns[2], t));
  if (s.body_frame) f = poses.orientation(s.body, t) * f;
  const double piece = piece_size(scene.bodies[static_cast<std::size_t>(s.body)]);
  const double length = 2.5 * piece * f.norm() / peak;
  if (!(length > 1e-3 * piece)) return std::nullopt;
  const core::Vec3 p = poses.position(s.body, t) + poses.orientation(s.body, t) * s.point;
  ForceArrow a;
  a.vector = to_glm(length * f.normalized());
  a.tail = to_glm(p) - a.vector;
  a.shaft_radius = static_cast<float>(0.05 * piece);
  return a;
}

std::optional<TorqueArc> torque_arc(const Drawing& scene, const PoseTrack& poses,
                                    const MechanismFrame& frame, int source, double t) {
  const SourceVisual& s = scene.sources[static_cast<std::size_t>(source)];
  const auto& columns = frame.source_columns[static_cast<std::size_t>(source)];
  const double peak = frame.source_peak[static_cast<std::size_t>(source)];
  if (s.kind != SourceVisual::Kind::torque || columns.size() != 1 || !(peak > 0.0)) {
    return std::nullopt;
  }
  const double value = poses.column_value(columns[0], t) / peak;
  if (!(std::abs(value) > 0.01)) return std::nullopt;
  const BodyVisual& b = scene.bodies[static_cast<std::size_t>(s.body)];
  TorqueArc arc;
  // Drawn about the joint it drives: an arm's joint, or the penalty joint holding the body
  // (a motor on it), else about the body's centre.
  const auto held = std::find_if(scene.joints.begin(), scene.joints.end(),
                                 [&](const JointVisual& j) { return j.child == s.body; });
  float tube = 0.07f;
  if (b.kind == BodyVisual::Kind::tree) {
    const std::vector<components::LinkPose> links = tree_poses(b, poses, s.body, t);
    const std::size_t j =
        static_cast<std::size_t>(std::clamp(s.joint, 0, static_cast<int>(links.size()) - 1));
    arc.centre = to_glm(links[j].p);
    const core::Vec3 axis = (links[j].q * b.tree->params().links[j].axis).normalized();
    arc.axis = to_glm(axis);
    // Outside the link's hub (a turret mesh about the waist hid its motor's arc), whose
    // surface the tube (0.09 of the radius) clears by a tenth of the reach.
    const double hub = hub_reach(b, links, static_cast<int>(j), links[j].p, axis);
    arc.radius = static_cast<float>(std::max(4.0 * b.widths[j], 1.2 * hub));
    tube = 0.09f;
  } else if (b.kind == BodyVisual::Kind::arm) {
    const std::vector<core::Vec3> joints = arm_joints(b, poses, s.body, t);
    const std::size_t j =
        static_cast<std::size_t>(std::clamp(s.joint, 0, static_cast<int>(b.widths.size()) - 1));
    arc.centre = to_glm(joints[j]);
    arc.axis = glm::normalize(to_glm(b.axis));
    arc.radius = static_cast<float>(4.0 * b.widths[j]);
    tube = 0.09f;
  } else if (held != scene.joints.end()) {
    arc.centre = to_glm(poses.position(s.body, t) + poses.orientation(s.body, t) * held->point);
    arc.axis = glm::normalize(to_glm(poses.orientation(s.body, t) * s.axis));
    arc.radius = static_cast<float>(3.0 * held->width);
    tube = 0.09f;
  } else {
    arc.centre = to_glm(poses.position(s.body, t));
    arc.axis = glm::normalize(to_glm(poses.orientation(s.body, t) * s.axis));
    arc.radius = static_cast<float>(b.kind == BodyVisual::Kind::sphere ? 1.35 * b.radius
                                                                       : 0.6 * b.size.norm());
    tube = b.kind == BodyVisual::Kind::sphere ? 0.07f : 0.05f;
  }
  // The arc is centred on the top (the axis's perpendicular nearest to +z), where it is seen
  // and clear of the ground under a ball.
  glm::vec3 top = glm::vec3(0.0f, 0.0f, 1.0f) - arc.axis.z * arc.axis;
  if (glm::length(top) < 0.1f) top = glm::vec3(1.0f, 0.0f, 0.0f) - arc.axis.x * arc.axis;
  top = glm::normalize(top);
  arc.sweep = static_cast<float>(value) * 1.5f * kPi;
  const float half = -0.5f * arc.sweep;
  arc.start = std::cos(half) * top + std::sin(half) * glm::cross(arc.axis, top);
  arc.tube_radius = tube * arc.radius;
  return arc;
}

std::optional<BeltRollers> belt_rollers(const Drawing& scene, const MechanismFrame& frame,
                                        const SurfaceVisual& s) {
  if (!s.moving || !s.moving->motion().belt_speed) return std::nullopt;
  const core::Vec3 n = s.normal;
  const core::Vec3 d = s.moving->belt_direction();
  const core::Vec3 w = n.cross(d).normalized();
  const core::Vec3 origin = s.offset * n;
  const components::SurfaceExtent& e = s.extent;
  // What the belt must carry in view: the bodies' run and the springs' world anchors.
  std::vector<core::Vec3> around;
  if (!frame.run.empty()) {
    for (int i = 0; i < 8; ++i) {
      around.emplace_back((i & 1) ? frame.run.max.x : frame.run.min.x,
                          (i & 2) ? frame.run.max.y : frame.run.min.y,
                          (i & 4) ? frame.run.max.z : frame.run.min.z);
    }
  }
  for (std::size_t i = 0; i < scene.springs.size(); ++i) {
    if (scene.springs[i].other >= 0) continue;
    const glm::vec3 p = to_glm(scene.springs[i].other_point) + frame.spring_setback[i];
    around.emplace_back(p.x, p.y, p.z);
  }
  if (around.empty()) around.push_back(origin);
  // The extent's range along an in-plane direction `dir` (from the plane's origin), if the
  // extent's own axis lies along it; infinite where it does not bound it.
  auto extent_range = [&](const core::Vec3& dir, bool along_u) {
    const double lo_default = -components::SurfaceExtent::kInf;
    std::pair<double, double> r{lo_default, -lo_default};
    if (!e.bounded()) return r;
    const core::Vec3 axis = along_u ? e.u : e.v;
    const double cosine = axis.dot(dir);
    if (std::abs(cosine) < 0.999) return r;
    const double c = (e.centre - origin).dot(dir);
    const double lo = along_u ? e.u_min : e.v_min, hi = along_u ? e.u_max : e.v_max;
    r = cosine > 0.0 ? std::pair{c + lo, c + hi} : std::pair{c - hi, c - lo};
    return r;
  };
  auto range = [&](const core::Vec3& dir, std::pair<double, double> r) {
    double lo = 1e300, hi = -1e300;
    for (const core::Vec3& p : around) {
      lo = std::min(lo, (p - origin).dot(dir));
      hi = std::max(hi, (p - origin).dot(dir));
    }
    const double margin = 2.5 * frame.scale;
    if (!std::isfinite(r.first)) r.first = lo - margin;
    if (!std::isfinite(r.second)) r.second = hi + margin;
    return r;
  };
  std::pair<double, double> along = range(d, extent_range(d, true));
  if (!std::isfinite(extent_range(d, true).first) && std::isfinite(extent_range(d, false).first)) {
    along = range(d, extent_range(d, false));
  }
  std::pair<double, double> across = range(w, extent_range(w, false));
  if (!std::isfinite(extent_range(w, false).first) && std::isfinite(extent_range(w, true).first)) {
    across = range(w, extent_range(w, true));
  }
  const double width = across.second - across.first;
  BeltRollers r;
  r.radius = static_cast<float>(std::clamp(0.12 * width, 0.2 * frame.scale, 0.5 * frame.scale));
  r.half_length = static_cast<float>(0.55 * width);
  r.axis = to_glm(w);
  const double mid = 0.5 * (across.first + across.second);
  for (int k = 0; k < 2; ++k) {
    const double at = k == 0 ? along.first : along.second;
    r.centre[k] = to_glm(origin + at * d + mid * w - r.radius * n);
  }
  r.span_min = along.first;
  r.span_max = along.second;
  return r;
}

std::optional<PivotAxle> pivot_axle(const MechanismFrame& frame, const SurfaceVisual& s, double t) {
  if (!s.moving || !s.moving->motion().tilt) return std::nullopt;
  const components::SurfaceMotion& m = s.moving->motion();
  const core::Vec3 axis = m.tilt_axis.normalized();
  const components::SurfaceExtent& e = s.extent;
  double lo = -4.0 * frame.scale, hi = 4.0 * frame.scale;
  if (e.bounded() && std::isfinite(e.u_min) && std::isfinite(e.u_max) && std::isfinite(e.v_min) &&
      std::isfinite(e.v_max)) {
    lo = 1e300;
    hi = -1e300;
    for (double a : {e.u_min, e.u_max}) {
      for (double b : {e.v_min, e.v_max}) {
        const double x = (e.centre + a * e.u + b * e.v - m.pivot).dot(axis);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    }
    const double pad = 0.12 * (hi - lo);  // the axle stands out of the board on both sides
    lo -= pad;
    hi += pad;
  }
  const core::Vec3 normal = s.moving->surface(t).rotation * s.normal;
  PivotAxle axle;
  axle.radius = static_cast<float>(0.25 * frame.scale);
  const core::Vec3 below = m.pivot - static_cast<double>(axle.radius) * normal;
  axle.a = to_glm(below + lo * axis);
  axle.b = to_glm(below + hi * axis);
  return axle;
}

void add_mechanism_items(std::vector<DrawItem>& items, const Drawing& scene, const PoseTrack& poses,
                         const MechanismFrame& frame, double t) {
  const Material steel = plain(kSpringColour, 0.6f, 64.0f);
  for (std::size_t i = 0; i < scene.springs.size(); ++i) {
    const SpringVisual& s = scene.springs[i];
    const SpringEnds e = spring_ends(scene, poses, frame, static_cast<int>(i), t);
    CoilShape shape;
    shape.coil_radius = e.coil_radius;
    // The coil casts no shadow: its ~80 pieces would be drawn again into the shadow map, a
    // third of the layer's cost on llvmpipe, for a shadow the post and the body already give.
    add_tube(items, coil_path(e.a, e.b, shape), 0.17f * e.coil_radius, steel, false);
    if (s.damping > 0.0) {
      // A damper inside the coil: a dark cylinder from one end, a bright rod from the other,
      // sliding into it as the spring works.
      const glm::vec3 d = e.b - e.a;
      add_cylinder(items, e.a + 0.12f * d, e.a + 0.6f * d, 0.5f * e.coil_radius,
                   plain(kDamperColour));
      add_cylinder(items, e.a + 0.45f * d, e.b, 0.16f * e.coil_radius, steel);
    }
    if (e.post) {
      const float r = 0.9f * e.coil_radius;
      add_cylinder(items, e.post_foot, e.b + glm::vec3(0.0f, 0.0f, r), r, plain(kPostColour));
    }
  }
  const Material load = plain(kSourceColour, 0.4f, 48.0f);
  for (std::size_t i = 0; i < scene.sources.size(); ++i) {
    if (const auto a = force_arrow(scene, poses, frame, static_cast<int>(i), t)) {
      ArrowStyle style;
      style.shaft_radius = a->shaft_radius;
      add_arrow(items, a->tail, a->vector, load, style);
    }
    if (const auto arc = torque_arc(scene, poses, frame, static_cast<int>(i), t)) {
      const glm::vec3 e2 = glm::cross(arc->axis, arc->start);
      const float head = 0.6f * arc->radius;  // along the tangent, half of it the cone
      const float sign = arc->sweep >= 0.0f ? 1.0f : -1.0f;
      const float end =
          arc->sweep - sign * std::min(head / arc->radius, 0.5f * std::abs(arc->sweep));
      const int n = std::max(2, static_cast<int>(std::ceil(std::abs(end) / (kPi / 16.0f))));
      std::vector<glm::vec3> path;
      for (int k = 0; k <= n; ++k) {
        const float phi = end * static_cast<float>(k) / static_cast<float>(n);
        path.push_back(arc->centre +
                       arc->radius * (std::cos(phi) * arc->start + std::sin(phi) * e2));
      }
      add_tube(items, path, arc->tube_radius, load, false);
      const glm::vec3 tangent = sign * (-std::sin(end) * arc->start + std::cos(end) * e2);
      ArrowStyle style;
      style.shaft_radius = arc->tube_radius;
      style.head_length = head;
      add_arrow(items, path.back(), head * tangent, load, style);
    }
  }
  for (const SurfaceVisual& s : scene.surfaces) {
    if (const auto r = belt_rollers(scene, frame, s)) {
      const double travel = s.moving->belt_travel(t);
      const glm::vec3 n = to_glm(s.normal), d = to_glm(s.moving->belt_direction());
      // The roller turns with the belt: its top moves along d by the belt's travel.
      const float angle = static_cast<float>(travel / r->radius);
      for (const glm::vec3& c : r->centre) {
        // Rollers, their stripes, axles and trestles cast no shadow: they lie far apart at the
        // ends of a belt or a board, and shadow casters spread over the picture make every
        // pixel pay for the shadow lookups (shadow_region.hpp).
        add_cylinder(items, c - r->half_length * r->axis, c + r->half_length * r->axis, r->radius,
                     plain(kRollerColour, 0.5f, 48.0f), false);
        const glm::vec3 at = c + 0.93f * r->radius * (std::cos(angle) * n + std::sin(angle) * d);
        add_cylinder(items, at - 1.01f * r->half_length * r->axis,
                     at + 1.01f * r->half_length * r->axis, 0.12f * r->radius, plain(kRollerStripe),
                     false);
      }
    }
    if (const auto axle = pivot_axle(frame, s, t)) {
      const Material metal = plain(glm::vec3(0.35f), 0.5f, 48.0f);
      add_cylinder(items, axle->a, axle->b, axle->radius, metal, false);
      // Two trestles from the floor hold the axle at its ends.
      for (const glm::vec3& end : {axle->a, axle->b}) {
        const glm::vec3 foot(end.x, end.y, floor_under(scene, frame, end));
        add_cylinder(items, foot, end, 0.8f * axle->radius, plain(kPostColour), false);
      }
    }
  }
}

std::vector<glm::vec3> mechanism_points(const Drawing& scene, const PoseTrack& poses,
                                        const MechanismFrame& frame, double t) {
  std::vector<glm::vec3> points;
  for (std::size_t i = 0; i < scene.springs.size(); ++i) {
    const SpringEnds e = spring_ends(scene, poses, frame, static_cast<int>(i), t);
    add_box_points(points, e.a, e.coil_radius);
    add_box_points(points, e.b, e.coil_radius);
    if (e.post) points.push_back(e.post_foot);
  }
  for (std::size_t i = 0; i < scene.sources.size(); ++i) {
    if (const auto a = force_arrow(scene, poses, frame, static_cast<int>(i), t)) {
      points.push_back(a->tail);
      points.push_back(a->tail + a->vector);
    }
    if (const auto arc = torque_arc(scene, poses, frame, static_cast<int>(i), t)) {
      const glm::vec3 e2 = glm::cross(arc->axis, arc->start);
      for (const glm::vec3& dir : {arc->start, -arc->start, e2, -e2}) {
        points.push_back(arc->centre + 1.1f * arc->radius * dir);
      }
    }
  }
  for (const SurfaceVisual& s : scene.surfaces) {
    if (const auto r = belt_rollers(scene, frame, s)) {
      for (const glm::vec3& c : r->centre) {
        points.push_back(c + r->half_length * r->axis);
        points.push_back(c - r->half_length * r->axis);
      }
    }
    if (const auto axle = pivot_axle(frame, s, t)) {
      for (const glm::vec3& end : {axle->a, axle->b}) {
        points.push_back(end);
        points.push_back(glm::vec3(end.x, end.y, floor_under(scene, frame, end)));
      }
    }
  }
  return points;
}

bool has_world_parts(const Drawing& scene) {
  for (const SpringVisual& s : scene.springs) {
    if (s.other < 0) return true;
  }
  for (const SurfaceVisual& s : scene.surfaces) {
    if (s.moving && (s.moving->motion().belt_speed || s.moving->motion().tilt)) return true;
  }
  return false;
}

}  // namespace stiction::render
