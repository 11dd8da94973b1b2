// The mechanism's elements that are not bodies, surfaces or joints (springs, dampers and
// sources), found for describe_scene: from the network's impedances (by type) and their
// tables in the scene document (their wiring: body, point, other, other_point, frame, axis,
// joint), which is where the scene states the attachment points.
#pragma once

#include <toml++/toml.h>

#include "core/network.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {

// Fills scene.springs and scene.sources; scene.bodies must be filled already. Springs on an
// arm's joint (torsional, no attachment points) are not drawn.
void describe_mechanism(const core::Network& network, const toml::table& document,
                        SceneDescription& scene);

}  // namespace stiction::render
