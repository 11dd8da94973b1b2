// The files of a URDF's mesh visuals, found and read when the scene is loaded, so that a
// missing or escaping mesh is bad input at once (exit code 2), with or without a video.
#include <map>
#include <memory>

#include "scene/mesh_file.hpp"
#include "scene/mesh_path.hpp"
#include "scene/urdf_loader.hpp"

namespace stiction::scene {

void read_urdf_meshes(UrdfRobot& robot, const std::filesystem::path& urdf_file,
                      const std::vector<std::filesystem::path>& search, std::size_t max_triangles) {
  std::map<std::filesystem::path, std::shared_ptr<const TriangleMesh>> read;  // each file once
  std::size_t used = 0;
  for (UrdfVisual& v : robot.visuals) {
    if (v.shape != UrdfVisual::Shape::mesh) continue;
    const std::string where =
        urdf_file.string() + ": link '" + v.link_name + "': mesh '" + v.mesh + "': ";
    try {
      const ResolvedMesh found = resolve_mesh_path(v.mesh, urdf_file, search);
      auto& mesh = read[found.file];
      if (!mesh) {
        mesh = std::make_shared<const TriangleMesh>(
            load_mesh_file(found.file, found.folder, max_triangles - used));
      }
      // Every use counts towards the bound: each is drawn.
      const std::size_t n = mesh->triangle_count();
      if (n > max_triangles - used) {
        throw MeshFileError(std::string("its ") + std::to_string(n) +
                            " triangles take the robot's meshes past the scene's bound of " +
                            std::to_string(kMaxSceneTriangles) + " triangles (" +
                            std::to_string(max_triangles - used) + " were left)");
      }
      used += n;
      v.mesh_file = found.file;
      v.triangles = mesh;
    } catch (const MeshPathError& e) {
      throw UrdfError(where + e.what());
    } catch (const MeshFileError& e) {
      throw UrdfError(where + e.what());
    }
  }
}

}  // namespace stiction::scene
