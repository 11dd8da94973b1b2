// A cylinder body's draw items: the body in the sphere's octant pattern (its four sectors
// about the axis show the rolling), and for a hollow one (a ring) a dark bore on each cap.
#pragma once

#include <vector>

#include "render/scene_view.hpp"

namespace stiction::render {

void add_cylinder(std::vector<DrawItem>& items, const BodyVisual& b, int index,
                  const core::Vec3& position, const core::Quat& orientation);

}  // namespace stiction::render
