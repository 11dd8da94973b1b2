// What the fuzz target does with one input, shared with the regression test that replays
// the findings (tests/reliability/test_fuzz_regressions.cpp). Returns true if the scene was built,
// false if it was refused with a scene::InputError; anything else propagates.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/run_limits.hpp"
#include "scene/overrides.hpp"
#include "scene/scene.hpp"
#include "scene/toml_shape.hpp"

namespace stiction::fuzz {

inline bool load_fuzz_input(const std::string& input) {
  std::string document = input;
  std::vector<std::string> overrides;
  if (const std::size_t split = input.find("\n%%\n"); split != std::string::npos) {
    document = input.substr(0, split);
    std::istringstream lines(input.substr(split + 4));
    for (std::string line; std::getline(lines, line);) {
      if (!line.empty()) overrides.push_back(line);
    }
  }
  try {
    toml::table parsed;
    scene::check_toml_shape(document, "fuzz.toml");  // as load_scene does before toml++
    try {
      parsed = toml::parse(std::string_view(document), std::string_view("fuzz.toml"));
    } catch (const toml::parse_error& e) {
      throw scene::InputError::at(e.source(), std::string(e.description()));
    }
    for (const std::string& o : overrides) scene::apply_override(parsed, o);
    scene::Scene scene = scene::build_scene(std::move(parsed), "fuzz.toml");
    if (core::check_run_limits(scene.run)) return false;
    // Evaluate the network once at its initial state: components reject what they cannot
    // represent at construction, and must not crash on what they accepted.
    const core::Vec x = scene.network->initial_state();
    core::Vec x_dot(x.size());
    scene.network->derivative(0.0, x, scene.run.dt, x_dot);
    return true;
  } catch (const scene::InputError&) {
    return false;
  }
}

}  // namespace stiction::fuzz
