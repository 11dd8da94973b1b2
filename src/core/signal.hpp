// Named outputs of a component (DESIGN section 4): a signal is a scalar (no axes) or a
// vector whose entries are named by its axes ("x y z", "w x y z", "0 1 ...").
#pragma once

#include <string>
#include <vector>

namespace stiction::core {

struct SignalInfo {
  std::string name{};
  std::vector<std::string> axes{};  // empty: a scalar
  // An angle that the component reports modulo 2 pi; the recorder unwraps it so that a
  // joint that turns twice reads 4 pi, as an arm's own joint angle does.
  bool unwrap = false;
  // What the numbers mean, for plots and summary.json `columns` (DESIGN section 4). The
  // defaults keep older components compiling; every bundled component fills them in.
  std::string unit{};         // SI, e.g. "m/s", "N·m", "rad"; "1" for a dimensionless number
  std::string frame{};        // "world", "body", "joint", "surface" or "" when not a vector
  std::string description{};  // a short phrase, e.g. "velocity of the centre of mass"

  int size() const { return axes.empty() ? 1 : static_cast<int>(axes.size()); }
};

inline const std::vector<std::string>& xyz_axes() {
  static const std::vector<std::string> axes{"x", "y", "z"};
  return axes;
}
inline const std::vector<std::string>& wxyz_axes() {
  static const std::vector<std::string> axes{"w", "x", "y", "z"};
  return axes;
}
std::vector<std::string> index_axes(int n);

// "<component>.<signal>" or "<component>.<signal>.<axis>", one name per entry.
std::vector<std::string> column_names(const std::string& component,
                                      const std::vector<SignalInfo>& signals);

}  // namespace stiction::core
