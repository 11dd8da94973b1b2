#include "plot/plot_spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <sstream>

#include "image/png.hpp"
#include "scene/toml_reader.hpp"
#include "text/font.hpp"
#include "text/number_text.hpp"

namespace stiction::plot {
namespace {

using scene::InputError;

std::string join(const std::vector<std::string>& items, std::size_t limit = 60) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < limit; ++i) out += (i ? ", " : "") + items[i];
  if (items.size() > limit) out += ", ... (" + std::to_string(items.size()) + " in all)";
  return out;
}

std::vector<std::string> signal_columns(const std::vector<std::string>& columns) {
  std::vector<std::string> out;
  for (const std::string& c : columns) {
    if (c != "t") out.push_back(c);
  }
  return out;
}

// A user's panel without a label or a unit gets them from the columns it shows.
void complete_axis(PanelSpec& panel, const std::vector<core::ColumnInfo>& columns) {
  const auto unit_of = [&](const std::string& name) {
    const auto it = std::find_if(columns.begin(), columns.end(),
                                 [&](const core::ColumnInfo& c) { return c.name == name; });
    const std::string declared = it != columns.end() ? it->unit : std::string();
    return declared.empty() ? core::guess_unit(name) : declared;
  };
  if (panel.unit.empty()) {
    std::set<std::string> units;
    for (const std::string& s : panel.signals) units.insert(unit_of(s));
    if (units.size() == 1) panel.unit = *units.begin();
  }
  if (panel.label.empty()) {
    constexpr std::size_t kLongest = 40;  // longer lists wrap the axis label into a column
    const std::string names = join(panel.signals);
    if (panel.signals.size() == 1 || names.size() <= kLongest) panel.label = names;
  }
}

std::string unknown_signal_message(const std::string& where, const std::string& signal,
                                   const std::vector<std::string>& columns) {
  return where + ": unknown signal '" + signal + "'; the run has: " + join(signal_columns(columns));
}

InputError error_at(const toml::node& node, const std::string& file, const std::string& message) {
  if (node.source().path) return InputError::at(node.source(), message);
  std::ostringstream out;
  out << (file.empty() ? std::string("-") : file) << ':' << node.source().begin.line << ':'
      << node.source().begin.column << ": error: " << message;
  return InputError(out.str());
}

bool has_column(const std::vector<std::string>& columns, const std::string& name) {
  return std::find(columns.begin(), columns.end(), name) != columns.end();
}

PanelSpec read_panel(scene::TableReader& table, const std::string& file,
                     const std::vector<std::string>& columns) {
  PanelSpec panel;
  const toml::node* signals = table.node("signals");
  if (!signals) table.fail("signals", "missing (an array of signal names is required)");
  panel.signals = table.strings("signals");
  if (panel.signals.empty()) table.fail("signals", "must name at least one signal");
  const toml::array& array = *signals->as_array();
  for (std::size_t i = 0; i < panel.signals.size(); ++i) {
    if (!has_column(columns, panel.signals[i])) {
      throw error_at(array[i], file,
                     unknown_signal_message(table.path() + ".signals", panel.signals[i], columns));
    }
  }
  panel.legend = table.strings("legend");
  if (!panel.legend.empty() && panel.legend.size() != panel.signals.size()) {
    table.fail("legend", "needs one entry per signal (" + std::to_string(panel.signals.size()) +
                             "), got " + std::to_string(panel.legend.size()));
  }
  for (const std::string& c : table.strings("colors")) {
    if (c.size() != 7 || c[0] != '#' ||
        c.find_first_not_of("0123456789abcdefABCDEF", 1) != std::string::npos) {
      table.fail("colors", "expected \"#rrggbb\" colours, got \"" + c + "\"");
    }
    const auto channel = [&](int at) {
      return static_cast<std::uint8_t>(
          std::stoi(c.substr(static_cast<std::size_t>(at), 2), nullptr, 16));
    };
    panel.colors.push_back({channel(1), channel(3), channel(5), 255});
  }
  if (!panel.colors.empty() && panel.colors.size() != panel.signals.size()) {
    table.fail("colors", "needs one entry per signal (" + std::to_string(panel.signals.size()) +
                             "), got " + std::to_string(panel.colors.size()));
  }
  panel.label = table.string("label", "");
  panel.unit = table.string("unit", "");
  panel.log = table.boolean("log", false);
  if (table.has("relative_to")) panel.relative_to = table.non_negative("relative_to", 0.0);
  for (scene::TableReader& reference : table.array_of_tables("references")) {
    panel.references.push_back({reference.required_number("value"), reference.string("label", "")});
    reference.finish();
  }
  table.finish();
  return panel;
}

// The components of a run ("ground" of "ground.slip.x"): what an event selector may name.
std::vector<std::string> components_of(const std::vector<std::string>& columns) {
  std::vector<std::string> out;
  for (const std::string& c : signal_columns(columns)) {
    const std::string component = c.substr(0, c.find('.'));
    if (!has_column(out, component)) out.push_back(component);
  }
  return out;
}

