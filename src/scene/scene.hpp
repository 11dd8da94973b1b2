// Scene files (TOML) -> a finalized Network plus run options. The format is documented in
// docs/scene_format.md. Every key is checked against the schema: an unknown key, a value
// of the wrong type or out of range is an InputError "FILE:LINE:COL: error: KEY: ...".
// The tables `render`, `camera`, `overlay` and `plots` belong to the renderer and the
// plotter: they are kept in `document` and not validated here.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "core/network.hpp"
#include "core/simulation.hpp"
#include "scene/plausibility.hpp"
#include "scene/toml_reader.hpp"

namespace stiction::scene {

struct Scene {
  std::string name;
  std::string description;
  std::filesystem::path path;                      // file it came from
  std::unique_ptr<core::Network> network;          // finalized; owns every component
  core::RunOptions run;                            // [simulation]
  toml::table document;                            // whole parsed document after overrides
  // The smaller of the scene file's step and the step after --set: the step guard's pilot
  // runs at no more than this (app/step_check.hpp), so a larger step asked for on the
  // command line cannot hide the regimes it would blow up in.
  double authored_dt = 0.0;
  // Plausibility warnings (scene/plausibility.hpp): valid values that look like a mistake.
  std::vector<Warning> warnings;

  Scene() = default;
  Scene(Scene&&) noexcept = default;
  Scene& operator=(Scene&&) noexcept = default;
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
};

// A path to an existing file, or the name of a bundled scene (searched in the install data
// dir, then in the source tree). InputError if neither.
std::filesystem::path find_scene(const std::string& name_or_path);

// Reads, applies the overrides ("KEY=VALUE", in order), validates and builds.
Scene load_scene(const std::string& name_or_path, const std::vector<std::string>& overrides = {});

// Builds a scene from a document already parsed (tests; `path` only names the origin).
Scene build_scene(toml::table document, const std::filesystem::path& path);

// Name and one-line description of every bundled scene, sorted by name.
std::vector<std::pair<std::string, std::string>> bundled_scenes();

// Directories searched for bundled scenes, in order.
std::vector<std::filesystem::path> scene_directories();

}  // namespace stiction::scene
