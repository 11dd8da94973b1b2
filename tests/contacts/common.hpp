// Helpers for the contact tests: scenes from text, column access on a run.
#pragma once

#include <cmath>
#include <random>
#include <string>

#include "scenario.hpp"
#include "toml_number.hpp"

namespace stiction::testing {

inline ScenarioRun run_text(const std::string& text) {
  ScenarioRun run{scene::build_scene(toml::parse(text, std::string_view("gen.toml")), "gen.toml"),
                  {}};
  core::RunOptions options = run.scene.run;
  run.result = core::simulate(*run.scene.network, options);
  return run;
}

// Rows of a run: time and a column by index.
inline double cell(const ScenarioRun& run, int row, int column) {
  return run.result.trajectory.at(row, column);
}

}  // namespace stiction::testing
