#include "render/tree_items.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <utility>

#include "render/scene_geometry.hpp"

namespace stiction::render {
namespace {

const glm::vec3 kRodColour{0.10f, 0.28f, 0.62f};
const glm::vec3 kRodColour2{0.15f, 0.50f, 0.75f};
const glm::vec3 kJointColour{0.06f, 0.06f, 0.07f};

// Frame of a visual (link -1: the base).
components::LinkPose visual_frame(const BodyVisual& b,
                                  const std::vector<components::LinkPose>& links,
                                  const scene::UrdfVisual& v) {
  components::LinkPose at;
  if (v.link < 0) {
    at.p = b.tree->params().base_position;
    at.q = b.tree->params().base_orientation;
  } else {
    at = links[static_cast<std::size_t>(v.link)];
  }
  return {at.p + at.q * v.origin, at.q * v.rotation};
}

// The end points of each link's rods: its children's joints, or for a leaf twice its
// centre of mass from its joint.
std::vector<std::pair<core::Vec3, core::Vec3>> rods(const BodyVisual& b,
                                                    const std::vector<components::LinkPose>& p) {
  const auto& links = b.tree->params().links;
  std::vector<std::pair<core::Vec3, core::Vec3>> out;
  std::vector<bool> has_child(links.size(), false);
  for (std::size_t i = 0; i < links.size(); ++i) {
    const int parent = links[i].parent;
    const core::Vec3 from =
        parent < 0 ? b.tree->params().base_position : p[static_cast<std::size_t>(parent)].p;
    if (parent >= 0) has_child[static_cast<std::size_t>(parent)] = true;
    out.emplace_back(from, p[i].p);
  }
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (!has_child[i] && links[i].com.norm() > 1e-9) {
      out.emplace_back(p[i].p, p[i].p + p[i].q * (2.0 * links[i].com));
    }
  }
  return out;
}

glm::mat4 frame_matrix(const components::LinkPose& f) {
  return glm::translate(glm::mat4(1.0f), to_glm(f.p)) * to_glm(f.q);
}

// A mesh part's unit cube (render/mesh.hpp unit_mesh) onto its place: the part's bounding
// box, scaled by the URDF's scale, on the visual's frame.
glm::mat4 part_model(const scene::UrdfVisual& v, const components::LinkPose& f,
                     const scene::TriangleMesh::Part& part) {
  const Eigen::Vector3f c = part.centre(), h = part.half_extent();
  return frame_matrix(f) * glm::scale(glm::mat4(1.0f), to_glm(v.size)) *
         glm::translate(glm::mat4(1.0f), glm::vec3(c.x(), c.y(), c.z())) *
         glm::scale(glm::mat4(1.0f), glm::vec3(h.x(), h.y(), h.z()));
}

// A primitive's unit shape onto its place.
glm::mat4 primitive_model(const scene::UrdfVisual& v, const components::LinkPose& f) {
  glm::vec3 half(0.0f);
  switch (v.shape) {
    case scene::UrdfVisual::Shape::box:
      half = 0.5f * to_glm(v.size);
      break;
    case scene::UrdfVisual::Shape::cylinder:
      half = glm::vec3(to_glm(v.size).x, to_glm(v.size).y, 0.5f * to_glm(v.size).z);
      break;
    case scene::UrdfVisual::Shape::sphere:
    case scene::UrdfVisual::Shape::mesh:
      half = to_glm(v.size);
      break;
  }
  return frame_matrix(f) * glm::scale(glm::mat4(1.0f), half);
}

glm::vec3 colour_of(const Eigen::Vector4d& rgba) {
  return {static_cast<float>(rgba[0]), static_cast<float>(rgba[1]), static_cast<float>(rgba[2])};
}

// The lowest height of a visual on frame `f`: exact for the primitives and, with `exact`, for
// a mesh (its lowest vertex: a robot's base stands on the floor put there); else a mesh's
// bounding box's lowest corner (below or at the mesh: cheap enough for every frame).
double lowest_z(const scene::UrdfVisual& v, const components::LinkPose& f, bool exact) {
  const core::Mat3 R = f.q.toRotationMatrix();
  switch (v.shape) {
    case scene::UrdfVisual::Shape::box:
      return f.p.z() - 0.5 * (R.row(2).cwiseAbs() * v.size).value();
    case scene::UrdfVisual::Shape::cylinder: {
      const double az = std::min(1.0, std::abs(R(2, 2)));  // the axis' vertical part
      return f.p.z() - v.size.x() * std::sqrt(1.0 - az * az) - 0.5 * v.size.z() * az;
    }
    case scene::UrdfVisual::Shape::sphere:
      return f.p.z() - v.size.x();
    case scene::UrdfVisual::Shape::mesh: {
      double low = f.p.z();
      if (!v.triangles) return low;
      low = std::numeric_limits<double>::infinity();
      const auto height = [&](const Eigen::Vector3f& p) {
        return f.p.z() + R.row(2).dot(v.size.cwiseProduct(p.cast<double>()));
      };
      for (const auto& part : v.triangles->parts) {
        if (exact) {
          for (const Eigen::Vector3f& p : part.positions) low = std::min(low, height(p));
          continue;
        }
        for (int k = 0; k < 8; ++k) {
          low = std::min(low, height(Eigen::Vector3f((k & 1) ? part.upper.x() : part.lower.x(),
                                                     (k & 2) ? part.upper.y() : part.lower.y(),
                                                     (k & 4) ? part.upper.z() : part.lower.z())));
        }
      }
      return low;
    }
  }
  return f.p.z();
}

void add_rod(std::vector<DrawItem>& items, const core::Vec3& a, const core::Vec3& b, float radius,
             glm::vec3 colour) {
  const core::Vec3 d = b - a;
  const double length = d.norm();
  if (length < 1e-9) return;
  DrawItem rod;
  rod.shape = Shape::cylinder;
  rod.model =
      glm::translate(glm::mat4(1.0f), to_glm(0.5 * (a + b))) * align_z(d / length) *
      glm::scale(glm::mat4(1.0f), glm::vec3(radius, radius, 0.5f * static_cast<float>(length)));
  rod.material.colour = colour;
  items.push_back(rod);
}

}  // namespace