// Whether an event selector's element is a component ("floor", a body "box") or one contact
// point of a component with several ("floor.0": its columns are "floor.0.f.x", ...).
bool names_an_element(const std::string& element, const std::vector<std::string>& components,
                      const std::vector<std::string>& columns) {
  if (has_column(components, element)) return true;
  const std::size_t dot = element.find('.');
  if (dot == std::string::npos || !has_column(components, element.substr(0, dot))) return false;
  const std::string index = element.substr(dot + 1);
  if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos) return false;
  return std::any_of(columns.begin(), columns.end(),
                     [&](const std::string& c) { return c.rfind(element + ".", 0) == 0; });
}

// A list of event selectors (`events` or `labels`), each checked: a known event word after
// the element, and an element that is a component of the run.
std::vector<std::string> read_selectors(scene::TableReader& table, const std::string& key,
                                        const std::string& file,
                                        const std::vector<std::string>& columns) {
  const std::vector<std::string> selectors = table.strings(key);
  const toml::array& array = *table.node(key)->as_array();
  const std::vector<std::string> components = components_of(columns);
  for (std::size_t i = 0; i < selectors.size(); ++i) {
    const std::string where = table.path() + "." + key + "[" + std::to_string(i) + "]: ";
    std::string why;
    const std::optional<EventSelector> selector = parse_event_selector(selectors[i], why);
    if (!selector) throw error_at(array[i], file, where + why);
    if (!names_an_element(selector->element, components, columns)) {
      throw error_at(array[i], file,
                     where + "'" + selector->element +
                         "' is not a component of the run (or one of its contact points, "
                         "NAME.0, NAME.1, ...); it has: " +
                         join(components));
    }
  }
  return selectors;
}

// A length on paper: a number of millimetres, or a string "88 mm", "8.8 cm", "3.5 in".
double read_length_mm(scene::TableReader& table, const std::string& key) {
  const toml::node* node = table.node(key);
  const std::string expected =
      "expected a length such as \"88 mm\", \"8.8 cm\", \"3.5 in\" or a "
      "number of millimetres";
  double mm = 0.0;
  if (node->is_number()) {
    mm = scene::finite_number(*node, table.path() + "." + key);
  } else if (node->is_string()) {
    const std::string text = node->as_string()->get();
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(text, &used);
    } catch (const std::exception&) {
      table.fail(key, expected + ", got \"" + text + "\"");
    }
    std::string unit = text.substr(used);
    unit.erase(0, unit.find_first_not_of(' '));
    if (unit == "mm") {
      mm = value;
    } else if (unit == "cm") {
      mm = 10.0 * value;
    } else if (unit == "in") {
      mm = 25.4 * value;
    } else {
      table.fail(key, expected + " (unit mm, cm or in), got \"" + text + "\"");
    }
  } else {
    table.fail(key, expected);
  }
  if (!(mm >= 20.0 && mm <= 1000.0)) {
    table.fail(key, "expected 20 mm .. 1000 mm, got " + text::shortest(mm) + " mm");
  }
  return mm;
}

