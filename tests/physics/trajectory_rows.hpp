// Reading a run's rows at a time, for the closed-form tests.
#pragma once

#include <algorithm>
#include <cmath>
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

// How far body `body`'s pose moved from `from` to `to`: the largest change of its position
// and orientation entries (p.x .. q.z), the creep of a held or stopped body.
inline double pose_change(const core::Trajectory& tr, const std::string& body, double from,
                          double to) {
  double worst = 0.0;
  for (const char* entry : {".p.x", ".p.y", ".p.z", ".q.w", ".q.x", ".q.y", ".q.z"}) {
    std::string name = body;
    name += entry;
    worst = std::max(worst, std::abs(column_at(tr, name, to) - column_at(tr, name, from)));
  }
  return worst;
}

}  // namespace stiction::testing