std::vector<components::LinkPose> tree_poses(const BodyVisual& tree, const PoseTrack& poses,
                                             int index, double t) {
  const int n = tree.tree->joint_count();
  core::Vec q(n);
  for (int i = 0; i < n; ++i) q[i] = poses.angle(index, i, t);
  return tree.tree->link_poses(q);
}

std::vector<core::Vec3> tree_points(const BodyVisual& b, const PoseTrack& poses, int index,
                                    double t, bool links_only) {
  const std::vector<components::LinkPose> p = tree_poses(b, poses, index, t);
  std::vector<core::Vec3> out;
  if (!links_only) out.push_back(b.tree->params().base_position);
  for (const auto& [from, to] : rods(b, p)) {
    // A rod from the base starts at the base; its end is the first joint.
    if (!links_only || from != b.tree->params().base_position) out.push_back(from);
    out.push_back(to);
  }
  for (const auto& v : b.visuals) {
    if (links_only && v.link < 0) continue;
    const components::LinkPose f = visual_frame(b, p, v);
    if (v.shape == scene::UrdfVisual::Shape::mesh) {
      // The corners of each part's bounding box, where it is drawn.
      if (!v.triangles) continue;
      for (const auto& part : v.triangles->parts) {
        const glm::mat4 model = part_model(v, f, part);
        for (int k = 0; k < 8; ++k) {
          const glm::vec4 c = model * glm::vec4((k & 1) ? 1.0f : -1.0f, (k & 2) ? 1.0f : -1.0f,
                                                (k & 4) ? 1.0f : -1.0f, 1.0f);
          out.emplace_back(c.x, c.y, c.z);
        }
      }
      continue;
    }
    const double r = 0.5 * v.size.norm();
    for (int k = 0; k < 8; ++k) {
      out.push_back(f.p + core::Vec3((k & 1) ? r : -r, (k & 2) ? r : -r, (k & 4) ? r : -r));
    }
  }
  return out;
}

double hub_reach(const BodyVisual& b, const std::vector<components::LinkPose>& links, int link,
                 const core::Vec3& centre, const core::Vec3& axis) {
  auto radial = [&](const glm::vec4& p) {
    const core::Vec3 d = core::Vec3(p.x, p.y, p.z) - centre;
    return (d - axis.dot(d) * axis).norm();
  };
  double reach = 0.0;
  auto add_box = [&](const glm::mat4& model) {
    double far = 0.0;
    for (int k = 0; k < 8; ++k) {
      far = std::max(far, radial(model * glm::vec4((k & 1) ? 1.0f : -1.0f, (k & 2) ? 1.0f : -1.0f,
                                                   (k & 4) ? 1.0f : -1.0f, 1.0f)));
    }
    if (radial(model * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)) <= 0.25 * far) {
      reach = std::max(reach, far);
    }
  };
  for (const auto& v : b.visuals) {
    if (v.link != link) continue;
    const components::LinkPose f = visual_frame(b, links, v);
    if (v.shape == scene::UrdfVisual::Shape::mesh) {
      if (!v.triangles) continue;
      for (const auto& part : v.triangles->parts) add_box(part_model(v, f, part));
    } else {
      add_box(primitive_model(v, f));
    }
  }
  return reach;
}

