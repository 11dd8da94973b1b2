#include "render/mesh.hpp"

#include <cmath>
#include <cstddef>
#include <glm/gtc/constants.hpp>

namespace stiction::render {

MeshData make_sphere(int slices, int stacks) {
  MeshData m;
  for (int i = 0; i <= stacks; ++i) {
    const float phi = glm::pi<float>() * float(i) / float(stacks);  // from +z down
    for (int j = 0; j <= slices; ++j) {
      const float theta = 2.0f * glm::pi<float>() * float(j) / float(slices);
      const glm::vec3 p(std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta),
                        std::cos(phi));
      m.vertices.push_back({p, p});
    }
  }
  const auto row = static_cast<std::uint32_t>(slices + 1);
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const std::uint32_t a = i * row + j, b = a + row, c = b + 1, d = a + 1;
      if (i != 0) m.indices.insert(m.indices.end(), {a, b, d});
      if (i != stacks - 1) m.indices.insert(m.indices.end(), {d, b, c});
    }
  }
  return m;
}

MeshData make_box() {
  MeshData m;
  const glm::vec3 normals[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  for (const glm::vec3& n : normals) {
    // Two axes spanning the face, ordered so that (u, v, n) is right-handed.
    const glm::vec3 u = std::abs(n.z) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
    const glm::vec3 v = glm::cross(n, u);
    const auto base = static_cast<std::uint32_t>(m.vertices.size());
    const float s[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : s) m.vertices.push_back({n + c[0] * u + c[1] * v, n});
    // (u, v, n) right-handed means counter-clockwise seen from outside.
    if (glm::dot(glm::cross(u, v), n) > 0) {
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    } else {
      m.indices.insert(m.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  }
  return m;
}

MeshData make_cylinder(int slices) {
  MeshData m;
  for (int j = 0; j <= slices; ++j) {
    const float theta = 2.0f * glm::pi<float>() * float(j) / float(slices);
    const glm::vec3 n(std::cos(theta), std::sin(theta), 0.0f);
    m.vertices.push_back({n + glm::vec3(0, 0, -1), n});
    m.vertices.push_back({n + glm::vec3(0, 0, 1), n});
  }
  for (int j = 0; j < slices; ++j) {
    const auto a = static_cast<std::uint32_t>(2 * j);
    m.indices.insert(m.indices.end(), {a, a + 2, a + 1, a + 1, a + 2, a + 3});
  }
  for (float z : {-1.0f, 1.0f}) {
    const auto centre = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.push_back({{0, 0, z}, {0, 0, z}});
    for (int j = 0; j <= slices; ++j) {
      const float theta = 2.0f * glm::pi<float>() * float(j) / float(slices);
      m.vertices.push_back({{std::cos(theta), std::sin(theta), z}, {0, 0, z}});
    }
    for (int j = 0; j < slices; ++j) {
      const auto a = static_cast<std::uint32_t>(centre + 1 + j);
      if (z > 0) {
        m.indices.insert(m.indices.end(), {centre, a, a + 1});
      } else {
        m.indices.insert(m.indices.end(), {centre, a + 1, a});
      }
    }
  }
  return m;
}

MeshData make_cone(int slices) {
  MeshData m;
  // The side: per slice an apex vertex of its own, so each facet's normals are smooth around
  // and tilted up by the half-angle (45 degrees for a unit cone).
  const float k = std::sqrt(0.5f);
  for (int j = 0; j <= slices; ++j) {
    const float theta = 2.0f * glm::pi<float>() * float(j) / float(slices);
    const glm::vec3 radial(std::cos(theta), std::sin(theta), 0.0f);
    const glm::vec3 n = k * radial + glm::vec3(0, 0, k);
    m.vertices.push_back({radial, n});
    m.vertices.push_back({{0, 0, 1}, n});
  }
  for (int j = 0; j < slices; ++j) {
    const auto a = static_cast<std::uint32_t>(2 * j);
    m.indices.insert(m.indices.end(), {a, a + 2, a + 1});
  }
  const auto centre = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.push_back({{0, 0, 0}, {0, 0, -1}});
  for (int j = 0; j <= slices; ++j) {
    const float theta = 2.0f * glm::pi<float>() * float(j) / float(slices);
    m.vertices.push_back({{std::cos(theta), std::sin(theta), 0.0f}, {0, 0, -1}});
  }
  for (int j = 0; j < slices; ++j) {
    const auto a = static_cast<std::uint32_t>(centre + 1 + j);
    m.indices.insert(m.indices.end(), {centre, a + 1, a});
  }
  return m;
}

MeshData make_plane(int cells) {
  MeshData m;
  for (int i = 0; i <= cells; ++i) {
    for (int j = 0; j <= cells; ++j) {
      const float x = -1.0f + 2.0f * float(j) / float(cells);
      const float y = -1.0f + 2.0f * float(i) / float(cells);
      m.vertices.push_back({{x, y, 0.0f}, {0, 0, 1}});
    }
  }
  const auto row = static_cast<std::uint32_t>(cells + 1);
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      const std::uint32_t a = i * row + j, b = a + 1, c = a + row + 1, d = a + row;
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  }
  return m;
}

MeshData unit_mesh(const scene::TriangleMesh::Part& part) {
  const Eigen::Vector3f centre = part.centre(), half = part.half_extent();
  const glm::vec3 c(centre.x(), centre.y(), centre.z()), h(half.x(), half.y(), half.z());
  MeshData m;
  m.vertices.reserve(part.positions.size());
  for (std::size_t i = 0; i < part.positions.size(); ++i) {
    const Eigen::Vector3f& p = part.positions[i];
    const Eigen::Vector3f& n = part.normals[i];
    // Positions scaled by 1 / h: normals by h (the inverse transpose), then made unit again.
    const glm::vec3 scaled = glm::vec3(n.x(), n.y(), n.z()) * h;
    const float length = glm::length(scaled);
    m.vertices.push_back({(glm::vec3(p.x(), p.y(), p.z()) - c) / h,
                          length > 0.0f ? scaled / length : glm::vec3(0.0f, 0.0f, 1.0f)});
  }
  m.indices = part.indices;
  return m;
}

Mesh::Mesh(const MeshData& data)
    : vao_(make_vertex_array()),
      vertices_(make_buffer()),
      indices_(make_buffer()),
      count_(static_cast<GLsizei>(data.indices.size())) {
  glBindVertexArray(vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.vertices.size() * sizeof(Vertex)),
               data.vertices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(data.indices.size() * sizeof(std::uint32_t)),
               data.indices.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                        reinterpret_cast<const void*>(offsetof(Vertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                        reinterpret_cast<const void*>(offsetof(Vertex, normal)));
  glBindVertexArray(0);
  check_gl("mesh upload");
}

void Mesh::draw() const {
  glBindVertexArray(vao_.get());
  glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace stiction::render
