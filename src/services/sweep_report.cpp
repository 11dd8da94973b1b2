// sweep.md (the table as Markdown, with the status counts) and sweep.png / sweep.svg (the
// chosen records against the first varied key, one line per combination of the other keys'
// values; the same figure as a bitmap and as vectors).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "plot/figure.hpp"
#include "plot/plot_spec.hpp"
#include "scene/toml_reader.hpp"
#include "services/sweep.hpp"
#include "text/number_text.hpp"

namespace stiction::services {
namespace {

constexpr std::size_t kMarkdownRows = 200;

double number(const std::string& text) {
  double v = std::nan("");
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size()) return std::nan("");
  return v;
}

int column_of(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return static_cast<int>(i);
  }
  return -1;
}

bool is_event_time(const std::string& column) {
  for (const std::string suffix : {".stick_time", ".first_slip", ".last_stick"}) {
    if (column.size() > suffix.size() &&
        column.compare(column.size() - suffix.size(), suffix.size(), suffix) == 0)
      return true;
  }
  return false;
}

// A measured value of the table (an event time, a final state) for sweep.md: stated
// significant digits by the number rule (sweep.csv keeps every digit); text stays as it is.
std::string reader_value(const std::string& cell) {
  const double v = number(cell);
  return std::isfinite(v) ? text::significant(v, text::kEventTimeDigits) : cell;
}

// The values of the other keys that tell a sweep figure's lines apart, ordered as numbers
// where both are numbers (-40, -20, 0, 5; not "-20", "-40", "0", "5" as text).
struct LineKey {
  std::vector<std::string> values;
  bool operator<(const LineKey& other) const {
    for (std::size_t i = 0; i < values.size() && i < other.values.size(); ++i) {
      const double a = number(values[i]), b = number(other.values[i]);
      if (std::isfinite(a) && std::isfinite(b)) {
        if (a != b) return a < b;
      } else if (values[i] != other.values[i]) {
        return values[i] < other.values[i];
      }
    }
    return values.size() < other.values.size();
  }
};

// The columns the figure shows: the plan's, less those no finished point has a value of (a
// ball that only slips has no stick time), at most kPanels; when none is left, the first
// record (the first column after the event columns).
constexpr std::size_t kPanels = 4;
std::vector<std::string> plotted_columns(const SweepPlan& plan, const SweepTable& table) {
  const int status = column_of(table.header, "status");
  const auto has_value = [&](int c) {
    for (const auto& [index, row] : table.rows) {
      if (row[status] == "ok" && std::isfinite(number(row[c]))) return true;
    }
    return false;
  };
  std::vector<std::string> shown;
  for (const std::string& p : plan.plot) {
    const int c = column_of(table.header, p);
    if (c >= 0 && has_value(c) && shown.size() < kPanels) shown.push_back(p);
  }
  if (!shown.empty() || plan.plot.empty()) return shown;
  int first_record = column_of(table.header, "note") + 1;
  for (int c = first_record; c < static_cast<int>(table.header.size()); ++c) {
    const std::string& name = table.header[c];
    if (name.size() > 7 && name.compare(name.size() - 7, 7, ".events") == 0) first_record = c + 1;
  }
  if (first_record > 0 && first_record < static_cast<int>(table.header.size()))
    shown.push_back(table.header[first_record]);
  return shown;
}

std::string markdown(const SweepPlan& plan, const SweepTable& table) {
  std::map<std::string, int> statuses;
  const int status = column_of(table.header, "status");
  for (const auto& [index, row] : table.rows) ++statuses[row[status]];
  std::string md = "# Sweep of " + plan.scene + "\n\n";
  md += std::to_string(plan.points.size()) + " points (" + (plan.zip ? "zipped" : "grid") + "):";
  for (const VaryKey& k : plan.keys) {
    md += " `" + k.key + "` (" + std::to_string(k.values.size()) + " values)";
  }
  md += ".\n\nStatus:";
  for (const auto& [name, count] : statuses) md += " " + name + " " + std::to_string(count) + ";";
  const std::vector<std::string> plotted = plotted_columns(plan, table);
  md += "\n\nThe full table is `sweep.csv`";
  if (plotted.empty()) {
    md += "; no column has a value to plot.\n\n";
  } else {
    md += "; `sweep.png` (and `sweep.svg`) plot";
    for (const std::string& p : plotted) md += " `" + p + "`";
    md += " against `" + plan.keys.front().key + "`.\n\n";
  }
  // The Markdown table keeps the parameters, the status and the plotted records.
  std::vector<int> shown;
  for (std::size_t i = 0; i <= plan.keys.size(); ++i) shown.push_back(static_cast<int>(i));
  for (const char* c : {"status", "steps", "wall_s"}) shown.push_back(column_of(table.header, c));
  for (const std::string& p : plotted) shown.push_back(column_of(table.header, p));
  std::string head = "|", rule = "|";
  for (int c : shown) {
    head += " " + table.header[c] + " |";
    rule += "---|";
  }
  md += head + "\n" + rule + "\n";
  // The parameters as given (shortest round-trip), the records measured: stated digits.
  const std::size_t first_record = plan.keys.size() + 4;  // after status, steps, wall_s
  std::size_t n = 0;
  for (const auto& [index, row] : table.rows) {
    if (++n > kMarkdownRows) break;
    md += "|";
    for (std::size_t i = 0; i < shown.size(); ++i) {
      const std::string& cell = row[shown[i]];
      md += " " + (i >= first_record ? reader_value(cell) : cell) + " |";
    }
    md += "\n";
  }
  if (table.rows.size() > kMarkdownRows) {
    md += "\n(" + std::to_string(table.rows.size() - kMarkdownRows) + " more rows in sweep.csv)\n";
  }
  return md;
}

}  // namespace