void add_tree_items(std::vector<DrawItem>& items, const BodyVisual& b, const PoseTrack& poses,
                    int index, double t) {
  const std::vector<components::LinkPose> p = tree_poses(b, poses, index, t);
  if (!b.visuals.empty()) {
    for (const auto& v : b.visuals) {
      const components::LinkPose f = visual_frame(b, p, v);
      DrawItem item;
      item.material.colour = colour_of(v.rgba);
      if (v.shape == scene::UrdfVisual::Shape::mesh) {
        if (!v.triangles) continue;  // a drawing built without its files (parse_urdf)
        item.shape = Shape::mesh;
        item.mesh = v.triangles;
        for (std::size_t k = 0; k < v.triangles->parts.size(); ++k) {
          const auto& part = v.triangles->parts[k];
          item.mesh_part = k;
          item.model = part_model(v, f, part);
          // The URDF's colour first, else the file's own for this part, else grey.
          item.material.colour = colour_of(!v.rgba_given && part.has_colour ? part.rgba : v.rgba);
          items.push_back(item);
        }
        continue;
      }
      item.shape = v.shape == scene::UrdfVisual::Shape::box        ? Shape::box
                   : v.shape == scene::UrdfVisual::Shape::cylinder ? Shape::cylinder
                                                                   : Shape::sphere;
      item.model = primitive_model(v, f);
      items.push_back(item);
    }
    return;
  }
  const auto& links = b.tree->params().links;
  std::size_t k = 0;
  for (const auto& [from, to] : rods(b, p)) {
    const std::size_t link = std::min(k, links.size() - 1);
    add_rod(items, from, to, 0.5f * static_cast<float>(b.widths[link]),
            k % 2 == 0 ? kRodColour : kRodColour2);
    ++k;
  }
  for (std::size_t i = 0; i < links.size(); ++i) {
    const core::Vec3 axis = (p[i].q * links[i].axis).normalized();
    const float w = static_cast<float>(b.widths[i]);
    DrawItem pin;
    pin.shape = Shape::cylinder;
    pin.model = glm::translate(glm::mat4(1.0f), to_glm(p[i].p)) * align_z(axis) *
                glm::scale(glm::mat4(1.0f), glm::vec3(0.8f * w, 0.8f * w, 0.9f * w));
    pin.material.colour = kJointColour;
    pin.material.specular = 0.5f;
    items.push_back(pin);
  }
}

std::optional<double> tree_base_floor(const Drawing& scene, const PoseTrack& poses) {
  if (scene.bodies.empty() || !scene.springs.empty() || !scene.joints.empty()) return std::nullopt;
  double floor = std::numeric_limits<double>::infinity();
  for (const BodyVisual& b : scene.bodies) {
    // A stick figure (no visuals) has its first pin at the base: it keeps the usual floor.
    if (b.kind != BodyVisual::Kind::tree || b.tree == nullptr || b.visuals.empty()) {
      return std::nullopt;
    }
    const components::LinkPose base{b.tree->params().base_position,
                                    b.tree->params().base_orientation};
    bool has_base_visual = false;
    for (const auto& v : b.visuals) {
      if (v.link >= 0) continue;
      has_base_visual = true;
      floor = std::min(floor, lowest_z(v, visual_frame(b, {}, v), true));
    }
    if (!has_base_visual) floor = std::min(floor, base.p.z());
  }
  // The moving links over the run (sampled as run_bounds does): their visuals must stay
  // above it.
  constexpr int kSamples = 32;
  const double t0 = poses.start_time(), t1 = poses.end_time();
  const double tolerance = 1e-9 * std::max(1.0, std::abs(floor));
  for (int k = 0; k < kSamples; ++k) {
    const double t = t0 + (t1 - t0) * k / (kSamples - 1);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const BodyVisual& b = scene.bodies[i];
      const std::vector<components::LinkPose> p = tree_poses(b, poses, static_cast<int>(i), t);
      double low = std::numeric_limits<double>::infinity();
      for (const auto& v : b.visuals) {
        if (v.link >= 0) low = std::min(low, lowest_z(v, visual_frame(b, p, v), false));
      }
      if (low < floor - tolerance) return std::nullopt;
    }
  }
  return floor;
}

}  // namespace stiction::render