// `font_size`: points, a number or a string "8 pt".
double read_font_pt(scene::TableReader& table) {
  const toml::node* node = table.node("font_size");
  double pt = 0.0;
  if (node->is_number()) {
    pt = scene::finite_number(*node, table.path() + ".font_size");
  } else if (node->is_string()) {
    const std::string text = node->as_string()->get();
    std::size_t used = 0;
    try {
      pt = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    std::string unit = text.substr(used);
    unit.erase(0, unit.find_first_not_of(' '));
    if (used == 0 || unit != "pt") {
      table.fail("font_size", "expected a size in points: 8 or \"8 pt\", got \"" + text + "\"");
    }
  } else {
    table.fail("font_size", "expected a size in points: 8 or \"8 pt\"");
  }
  if (!(pt >= 4.0 && pt <= 72.0)) {
    table.fail("font_size", "expected 4 .. 72 pt, got " + text::shortest(pt) + " pt");
  }
  return pt;
}

PlotSpec read_plot(scene::TableReader& table, std::size_t index, const std::string& file,
                   const std::vector<std::string>& columns) {
  PlotSpec spec;
  spec.name = table.string("name", "plot" + std::to_string(index + 1));
  if (spec.name.empty() ||
      spec.name.find_first_not_of(
          "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") !=
          std::string::npos ||
      spec.name.front() == '.') {
    table.fail("name", "must be a file name of letters, digits, '_', '-' and '.'");
  }
  // "fig.svg": the extension picks the format (and is not part of the stem).
  for (Format f : {Format::png, Format::svg, Format::pdf}) {
    const std::string ext = extension(f);
    if (spec.name.size() > ext.size() &&
        parse_format(spec.name.substr(spec.name.size() - 3)) == f &&
        spec.name[spec.name.size() - 4] == '.') {
      spec.name.resize(spec.name.size() - ext.size());
      spec.format = f;
    }
  }
  if (table.has("format")) {
    const std::string name = table.string("format", "png");
    const std::optional<Format> f = parse_format(name);
    if (!f) table.fail("format", "expected \"png\", \"svg\" or \"pdf\", got \"" + name + "\"");
    if (spec.format && *spec.format != *f) {
      table.fail("format", "\"" + name + "\" contradicts the extension of name");
    }
    spec.format = f;
  }
  if (table.has("dpi")) {
    spec.dpi = table.positive("dpi", spec.dpi);
    if (spec.dpi < 10.0 || spec.dpi > 10000.0) table.fail("dpi", "expected 10 .. 10000");
  }
  spec.title = table.string("title", "");
  if (table.has("size")) {
    for (const char* key : {"width", "height", "font_size"}) {
      if (table.has(key)) {
        table.fail("size", std::string("size (pixels, text scaling with them) excludes ") + key +
                               " (a print size): give one or the other");
      }
    }
    spec.print.reset();
    const std::vector<double> size = table.numbers("size");
    if (size.size() != 2 || size[0] != std::floor(size[0]) || size[1] != std::floor(size[1]) ||
        size[0] < 200 || size[1] < 150 || size[0] > 16384 || size[1] > 16384) {
      table.fail("size",
                 "expected [width, height] in whole pixels, at least [200, 150] and at "
                 "most [16384, 16384]");
    }
    spec.width = static_cast<int>(size[0]);
    spec.height = static_cast<int>(size[1]);
  }
  if (table.has("width")) spec.print->width_mm = read_length_mm(table, "width");
  if (table.has("height")) spec.print->height_mm = read_length_mm(table, "height");
  if (table.has("font_size")) spec.print->font_pt = read_font_pt(table);
  if (table.has("time")) {
    const std::vector<double> time = table.numbers("time");
    if (time.size() != 2 || !(time[1] > time[0])) {
      table.fail("time", "expected [start, end] in seconds with end > start");
    }
    spec.t_min = time[0];
    spec.t_max = time[1];
  }
  if (const toml::node* events = table.node("events")) {
    if (events->is_boolean()) {
      spec.mark_events = events->as_boolean()->get();
    } else if (events->is_array()) {
      spec.only_events = read_selectors(table, "events", file, columns);
      spec.mark_events = !spec.only_events.empty();
    } else {
      table.fail("events", "expected true, false or a list of event selectors");
    }
  }
  if (const toml::node* labels = table.node("labels")) {
    const std::string expected =
        "expected \"important\", \"all\", \"none\" or a list of event selectors";
    if (labels->is_string()) {
      const std::string mode = labels->as_string()->get();
      if (mode == "important") {
        spec.labels.mode = EventLabels::Mode::important;
      } else if (mode == "all") {
        spec.labels.mode = EventLabels::Mode::all;
      } else if (mode == "none") {
        spec.labels.mode = EventLabels::Mode::none;
      } else {
        table.fail("labels", expected + ", got \"" + mode + "\"");
      }
    } else if (labels->is_array()) {
      spec.labels.mode = EventLabels::Mode::listed;
      spec.labels.selectors = read_selectors(table, "labels", file, columns);
    } else {
      table.fail("labels", expected);
    }
  }
  for (scene::TableReader& panel : table.array_of_tables("panels")) {
    spec.panels.push_back(read_panel(panel, file, columns));
  }
  if (spec.panels.empty()) table.fail("panels", "missing (at least one [[plots.panels]] table)");
  if (spec.print) {
    // The pixels the drawing needs: 200 x 150 .. 16384 x 16384 (plot::draw).
    const double w = spec.print->width_mm / 25.4 * spec.dpi;
    const double h =
        spec.print->height_mm.value_or(default_height_mm(spec.panels.size())) / 25.4 * spec.dpi;
    if (w < 200.0 || h < 150.0 || w > 16384.0 || h > 16384.0) {
      const std::string key = table.has("dpi") ? "dpi" : table.has("width") ? "width" : "height";
      table.fail(key, "the figure would be " + text::significant(w, 4) + " x " +
                          text::significant(h, 4) + " pixels at " + text::shortest(spec.dpi) +
                          " dpi; a figure has 200 x 150 to 16384 x 16384 (change dpi or the size)");
    }
  }
  table.finish();
  return spec;
}

std::string signal_label(const std::string& column) { return column; }

// Values of one signal against time over the spec's time window; `relative_to` subtracts the
// value at that time (linear interpolation) and drops the samples before it.
void signal_series(const core::Trajectory& trajectory, int column, const PanelSpec& panel,
                   std::vector<double>& x, std::vector<double>& y) {
  const int rows = trajectory.row_count();
  x.clear();
  y.clear();
  double reference = 0.0;
  if (panel.relative_to) {
    reference = std::numeric_limits<double>::quiet_NaN();
    for (int r = 0; r < rows; ++r) {
      const double t = trajectory.at(r, 0);
      if (t >= *panel.relative_to) {
        if (r == 0 || t == *panel.relative_to) {
          reference = trajectory.at(r, column);
        } else {
          const double t0 = trajectory.at(r - 1, 0);
          const double a = (*panel.relative_to - t0) / (t - t0);
          reference = (1 - a) * trajectory.at(r - 1, column) + a * trajectory.at(r, column);
        }
        break;
      }
    }
  }
  for (int r = 0; r < rows; ++r) {
    const double t = trajectory.at(r, 0);
    if (panel.relative_to && t < *panel.relative_to) continue;
    x.push_back(t);
    y.push_back(trajectory.at(r, column) - reference);
  }
}

std::vector<const PanelSpec*> panels_of(const PlotSpec& spec) {
  std::vector<const PanelSpec*> out;
  for (const PanelSpec& p : spec.panels) out.push_back(&p);
  return out;
}

Figure figure_frame(const PlotSpec& spec) {
  Figure figure;
  figure.title = spec.title;
  figure.width = spec.width;
  figure.height = spec.height;
  figure.x_min = spec.t_min;
  figure.x_max = spec.t_max;
  if (spec.print) {
    figure.print = Figure::Print{
        spec.print->width_mm, spec.print->height_mm.value_or(default_height_mm(spec.panels.size())),
        spec.print->font_pt, spec.dpi};
  }
  return figure;
}

// Whether a column is exactly zero in every row (a component of motion the scene never has).
bool all_zero(const core::Trajectory& trajectory, int column) {
  for (int r = 0; r < trajectory.row_count(); ++r) {
    if (trajectory.at(r, column) != 0.0) return false;
  }
  return true;
}

// The signals of a panel to draw: all of them, or, for a panel that omits zero signals, those
// not zero in every one of `runs` (all of them when every one is zero). The names left out
// are added to the caption: "sphere.v: velocity (v.y = v.z = 0, not drawn)".
std::vector<std::size_t> drawn_signals(const PanelSpec& spec,
                                       const std::vector<const core::Trajectory*>& runs,
                                       Panel& panel) {
  std::string& caption = panel.caption;
  std::vector<std::size_t> drawn, zero;
  for (std::size_t i = 0; i < spec.signals.size(); ++i) {
    const bool is_zero =
        spec.omit_zero_signals && std::all_of(runs.begin(), runs.end(), [&](const auto* run) {
          return all_zero(*run, *run->find(spec.signals[i]));
        });
    (is_zero ? zero : drawn).push_back(i);
  }
  caption = spec.caption;
  if (drawn.empty()) {
    drawn.swap(zero);
  } else if (!zero.empty()) {
    std::string names;
    // Named without the component the caption begins with ("v.y", "e.1"): an axis name
    // alone reads as a value ("1 = 0").
    for (std::size_t i : zero) {
      const std::string& signal = spec.signals[i];
      names += signal.substr(signal.find('.') + 1) + " = ";
    }
    caption += (caption.empty() ? "" : " ") + std::string("(") + names + "0, not drawn)";
    // One axis left: the axis label names it ("v.x"), as no legend will.
    if (drawn.size() == 1 && !spec.legend.empty()) panel.label += "." + spec.legend[drawn[0]];
  }
  return drawn;
}

Panel panel_frame(const PanelSpec& spec) {
  Panel panel;
  panel.references = spec.references;
  panel.label = spec.label;
  panel.unit = spec.unit;
  panel.log = spec.log;
  panel.caption = spec.caption;
  return panel;
}

// Restricts x (time) to the figure's window, keeping one sample beyond each end so the line
// reaches the frame.
void clip_to_window(const Figure& figure, Series& series) {
  if (!figure.x_min && !figure.x_max) return;
  const double lo = figure.x_min.value_or(-std::numeric_limits<double>::infinity());
  const double hi = figure.x_max.value_or(std::numeric_limits<double>::infinity());
  std::vector<double> x, y;
  for (std::size_t i = 0; i < series.x.size(); ++i) {
    const bool next_in = i + 1 < series.x.size() && series.x[i + 1] >= lo;
    const bool prev_in = i > 0 && series.x[i - 1] <= hi;
    if ((series.x[i] >= lo || next_in) && (series.x[i] <= hi || prev_in)) {
      x.push_back(series.x[i]);
      y.push_back(series.y[i]);
    }
  }
  series.x = std::move(x);
  series.y = std::move(y);
}

}  // namespace

