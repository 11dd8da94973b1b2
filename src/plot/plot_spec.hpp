// Scene-driven plots: the top-level [[plots]] array of a scene file, turned into figures of
// a run's trajectory; the paper's figures as default specs; comparison figures over runs.
//
// A scene lists its plots like this (every key but `signals` is optional):
//
//   [[plots]]
//   name = "fig4"                      # file stem: plots/fig4.png (default "plot<N>"); with an
//                                     # extension (.png, .svg, .pdf) it also picks the format
//   format = "pdf"                     # png (default), svg or pdf; --plot-format overrides it
//   width = "88 mm"                    # print width: "88 mm", "3.5 in", "8.8 cm" or a number
//                                     # of mm (default 88 mm, a one-column journal figure)
//   height = "70 mm"                  # default: by panel count (default_height_mm)
//   font_size = 8                      # text size in pt (default 8)
//   dpi = 300                          # pixels per inch of a PNG (default 300)
//   title = "Simulation I: ..."       # default: none
//   size = [1600, 1000]               # legacy: pixels, each 200..16384, text scaling with them
//                                     # (excludes width, height and font_size)
//   time = [0.0, 1.5]                 # time range (default: the whole run)
//   events = true                     # mark the run's events (default true); or a list of
//                                     # event selectors (plot/event_selection.hpp): "ground",
//                                     # "ground.stick", "ground.first_stick", "box.tip", ...
//   labels = "important"              # which marked events are labelled: "important"
//                                     # (default), "all", "none" or a list of selectors
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

#include "core/column_info.hpp"
#include "core/trajectory.hpp"
#include "plot/event_selection.hpp"
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
  std::string caption;  // drawn above the panel (the default figures: group and description)
  // Leave out the signals that are exactly zero over the whole run (the default figures: a
  // sphere rolling along x has v.y = v.z = 0), naming them in the caption. A panel whose
  // signals are all zero keeps them.
  bool omit_zero_signals = false;
};

// Which marked events a figure labels (the rest are unlabelled ticks).
struct EventLabels {
  enum class Mode { important, all, none, listed };
  Mode mode = Mode::important;
  std::vector<std::string> selectors;  // Mode::listed
};

// The size of a figure as printed (Figure::Print): a one-column journal figure by default.
struct PrintSize {
  double width_mm = 88.0;
  std::optional<double> height_mm;  // default: default_height_mm(panel count)
  double font_pt = 8.0;
};
// A height that suits `panels` panels stacked in a figure 88 mm wide: 28 mm for the title,
// the event labels and the time axis, plus 26 mm per panel (54 mm for one, 80 for two, 132
// for four), at most 230 mm (a journal page).
double default_height_mm(std::size_t panels);

struct PlotSpec {
  std::string name;              // file stem, without extension
  std::optional<Format> format;  // from the name's extension or `format`; default PNG
  double dpi = 300.0;
  std::string title;
  std::vector<PanelSpec> panels;
  // The size on paper; nullopt for the legacy `size` key (pixels, text scaling with them).
  std::optional<PrintSize> print = PrintSize{};
  int width = 1600;  // pixels of a figure without `print`
  int height = 1000;
  std::optional<double> t_min, t_max;
  bool mark_events = true;
  std::vector<std::string> only_events;  // selectors; empty: every event given to write_plot
  EventLabels labels;
};

// Reads the document's [[plots]] (none: an empty vector). `file` is used in messages when the
// document carries no source path. Every signal must be one of `columns`. Throws
// scene::InputError on any bad key, value or signal; unknown keys are errors too.
std::vector<PlotSpec> read_plot_specs(const toml::table& document, const std::string& file,
                                      const std::vector<std::string>& columns);

// The same, against the run's column descriptions, and with what a panel leaves out filled in
// from them: no `unit`, the unit its signals share (none when they differ); no `label`, the
// signal's name for one signal, else their names when short (the legend tells them apart).
std::vector<PlotSpec> read_plot_specs(const toml::table& document, const std::string& file,
                                      const std::vector<core::ColumnInfo>& columns);

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
// penalty variant), then figures with a panel per signal group ("<component>.<signal>",
// labelled with its unit) that together show EVERY signal: "signals" when one figure holds
// them all, else "signals_1", "signals_2", ... of at most kPanelsPerFigure panels each, and
// at most kMaxDefaultFigures of them: the groups beyond, in column order, are not drawn and
// their names ("ball.v", "pair_3.f") are appended to `not_drawn` when given.
inline constexpr int kPanelsPerFigure = 4;
inline constexpr int kMaxDefaultFigures = 12;
std::vector<PlotSpec> default_plot_specs(const std::vector<core::ColumnInfo>& columns,
                                         std::vector<std::string>* not_drawn = nullptr);
