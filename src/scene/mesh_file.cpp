#include "scene/mesh_file.hpp"

#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include "scene/mesh_path.hpp"
#include "sys/read_file.hpp"

namespace stiction::scene {

namespace fs = std::filesystem;

namespace {

// assimp's file access for one mesh: only regular files inside the folder, read whole with
// the project's bounded reader and served from memory. Anything else "does not exist".
class ConfinedIo final : public Assimp::IOSystem {
 public:
  ConfinedIo(fs::path folder, fs::path base) : folder_(std::move(folder)), base_(std::move(base)) {}

  bool Exists(const char* file) const override { return where(file).has_value(); }
  char getOsSeparator() const override { return '/'; }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (mode == nullptr || std::strpbrk(mode, "wa+") != nullptr) return nullptr;
    const std::optional<fs::path> path = where(file);
    if (!path) return nullptr;
    std::string bytes;
    try {
      bytes = sys::read_regular_file(*path);
    } catch (const sys::FileRefused&) {
      return nullptr;
    }
    auto buffer = std::make_unique<std::uint8_t[]>(bytes.size());
    std::memcpy(buffer.get(), bytes.data(), bytes.size());
    return new Assimp::MemoryIOStream(buffer.release(), bytes.size(), /*own=*/true);
  }

  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  // A relative name is taken from the mesh's own folder (assimp composes an .mtl's path
  // from the model's, but a bare name must not mean the working directory).
  std::optional<fs::path> where(const char* file) const {
    if (file == nullptr || *file == '\0') return std::nullopt;
    const fs::path p(file);
    return confined_file(p.is_absolute() ? p : base_ / p, folder_);
  }

  fs::path folder_;
  fs::path base_;
};

// Triangles the faces will make once split (a polygon of n corners makes n - 2).
std::size_t triangles_of(const aiScene& scene) {
  std::size_t n = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      if (mesh.mFaces[f].mNumIndices >= 3) n += mesh.mFaces[f].mNumIndices - 2;
    }
  }
  return n;
}

// The material's diffuse colour and opacity, unless it is assimp's stand-in for none.
bool own_colour(const aiMaterial& material, Eigen::Vector4d& rgba) {
  aiString name;
  if (material.Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS &&
      std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME) {
    return false;
  }
  aiColor4D c;
  if (material.Get(AI_MATKEY_COLOR_DIFFUSE, c) != aiReturn_SUCCESS) return false;
  float opacity = 1.0f;
  if (material.Get(AI_MATKEY_OPACITY, opacity) != aiReturn_SUCCESS) opacity = c.a;
  rgba = Eigen::Vector4d(c.r, c.g, c.b, opacity);
  return rgba.allFinite();
}

std::string count_message(std::size_t n, std::size_t max) {
  return std::string("it has ") + std::to_string(n) + " triangles, more than the " +
         std::to_string(max) + " left of the scene's bound of " +
         std::to_string(kMaxSceneTriangles) + " triangles for all its meshes";
}

}  // namespace

TriangleMesh load_mesh_file(const fs::path& file, const fs::path& folder,
                            std::size_t max_triangles) {
  Assimp::Importer importer;
  importer.SetIOHandler(new ConfinedIo(folder, file.parent_path()));  // the importer owns it
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, 60.0f);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Read without post-processing first: the bound is checked before the (costlier) steps.
  const aiScene* raw = importer.ReadFile(file.string(), 0);
  if (raw == nullptr) {
    throw MeshFileError(std::string("cannot read it as a mesh: ") + importer.GetErrorString());
  }
  if (const std::size_t n = triangles_of(*raw); n > max_triangles) {
    throw MeshFileError(count_message(n, max_triangles));
  }
  const aiScene* scene = importer.ApplyPostProcessing(
      aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_PreTransformVertices |
      aiProcess_GenSmoothNormals | aiProcess_JoinIdenticalVertices | aiProcess_FindInvalidData);
  if (scene == nullptr) {
    throw MeshFileError(std::string("cannot read it as a mesh: ") + importer.GetErrorString());
  }

  TriangleMesh out;
  std::map<unsigned, std::size_t> part_of_material;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || mesh.mNormals == nullptr) continue;
    auto [it, added] = part_of_material.emplace(mesh.mMaterialIndex, out.parts.size());
    if (added) {
      out.parts.emplace_back();
      if (mesh.mMaterialIndex < scene->mNumMaterials) {
        TriangleMesh::Part& part = out.parts.back();
        part.has_colour = own_colour(*scene->mMaterials[mesh.mMaterialIndex], part.rgba);
      }
    }
    TriangleMesh::Part& part = out.parts[it->second];
    const auto first = static_cast<std::uint32_t>(part.positions.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      const aiVector3D& n = mesh.mNormals[v];
      Eigen::Vector3f normal(n.x, n.y, n.z);
      const float length = normal.norm();
      // A vertex only on degenerate faces has no normal: any unit vector draws it.
      normal = std::isfinite(length) && length > 0.0f ? Eigen::Vector3f(normal / length)
                                                      : Eigen::Vector3f::UnitZ();
      part.positions.emplace_back(p.x, p.y, p.z);
      part.normals.push_back(normal);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k) part.indices.push_back(first + face.mIndices[k]);
    }
  }
  std::erase_if(out.parts, [](const TriangleMesh::Part& p) { return p.indices.empty(); });
  if (out.parts.empty()) throw MeshFileError("it has no triangles");
  for (TriangleMesh::Part& part : out.parts) {
    part.lower = part.upper = part.positions.front();
    for (const Eigen::Vector3f& p : part.positions) {
      if (!p.allFinite()) throw MeshFileError("it has a vertex that is not a finite number");
      part.lower = part.lower.cwiseMin(p);
      part.upper = part.upper.cwiseMax(p);
    }
  }
  if (const std::size_t n = out.triangle_count(); n > max_triangles) {
    throw MeshFileError(count_message(n, max_triangles));
  }
  return out;
}

}  // namespace stiction::scene