void check_signals(const PlotSpec& spec, const std::vector<std::string>& columns) {
  for (std::size_t p = 0; p < spec.panels.size(); ++p) {
    for (const std::string& s : spec.panels[p].signals) {
      if (!has_column(columns, s)) {
        throw InputError(unknown_signal_message(
            "plot '" + spec.name + "' panel " + std::to_string(p + 1), s, columns));
      }
    }
  }
}

std::vector<PlotSpec> read_plot_specs(const toml::table& document, const std::string& file,
                                      const std::vector<std::string>& columns) {
  std::vector<PlotSpec> specs;
  scene::TableReader root(document, "");
  std::vector<scene::TableReader> plots = root.array_of_tables("plots");
  std::set<std::string> names;
  for (std::size_t i = 0; i < plots.size(); ++i) {
    specs.push_back(read_plot(plots[i], i, file, columns));
    if (!names.insert(specs.back().name).second) {
      plots[i].fail("name", "a plot named '" + specs.back().name + "' exists already");
    }
  }
  return specs;
}

std::vector<PlotSpec> read_plot_specs(const toml::table& document, const std::string& file,
                                      const std::vector<core::ColumnInfo>& columns) {
  std::vector<std::string> names;
  for (const core::ColumnInfo& c : columns) names.push_back(c.name);
  std::vector<PlotSpec> specs = read_plot_specs(document, file, names);
  for (PlotSpec& spec : specs) {
    for (PanelSpec& panel : spec.panels) complete_axis(panel, columns);
  }
  return specs;
}

namespace {

PanelSpec panel_spec(std::vector<std::string> signals, std::vector<std::string> legend,
                     std::string label, std::string unit) {
  PanelSpec panel;
  panel.signals = std::move(signals);
  panel.legend = std::move(legend);
  panel.label = std::move(label);
  panel.unit = std::move(unit);
  return panel;
}

}  // namespace

