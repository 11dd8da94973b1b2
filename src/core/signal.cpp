#include "core/signal.hpp"

namespace stiction::core {

std::vector<std::string> index_axes(int n) {
  std::vector<std::string> axes;
  for (int i = 0; i < n; ++i) axes.push_back(std::to_string(i));
  return axes;
}

std::vector<std::string> column_names(const std::string& component,
                                      const std::vector<SignalInfo>& signals) {
  std::vector<std::string> names;
  for (const auto& s : signals) {
    if (s.axes.empty()) {
      names.push_back(component + "." + s.name);
    } else {
      for (const auto& a : s.axes) names.push_back(component + "." + s.name + "." + a);
    }
  }
  return names;
}

}  // namespace stiction::core
