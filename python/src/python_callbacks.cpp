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

namespace {

std::string shape_text(int n) {
  return n == 1 ? "a number" : "a sequence of " + std::to_string(n) + " numbers";
}

double number(py::handle item, int n, const std::string& what) {
  const double v = PyFloat_AsDouble(item.ptr());
  if (v == -1.0 && PyErr_Occurred() != nullptr) {
    PyErr_Clear();
    raise(PyExc_TypeError,
          what + " " + std::string(py::repr(item)) + ", expected " + shape_text(n));
  }
  return v;
}

}  // namespace

void read_values(py::handle value, double* out, int n, const std::string& what) {
  if (n == 1 && (PyFloat_Check(value.ptr()) || PyLong_Check(value.ptr()))) {
    out[0] = PyFloat_AsDouble(value.ptr());
    if (out[0] == -1.0 && PyErr_Occurred() != nullptr) throw py::error_already_set();
    return;
  }
  if (py::isinstance<py::array>(value)) {
    auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!array) throw py::error_already_set();
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
    raise(PyExc_TypeError,
          what + " " + std::string(py::repr(value)) + ", expected " + shape_text(n));
  }
  const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
  if (static_cast<int>(items.size()) != n) {
    raise(PyExc_TypeError,
          what + " " + std::to_string(items.size()) + " values, expected " + shape_text(n));
  }
  for (int i = 0; i < n; ++i) out[i] = number(items[static_cast<std::size_t>(i)], n, what);
}

}  // namespace stiction::python
