// What every trajectory column means (DESIGN section 4, summary.json `columns`): the time
// column `t` first, then one entry per signal column in Network::signal_columns() order,
// with the unit, frame and description the component declared in its SignalInfo.
#pragma once

#include <string>
#include <vector>

#include "core/network.hpp"

namespace stiction::core {

struct ColumnInfo {
  std::string name;  // as in the CSV header
  std::string unit;
  std::string frame;
  std::string description;
};

// `t` and every signal column of the network.
std::vector<ColumnInfo> column_infos(const Network& network);

// The unit of a column by the usual meaning of its signal name (p: m, v: m/s, theta: rad ...),
// for signals whose component declares none; "" when the name is not a known one.
std::string guess_unit(const std::string& column);

}  // namespace stiction::core
