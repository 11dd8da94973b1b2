// stiction._Scene: a scene loaded from a bundled name, a file or a TOML text, with `--set`
// overrides; what Python reads of it (name, step, columns with units, the document as TOML).
#include <sstream>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "core/column_info.hpp"
#include "services/step_guard.hpp"

namespace stiction::python {

void bind_scene(py::module_& m) {
  py::class_<SceneHandle, std::shared_ptr<SceneHandle>>(m, "_Scene")
      .def_static(
          "load",
          [](const std::string& name_or_path, const std::vector<std::string>& overrides) {
            auto h = std::make_shared<SceneHandle>();
            h->source = scene::SceneSource(name_or_path);
            h->overrides = overrides;
            h->reload();
            return h;
          },
          py::arg("name_or_path"), py::arg("overrides") = std::vector<std::string>{})
      .def_static(
          "from_text",
          [](const std::string& text, const std::string& origin,
             const std::vector<std::string>& overrides) {
            auto h = std::make_shared<SceneHandle>();
            h->source = scene::SceneSource::from_text(text, origin);
            h->overrides = overrides;
            h->reload();
            return h;
          },
          py::arg("text"), py::arg("origin"), py::arg("overrides") = std::vector<std::string>{})
      .def(
          "copy",
          [](const SceneHandle& h) { return std::make_shared<SceneHandle>(h); },
          "A copy sharing nothing that changes: set() on it leaves this one as it is.")
      .def(
          "set",
          [](SceneHandle& h, const std::vector<std::string>& assignments) {
            const std::vector<std::string> before = h.overrides;
            h.overrides.insert(h.overrides.end(), assignments.begin(), assignments.end());
            try {
              h.reload();
            } catch (...) {
              h.overrides = before;  // the scene stays as it was
              throw;
            }
          },
          py::arg("assignments"))
      .def_property_readonly("overrides", [](const SceneHandle& h) { return h.overrides; })
      .def_property_readonly("name", [](const SceneHandle& h) { return h.loaded->name; })
      .def_property_readonly("description", [](const SceneHandle& h) { return h.loaded->description; })
      .def_property_readonly("path", [](const SceneHandle& h) { return h.loaded->path; })
      .def_property_readonly("is_text", [](const SceneHandle& h) { return h.source.is_text(); })
      .def_property_readonly("source_name", [](const SceneHandle& h) { return h.source.name_or_path; })
      .def_property_readonly("toml",
                             [](const SceneHandle& h) {
                               std::ostringstream out;
                               out << h.loaded->document;
                               return out.str();
                             })
      .def_property_readonly("integrator", [](const SceneHandle& h) { return h.loaded->run.integrator; })
      .def_property_readonly("dt", [](const SceneHandle& h) { return h.loaded->run.dt; })
      .def_property_readonly("duration", [](const SceneHandle& h) { return h.loaded->run.duration; })
      .def_property_readonly("output_rate", [](const SceneHandle& h) { return h.loaded->run.output_rate; })
      .def_property_readonly("tolerance", [](const SceneHandle& h) { return h.loaded->run.tolerance; })
      .def_property_readonly("state_size",
                             [](const SceneHandle& h) { return h.loaded->network->state_dim(); })
      .def_property_readonly("columns",
                             [](const SceneHandle& h) {
                               std::vector<std::tuple<std::string, std::string, std::string>> out;
                               for (const core::ColumnInfo& c : core::column_infos(*h.loaded->network))
                                 out.emplace_back(c.name, c.unit, c.description);
                               return out;
                             })
      .def_property_readonly("warnings", [](const SceneHandle& h) {
        return to_python(services::warnings_json(h.loaded->warnings));
      });

  m.def("_bundled_scenes", [] { return scene::bundled_scenes(); });
}

}  // namespace stiction::python
