// What every binding shares: the services' exceptions as the package's
// (python/stiction/errors.py), JSON as Python objects, the main-thread test. A scene error with
// its file, line, column and key; an I/O error; anything else as RuntimeError.
#include <exception>

#include "bindings.hpp"
#include "io/atomic_file.hpp"
#include "scene/toml_reader.hpp"
#include "sys/interrupt.hpp"

namespace stiction::python {

namespace {

template <class Json>
py::object json_to_python(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null: return py::none();
    case Json::value_t::boolean: return py::bool_(value.template get<bool>());
    case Json::value_t::number_integer: return py::int_(value.template get<long long>());
    case Json::value_t::number_unsigned: return py::int_(value.template get<unsigned long long>());
    case Json::value_t::number_float: return py::float_(value.template get<double>());
    case Json::value_t::string: return py::str(value.template get_ref<const std::string&>());
    case Json::value_t::array: {
      py::list list;
      for (const auto& item : value) list.append(json_to_python(item));
      return list;
    }
    case Json::value_t::object: {
      py::dict dict;
      for (const auto& [key, item] : value.items()) dict[py::str(key)] = json_to_python(item);
      return dict;
    }
    default: return py::none();
  }
}

}  // namespace

py::object to_python(const nlohmann::ordered_json& value) { return json_to_python(value); }
py::object to_python(const nlohmann::json& value) { return json_to_python(value); }

bool on_main_thread() {
  py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

py::object error_class(const char* name) {
  return py::module_::import("stiction.errors").attr(name);
}

void bind_errors(py::module_&) {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const scene::InputError& e) {
      py::object error = error_class("SceneError")(e.what());
      PyErr_SetObject(error.get_type().ptr(), error.ptr());
    } catch (const sys::Interrupted&) {
      py::object error = error_class("Interrupted")("interrupted (SIGINT) before anything was kept");
      PyErr_SetObject(error.get_type().ptr(), error.ptr());
    } catch (const io::IoError& e) {
      py::object error = error_class("OutputError")(e.what());
      PyErr_SetObject(error.get_type().ptr(), error.ptr());
    }
  });
}

}  // namespace stiction::python
