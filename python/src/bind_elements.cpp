// Controllers and custom elements written in Python (scene/external_elements.hpp):
// - _set_source(scene, name, law, signals): the law of a torque_source or force_source is a
//   Python callable law(t, state) -> a torque (N·m) or 3 force entries (N), called at every
//   integrator stage from the stage state; `state` is a State, a read-only mapping from the
//   signals' column names to their values at the stage (one object per scene build, its
//   values copied in before each call: no dict is built per call);
// - _set_element(scene, name, make): `make()` returns a fresh stiction.Impedance for every
//   scene build (python_impedance.hpp).
// Both live in the scene's SceneSource, so every service loading fresh copies of the scene
// (a sweep's points, the accuracy companion) gets them. The calls take the GIL (stiction.run
// releases it); an exception raised in Python stops the run and reaches the caller.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <unordered_map>

#include "bindings.hpp"
#include "python_callbacks.hpp"
#include "python_impedance.hpp"
#include "scene/external_elements.hpp"

namespace stiction::python {

namespace {

// What a source law reads: the stage values of its signals, by column name.
struct State {
  std::vector<std::string> names;
  std::unordered_map<std::string, std::size_t> index;
  std::vector<double> values;

  double at(const std::string& name) const {
    const auto found = index.find(name);
    if (found == index.end()) throw py::key_error(name);  // in Python only: a KeyError
    return values[found->second];
  }
};

scene::SourceLaw make_law(const std::shared_ptr<py::object>& law, const std::string& source,
                          const std::vector<std::string>& names, int count) {
  py::gil_scoped_acquire gil;  // scenes may be loaded with the GIL released
  auto state = std::make_shared<State>();
  state->names = names;
  for (std::size_t i = 0; i < names.size(); ++i) state->index.emplace(names[i], i);
  state->values.assign(names.size(), 0.0);
  State* values = state.get();
  std::shared_ptr<py::object> argument = keep(py::cast(std::move(state)));
  return [law, argument, values, count, what = "source '" + source + "' returned"](
             double t, const double* signals, double* out) {
    py::gil_scoped_acquire gil;
    std::copy(signals, signals + values->values.size(), values->values.begin());
    read_values((*law)(t, *argument), out, count, what);
    // A non-finite torque or force is the law's fault, not the step's (issue 39).
    for (int i = 0; i < count; ++i) {
      if (std::isfinite(out[i])) continue;
      std::string m = what + " a non-finite value (" + std::to_string(out[i]) + ") at t = " +
                      std::to_string(t) + " s, for the signals {";
      for (std::size_t k = 0; k < values->names.size(); ++k) {
        m += (k ? ", " : "") + values->names[k] + ": " + std::to_string(values->values[k]);
      }
      raise(PyExc_ValueError, m + "}");
    }
  };
}

// Sets (or with None removes) the law of source `name`.
// The fingerprint Python computes for a law or an element maker (_elements._fingerprint;
// empty: none, the scene is not cached).
std::string fingerprint_of(const py::object& obj) {
  const py::object text = py::module_::import("stiction._elements").attr("_fingerprint")(obj);
  return text.is_none() ? std::string() : text.cast<std::string>();
}

void set_source(scene::ExternalElements& e, const std::string& name, py::object law,
                std::optional<std::vector<std::string>> signals) {
  if (law.is_none()) {
    e.sources.erase(name);
    e.fingerprints.erase(name);
    return;
  }
  e.fingerprints[name] =
      fingerprint_of(law) + (signals ? " signals " + std::string(py::repr(py::cast(*signals)))
                                     : std::string());
  e.sources[name] = {std::move(signals), [law = keep(std::move(law)), name](
                                             const std::vector<std::string>& names, int count) {
                       return make_law(law, name, names, count);
                     }};
}

// Sets (or with None removes) the element `name`: make() returns a fresh Python object.
void set_element(scene::ExternalElements& e, const std::string& name, py::object make) {
  if (make.is_none()) {
    e.impedances.erase(name);
    e.fingerprints.erase(name);
    return;
  }
  e.fingerprints[name] = fingerprint_of(make);
  e.impedances[name] = [make = keep(std::move(make))](const std::string& element_name) {
    py::gil_scoped_acquire gil;
    return make_python_impedance(element_name, (*make)());
  };
}

// Replaces the scene's elements supplied in code by `change`d copies and reloads it; the
// scene stays as it was when the reload fails.
template <typename Change>
void change_externals(SceneHandle& h, Change change) {
  auto next = std::make_shared<scene::ExternalElements>(
      h.source.externals ? *h.source.externals : scene::ExternalElements{});
  change(*next);
  const auto before = h.source.externals;
  h.source.externals = next;
  try {
    h.reload();
  } catch (...) {
    h.source.externals = before;
    throw;
  }
}

}  // namespace

void bind_elements(py::module_& m) {
  py::class_<State, std::shared_ptr<State>>(
      m, "State",
      "The signals a source law reads at an integrator stage, by CSV column name (SI units, "
      "scene.units): a read-only mapping, state[\"arm.theta.0\"]. It is refilled before every "
      "call: copy what you keep (dict(state)).")
      .def("__getitem__", &State::at, py::arg("column"))
      .def("__len__", [](const State& s) { return s.names.size(); })
      .def("__contains__", [](const State& s, const std::string& k) { return s.index.contains(k); })
      .def(
          "__iter__",
          [](const State& s) { return py::make_iterator(s.names.begin(), s.names.end()); },
          py::keep_alive<0, 1>())
      .def("keys", [](const State& s) { return s.names; })
      .def("values", [](const State& s) { return s.values; })
      .def("items",
           [](const State& s) {
             std::vector<std::pair<std::string, double>> out;
             for (std::size_t i = 0; i < s.names.size(); ++i)
               out.emplace_back(s.names[i], s.values[i]);
             return out;
           })
      .def(
          "get",
          [](const State& s, const std::string& k, py::object fallback) -> py::object {
            const auto found = s.index.find(k);
            return found == s.index.end() ? fallback : py::float_(s.values[found->second]);
          },
          py::arg("column"), py::arg("default") = py::none())
      .def_property_readonly(
          "array",
          [](const State& s) {
            return py::array_t<double>(static_cast<py::ssize_t>(s.values.size()), s.values.data());
          },
          "The values as a NumPy array (a copy), in the order of keys().")
      .def("__repr__", [](const State& s) {
        std::string out = "<stiction.State";
        for (std::size_t i = 0; i < s.names.size(); ++i) {
          out += (i == 0 ? " " : ", ") + s.names[i] + "=" +
                 std::string(py::repr(py::float_(s.values[i])));
        }
        return out + ">";
      });

  m.def(
      "_set_source",
      [](SceneHandle& h, const std::string& name, py::object law,
         std::optional<std::vector<std::string>> signals) {
        change_externals(h, [&](scene::ExternalElements& e) {
          set_source(e, name, std::move(law), std::move(signals));
        });
      },
      py::arg("scene"), py::arg("name"), py::arg("law"), py::arg("signals") = py::none());

  m.def(
      "_set_element",
      [](SceneHandle& h, const std::string& name, py::object make) {
        change_externals(
            h, [&](scene::ExternalElements& e) { set_element(e, name, std::move(make)); });
      },
      py::arg("scene"), py::arg("name"), py::arg("make"));

  // A scene loaded with its elements in code from the start (its file may need them to load).
  m.def(
      "_load_with_elements",
      [](const std::string& name_or_path, const std::string& text, const std::string& origin,
         const std::vector<std::string>& overrides, const py::list& sources,
         const py::list& elements) {
        auto h = std::make_shared<SceneHandle>();
        h->source = text.empty() ? scene::SceneSource(name_or_path)
                                 : scene::SceneSource::from_text(text, origin);
        h->overrides = overrides;
        auto externals = std::make_shared<scene::ExternalElements>();
        for (const auto& item : sources) {
          const auto entry = item.cast<py::tuple>();
          set_source(*externals, entry[0].cast<std::string>(), entry[1],
                     entry[2].cast<std::optional<std::vector<std::string>>>());
        }
        for (const auto& item : elements) {
          const auto entry = item.cast<py::tuple>();
          set_element(*externals, entry[0].cast<std::string>(), entry[1]);
        }
        h->source.externals = std::move(externals);
        h->reload();
        return h;
      },
      py::arg("name_or_path"), py::arg("text"), py::arg("origin"), py::arg("overrides"),
      py::arg("sources"), py::arg("elements"));

  m.def(
      "_externals",
      [](const SceneHandle& h) {
        std::vector<std::string> sources, elements;
        if (h.source.externals) {
          for (const auto& [n, s] : h.source.externals->sources) sources.push_back(n);
          for (const auto& [n, f] : h.source.externals->impedances) elements.push_back(n);
        }
        return std::make_pair(sources, elements);
      },
      py::arg("scene"), "The names of the sources and elements supplied in code.");
}

}  // namespace stiction::python
