#include "render/camera_preset.hpp"

#include <algorithm>

#include "scene/toml_reader.hpp"

namespace stiction::render {

const std::vector<std::string>& camera_view_names() {
  static const std::vector<std::string> names{"auto", "side", "top", "three_quarter", "follow"};
  return names;
}

CameraView read_camera_view(scene::TableReader& camera) {
  const std::string name = camera.string("view", "auto");
  const auto& names = camera_view_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "\"" : ", \"") + n + "\"";
    camera.fail("view", "unknown view '" + name + "' (one of: " + list + ")");
  }
  return static_cast<CameraView>(it - names.begin());
}

}  // namespace stiction::render
