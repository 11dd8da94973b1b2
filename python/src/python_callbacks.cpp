#include "python_callbacks.hpp"

#include <pybind11/numpy.h>

#include <cstring>

namespace stiction::python {

std::shared_ptr<py::object> keep(py::object object) {
  return {new py::object(std::move(object)), [](py::object* o) {
            if (Py_IsInitialized() != 0) {
              py::gil_scoped_acquire gil;
              delete o;
            } else {
              o->release();  // the interpreter is gone: nothing left to release it to
              delete o;
            }
          }};
}

void raise(PyObject* type, const std::string& message) {
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

std::string value_text(py::handle value) {
  // repr() may itself fail (an int of more than 4300 digits, an object whose __repr__
  // raises): the type's name then; a long repr is cut.
  PyObject* text = PyObject_Repr(value.ptr());
  std::string out;
  if (text != nullptr) {
    Py_ssize_t size = 0;
    const char* utf8 = PyUnicode_AsUTF8AndSize(text, &size);
    if (utf8 != nullptr) out.assign(utf8, static_cast<std::size_t>(size));
    Py_DECREF(text);
  }
  if (PyErr_Occurred() != nullptr) PyErr_Clear();
  if (out.empty()) return std::string("a ") + Py_TYPE(value.ptr())->tp_name;
  constexpr std::size_t kLongest = 200;
  if (out.size() > kLongest) out = out.substr(0, kLongest) + "...";
  return out;
}

namespace {

std::string shape_text(int n) {
  return n == 1 ? "a number" : "a sequence of " + std::to_string(n) + " numbers";
}

double number(py::handle item, int n, const std::string& what) {
  const double v = PyFloat_AsDouble(item.ptr());
  if (v == -1.0 && PyErr_Occurred() != nullptr) {
    PyErr_Clear();
    raise(PyExc_TypeError, what + " " + value_text(item) + ", expected " + shape_text(n));
  }
  return v;
}

}  // namespace

void read_values(py::handle value, double* out, int n, const std::string& what) {
  if (n == 1 && (PyFloat_Check(value.ptr()) || PyLong_Check(value.ptr()))) {
    out[0] = PyFloat_AsDouble(value.ptr());
    if (out[0] == -1.0 && PyErr_Occurred() != nullptr) {  // an int too large for a double
      PyErr_Clear();
      raise(PyExc_OverflowError, what + " " + value_text(value) + ", beyond the range of a double");
    }
    return;
  }
  if (py::isinstance<py::array>(value)) {
    // ensure() clears the error of an array it cannot convert (strings, objects): the
    // TypeError is raised here, naming the callback (issue 39, found by fuzz/fuzz_python.py).
    auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!array) {
      raise(PyExc_TypeError, what + " " + value_text(value) + " (an array of dtype " +
                                 std::string(py::str(value.attr("dtype"))) + "), expected " +
                                 shape_text(n));
    }
    if (array.size() != n) {
      raise(PyExc_TypeError, what + " an array of " + std::to_string(array.size()) +
                                 " entries, expected " + shape_text(n));
    }
    if (n > 0) std::memcpy(out, array.data(), sizeof(double) * static_cast<std::size_t>(n));
    return;
  }
  if (PySequence_Check(value.ptr()) == 0 || PyUnicode_Check(value.ptr()) != 0) {
    if (n == 1) {
      out[0] = number(value, n, what);
      return;
    }
    raise(PyExc_TypeError, what + " " + value_text(value) + ", expected " + shape_text(n));
  }
  const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
  if (static_cast<int>(items.size()) != n) {
    raise(PyExc_TypeError,
          what + " " + std::to_string(items.size()) + " values, expected " + shape_text(n));
  }
  for (int i = 0; i < n; ++i) out[i] = number(items[static_cast<std::size_t>(i)], n, what);
}

}  // namespace stiction::python
