// The pieces of the `_stiction` extension (python/CMakeLists.txt), one bind_<area> per file,
// and what they share: the scene a Python object stands for, and the translation of the
// services' exceptions into the package's (python/stiction/errors.py).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

#include "scene/scene.hpp"

namespace stiction::python {

namespace py = pybind11;

// A scene as Python holds it: where it comes from and the overrides set on it, with the
// scene loaded from them (reloaded after every change, so errors surface at the call that
// caused them). Services that need fresh copies load them from source + overrides.
struct SceneHandle {
  scene::SceneSource source;
  std::vector<std::string> overrides;
  std::shared_ptr<scene::Scene> loaded;

  void reload() { loaded = std::make_shared<scene::Scene>(scene::load_scene(source, overrides)); }
  // A fresh copy to simulate (a run changes its scene's network state).
  scene::Scene fresh() const { return scene::load_scene(source, overrides); }
};

// nlohmann JSON -> Python objects (dicts keep the order of the keys).
py::object to_python(const nlohmann::ordered_json& value);
py::object to_python(const nlohmann::json& value);

// True on Python's main thread, the one SIGINT reaches: only there may a call install
// sys::ScopedInterrupt for Ctrl-C.
bool on_main_thread();

// The class `name` of stiction.errors.
py::object error_class(const char* name);

void bind_errors(py::module_& m);
void bind_scene(py::module_& m);
void bind_run(py::module_& m);
void bind_elements(py::module_& m);
void bind_tools(py::module_& m);
void bind_pictures(py::module_& m);

}  // namespace stiction::python
