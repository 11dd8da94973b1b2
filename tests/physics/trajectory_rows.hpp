// Reading a run's rows at a time, for the closed-form tests.
#pragma once

#include <string>

#include "core/trajectory.hpp"

namespace stiction::testing {

// The first row at or after t (the last row if none is).
inline int row_at(const core::Trajectory& tr, double t) {
  int row = 0;
  while (row + 1 < tr.row_count() && tr.at(row, 0) < t - 1e-9) ++row;
  return row;
}

// Column `name` of that row.
inline double column_at(const core::Trajectory& tr, const std::string& name, double t) {
  return tr.at(row_at(tr, t), *tr.find(name));
}

}  // namespace stiction::testing
