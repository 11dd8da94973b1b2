// build_items: the draw items of a scene at time t (surfaces, bodies, arms, joints).
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <optional>
#include <utility>

#include "render/cylinder_items.hpp"
#include "render/mechanism_items.hpp"
#include "render/scene_geometry.hpp"
#include "render/scene_view.hpp"
#include "render/tree_items.hpp"

namespace stiction::render {
namespace {

// A round value no larger than `size`: 0.01, 0.02, 0.05, 0.1, ...
double nice_floor(double size) {
  double best = 0.01;
  for (double decade = 0.01; decade <= 100.0; decade *= 10.0) {
    for (double m : {1.0, 2.0, 5.0}) {
      if (m * decade <= size) best = m * decade;
    }
  }
  return best;
}

const glm::vec3 kSphereColour{0.90f, 0.30f, 0.03f};
const glm::vec3 kSphereColour2{0.86f, 0.86f, 0.82f};
const glm::vec3 kSphereColourOther{0.05f, 0.45f, 0.55f};  // every other ball: teal for orange
const glm::vec3 kBoxColour{0.10f, 0.28f, 0.62f};
const glm::vec3 kLinkColour2{0.15f, 0.50f, 0.75f};  // every other link of a chain
const glm::vec3 kJointColour{0.06f, 0.06f, 0.07f};
const glm::vec3 kPinColour{0.80f, 0.80f, 0.82f};
const glm::vec3 kBlockColour{0.72f, 0.10f, 0.08f};
const glm::vec3 kGroundLight{0.78f, 0.78f, 0.76f};
const glm::vec3 kGroundDark{0.55f, 0.57f, 0.60f};
const glm::vec3 kBeltLight{0.36f, 0.36f, 0.38f};  // moving surfaces: darker, rubber-like
const glm::vec3 kBeltDark{0.16f, 0.16f, 0.18f};
// A contact surface as checkered squares: the plane within `half` of the scene's centre,
// cut to the surface's extent (a rectangle in the plane's u, v coordinates, covered by
// squares of its shorter side so the checker keeps square cells), tilted and scrolled as the
// surface moves at time t.
// A belt is cut to `belt_span` (along its direction from the plane's origin: between its
// rollers).
void add_surface(std::vector<DrawItem>& items, const SurfaceVisual& s, const Bounds& around,
                 float half, float checker, double t,
                 std::optional<std::pair<double, double>> belt_span = std::nullopt) {
  const bool bounded = s.extent.bounded();
  core::Vec3 u, v;
  if (bounded) {
    u = s.extent.u;
    v = s.extent.v;
  } else {
    tangents(s.normal, u, v);
  }
  // Everything in the plane at rest, then moved as a whole.
  core::Quat rotation = core::Quat::Identity();
  core::Vec3 pivot = core::Vec3::Zero();
  double travel_u = 0.0, travel_v = 0.0;
  if (s.moving) {
    const components::SurfaceState st = s.moving->surface(t);
    rotation = st.rotation;
    pivot = s.moving->motion().pivot;
    if (s.moving->motion().belt_speed) {
      const double travel = s.moving->belt_travel(t);
      travel_u = travel * s.moving->belt_direction().dot(u);
      travel_v = travel * s.moving->belt_direction().dot(v);
    }
  }
  const core::Vec3 origin = s.offset * s.normal;
  const core::Vec3 c(around.empty() ? 0.0 : around.centre().x,
                     around.empty() ? 0.0 : around.centre().y,
                     around.empty() ? 0.0 : around.centre().z);
  // The scene centre carried back to the plane at rest.
  const core::Vec3 c_rest = pivot + rotation.conjugate() * (c - pivot);
  double a0 = (c_rest - origin).dot(u) - half, a1 = (c_rest - origin).dot(u) + half;
  double b0 = (c_rest - origin).dot(v) - half, b1 = (c_rest - origin).dot(v) + half;
  if (bounded) {
    const double ca = (s.extent.centre - origin).dot(u), cb = (s.extent.centre - origin).dot(v);
    a0 = std::max(a0, ca + s.extent.u_min);
    a1 = std::min(a1, ca + s.extent.u_max);
    b0 = std::max(b0, cb + s.extent.v_min);
    b1 = std::min(b1, cb + s.extent.v_max);
    if (!(a1 > a0) || !(b1 > b0)) return;
  }
  if (belt_span && s.moving) {
    const double cosine = s.moving->belt_direction().dot(u);
    if (std::abs(cosine) > 0.999) {
      const double lo = cosine > 0.0 ? belt_span->first : -belt_span->second;
      const double hi = cosine > 0.0 ? belt_span->second : -belt_span->first;
      a0 = std::max(a0, lo);
      a1 = std::min(a1, hi);
      if (!(a1 > a0)) return;
    }
  }
  const double side = std::min(a1 - a0, b1 - b0);
  // A long narrow strip (a belt) is drawn over at most 64 of its squares around the scene.
  constexpr int kMost = 64;
  auto shorten = [&](double& lo, double& hi, double centre) {
    if (hi - lo <= kMost * side) return;
    const double from = std::clamp(centre - 0.5 * kMost * side, lo, hi - kMost * side);
    lo = from;
    hi = from + kMost * side;
  };
  shorten(a0, a1, (c_rest - origin).dot(u));
  shorten(b0, b1, (c_rest - origin).dot(v));
  const int na = std::max(1, static_cast<int>(std::ceil((a1 - a0) / side - 1e-9)));
  const int nb = std::max(1, static_cast<int>(std::ceil((b1 - b0) / side - 1e-9)));
  const double grid = 5.0 * checker;
  const double period = 2.0 * grid;
  for (int i = 0; i < na; ++i) {
    for (int j = 0; j < nb; ++j) {
      // Squares from the low corner, the last one flush with the far edge (they overlap).
      const double ma =
          na == 1 ? 0.5 * (a0 + a1) : a0 + 0.5 * side + (a1 - a0 - side) * i / (na - 1);
      const double mb =
          nb == 1 ? 0.5 * (b0 + b1) : b0 + 0.5 * side + (b1 - b0 - side) * j / (nb - 1);
      const core::Vec3 at = pivot + rotation * (origin + ma * u + mb * v - pivot);
      DrawItem item;
      item.shape = Shape::plane;
      item.model = glm::translate(glm::mat4(1.0f), render::to_glm(at)) *
                   rotation_from_basis(rotation * u, rotation * v, rotation * s.normal) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(0.5f * static_cast<float>(side),
                                                         0.5f * static_cast<float>(side), 1.0f));
      item.material.kind = MaterialKind::checker;
      item.material.colour = s.moving ? kBeltLight : kGroundLight;
      item.material.colour2 = s.moving ? kBeltDark : kGroundDark;
      item.material.checker_size = checker;
      item.material.grid_spacing = static_cast<float>(grid);
      item.material.local_scale = 0.5f * static_cast<float>(side);
      // The pattern repeats every 10 checker squares: an offset reduced modulo that keeps
      // the shader's coordinates small, hence precise. A belt shifts it by its travel.
      const double oa = ma - travel_u, ob = mb - travel_v;
      item.material.local_offset =
          glm::vec2(static_cast<float>(oa - period * std::floor(oa / period)),
                    static_cast<float>(ob - period * std::floor(ob / period)));
      item.material.specular = 0.05f;
      item.casts_shadow = false;
      items.push_back(item);
    }
  }
}

// A pin through a joint's hub (radius 0.95 w, half-height 0.85 w): a bright steel rod
// standing out on both faces, so the joint reads as a pin and not as a dark disc.
void add_pin(std::vector<DrawItem>& items, const core::Vec3& at, const core::Vec3& axis, float w) {
  DrawItem pin;
  pin.shape = Shape::cylinder;
  pin.model = glm::translate(glm::mat4(1.0f), to_glm(at)) * align_z(axis.normalized()) *
              glm::scale(glm::mat4(1.0f), glm::vec3(0.38f * w, 0.38f * w, 1.05f * w));
  pin.material.colour = kPinColour;
  pin.material.specular = 0.7f;
  pin.material.shininess = 64.0f;
  items.push_back(pin);
}

}  // namespace

