// Where a URDF <mesh filename="..."> is, by one rule that never leaves the folders it names
// (docs/scene_format.md, "Mesh files"):
//   - a relative name ("meshes/link.stl"): in the URDF file's folder;
//   - "package://NAME/REST": REST inside the package folder NAME: for the URDF's folder and
//     then each folder P of the search path in order, P itself if its name is NAME, else
//     P/NAME; the first of these that holds REST (DESIGN.md section 3: never elsewhere, so
//     the ROS layout NAME/urdf/robot.urdf needs the folder holding NAME on the search path);
//   - "file:///ABS" or an absolute name "/ABS": only inside the URDF's folder or a folder
//     of the search path.
// The search path is the environment variable STICTION_MESH_PATH, folders separated by
// ':' (as ROS_PACKAGE_PATH). Every candidate is checked first by its text (no ".."
// climbing out of its folder) and then with its symbolic links resolved (a link inside
// pointing outside is refused), before the file system is asked whether it is a regular
// file. Only .stl, .obj and .dae files (any case) are accepted. Nothing is opened here.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace stiction::scene {

// Why a mesh name was refused, as a clause ("no file ... in ..."); the caller names the
// URDF file and the link.
class MeshPathError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ResolvedMesh {
  std::filesystem::path file;    // canonical
  std::filesystem::path folder;  // canonical: the folder it was found in, which its own
                                 // references (an OBJ's .mtl) must stay inside too
};

// The folders of STICTION_MESH_PATH (empty entries skipped), as written.
std::vector<std::filesystem::path> package_search_path();

// Resolves `name` as written in the URDF at `urdf_file` with the search path `search`.
ResolvedMesh resolve_mesh_path(const std::string& name, const std::filesystem::path& urdf_file,
                               const std::vector<std::filesystem::path>& search);

// The canonical path of `path` (absolute) if it is a regular file inside the canonical
// `folder`, by its text and with its links resolved; nothing otherwise. For the files a mesh
// file names itself (an OBJ's material library), which must stay in the mesh's folder.
std::optional<std::filesystem::path> confined_file(const std::filesystem::path& path,
                                                   const std::filesystem::path& folder);

// True if `path` is `folder` or inside it, comparing their components (both normalized).
bool inside_folder(const std::filesystem::path& path, const std::filesystem::path& folder);

}  // namespace stiction::scene