std::string sweep_markdown(const SweepPlan& plan, const SweepTable& table) {
  return markdown(plan, table);
}

plot::Figure sweep_figure(const SweepPlan& plan, const SweepTable& table) {
  const int status = column_of(table.header, "status");
  plot::Figure figure;
  figure.title = "Sweep of " + plan.scene;
  figure.x_label = plan.keys.front().key;
  figure.x_unit.clear();
  for (const std::string& record : plotted_columns(plan, table)) {
    const int c = column_of(table.header, record);
    plot::Panel& panel = figure.panels.emplace_back();
    panel.label = record;
    if (is_event_time(record)) panel.unit = "s";
    // One series per combination of the other keys' values, in numeric order of those values,
    // points in order of x; a combination with no value of this record has no line (and no
    // legend entry) in this panel.
    std::map<LineKey, std::map<double, double>> lines;
    for (const auto& [index, row] : table.rows) {
      if (row[status] != "ok") continue;
      const double x = number(row[1]);
      if (!std::isfinite(x)) continue;
      LineKey key;
      for (std::size_t k = 1; k < plan.keys.size(); ++k) key.values.push_back(row[1 + k]);
      lines[key][x] = number(row[c]);
    }
    for (const auto& [key, points] : lines) {
      if (std::none_of(points.begin(), points.end(),
                       [](const auto& p) { return std::isfinite(p.second); })) {
        continue;
      }
      plot::Series& s = panel.series.emplace_back();
      for (std::size_t k = 0; k < key.values.size(); ++k) {
        s.label += (k ? ", " : "") + plan.keys[k + 1].key + " = " + key.values[k];
      }
      for (const auto& [x, y] : points) {
        s.x.push_back(x);
        s.y.push_back(y);
      }
    }
  }
  // The print size of every figure: one journal column, its height by the panel count.
  const plot::PrintSize print;
  figure.print = plot::Figure::Print{print.width_mm, plot::default_height_mm(figure.panels.size()),
                                     print.font_pt, 300.0};
  return figure;
}

bool write_sweep_report(const SweepPlan& plan, const SweepTable& table,
                        const std::filesystem::path& dir) {
  io::write_file_atomically(dir / "sweep.md", markdown(plan, table));
  if (plotted_columns(plan, table).empty()) {
    // Nothing to draw: no figure of an earlier run of this sweep may stay as if it were this.
    std::filesystem::remove(dir / "sweep.png");
    std::filesystem::remove(dir / "sweep.svg");
    return false;
  }
  const plot::Figure figure = sweep_figure(plan, table);
  plot::write_figure(figure, dir / "sweep.png", plot::Format::png, figure.print->dpi);
  plot::write_figure(figure, dir / "sweep.svg", plot::Format::svg, figure.print->dpi);
  return true;
}

std::string SweepPlan::to_json() const {
  nlohmann::ordered_json j;
  j["scene"] = scene;
  j["zip"] = zip;
  nlohmann::ordered_json keys_json = nlohmann::ordered_json::array();
  for (const VaryKey& k : keys) keys_json.push_back({{"key", k.key}, {"values", k.values}});
  j["keys"] = keys_json;
  j["points"] = points.size();
  j["columns"] = columns;
  j["plot"] = plot;
  j["settings"] = settings;
  return j.dump(2) + "\n";
}

SweepPlan SweepPlan::from_json(const std::string& text, const std::filesystem::path& origin) {
  SweepPlan plan;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    plan.scene = j.at("scene").get<std::string>();
    plan.zip = j.at("zip").get<bool>();
    for (const auto& k : j.at("keys")) {
      plan.keys.push_back(
          {k.at("key").get<std::string>(), k.at("values").get<std::vector<std::string>>()});
    }
    plan.columns = j.at("columns").get<std::vector<std::string>>();
    plan.plot = j.at("plot").get<std::vector<std::string>>();
    if (j.contains("settings")) plan.settings = j["settings"].get<std::vector<std::string>>();
    plan.points = make_points(plan.keys, plan.zip);
    if (plan.points.size() != j.at("points").get<std::size_t>()) {
      throw scene::InputError(origin.string() + ": error: the point count does not match the keys");
    }
  } catch (const nlohmann::json::exception& e) {
    throw scene::InputError(origin.string() + ": error: not a sweep plan: " + e.what());
  }
  return plan;
}

}  // namespace stiction::services
