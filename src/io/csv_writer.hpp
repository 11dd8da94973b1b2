// trajectory.csv (DESIGN section 4): a header row of column names, then one row per sample.
// Numbers are written as the shortest text that reads back to the same double
// (std::to_chars), so the file is exact and compact; whole numbers get ".0" so that every
// column reads as floats; non-finite values read nan / inf.
#pragma once

#include <filesystem>
#include <string>

#include "core/trajectory.hpp"

namespace stiction::io {

// Appends the shortest round-trip representation of v, always as a float: 0 -> "0.0",
// 12 -> "12.0", 1e+20 stays "1e+20".
void append_number(std::string& out, double v);

std::string to_csv(const core::Trajectory& trajectory);
// Written atomically; IoError on failure.
void write_csv(const core::Trajectory& trajectory, const std::filesystem::path& path);

}  // namespace stiction::io
