#include "services/comparison.hpp"

#include <algorithm>
#include <map>

#include "io/atomic_file.hpp"
#include "plot/plot_spec.hpp"

namespace stiction::services {
namespace fs = std::filesystem;

std::vector<std::string> comparison_labels(const std::vector<std::string>& names,
                                           const std::vector<std::vector<std::string>>& overrides) {
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::vector<std::string> own;
    for (const std::string& o : overrides[i]) {
      bool everywhere = true;
      for (std::size_t j = 0; j < names.size(); ++j) {
        const auto& other = overrides[j];
        if (std::find(other.begin(), other.end(), o) == other.end()) everywhere = false;
      }
      if (!everywhere) own.push_back(o);
    }
    std::string label = names[i];
    if (!own.empty()) {
      label += " (";
      for (std::size_t k = 0; k < own.size(); ++k) label += (k ? ", " : "") + own[k];
      label += ")";
    }
    labels.push_back(label);
  }
  std::map<std::string, int> uses;
  for (const std::string& l : labels) ++uses[l];
  std::map<std::string, int> seen;
  for (std::string& l : labels) {
    if (uses[l] > 1) {
      const std::string base = l;
      l += " (run " + std::to_string(++seen[base]) + ")";
    }
  }
  return labels;
}

void check_comparison_signals(const std::vector<std::string>& labels,
                              const std::vector<std::vector<std::string>>& signal_columns,
                              const std::vector<std::string>& signals) {
  if (signals.empty()) return;
  std::vector<core::Trajectory> empty;
  for (const std::vector<std::string>& signal : signal_columns) {
    std::vector<std::string> columns = signal;
    columns.insert(columns.begin(), "t");
    empty.emplace_back(columns);
  }
  std::vector<plot::Run> probe;
  for (std::size_t i = 0; i < empty.size(); ++i) probe.push_back({labels[i], &empty[i]});
  plot::comparison_spec(probe, signals);
}

void make_comparison_directory(const fs::path& out) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw io::IoError(out.string() + ": cannot create the output directory: " + ec.message());
}

fs::path write_comparison(const std::vector<ComparedRun>& compared,
                          const std::vector<std::string>& signals, const fs::path& out,
                          plot::Format format) {
  std::vector<plot::Run> runs;
  for (const ComparedRun& r : compared) runs.push_back({r.label, r.trajectory});
  std::vector<core::ColumnInfo> columns;
  for (const ComparedRun& r : compared) {
    for (const core::ColumnInfo& c : r.columns) {
      if (std::none_of(columns.begin(), columns.end(),
                       [&](const core::ColumnInfo& k) { return k.name == c.name; })) {
        columns.push_back(c);
      }
    }
  }
  plot::PlotSpec spec = signals.empty() ? plot::default_comparison_spec(runs)
                                        : plot::comparison_spec(runs, signals, columns);
  if (signals.empty()) {
    // Units for the default panels, from the components.
    for (plot::PanelSpec& panel : spec.panels) {
      if (!panel.unit.empty() || panel.signals.empty()) continue;
      const auto info =
          std::find_if(columns.begin(), columns.end(),
                       [&](const core::ColumnInfo& c) { return c.name == panel.signals.front(); });
      if (info != columns.end()) panel.unit = info->unit;
    }
  }
  make_comparison_directory(out);
  const fs::path path = out / (std::string("compare") + plot::extension(format));
  plot::write_comparison_plot(spec, runs, path, format);
  return path;
}

}  // namespace stiction::services
