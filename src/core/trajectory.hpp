// Sampled signals of a run: a time column "t" then one column per signal, row-major.
// The renderer and the plotter read runs only through this table.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace stiction::core {

class Trajectory {
 public:
  Trajectory() = default;
  explicit Trajectory(std::vector<std::string> columns) : columns_(std::move(columns)) {}

  const std::vector<std::string>& columns() const { return columns_; }
  int column_count() const { return static_cast<int>(columns_.size()); }
  int row_count() const {
    return columns_.empty() ? 0 : static_cast<int>(data_.size() / columns_.size());
  }
  std::optional<int> find(const std::string& column) const;
  double at(int row, int column) const { return data_[row * columns_.size() + column]; }
  const double* row(int r) const { return data_.data() + r * columns_.size(); }
  std::vector<double> column(int c) const;
  void append(const double* values) { data_.insert(data_.end(), values, values + columns_.size()); }
  void reserve_rows(int rows) { data_.reserve(static_cast<std::size_t>(rows) * columns_.size()); }
  // Keeps rows 0, 2, 4, ... in place (no allocation; the capacity stays).
  void keep_even_rows();

 private:
  std::vector<std::string> columns_;
  std::vector<double> data_;
};

}  // namespace stiction::core
