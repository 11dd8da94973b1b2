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
#include "scene/drawing.hpp"
#include "scene/expression.hpp"
#include "scene/plausibility.hpp"
#include "scene/toml_reader.hpp"
#include "scene/urdf_loader.hpp"

namespace stiction::scene {

// Elements a program supplies in code rather than in the file: a source's law or a whole
// impedance given by the caller (the Python module's callables, scene/external_elements.hpp).
struct ExternalElements;

// Where a scene comes from, so that a service can load fresh copies of it (a sweep's points,
// a study's runs): a bundled name or a path, or a TOML text (origin names it in errors), plus
// the elements supplied in code. Converts from a name or path.
struct SceneSource {
  std::string name_or_path;  // used when `text` is empty
  std::string text;          // a TOML document
  std::string origin;        // the text's name in messages and its scene's default name
  std::shared_ptr<const ExternalElements> externals;

  SceneSource() = default;
  SceneSource(std::string name) : name_or_path(std::move(name)) {}  // NOLINT: implicit
  SceneSource(const char* name) : name_or_path(name) {}            // NOLINT: implicit
  static SceneSource from_text(std::string toml_text, std::string origin);
  bool is_text() const { return !text.empty(); }
};

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
  // What is drawn (scene/drawing.hpp): the renderer and the figures read this and the
  // signals, never `document` or the network's component classes.
  Drawing drawing;
  // The sources' expressions (scene/expression.hpp), checked over the run's time span by
  // check_expressions().
  std::vector<std::shared_ptr<const Expression>> expressions;
  // The elements supplied in code it was built with (null: none).
  std::shared_ptr<const ExternalElements> externals;

  Scene() = default;
  Scene(Scene&&) noexcept = default;
  Scene& operator=(Scene&&) noexcept = default;
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
};

// A path to an existing file, or the name of a bundled scene (searched in the install data
// dir, then in the source tree). InputError if neither.
std::filesystem::path find_scene(const std::string& name_or_path);

// Reads, applies the overrides ("KEY=VALUE", in order), validates and builds. A text source
// is parsed with its origin as the file name.
Scene load_scene(const SceneSource& source, const std::vector<std::string>& overrides = {});

// Builds a scene from a document already parsed (tests; `path` only names the origin).
Scene build_scene(toml::table document, const std::filesystem::path& path,
                  std::shared_ptr<const ExternalElements> externals = nullptr);

// Evaluates every expression of t alone at t = 0, at the times of the output rows and at the
// end of the run (up to 10001 times, spread evenly past that): ExpressionValueError naming the
// expression's key and the first time its value is not finite. build_scene calls it with
// the scene's [simulation]; `check` again with the options after --duration and --set.
void check_expressions(const Scene& scene);

// Name and one-line description of every bundled scene, sorted by name.
std::vector<std::pair<std::string, std::string>> bundled_scenes();

// Directories searched for bundled scenes, in order.
std::vector<std::filesystem::path> scene_directories();

}  // namespace stiction::scene
