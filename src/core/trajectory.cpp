#include "core/trajectory.hpp"

#include <algorithm>

namespace stiction::core {

std::optional<int> Trajectory::find(const std::string& column) const {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (columns_[i] == column) return static_cast<int>(i);
  }
  return std::nullopt;
}

void Trajectory::keep_even_rows() {
  const std::size_t n = columns_.size();
  const int rows = row_count();
  int kept = 0;
  for (int r = 0; r < rows; r += 2, ++kept) {
    if (kept != r) {
      std::copy(data_.begin() + static_cast<std::ptrdiff_t>(r * n),
                data_.begin() + static_cast<std::ptrdiff_t>((r + 1) * n),
                data_.begin() + static_cast<std::ptrdiff_t>(kept * n));
    }
  }
  data_.resize(static_cast<std::size_t>(kept) * n);
}

std::vector<double> Trajectory::column(int c) const {
  std::vector<double> values(row_count());
  for (int r = 0; r < row_count(); ++r) values[r] = at(r, c);
  return values;
}

}  // namespace stiction::core
