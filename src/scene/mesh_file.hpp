// Reads a mesh file (STL ASCII or binary, OBJ, DAE) through assimp into a TriangleMesh: the
// file's node transforms applied (a DAE's scene graph), polygons split into triangles, points
// and lines dropped, a normal per vertex computed where the file has none (smooth across
// edges under 60 degrees, creased above, so a box stays a box), one part per material with
// its diffuse colour. A DAE's <up_axis> is not applied: its coordinates are taken as written,
// as for STL and OBJ, which is what a URDF's Z-up meshes expect; its <unit> is.
// Every file assimp opens (the mesh, an OBJ's .mtl) goes through sys::read_regular_file and
// must be inside `folder` (scene/mesh_path.hpp): a file cannot make it read another one
// elsewhere.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>

#include "scene/triangle_mesh.hpp"

namespace stiction::scene {

// Why a mesh file was not read, as a clause; the caller names the URDF, link and mesh.
class MeshFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The most triangles the meshes of one scene may have together (every use of a file counts):
// a 200k-triangle scene renders a 720p frame in well under a second with llvmpipe, where
// a few million would take many.
inline constexpr std::size_t kMaxSceneTriangles = 200000;

// Reads `file` (canonical, inside the canonical `folder`); refuses a file with more than
// `max_triangles` triangles, or none.
TriangleMesh load_mesh_file(const std::filesystem::path& file, const std::filesystem::path& folder,
                            std::size_t max_triangles);

}  // namespace stiction::scene
