#include "core/column_info.hpp"

#include <map>

namespace stiction::core {
namespace {

void add(std::vector<ColumnInfo>& out, const std::string& component,
         const std::vector<SignalInfo>& signals) {
  for (const SignalInfo& s : signals) {
    const std::vector<std::string> names = column_names(component, {s});
    for (std::size_t k = 0; k < names.size(); ++k) {
      std::string description = s.description;
      if (!s.axes.empty() && !description.empty()) description += ", component " + s.axes[k];
      std::string unit = s.unit.empty() ? guess_unit(names[k]) : s.unit;
      out.push_back({names[k], unit, s.frame, description});
    }
  }
}

}  // namespace

std::vector<ColumnInfo> column_infos(const Network& network) {
  std::vector<ColumnInfo> out;
  out.push_back({"t", "s", "", "time"});
  for (const auto& a : network.admittances()) add(out, a->name(), a->signals());
  for (const auto& i : network.impedances()) add(out, i->name(), i->signals());
  return out;
}

std::string guess_unit(const std::string& column) {
  static const std::map<std::string, std::string> units{
      {"p", "m"},         {"v", "m/s"}, {"q", "1"},     {"w", "rad/s"},  {"theta", "rad"},
      {"omega", "rad/s"}, {"f", "N"},   {"tau", "N·m"}, {"slip", "m/s"}, {"n_force", "N"}};
  const std::size_t first = column.find('.');
  if (first == std::string::npos) return column == "t" ? "s" : "";
  const std::size_t second = column.find('.', first + 1);
  const std::string signal = column.substr(
      first + 1, second == std::string::npos ? std::string::npos : second - first - 1);
  const auto it = units.find(signal);
  return it == units.end() ? "" : it->second;
}

}  // namespace stiction::core
