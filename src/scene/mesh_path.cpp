#include "scene/mesh_path.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <optional>
#include <string_view>
#include <system_error>

namespace stiction::scene {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPackage = "package://";
constexpr std::string_view kFile = "file://";

// The components of a normalized path, without the empty one a trailing '/' leaves.
std::vector<fs::path> components(const fs::path& p) {
  std::vector<fs::path> out(p.begin(), p.end());
  while (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

std::string quoted(const fs::path& p) { return std::string("'") + p.string() + "'"; }

// The canonical form of an existing folder, or nothing (missing, not a folder, unreadable).
std::optional<fs::path> existing_folder(const fs::path& p) {
  std::error_code ec;
  if (!fs::is_directory(p, ec) || ec) return std::nullopt;
  fs::path c = fs::canonical(p, ec);
  if (ec) return std::nullopt;
  return c;
}

void check_format(const fs::path& name) {
  std::string ext = name.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".stl" && ext != ".obj" && ext != ".dae") {
    throw MeshPathError(std::string("not a mesh format that is read (") +
                        (ext.empty() ? std::string("no extension") : std::string("'") + ext + "'") +
                        "; STL, OBJ or DAE: .stl, .obj, .dae)");
  }
}

// `relative` inside the canonical `folder`: its path if it is a regular file there, nothing
// if there is no such file. Refuses a name that climbs out of the folder by its text or
// through a symbolic link.
std::optional<fs::path> find_in(const fs::path& folder, const fs::path& relative,
                                const std::string& what) {
  if (relative.empty() || relative.has_root_path()) {
    throw MeshPathError(std::string("'") + relative.string() + "' is not a relative path inside " +
                        what);
  }
  const fs::path candidate = (folder / relative).lexically_normal();
  if (!inside_folder(candidate, folder) || candidate == folder) {
    throw MeshPathError(std::string("'") + relative.string() + "' leaves " + what + " " +
                        quoted(folder) + " (no '..' out of it)");
  }
  std::error_code ec;
  const fs::file_status status = fs::status(candidate, ec);
  if (!fs::exists(status)) return std::nullopt;
  const fs::path real = fs::canonical(candidate, ec);
  if (ec) return std::nullopt;
  if (!inside_folder(real, folder)) {
    throw MeshPathError(quoted(candidate) + " is a symbolic link to " + quoted(real) +
                        ", outside " + what + " " + quoted(folder));
  }
  if (!fs::is_regular_file(status)) {
    throw MeshPathError(quoted(candidate) + " is not a regular file");
  }
  return real;
}

ResolvedMesh in_package(const std::string& spec, const fs::path& urdf_folder,
                        const std::vector<fs::path>& search) {
  const std::size_t slash = spec.find('/');
  const std::string name = spec.substr(0, slash);
  const std::string rest = slash == std::string::npos ? "" : spec.substr(slash + 1);
  if (name.empty() || name == "." || name == ".." || rest.empty()) {
    throw MeshPathError("package:// needs a package name and a file in it: package://NAME/FILE");
  }
  // DESIGN.md section 3: the URDF's folder, then the search path's folders, never
  // elsewhere (not the URDF folder's parents: a ROS layout NAME/urdf/robot.urdf puts the
  // folder holding NAME on STICTION_MESH_PATH).
  std::vector<fs::path> roots;
  if (urdf_folder.filename() == name) {
    roots.push_back(urdf_folder);
  } else if (const auto sub = existing_folder(urdf_folder / name)) {
    roots.push_back(*sub);
  }
  for (const fs::path& p : search) {
    const std::optional<fs::path> folder = existing_folder(p);
    if (!folder) continue;
    if (folder->filename() == name) {
      roots.push_back(*folder);
    } else if (const auto sub = existing_folder(*folder / name)) {
      roots.push_back(*sub);
    }
  }
  if (roots.empty()) {
    throw MeshPathError(std::string("no package folder named '") + name +
                        "': the URDF's folder " + quoted(urdf_folder) +
                        " neither has that name nor holds it, and no folder of "
                        "STICTION_MESH_PATH is or holds one" +
                        (search.empty() ? " (STICTION_MESH_PATH is not set)" : ""));
  }
  std::string tried;
  for (const fs::path& root : roots) {
    if (auto file = find_in(root, rest, "the package folder")) return {*file, root};
    tried += (tried.empty() ? "" : ", ") + quoted(root);
  }
  throw MeshPathError(std::string("no file '") + rest + "' in the package folder " + tried);
}

ResolvedMesh at_absolute_path(const fs::path& path, const fs::path& urdf_folder,
                              const std::vector<fs::path>& search) {
  // The folders it may be in, each as written (made absolute) and canonical, so that a path
  // written through a folder's symbolic link is recognised; the file is looked for in the
  // canonical one.
  std::vector<std::pair<fs::path, fs::path>> folders{{urdf_folder, urdf_folder}};
  for (const fs::path& p : search) {
    if (const auto folder = existing_folder(p)) {
      std::error_code ec;
      folders.emplace_back(fs::absolute(p, ec).lexically_normal(), *folder);
      folders.emplace_back(*folder, *folder);
    }
  }
  const fs::path p = path.lexically_normal();
  for (const auto& [written, real] : folders) {
    if (!inside_folder(p, written) || p == written) continue;
    if (auto file = find_in(real, p.lexically_relative(written), "the folder"))
      return {*file, real};
    throw MeshPathError(std::string("no such file ") + quoted(p));
  }
  throw MeshPathError(std::string("an absolute path is read only inside the URDF's folder ") +
                      quoted(urdf_folder) + " or a folder of STICTION_MESH_PATH");
}

}  // namespace

std::optional<fs::path> confined_file(const fs::path& path, const fs::path& folder) {
  const fs::path p = path.lexically_normal();
  if (!inside_folder(p, folder) || p == folder) return std::nullopt;
  std::error_code ec;
  if (!fs::is_regular_file(p, ec) || ec) return std::nullopt;
  fs::path real = fs::canonical(p, ec);
  if (ec || !inside_folder(real, folder)) return std::nullopt;
  return real;
}

bool inside_folder(const fs::path& path, const fs::path& folder) {
  const std::vector<fs::path> p = components(path.lexically_normal());
  const std::vector<fs::path> f = components(folder.lexically_normal());
  return p.size() >= f.size() && std::equal(f.begin(), f.end(), p.begin());
}

std::vector<fs::path> package_search_path() {
  std::vector<fs::path> out;
  const char* value = std::getenv("STICTION_MESH_PATH");
  if (value == nullptr) return out;
  const std::string_view text(value);
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(':', start), text.size());
    if (end > start) out.emplace_back(std::string(text.substr(start, end - start)));
    start = end + 1;
  }
  return out;
}

