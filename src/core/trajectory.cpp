#include "core/trajectory.hpp"

namespace stiction::core {

std::optional<int> Trajectory::find(const std::string& column) const {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (columns_[i] == column) return static_cast<int>(i);
  }
  return std::nullopt;
}

std::vector<double> Trajectory::column(int c) const {
  std::vector<double> values(row_count());
  for (int r = 0; r < row_count(); ++r) values[r] = at(r, c);
  return values;
}

}  // namespace stiction::core
