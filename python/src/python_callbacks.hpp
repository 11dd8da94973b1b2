// What the C++ side of a Python callback needs, shared by source laws (bind_elements.cpp)
// and impedances (python_impedance.cpp), which run with the GIL released (stiction.run)
// and take it per call:
// - Python references that C++ objects keep (a scene's law, its element) are released
//   under the GIL, wherever the scene holding them dies (a sweep's worker thread too);
// - a callback's return value read into doubles, a wrong shape or type raised as a Python
//   TypeError. Errors go up as py::error_already_set, which is not a std::runtime_error:
//   the simulation loop takes those for an integrator's failure, this one must stop the run
//   and reach the caller of stiction.run as the exception Python raised.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

namespace stiction::python {

namespace py = pybind11;

// A reference to `object` that may be dropped on any thread: its last owner takes the GIL.
std::shared_ptr<py::object> keep(py::object object);

// Raises `type` with `message` as the pending Python error and throws it as
// py::error_already_set.
[[noreturn]] void raise(PyObject* type, const std::string& message);

// repr(value) for a message, at most about 200 characters; the type's name when repr fails.
std::string value_text(py::handle value);

// Reads `n` doubles from `value` (a number when n == 1, else a sequence or NumPy array of n
// numbers) into `out`. `what` names the value in the TypeError ("source 'motor' returned");
// an int beyond a double's range is an OverflowError that names it too.
void read_values(py::handle value, double* out, int n, const std::string& what);

}  // namespace stiction::python
