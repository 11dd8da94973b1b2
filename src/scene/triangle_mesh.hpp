// A triangle mesh read from a URDF <mesh> file (scene/mesh_file.hpp), as the scene declares
// it for drawing: in the file's own coordinates and units (metres once the URDF's scale is
// applied), one part per material of the file, each with a normal per vertex. Plain data,
// shared by every visual that names the same file; the renderer uploads it as it is.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace stiction::scene {

struct TriangleMesh {
  struct Part {
    std::vector<Eigen::Vector3f> positions;
    std::vector<Eigen::Vector3f> normals;  // unit, one per position
    std::vector<std::uint32_t> indices;    // three per triangle, counter-clockwise outside
    // The file's own diffuse colour for this part; used when the URDF gives none.
    bool has_colour = false;
    Eigen::Vector4d rgba{0.6, 0.6, 0.62, 1.0};
    // Bounds of the positions.
    Eigen::Vector3f lower = Eigen::Vector3f::Zero(), upper = Eigen::Vector3f::Zero();
    std::size_t triangle_count() const { return indices.size() / 3; }
    Eigen::Vector3f centre() const { return 0.5f * (lower + upper); }
    // Half the bounding box's sides, each at least a millionth of the largest: the renderer
    // draws a part as a unit cube's [-1, 1]^3 scaled by this (so bounds, framing and the
    // shadow fit treat it as any box), and a flat part (a plate) must not give a singular scale.
    Eigen::Vector3f half_extent() const {
      const Eigen::Vector3f h = 0.5f * (upper - lower);
      const float floor = std::max(1e-6f * h.maxCoeff(), 1e-9f);
      return h.cwiseMax(floor);
    }
  };
  std::vector<Part> parts;
  std::size_t triangle_count() const {
    std::size_t n = 0;
    for (const Part& p : parts) n += p.triangle_count();
    return n;
  }
};

}  // namespace stiction::scene
