// `stiction compare` as functions: runs labelled by their scene name plus the overrides that
// tell them apart, --signals checked against the scenes' columns before anything runs, and
// the overlay of finished runs, OUT/compare.png (the arm scenes get the drift comparison;
// other runs a figure of the signals they have in common, or of the ones asked for). The
// command line loads, guards and simulates the scenes and prints; the Python module runs
// them with stiction.run.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/column_info.hpp"
#include "core/trajectory.hpp"
#include "plot/figure.hpp"

namespace stiction::services {

// Scene name plus the overrides (each run's own, "KEY=VALUE") not shared by every run;
// "(run N)" when two runs would still read the same.
std::vector<std::string> comparison_labels(const std::vector<std::string>& names,
                                           const std::vector<std::vector<std::string>>& overrides);

// scene::InputError (exit 2) for a signal of `signals` that some run does not have; each run
// is given by its label and its trajectory's columns after "t".
void check_comparison_signals(const std::vector<std::string>& labels,
                              const std::vector<std::vector<std::string>>& signal_columns,
                              const std::vector<std::string>& signals);

// One finished run to overlay.
struct ComparedRun {
  std::string label;
  const core::Trajectory* trajectory = nullptr;
  std::vector<core::ColumnInfo> columns;  // its scene's columns (units of the panels)
};

// Creates `out` (and its parents); io::IoError when it cannot.
void make_comparison_directory(const std::filesystem::path& out);

// Writes the comparison figure of `runs` into `out` (compare.png, or .svg/.pdf by `format`)
// and returns its path. `signals` empty: the default comparison.
std::filesystem::path write_comparison(const std::vector<ComparedRun>& runs,
                                       const std::vector<std::string>& signals,
                                       const std::filesystem::path& out, plot::Format format);

}  // namespace stiction::services
