#include "render/scene_view.hpp"

#include <algorithm>

namespace stiction::render {

glm::vec3 to_glm(const core::Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

bool is_axis_of(const std::string& column, const std::string& signal) {
  if (column.size() <= signal.size() + 1 || column.compare(0, signal.size(), signal) != 0 ||
      column[signal.size()] != '.') {
    return false;
  }
  const std::string axis = column.substr(signal.size() + 1);
  if (axis == "x" || axis == "y" || axis == "z" || axis == "w") return true;
  return std::all_of(axis.begin(), axis.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

}  // namespace stiction::render
