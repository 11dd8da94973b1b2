#include "scene/drawing.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::scene {

int body_index(const Drawing& drawing, const std::string& name) {
  for (std::size_t i = 0; i < drawing.bodies.size(); ++i) {
    if (drawing.bodies[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

BodyVisual arm_visual(const std::string& name, const core::Vec3& base, const core::Vec3& plane_x,
                      const core::Vec3& plane_y, const core::Vec3& axis,
                      const std::vector<double>& lengths, const std::vector<double>& widths) {
  BodyVisual b;
  b.kind = BodyVisual::Kind::arm;
  b.name = name;
  b.base = base;
  b.plane_x = plane_x;
  b.plane_y = plane_y;
  b.axis = axis;
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    const double width = i < widths.size() ? widths[i] : 0.0;
    b.lengths.push_back(lengths[i]);
    b.widths.push_back(width > 0.0 ? width : 0.1 * lengths[i]);
  }
  return b;
}

BodyVisual cylinder_visual(const std::string& name, double radius, double length,
                           const core::Vec3& axis, bool hollow) {
  BodyVisual b;
  b.kind = BodyVisual::Kind::cylinder;
  b.name = name;
  b.radius = radius;
  b.length = length;
  b.hollow = hollow;
  b.axis = axis.normalized();
  // The body-frame box around it (what the box-like parts of framing and bounds use).
  for (int i = 0; i < 3; ++i) {
    const double a = std::abs(b.axis[i]);
    b.size[i] = b.length * a + 2.0 * b.radius * std::sqrt(std::max(0.0, 1.0 - a * a));
  }
  return b;
}

BodyVisual tree_visual(const components::SpatialTree& tree, std::vector<UrdfVisual> visuals) {
  BodyVisual b;
  b.kind = BodyVisual::Kind::tree;
  b.name = tree.name();
  b.tree = &tree;
  const auto& links = tree.params().links;
  b.lengths.assign(links.size(), 0.0);
  for (std::size_t i = 0; i < links.size(); ++i) {
    b.lengths[i] = std::max(b.lengths[i], 2.0 * links[i].com.norm());
    if (links[i].parent >= 0) {
      auto& reach = b.lengths[static_cast<std::size_t>(links[i].parent)];
      reach = std::max(reach, links[i].origin.norm());
    }
  }
  for (double& l : b.lengths) l = std::max(l, 0.02);
  for (double l : b.lengths) b.widths.push_back(std::clamp(0.12 * l, 0.01, 0.08));
  b.visuals = std::move(visuals);
  return b;
}

void add_surface(Drawing& drawing, const SurfaceVisual& s) {
  // A floor named by several tables (one per body on it) is drawn once.
  const bool seen =
      s.moving == nullptr && !s.extent.bounded() &&
      std::any_of(drawing.surfaces.begin(), drawing.surfaces.end(), [&](const auto& o) {
        return o.moving == nullptr && !o.extent.bounded() && (o.normal - s.normal).norm() < 1e-9 &&
               std::abs(o.offset - s.offset) < 1e-9;
      });
  if (!seen) drawing.surfaces.push_back(s);
}

}  // namespace stiction::scene
