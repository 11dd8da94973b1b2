// The scene's network as Graphviz DOT: the picture of the paper's Fig. 2 for one scene.
// Admittances are boxes, impedances ellipses; an edge from an admittance to an impedance
// carries the motion x_hat (Psi), the edge back carries the force u (Phi).
#pragma once

#include <filesystem>

#include "scene/scene.hpp"

namespace stiction::services {

void write_network_dot(const scene::Scene& scene, const std::filesystem::path& path);

}  // namespace stiction::services
