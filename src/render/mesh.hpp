// Triangle meshes: CPU generators (unit shapes, scaled by the model matrix), a URDF mesh
// file's parts brought to the unit cube, and their GPU buffers. Attribute 0 is the position, 1 the normal.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/gl.hpp"
#include "scene/triangle_mesh.hpp"

namespace stiction::render {

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
};

struct MeshData {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// Unit sphere (radius 1) as a latitude-longitude grid; 2 * slices * (stacks - 1) triangles.
MeshData make_sphere(int slices, int stacks);
// Cube from -1 to 1 on each axis (scale by the half extents), flat normals.
MeshData make_box();
// Cylinder of radius 1 along z from -1 to 1, with caps.
MeshData make_cylinder(int slices);
// Cone with its base (radius 1, capped) at z = 0 and its apex at z = 1: arrow heads.
MeshData make_cone(int slices);
// Square in the z = 0 plane from -1 to 1 (scale by the half size), normal +z. `cells` per
// side so that per-vertex lighting and depth precision stay good on a large floor.
MeshData make_plane(int cells);

// A URDF mesh's part as the renderer draws it (Shape::mesh): positions mapped from the
// part's bounding box onto [-1, 1]^3, normals mapped the other way (by the half extents, then
// unit) so that the model matrix's inverse transpose turns them back into the file's normals.
MeshData unit_mesh(const scene::TriangleMesh::Part& part);

class Mesh {
 public:
  explicit Mesh(const MeshData& data);
  void draw() const;

 private:
  GlVertexArray vao_;
  GlBuffer vertices_;
  GlBuffer indices_;
  GLsizei count_ = 0;
};

}  // namespace stiction::render
