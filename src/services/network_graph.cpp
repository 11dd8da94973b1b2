#include "services/network_graph.hpp"

#include <algorithm>
#include <sstream>

#include "components/maps/observing_map.hpp"
#include "io/atomic_file.hpp"

namespace stiction::services {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '\n') {
      out += "\\n";  // a line break inside a DOT label
      continue;
    }
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string signal_list(const std::vector<core::SignalInfo>& signals) {
  std::string out;
  for (const auto& s : signals) {
    if (!out.empty()) out += ", ";
    out += s.name;
  }
  return out;
}

}  // namespace

void write_network_dot(const scene::Scene& scene, const std::filesystem::path& path) {
  const core::Network& network = *scene.network;
  std::ostringstream dot;
  dot << "digraph " << quoted(scene.name) << " {\n"
      << "  rankdir=LR;\n  node [fontname=\"DejaVu Sans\"];\n"
      << "  label=" << quoted(scene.name + ": admittances (boxes) and impedances (ellipses); "
                              "motion x_hat flows right (Psi), force u flows back (Phi)")
      << ";\n  labelloc=t;\n";
  for (const auto& a : network.admittances()) {
    dot << "  " << quoted(a->name()) << " [shape=box, style=filled, fillcolor=\"#dbe8f7\", label="
        << quoted(a->name() + "\n" + std::string(a->type()) + "\nstate " +
                  std::to_string(a->state_size()) + ": " + signal_list(a->signals()))
        << "];\n";
  }
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const core::Impedance& imp = *network.impedances()[i];
    const core::CoordinateMap& map = network.map_of(static_cast<int>(i));
    dot << "  " << quoted(imp.name()) << " [shape=ellipse, style=filled, fillcolor=\"#f7e3d4\", label="
        << quoted(imp.name() + "\n" + std::string(imp.type()) + "\nstate " +
                  std::to_string(imp.state_size()))
        << "];\n";
    // A feedback element's map observes bodies and elements it does not drive: a dotted
    // edge, no force.
    const auto* observing = dynamic_cast<const components::ObservingMap*>(&map);
    const core::CoordinateMap& wiring = observing ? observing->inner() : map;
    if (observing) {
      std::vector<std::string> shown;
      for (const auto& o : observing->observed()) {
        const std::string& from = o.admittance ? o.admittance->name() : o.impedance->name();
        if (std::find(shown.begin(), shown.end(), from) != shown.end()) continue;
        shown.push_back(from);
        dot << "  " << quoted(from) << " -> " << quoted(imp.name())
            << " [style=dotted, label=\"observed\"];\n";
      }
    }
    for (const core::Admittance* a : wiring.admittances()) {
      dot << "  " << quoted(a->name()) << " -> " << quoted(imp.name())
          << " [label=" << quoted(std::string("x_hat (") + std::to_string(map.motion_size()) + ")") << "];\n";
      dot << "  " << quoted(imp.name()) << " -> " << quoted(a->name())
          << " [style=dashed, label=" << quoted(std::string("u (") + std::to_string(map.force_size()) + ")")
          << "];\n";
    }
  }
  dot << "}\n";
  io::write_file_atomically(path, dot.str());
}

}  // namespace stiction::services
