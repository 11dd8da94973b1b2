// The figures of a run (DESIGN section 4, plots/): every spec drawn in its format, the run's
// stick and slip events marked, the files written listed for the run to print.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "core/simulation.hpp"
#include "plot/plot_spec.hpp"

namespace stiction::services {

// Every event of every element with a slip speed (stick, slip and the lift-offs that make
// the next event a touch-down), for plot::make_figure.
std::vector<plot::PlotEvent> plot_events(const core::RunResult& result);

// A run's figure as `run` draws it: the spec over `rows` (the run's rows as run thins them
// for its figures: StreamedRows::for_plots, or run_outputs.hpp's plot_rows of all of them)
// with the result's events (plot_events). `run` writes it, `verify` compares it: one figure.
plot::Figure run_figure(const plot::PlotSpec& spec, const core::RunResult& result,
                        const core::Trajectory& rows);

// Writes every spec into `dir`, drawing `rows` (the run's rows, possibly thinned) and
// marking the result's events (plot::plot_path: its own format, or `format` when given, i.e.
// --plot-format); returns the files written, in spec order. Stops between two plots on an
// interrupt (sys::interrupted()).
std::vector<std::filesystem::path> write_run_plots(const std::vector<plot::PlotSpec>& specs,
                                                   const core::RunResult& result,
                                                   const core::Trajectory& rows,
                                                   const std::filesystem::path& dir,
                                                   std::optional<plot::Format> format);

}  // namespace stiction::services