// The same with units guessed from the signal names (core::guess_unit).
std::vector<PlotSpec> default_plot_specs(const std::vector<std::string>& columns,
                                         std::vector<std::string>* not_drawn = nullptr);

// The figure of one run, its events marked and labelled as the spec says (`only_events`,
// `labels`; plot/event_selection.hpp): each marker's `labelled` set, its label "stick
// 0.5843 s", with the element's name in front when the figure marks events of several
// elements ("joint1_friction stop 4.651 s"). The print size and dpi go to Figure::print.
Figure make_figure(const PlotSpec& spec, const core::Trajectory& trajectory,
                   const std::vector<PlotEvent>& events);
// Events by name -> time, "<element>.<kind>_time" ("ground.stick_time" is a stick).
// Without the run's lift-offs, no event of these is known to be a touch-down.
Figure make_figure(const PlotSpec& spec, const core::Trajectory& trajectory,
                   const std::map<std::string, double>& event_times);
// make_figure, written atomically in `format` (PNG when the spec and the caller name none).
// Throws scene::InputError for a missing signal, text::FontError / image::ImageError /
// io::IoError on I/O. Returns the layout drawn.
FigureLayout write_plot(const PlotSpec& spec, const core::Trajectory& trajectory,
                        const std::vector<PlotEvent>& events, const std::filesystem::path& path,
                        Format format);
void write_plot(const PlotSpec& spec, const core::Trajectory& trajectory,
                const std::map<std::string, double>& event_times, const std::filesystem::path& png);
// The file a spec is written to in `dir`: name + extension of its format (`override` first).
std::filesystem::path plot_path(const PlotSpec& spec, const std::filesystem::path& dir,
                                std::optional<Format> override = std::nullopt);

// Several runs in one figure: each panel shows its signals for every run, labelled by run
// name ("two_link", "two_link_lugre"); a run's colour is the same in every panel, and a
// legend of run names alone is drawn once (at the first such panel); a spec without a title gets
// "RUN vs RUN ...". Events are not marked. Every signal must exist in every run (scene::InputError
// otherwise, naming the run).
struct Run {
  std::string name;
  const core::Trajectory* trajectory = nullptr;
};
Figure make_comparison_figure(const PlotSpec& spec, const std::vector<Run>& runs);
void write_comparison_plot(const PlotSpec& spec, const std::vector<Run>& runs,
                           const std::filesystem::path& png);
FigureLayout write_comparison_plot(const PlotSpec& spec, const std::vector<Run>& runs,
                                   const std::filesystem::path& path, Format format);
// A comparison of more than two runs is a two-column figure, 180 mm wide.
// The comparison to draw for `stiction compare` without --signals: drift_comparison_spec()
// when every run has the arm's joint angles; else the signals common to all runs that differ
// most between them (the largest gap of a run from the first, relative to the signal's range
// over the runs): the one that differs most and those within kCompareShare of it, at most
// kCompareSignals, each in a panel of its own as comparison_spec draws a column given alone
// (so the legend is the runs' names, shown once); runs that agree everywhere: the first
// default figure of their common columns.
inline constexpr std::size_t kCompareSignals = 3;
inline constexpr std::size_t kComparePanels = kCompareSignals;
inline constexpr double kCompareShare = 0.25;
PlotSpec default_comparison_spec(const std::vector<Run>& runs);
// A comparison of chosen signals: one panel per signal group among `signals` (each a column
// of every run, or a group "<component>.<signal>" meaning all its axes), units from
// `columns` (guessed from the names where missing). scene::InputError for an unknown signal.
PlotSpec comparison_spec(const std::vector<Run>& runs, const std::vector<std::string>& signals,
                         const std::vector<core::ColumnInfo>& columns = {});

}  // namespace stiction::plot