PlotSpec paper_fig4_spec() {
  PlotSpec spec;
  spec.name = "fig4_sphere";
  spec.title = "Sphere rolling with slip (cf. paper Fig. 4)";  // one line at 88 mm, 9 pt
  spec.panels.push_back(panel_spec({"sphere.v.x", "ground.slip.x"},
                                   {"centre of the sphere", "contact point"}, "Horizontal velocity",
                                   "m/s"));
  spec.panels.push_back(
      panel_spec({"sphere.p.z"}, {"centre of the sphere"}, "Height of the centre", "m"));
  return spec;
}

PlotSpec paper_fig7_spec() {
  PlotSpec spec;
  spec.name = "fig7_two_link";
  spec.title = "Two-link arm, joint friction (cf. paper Fig. 7)";
  spec.panels.push_back(panel_spec({"arm.theta.0", "arm.theta.1"}, {"joint 0", "joint 1"},
                                   "Joint angle \u03B8", "rad"));
  PanelSpec torque =
      panel_spec({"motor0.tau", "motor1.tau"}, {"joint 0", "joint 1"}, "Motor torque", "N\u00B7m");
  torque.references.push_back({0.5, "friction level F"});
  spec.panels.push_back(torque);
  // The figure's story: each joint breaks away under the ramped torque and stops for good
  // (~4.6 s), then holds under the dither. The stick-slips between are ticks: eight labels
  // do not fit a one-column figure, and these four are what the paper's Fig. 7 shows.
  spec.labels.mode = EventLabels::Mode::listed;
  spec.labels.selectors = {"joint0_friction.slip_time", "joint1_friction.slip_time",
                           "joint0_friction.final_stop", "joint1_friction.final_stop"};
  spec.print->height_mm = 100.0;
  return spec;
}

PlotSpec drift_comparison_spec() {
  PlotSpec spec;
  spec.name = "compare_drift";
  spec.mark_events = false;
  // No title: make_comparison_figure names the runs ("two_link vs two_link_lugre").
  spec.panels.push_back(
      panel_spec({"arm.theta.0"}, {"\u03B8\u2080"}, "Joint angle \u03B8\u2080", "rad"));
  spec.panels.push_back(
      panel_spec({"arm.theta.1"}, {"\u03B8\u2081"}, "Joint angle \u03B8\u2081", "rad"));
  PanelSpec drift = panel_spec({"arm.theta.0", "arm.theta.1"}, {"\u03B8\u2080", "\u03B8\u2081"},
                               "Drift \u03B8(t) \u2212 \u03B8(5 s)", "rad");
  drift.relative_to = 5.0;
  spec.panels.push_back(drift);
  return spec;
}

std::vector<PlotSpec> default_plot_specs(const std::vector<core::ColumnInfo>& columns,
                                         std::vector<std::string>* not_drawn) {
  std::vector<std::string> names;
  for (const core::ColumnInfo& c : columns) names.push_back(c.name);
  std::vector<PlotSpec> specs;
  auto complete = [&](const PlotSpec& spec) {
    for (const PanelSpec& p : spec.panels) {
      for (const std::string& s : p.signals) {
        if (!has_column(names, s)) return false;
      }
    }
    return true;
  };
  for (const PlotSpec& spec : {paper_fig4_spec(), paper_fig7_spec()}) {
    if (complete(spec)) specs.push_back(spec);
  }
  if (has_column(names, "arm.theta.2")) {  // Fig. 7 is the two-link arm's, not a longer one's
    std::erase_if(specs, [](const PlotSpec& s) { return s.name == paper_fig7_spec().name; });
  }
  // A panel per signal group ("<component>.<signal>"), in column order, legend by axis.
  std::vector<PanelSpec> panels;
  std::map<std::string, std::size_t> panel_of;
  for (const core::ColumnInfo& c : columns) {
    if (c.name == "t") continue;
    const std::size_t first = c.name.find('.');
    const std::size_t second = first == std::string::npos ? first : c.name.find('.', first + 1);
    const std::string group = second == std::string::npos ? c.name : c.name.substr(0, second);
    auto [it, added] = panel_of.emplace(group, panels.size());
    if (added) {
      // The y label is the signal's name; the caption above the panel names the component in
      // full, whatever its length, and says what the signal is.
      PanelSpec panel;
      panel.label = first == std::string::npos ? group : group.substr(first + 1);
      panel.unit = c.unit.empty() ? core::guess_unit(c.name) : c.unit;
      std::string description = c.description;
      const std::size_t axis = description.rfind(", component ");
      if (axis != std::string::npos) description.resize(axis);
      panel.caption = description.empty() ? group : group + ": " + description;
      panel.omit_zero_signals = true;
      panels.push_back(panel);
    }
    PanelSpec& panel = panels[it->second];
    panel.signals.push_back(c.name);
    panel.legend.push_back(second == std::string::npos ? c.name : c.name.substr(second + 1));
  }
  for (PanelSpec& panel : panels) {
    if (panel.signals.size() != 1) continue;
    // One signal: the axis label names it, its axis included ("v.x", not "v": `compare
    // --signals ball.v.x`), and so does the caption.
    const std::string& signal = panel.signals.front();
    const std::string group = panel.caption.substr(0, panel.caption.find(": "));
    if (signal != group && signal.rfind(group + ".", 0) == 0) {
      panel.label += signal.substr(group.size());
      panel.caption = signal + panel.caption.substr(group.size());
    }
    panel.legend.clear();
  }
  // At most kMaxDefaultFigures figures (issue 39: 20 spheres with pairwise contacts drew 210
  // PNGs for a 3-row run); the groups beyond are named in `not_drawn`, never dropped silently.
  const std::size_t cap = static_cast<std::size_t>(kMaxDefaultFigures * kPanelsPerFigure);
  if (panels.size() > cap) {
    for (std::size_t i = cap; i < panels.size(); ++i) {
      if (not_drawn != nullptr) {
        const std::string& first = panels[i].signals.front();
        const std::size_t dot = first.find('.');
        const std::size_t second = dot == std::string::npos ? dot : first.find('.', dot + 1);
        not_drawn->push_back(second == std::string::npos ? first : first.substr(0, second));
      }
    }
    panels.resize(cap);
  }
  // As many figures as the groups need (up to the cap), the panels spread evenly.
  const std::size_t n = panels.size();
  const std::size_t figures = (n + kPanelsPerFigure - 1) / kPanelsPerFigure;
  for (std::size_t f = 0, next = 0; f < figures; ++f) {
    PlotSpec spec;
    spec.name = figures == 1 ? "signals" : "signals_" + std::to_string(f + 1);
    const std::size_t count = (n - next) / (figures - f);
    for (std::size_t k = 0; k < count; ++k) spec.panels.push_back(panels[next++]);
    // The events of the elements shown, not of every element of the scene.
    for (const PanelSpec& p : spec.panels) {
      const std::string component = p.signals.front().substr(0, p.signals.front().find('.'));
      if (!has_column(spec.only_events, component)) spec.only_events.push_back(component);
    }
    specs.push_back(spec);
  }
  return specs;
}

