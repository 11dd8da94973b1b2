// Runs a bundled scene (with overrides) and reads its trajectory by column name.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "core/simulation.hpp"
#include "scene/scene.hpp"

namespace stiction::testing {

struct ScenarioRun {
  scene::Scene scene;
  core::RunResult result;

  int column(const std::string& name) const {
    const auto c = result.trajectory.find(name);
    if (!c) throw std::runtime_error("no column " + name);
    return *c;
  }
  // Value of a column at the sample nearest to time t.
  double at(const std::string& name, double t) const {
    const auto& tr = result.trajectory;
    const double period = tr.row_count() > 1 ? tr.at(1, 0) - tr.at(0, 0) : 1.0;
    int row = static_cast<int>(t / period + 0.5);
    if (row >= tr.row_count()) row = tr.row_count() - 1;
    return tr.at(row, column(name));
  }
  std::vector<double> values(const std::string& name) const {
    return result.trajectory.column(column(name));
  }
  double stick_time(const std::string& component) const {
    for (const auto& h : result.slip_events) {
      if (h.component == component) return h.monitor.stick_time();
    }
    return -1.0;
  }
};

inline ScenarioRun run_scenario(const std::string& name,
                                const std::vector<std::string>& overrides = {}) {
  ScenarioRun run{scene::load_scene(name, overrides), {}};
  core::RunOptions options = run.scene.run;
  run.result = core::simulate(*run.scene.network, options);
  return run;
}

}  // namespace stiction::testing