std::vector<DrawItem> build_items(const Drawing& scene, const PoseTrack& poses, double t,
                                  const Bounds& focus) {
  std::vector<DrawItem> items;
  const Bounds all = run_bounds(scene, poses, 16);
  const double scale = body_scale(scene);
  const float checker = static_cast<float>(nice_floor(scale));

  // Surfaces: the contacts' planes, or a floor under the scene.
  std::vector<SurfaceVisual> surfaces = scene.surfaces;
  const MechanismFrame mechanism = mechanism_frame(scene, poses, &all);
  const double floor_z = mechanism.floor_z;
  if (surfaces.empty()) surfaces.push_back({core::Vec3::UnitZ(), floor_z, {}, nullptr});
  const Bounds& around = focus.empty() ? all : focus;
  const float half = std::max(20.0f, 8.0f * (around.empty() ? 1.0f : around.radius()));
  for (const auto& s : surfaces) {
    std::optional<std::pair<double, double>> span;
    if (const auto rollers = belt_rollers(scene, mechanism, s)) {
      span = std::pair{rollers->span_min, rollers->span_max};
    }
    add_surface(items, s, around, half, checker, t, span);
  }

  // Rigid boxes so far: every other one is lighter, as an arm's links are, so the links of a
  // chain and the boxes of a stack (a box on a pushed box) tell apart.
  int boxes = 0;
  int balls = 0;  // likewise, every other ball is teal: two colliding balls tell apart
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyVisual& b = scene.bodies[i];
    const int index = static_cast<int>(i);
    DrawItem item;
    switch (b.kind) {
      case BodyVisual::Kind::sphere: {
        item.shape = Shape::sphere;
        item.model = glm::translate(glm::mat4(1.0f), to_glm(poses.position(index, t))) *
                     to_glm(poses.orientation(index, t)) *
                     glm::scale(glm::mat4(1.0f), glm::vec3(static_cast<float>(b.radius)));
        item.material.kind = MaterialKind::sphere_pattern;
        item.body = index;
        item.material.colour = balls++ % 2 == 1 ? kSphereColourOther : kSphereColour;
        item.material.colour2 = kSphereColour2;
        item.material.shininess = 48.0f;
        item.material.specular = 0.35f;
        items.push_back(item);
        break;
      }
      case BodyVisual::Kind::box: {
        item.shape = Shape::box;
        item.model = glm::translate(glm::mat4(1.0f), to_glm(poses.position(index, t))) *
                     to_glm(poses.orientation(index, t)) *
                     glm::scale(glm::mat4(1.0f), 0.5f * to_glm(b.size));
        item.material.colour = kBoxColour;
        if (boxes++ % 2 == 1) item.material.colour = kLinkColour2;
        items.push_back(item);
        break;
      }
      case BodyVisual::Kind::cylinder:
        add_cylinder(items, b, index, poses.position(index, t), poses.orientation(index, t));
        break;
      case BodyVisual::Kind::block: {
        core::Vec3 t1, t2;
        tangents(b.up, t1, t2);
        const core::Vec3 centre_point = poses.position(index, t) + 0.5 * b.size.z() * b.up;
        item.shape = Shape::box;
        item.model = glm::translate(glm::mat4(1.0f), to_glm(centre_point)) *
                     rotation_from_basis(t1, t2, b.up) *
                     glm::scale(glm::mat4(1.0f), 0.5f * to_glm(b.size));
        item.material.colour = kBlockColour;
        items.push_back(item);
        break;
      }
      case BodyVisual::Kind::tree:
        add_tree_items(items, b, poses, index, t);
        break;
      case BodyVisual::Kind::arm: {
        const ArmPose pose = arm_pose(b, poses, index, t);
        const float w0 = static_cast<float>(b.widths.front());
        // A post from the floor to the base joint.
        // An arm in a tilted plane (a pendulum) would swing through a post under its base:
        // the post stands beside the plane, on the far side from the default camera (+y),
        // and an axle along the joint axis joins it to the base.
        const bool upright = std::abs(b.axis.z()) > 0.9;
        const core::Vec3 side = (b.axis.y() >= 0.0 ? 1.0 : -1.0) * b.axis;
        const core::Vec3 post_at =
            upright ? b.base : core::Vec3(b.base + 2.5 * b.widths.front() * side);
        if (!upright) {
          DrawItem axle;
          axle.shape = Shape::cylinder;
          core::Vec3 t1, t2;
          tangents(side, t1, t2);
          axle.model = glm::translate(glm::mat4(1.0f), to_glm(0.5 * (b.base + post_at))) *
                       rotation_from_basis(t1, t2, side) *
                       glm::scale(glm::mat4(1.0f),
                                  glm::vec3(0.35f * w0, 0.35f * w0,
                                            0.5f * static_cast<float>((post_at - b.base).norm())));
          axle.material.colour = glm::vec3(0.35f);
          items.push_back(axle);
        }
        if (scene.surfaces.empty()) {
          const float z0 = static_cast<float>(floor_z), z1 = static_cast<float>(b.base.z());
          DrawItem post;
          post.shape = Shape::cylinder;
          post.model =
              glm::translate(glm::mat4(1.0f),
                             glm::vec3(to_glm(post_at).x, to_glm(post_at).y, 0.5f * (z0 + z1))) *
              glm::scale(glm::mat4(1.0f), glm::vec3(0.7f * w0, 0.7f * w0, 0.5f * (z1 - z0)));
          post.material.colour = glm::vec3(0.35f);
          items.push_back(post);
        }
        for (std::size_t k = 0; k < b.lengths.size(); ++k) {
          const float w = static_cast<float>(b.widths[k]);
          const core::Vec3 mid = 0.5 * (pose.joints[k] + pose.joints[k + 1]);
          DrawItem link;
          link.shape = Shape::box;
          const core::Vec3 along =
              std::cos(pose.phi[k]) * b.plane_x + std::sin(pose.phi[k]) * b.plane_y;
          link.model =
              glm::translate(glm::mat4(1.0f), to_glm(mid)) *
              rotation_from_basis(along, b.axis.cross(along), b.axis) *
              glm::scale(glm::mat4(1.0f),
                         glm::vec3(0.5f * static_cast<float>(b.lengths[k]), 0.5f * w, 0.5f * w));
          link.material.colour = k % 2 == 0 ? kBoxColour : kLinkColour2;
          items.push_back(link);
          DrawItem joint;
          joint.shape = Shape::cylinder;
          joint.model = glm::translate(glm::mat4(1.0f), to_glm(pose.joints[k])) *
                        rotation_from_basis(b.plane_x, b.plane_y, b.axis) *
                        glm::scale(glm::mat4(1.0f), glm::vec3(0.95f * w, 0.95f * w, 0.85f * w));
          joint.material.colour = kJointColour;
          joint.material.specular = 0.5f;
          items.push_back(joint);
          add_pin(items, pose.joints[k], b.axis, w);
        }
        // The tip: a small sphere, so the end of the chain reads clearly.
        DrawItem tip;
        tip.shape = Shape::sphere;
        tip.model =
            glm::translate(glm::mat4(1.0f), to_glm(pose.joints.back())) *
            glm::scale(glm::mat4(1.0f), glm::vec3(0.6f * static_cast<float>(b.widths.back())));
        tip.material.colour = kJointColour;
        items.push_back(tip);
        break;
      }
    }
  }

  // Penalty joints, drawn as an arm's: a dark cylinder along the joint axis at the
  // articulation point, a post from the floor to a joint held by the ground, and a small
  // sphere at the free end of a chain's last link.
  for (const auto& j : scene.joints) {
    const float w = static_cast<float>(j.width);
    if (j.parent < 0 && scene.surfaces.empty()) {
      const float z0 = static_cast<float>(floor_z), z1 = static_cast<float>(j.parent_point.z());
      const glm::vec3 base = to_glm(j.parent_point);
      DrawItem post;
      post.shape = Shape::cylinder;
      post.model = glm::translate(glm::mat4(1.0f), glm::vec3(base.x, base.y, 0.5f * (z0 + z1))) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(0.7f * w, 0.7f * w, 0.5f * (z1 - z0)));
      post.material.colour = glm::vec3(0.35f);
      items.push_back(post);
    }
    DrawItem joint;
    joint.shape = Shape::cylinder;
    joint.model = glm::translate(glm::mat4(1.0f), to_glm(joint_point(j, poses, t))) *
                  align_z(joint_axis(j, poses, t)) *
                  glm::scale(glm::mat4(1.0f), glm::vec3(0.95f * w, 0.95f * w, 0.85f * w));
    joint.material.colour = kJointColour;
    joint.material.specular = 0.5f;
    items.push_back(joint);
    add_pin(items, joint_point(j, poses, t), joint_axis(j, poses, t), w);
    // The tip: the child's point mirrored through its centre, if the child is a box jointed
    // near one end and carries no further joint.
    const BodyVisual& child = scene.bodies[static_cast<std::size_t>(j.child)];
    const bool parent_of_another =
        std::any_of(scene.joints.begin(), scene.joints.end(),
                    [&](const JointVisual& o) { return o.parent == j.child; });
    if (child.kind == BodyVisual::Kind::box && !parent_of_another &&
        j.point.norm() > 0.25 * child.size.maxCoeff()) {
      const core::Vec3 end = poses.position(j.child, t) - poses.orientation(j.child, t) * j.point;
      DrawItem tip;
      tip.shape = Shape::sphere;
      tip.model = glm::translate(glm::mat4(1.0f), to_glm(end)) *
                  glm::scale(glm::mat4(1.0f), glm::vec3(0.6f * w));
      tip.material.colour = kJointColour;
      items.push_back(tip);
    }
  }
  add_mechanism_items(items, scene, poses, mechanism, t);
  return items;
}

}  // namespace stiction::render