std::vector<PlotSpec> default_plot_specs(const std::vector<std::string>& columns,
                                         std::vector<std::string>* not_drawn) {
  std::vector<core::ColumnInfo> infos;
  for (const std::string& c : columns) infos.push_back({c, core::guess_unit(c), "", ""});
  return default_plot_specs(infos, not_drawn);
}

double default_height_mm(std::size_t panels) {
  return std::min(230.0, 28.0 + 26.0 * static_cast<double>(std::max<std::size_t>(panels, 1)));
}

namespace {

bool any_selects(const std::vector<std::string>& selectors, const ClassifiedEvent& event) {
  for (const std::string& text : selectors) {
    std::string why;
    const std::optional<EventSelector> selector = parse_event_selector(text, why);
    if (selector && selects(*selector, event)) return true;
  }
  return false;
}

bool marked(const PlotSpec& spec, const ClassifiedEvent& event) {
  return spec.mark_events && (spec.only_events.empty() || any_selects(spec.only_events, event));
}

bool labelled(const EventLabels& labels, const ClassifiedEvent& event) {
  switch (labels.mode) {
    case EventLabels::Mode::important:
      return event.roles.important;
    case EventLabels::Mode::all:
      return true;
    case EventLabels::Mode::none:
      return false;
    case EventLabels::Mode::listed:
      return any_selects(labels.selectors, event);
  }
  return false;
}

}  // namespace

Figure make_figure(const PlotSpec& spec, const core::Trajectory& trajectory,
                   const std::map<std::string, double>& event_times) {
  std::vector<PlotEvent> events;
  for (const auto& [name, time] : event_times) {
    const std::size_t dot = name.rfind('.');
    std::string kind = dot == std::string::npos ? name : name.substr(dot + 1);
    if (kind.size() > 5 && kind.compare(kind.size() - 5, 5, "_time") == 0)
      kind.resize(kind.size() - 5);
    events.push_back({dot == std::string::npos ? "" : name.substr(0, dot), kind, time});
  }
  return make_figure(spec, trajectory, events);
}

Figure make_figure(const PlotSpec& spec, const core::Trajectory& trajectory,
                   const std::vector<PlotEvent>& events) {
  check_signals(spec, trajectory.columns());
  Figure figure = figure_frame(spec);
  for (const PanelSpec* ps : panels_of(spec)) {
    Panel panel = panel_frame(*ps);
    for (const std::size_t i : drawn_signals(*ps, {&trajectory}, panel)) {
      Series series;
      series.label = ps->legend.empty() ? signal_label(ps->signals[i]) : ps->legend[i];
      if (!ps->colors.empty()) {
        series.style = series_style(static_cast<int>(i));
        series.style->colour = ps->colors[i];
      }
      series.source = ps->signals[i];
      signal_series(trajectory, *trajectory.find(ps->signals[i]), *ps, series.x, series.y);
      clip_to_window(figure, series);
      panel.series.push_back(std::move(series));
    }
    figure.panels.push_back(std::move(panel));
  }
  // The marked events in time order, each labelled or a tick as the spec says; the element's
  // name goes into the labels when the figure marks events of several elements.
  std::vector<ClassifiedEvent> shown;
  for (const ClassifiedEvent& e : classify_events(events)) {
    if (marked(spec, e)) shown.push_back(e);
  }
  std::set<std::string> elements;
  for (const ClassifiedEvent& e : shown) elements.insert(e.event.element);
  for (const ClassifiedEvent& e : shown) {
    figure.events.push_back({e.event.time, event_label(e, elements.size() > 1), e.event.kind,
                             labelled(spec.labels, e)});
  }
  return figure;
}

