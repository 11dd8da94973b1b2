// `_stiction`: the C++ half of the Python package `stiction` (python/stiction/__init__.py is
// the public face; docs/python.md).
#include "bindings.hpp"

#include "sys/data_dirs.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_stiction, m) {
  m.doc() = "stiction's simulation services (use the package `stiction`, not this module)";
  m.def(
      "_set_install_root", [](const std::string& prefix) { stiction::sys::set_install_root(prefix); },
      "The prefix the package was installed in (a moved prefix too): the render plugin and the "
      "bundled scenes are found there.");
  stiction::python::bind_errors(m);
  stiction::python::bind_scene(m);
  stiction::python::bind_run(m);
  stiction::python::bind_elements(m);
  stiction::python::bind_tools(m);
  stiction::python::bind_pictures(m);
}
