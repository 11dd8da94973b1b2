// What the fuzz targets do with one input, shared with the regression test that replays
// the findings (tests/reliability/test_fuzz_regressions.cpp). load_fuzz_scene returns the
// scene built (fuzz_pairs and fuzz_urdf then step it: fuzz/step_fuzz_scene.hpp), or nothing
// if it was refused with a scene::InputError; load_fuzz_input says which; anything else
// propagates. STICTION_FUZZ_VERBOSE=1 prints each refusal's message to stderr.
//
// An input is a scene file, optionally followed by a line "%%urdf" and a URDF text, then
// optionally by a line "%%" and one --set assignment per line. With a URDF, the scene and
// the URDF are written as fuzz.toml and fuzz.urdf into a directory of this process
// (fuzz/scratch_directory.hpp) and the scene is built from there, so that a `urdf` body's
// `file = "fuzz.urdf"` reads the fuzzed text through the scene builder as `run` does.
#pragma once

#include <toml++/toml.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/run_limits.hpp"
#include "fuzz/scratch_directory.hpp"
#include "scene/overrides.hpp"
#include "scene/scene.hpp"
#include "scene/toml_shape.hpp"

namespace stiction::fuzz {

inline void write_scratch_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

// The scene an input builds (evaluated once at its initial state), or nothing when it is
// refused with a scene::InputError or breaks the run limits as `run` would refuse it.
inline std::optional<scene::Scene> load_fuzz_scene(const std::string& input) {
  std::string document = input;
  std::vector<std::string> overrides;
  if (const std::size_t split = input.find("\n%%\n"); split != std::string::npos) {
    document = input.substr(0, split);
    std::istringstream lines(input.substr(split + 4));
    for (std::string line; std::getline(lines, line);) {
      if (!line.empty()) overrides.push_back(line);
    }
  }
  std::filesystem::path origin = "fuzz.toml";  // a text scene: urdf files from the working dir
  if (const std::size_t split = document.find("\n%%urdf\n"); split != std::string::npos) {
    const std::filesystem::path dir = scratch_directory();
    write_scratch_file(dir / "fuzz.urdf", document.substr(split + 8));
    document.resize(split);
    origin = dir / "fuzz.toml";
    write_scratch_file(origin, document);
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
    scene::Scene scene = scene::build_scene(std::move(parsed), origin);
    if (core::check_run_limits(scene.run)) return std::nullopt;
    // Evaluate the network once at its initial state: components reject what they cannot
    // represent at construction, and must not crash on what they accepted.
    const core::Vec x = scene.network->initial_state();
    core::Vec x_dot(x.size());
    scene.network->derivative(0.0, x, scene.run.dt, x_dot);
    return scene;
  } catch (const scene::InputError& e) {
    if (std::getenv("STICTION_FUZZ_VERBOSE") != nullptr) std::fprintf(stderr, "%s\n", e.what());
    return std::nullopt;
  }
}

inline bool load_fuzz_input(const std::string& input) { return load_fuzz_scene(input).has_value(); }

}  // namespace stiction::fuzz