std::filesystem::path plot_path(const PlotSpec& spec, const std::filesystem::path& dir,
                                std::optional<Format> override) {
  const Format format = override ? *override : spec.format.value_or(Format::png);
  return dir / (spec.name + extension(format));
}

FigureLayout write_plot(const PlotSpec& spec, const core::Trajectory& trajectory,
                        const std::vector<PlotEvent>& events, const std::filesystem::path& path,
                        Format format) {
  return write_figure(make_figure(spec, trajectory, events), path, format, spec.dpi);
}

void write_plot(const PlotSpec& spec, const core::Trajectory& trajectory,
                const std::map<std::string, double>& event_times,
                const std::filesystem::path& png) {
  write_figure(make_figure(spec, trajectory, event_times), png, Format::png, spec.dpi);
}

Figure make_comparison_figure(const PlotSpec& spec, const std::vector<Run>& runs) {
  for (const Run& run : runs) {
    if (!run.trajectory) throw std::invalid_argument("comparison run without a trajectory");
    try {
      check_signals(spec, run.trajectory->columns());
    } catch (const InputError& e) {
      throw InputError("run '" + run.name + "': " + e.what());
    }
  }
  Figure figure = figure_frame(spec);
  if (figure.title.empty()) {
    for (std::size_t r = 0; r < runs.size(); ++r) {
      figure.title += (r ? " vs " : "") + runs[r].name;
    }
  }
  std::vector<const core::Trajectory*> trajectories;
  for (const Run& run : runs) trajectories.push_back(run.trajectory);
  // A panel of one signal per run has a legend of the run names alone, in the same colours
  // and dashes in every panel: it is shown once, at the first such panel (a one-column
  // figure has no room to repeat it, and a reader needs it once).
  bool runs_legend_shown = false;
  for (const PanelSpec* ps : panels_of(spec)) {
    Panel panel = panel_frame(*ps);
    const int n_runs = static_cast<int>(runs.size());
    const bool repeat_of_runs_legend = ps->signals.size() == 1 && runs_legend_shown;
    runs_legend_shown = runs_legend_shown || ps->signals.size() == 1;
    for (const std::size_t i : drawn_signals(*ps, trajectories, panel)) {
      for (int r = 0; r < n_runs; ++r) {
        const Run& run = runs[r];
        Series series;
        const std::string what = ps->legend.empty() ? signal_label(ps->signals[i]) : ps->legend[i];
        series.label = ps->signals.size() == 1 ? (repeat_of_runs_legend ? "" : run.name)
                                               : run.name + ": " + what;
        series.source = ps->signals[i];
        signal_series(*run.trajectory, *run.trajectory->find(ps->signals[i]), *ps, series.x,
                      series.y);
        clip_to_window(figure, series);
        // Colour by run (the same in every panel); the dash pattern tells the signals apart.
        LineStyle style = series_style(r);
        style.dash = series_style(static_cast<int>(i) * n_runs + r).dash;
        style.width = series_style(static_cast<int>(i) * n_runs + r).width;
        series.style = style;
        panel.series.push_back(std::move(series));
      }
    }
    figure.panels.push_back(std::move(panel));
  }
  return figure;
}

void write_comparison_plot(const PlotSpec& spec, const std::vector<Run>& runs,
                           const std::filesystem::path& png) {
  write_figure(make_comparison_figure(spec, runs), png, Format::png, spec.dpi);
}

FigureLayout write_comparison_plot(const PlotSpec& spec, const std::vector<Run>& runs,
                                   const std::filesystem::path& path, Format format) {
  return write_figure(make_comparison_figure(spec, runs), path, format, spec.dpi);
}