ResolvedMesh resolve_mesh_path(const std::string& name, const fs::path& urdf_file,
                               const std::vector<fs::path>& search) {
  if (name.empty()) throw MeshPathError("the file name is empty");
  // A NUL (an XML character reference &#0;) would cut the name the file system sees short of
  // the one checked here.
  if (name.find('\0') != std::string::npos) throw MeshPathError("the file name holds a NUL");
  std::error_code ec;
  const fs::path urdf_path = fs::absolute(urdf_file, ec);
  const std::optional<fs::path> urdf_folder =
      ec ? std::nullopt : existing_folder(urdf_path.parent_path());
  if (!urdf_folder) throw MeshPathError("the URDF's folder cannot be read");
  const std::string_view text(name);
  if (text.substr(0, kPackage.size()) == kPackage) {
    const std::string spec(text.substr(kPackage.size()));
    check_format(spec);
    return in_package(spec, *urdf_folder, search);
  }
  if (text.substr(0, kFile.size()) == kFile) {
    const fs::path path(std::string(text.substr(kFile.size())));
    check_format(path);
    if (!path.is_absolute()) {
      throw MeshPathError("file:// needs an absolute path (file:///folder/mesh.stl)");
    }
    return at_absolute_path(path, *urdf_folder, search);
  }
  if (const std::size_t scheme = text.find("://"); scheme != std::string_view::npos) {
    throw MeshPathError(std::string("'") + std::string(text.substr(0, scheme + 3)) +
                        "' is not read: a mesh is a relative path, package:// or file://");
  }
  const fs::path path(name);
  check_format(path);
  if (path.is_absolute()) return at_absolute_path(path, *urdf_folder, search);
  if (auto file = find_in(*urdf_folder, path, "the URDF's folder")) return {*file, *urdf_folder};
  throw MeshPathError(std::string("no file '") + name + "' in the URDF's folder " +
                      quoted(*urdf_folder));
}

}  // namespace stiction::scene
