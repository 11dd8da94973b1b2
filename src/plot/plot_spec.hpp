// Scene-driven plots: the top-level [[plots]] array of a scene file, turned into figures of
// a run's trajectory; the paper's figures as default specs; comparison figures over runs.
//
// A scene lists its plots like this (every key but `signals` is optional):
//
//   [[plots]]
//   name = "fig4"                      # file stem: plots/fig4.png (default "plot<N>")
//   title = "Simulation I: ..."       # default: none
//   size = [1600, 1000]               # pixels, each 200..16384 (default 1600x1000)
//   time = [0.0, 1.5]                 # time range (default: the whole run)
//   events = true                     # mark the run's events (default true); or a list of
//                                     # event names to mark, e.g. ["ground.stick_time"]
//     [[plots.panels]]
//     signals = ["sphere.v.x", "ground.slip.x"]   # trajectory columns
//     legend = ["centre", "contact point"]        # default: the signal names
//     colors = ["#0072b2", "#d55e00"]             # "#rrggbb" per signal (default: palette)
//     label = "Horizontal velocity"               # vertical axis label
//     unit = "m/s"                                # printed as "label [unit]"
//     log = false                                 # logarithmic vertical axis
//     relative_to = 5.0   # optional: plot s(t) - s(relative_to) for t >= relative_to
//     references = [{ value = 0.5, label = "static friction F" }]   # horizontal lines
//
// A signal that is not a column of the run is an InputError "FILE:LINE:COL: error: ..."
// naming the signal and listing the columns that exist (exit code 2 in the app).
#pragma once

#include <toml++/toml.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/trajectory.hpp"
#include "plot/figure.hpp"

namespace stiction::plot {

struct PanelSpec {
  std::vector<std::string> signals;
  std::vector<std::string> legend;  // empty, or one entry per signal
  std::vector<image::Rgba> colors;  // empty, or one entry per signal (dashes stay the palette's)
  std::string label;
  std::string unit;
  bool log = false;
  std::optional<double> relative_to;
  std::vector<ReferenceLine> references;
};

struct PlotSpec {
  std::string name;
  std::string title;
  std::vector<PanelSpec> panels;
  int width = 1600;
  int height = 1000;
  std::optional<double> t_min, t_max;
  bool mark_events = true;
  std::vector<std::string> only_events;  // empty: every event given to write_plot
};

// Reads the document's [[plots]] (none: an empty vector). `file` is used in messages when the
// document carries no source path. Every signal must be one of `columns`. Throws
// scene::InputError on any bad key, value or signal; unknown keys are errors too.
std::vector<PlotSpec> read_plot_specs(const toml::table& document, const std::string& file,
                                      const std::vector<std::string>& columns);

// Checks a spec built in code against a run's columns; scene::InputError naming the plot,
// the signal and the existing columns.
void check_signals(const PlotSpec& spec, const std::vector<std::string>& columns);

// The paper's figures (see docs/plots.md):
//   Fig. 4 (Simulation I, sphere_roll): horizontal velocity of the centre `sphere.v.x` and of
//   the contact point `ground.slip.x` in one panel, height of the centre `sphere.p.z` below;
//   the run's events (the stick time) marked.
//   Fig. 7 (Simulation II, two_link): joint angles `arm.theta.0/1`, applied motor torques
//   `motor0.tau`, `motor1.tau`.
//   LuGre comparison (two_link vs two_link_lugre): both joint angles of every run and their
//   change after the arm has stopped (relative to t = 5 s), where LuGre's drift shows.
PlotSpec paper_fig4_spec();
PlotSpec paper_fig7_spec();
PlotSpec drift_comparison_spec();

// The figures to draw for a run whose scene lists no [[plots]]: the paper figures whose
// signals all exist among `columns` (Fig. 4 for sphere_roll, Fig. 7 for two_link and its
// penalty variant), else one figure with a panel per signal group (up to 6 groups).
std::vector<PlotSpec> default_plot_specs(const std::vector<std::string>& columns);

// "ground.stick_time" at 0.5831 -> "ground stick: t = 0.583 s".
std::string event_label(const std::string& name, double time);

// The figure of one run. Events (name -> time in s) are marked as the spec says.
Figure make_figure(const PlotSpec& spec, const core::Trajectory& trajectory,
                   const std::map<std::string, double>& event_times);
// make_figure, rendered with the bundled font and written atomically as PNG. Throws
// scene::InputError for a missing signal, text::FontError / image::ImageError on I/O.
void write_plot(const PlotSpec& spec, const core::Trajectory& trajectory,
                const std::map<std::string, double>& event_times, const std::filesystem::path& png);

// Several runs in one figure: each panel shows its signals for every run, labelled by run
// name ("two_link", "two_link_lugre"); a run's colour is the same in every panel; a spec
// without a title gets "RUN vs RUN ...". Events are not marked. Every
// signal must exist in every run (scene::InputError otherwise, naming the run).
struct Run {
  std::string name;
  const core::Trajectory* trajectory = nullptr;
};
Figure make_comparison_figure(const PlotSpec& spec, const std::vector<Run>& runs);
void write_comparison_plot(const PlotSpec& spec, const std::vector<Run>& runs,
                           const std::filesystem::path& png);
// The comparison to draw for `stiction compare`: drift_comparison_spec() when every run has
// the arm's joint angles, else the first default spec of the columns common to all runs.
PlotSpec default_comparison_spec(const std::vector<Run>& runs);

}  // namespace stiction::plot