namespace {

// How much a column differs between the runs: the largest gap of any run from the first over
// the time they share (each run's value interpolated linearly at the first run's rows),
// relative to the column's range over all runs (its largest magnitude when it is flat; 0
// when it is zero everywhere). 0: the same in every run.
double run_difference(const std::vector<Run>& runs, const std::string& column) {
  const core::Trajectory& first = *runs.front().trajectory;
  const std::optional<int> t0 = first.find("t"), c0 = first.find(column);
  if (!t0 || !c0) return 0.0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, magnitude = 0.0;
  for (const Run& run : runs) {
    const core::Trajectory& tr = *run.trajectory;
    const std::optional<int> c = tr.find(column);
    if (!c) return 0.0;
    for (int r = 0; r < tr.row_count(); ++r) {
      const double v = tr.at(r, *c);
      if (!std::isfinite(v)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      magnitude = std::max(magnitude, std::abs(v));
    }
  }
  const double scale = hi - lo > 1e-12 * magnitude ? hi - lo : magnitude;
  if (!(scale > 0.0) || !std::isfinite(scale)) return 0.0;
  double gap = 0.0;
  for (std::size_t k = 1; k < runs.size(); ++k) {
    const core::Trajectory& tr = *runs[k].trajectory;
    const std::optional<int> t = tr.find("t"), c = tr.find(column);
    if (!t || !c || tr.row_count() == 0) continue;
    int j = 0;
    for (int r = 0; r < first.row_count(); ++r) {
      const double time = first.at(r, *t0);
      while (j + 1 < tr.row_count() && tr.at(j + 1, *t) < time) ++j;
      if (j + 1 >= tr.row_count() || time < tr.at(0, *t)) continue;  // outside the time shared
      const double ta = tr.at(j, *t), tb = tr.at(j + 1, *t);
      const double w = tb > ta ? std::clamp((time - ta) / (tb - ta), 0.0, 1.0) : 0.0;
      const double other = (1.0 - w) * tr.at(j, *c) + w * tr.at(j + 1, *c);
      const double d = std::abs(first.at(r, *c0) - other);
      if (std::isfinite(d))
        gap = std::max(gap, d);
      else if (std::isfinite(first.at(r, *c0)) != std::isfinite(other))
        gap = scale;
    }
  }
  return gap / scale;
}

// A comparison of more than two runs is a two-column figure (180 mm): its legend, one entry
// per run and signal, has no room beside or above the panels of a one-column page.
PlotSpec widen_for_runs(PlotSpec spec, std::size_t runs) {
  if (runs > 2 && spec.print) spec.print->width_mm = 180.0;
  return spec;
}

}  // namespace

PlotSpec default_comparison_spec(const std::vector<Run>& runs) {
  std::vector<std::string> common;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (!runs[r].trajectory) continue;
    const std::vector<std::string>& columns = runs[r].trajectory->columns();
    if (r == 0) {
      common = columns;
    } else {
      std::erase_if(common, [&](const std::string& c) { return !has_column(columns, c); });
    }
  }
  if (has_column(common, "arm.theta.0") && has_column(common, "arm.theta.1")) {
    return drift_comparison_spec();
  }
  // The signals that differ most between the runs (run_difference, relative to each one's
  // range): the first, and those within kCompareShare of it, at most kCompareSignals, in the
  // order of the columns, each in a panel of its own. One signal per panel, the runs told
  // apart by colour, makes the legend the runs' names alone, shown once for the figure (a
  // panel of two axes of two runs had four "run: axis" entries, and on an 88 x 70 mm page
  // legends beside the axes took 40% of its width).
  std::vector<std::pair<double, std::size_t>> scored;
  for (std::size_t i = 0; i < common.size(); ++i) {
    if (common[i] == "t") continue;
    const double d = run_difference(runs, common[i]);
    if (d > 1e-9) scored.push_back({d, i});
  }
  std::stable_sort(scored.begin(), scored.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<std::size_t> picked;
  for (const auto& [d, i] : scored) {
    if (picked.size() >= kCompareSignals || d < kCompareShare * scored.front().first) break;
    picked.push_back(i);
  }
  if (!picked.empty()) {
    std::sort(picked.begin(), picked.end());
    PlotSpec spec;
    for (std::size_t i : picked) {
      PlotSpec one = comparison_spec(runs, {common[i]}, {});
      if (spec.panels.empty()) {
        spec = std::move(one);
      } else {
        spec.panels.insert(spec.panels.end(), one.panels.begin(), one.panels.end());
      }
    }
    return spec;
  }
  // The runs agree everywhere: the first default figure of what they share.
  std::vector<PlotSpec> specs = default_plot_specs(common);
  if (specs.empty()) throw InputError("the runs have no signal in common to compare");
  PlotSpec spec = specs.front();
  spec.name = "compare";
  return widen_for_runs(spec, runs.size());
}

PlotSpec comparison_spec(const std::vector<Run>& runs, const std::vector<std::string>& signals,
                         const std::vector<core::ColumnInfo>& columns) {
  std::vector<std::string> common;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (!runs[r].trajectory) continue;
    const std::vector<std::string>& cs = runs[r].trajectory->columns();
    if (r == 0) {
      common = cs;
    } else {
      std::erase_if(common, [&](const std::string& c) { return !has_column(cs, c); });
    }
  }
  // Each requested name is a column or a group prefix: "sphere.v" means sphere.v.x/y/z.
  std::vector<core::ColumnInfo> chosen;
  for (const std::string& name : signals) {
    bool found = false;
    for (const std::string& c : common) {
      if (c != "t" && (c == name || c.rfind(name + ".", 0) == 0)) {
        found = true;
        const auto info = std::find_if(columns.begin(), columns.end(),
                                       [&](const core::ColumnInfo& i) { return i.name == c; });
        chosen.push_back(info != columns.end() ? *info
                                               : core::ColumnInfo{c, core::guess_unit(c), "", ""});
      }
    }
    if (!found) {
      const std::vector<std::string> shared = signal_columns(common);
      throw InputError("--signals: '" + name + "' is not a signal of every run; " +
                       (shared.empty()
                            ? std::string("the runs have no signal in common (compare runs of "
                                          "scenes that share a component name)")
                            : "the signals they all have: " + join(shared)));
    }
  }
  std::vector<core::ColumnInfo> unique;
  for (const core::ColumnInfo& c : chosen) {
    if (std::none_of(unique.begin(), unique.end(),
                     [&](const core::ColumnInfo& u) { return u.name == c.name; })) {
      unique.push_back(c);
    }
  }
  unique.insert(unique.begin(), core::ColumnInfo{"t", "s", "", "time"});
  // One figure for a comparison: every chosen group is a panel.
  PlotSpec spec;
  spec.name = "compare";
  for (const PlotSpec& s : default_plot_specs(unique)) {
    if (s.name.rfind("signals", 0) != 0) continue;  // the paper figures
    spec.panels.insert(spec.panels.end(), s.panels.begin(), s.panels.end());
  }
  return widen_for_runs(spec, runs.size());
}

}  // namespace stiction::plot
