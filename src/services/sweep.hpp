// `stiction sweep` (docs/sweeps.md): one run of a scene per point of a grid of --set values,
// in one process on several threads; sweep.csv, .md, .png, .svg; shards and their merge.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "plot/figure.hpp"
#include "services/sweep_plan.hpp"
#include "services/sweep_table.hpp"

namespace stiction::services {

// What a sweep directory records so that shards can be checked and merged: the scene, the
// keys, every point's values, the table's columns and the records to plot. Every shard
// writes the same sweep.plan.json; one that differs means two sweeps share a directory.
struct SweepPlan {
  std::string scene;
  std::vector<VaryKey> keys;
  bool zip = false;
  std::vector<SweepPoint> points;
  std::vector<std::string> columns;
  std::vector<std::string> plot;  // columns plotted against the first key
  // What else makes its points what they are: the scene's document after --set (a hash),
  // --dt, --duration, --integrator, --tolerance. A sweep that differs here is another sweep.
  std::vector<std::string> settings;
  std::string to_json() const;
  static SweepPlan from_json(const std::string& text, const std::filesystem::path& origin);
};

// sweep.md's text: the table as Markdown, parameters as given, measured records with
// text::kEventTimeDigits significant digits (sweep.csv keeps every digit).
std::string sweep_markdown(const SweepPlan& plan, const SweepTable& table);
// sweep.png's figure: the plotted records against the first key, a line per combination of
// the other keys' values in their numeric order; one journal column (Figure::print).
plot::Figure sweep_figure(const SweepPlan& plan, const SweepTable& table);

// sweep.md, sweep.png and sweep.svg (the same figure as vectors) of a full table. The figure
// shows the plan's columns that some finished point has a value of (at most four), else the
// first record; false (and no figure left in `dir`) when there is nothing to plot.
bool write_sweep_report(const SweepPlan& plan, const SweepTable& table,
                        const std::filesystem::path& dir);

}  // namespace stiction::services
