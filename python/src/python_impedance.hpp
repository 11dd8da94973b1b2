// An impedance whose law is a Python object (a subclass of stiction.Impedance): its sizes,
// state labels, initial state and signals are read once when the scene is built, and
// evaluate() / write_signals() are called with the GIL taken, on NumPy arrays the element
// owns (x_hat and y copied in: a few doubles, and no array made per call).
// The capabilities of the bundled elements follow what the object defines:
// slip_velocity(x_hat) makes it a sliding pair (stick/slip events) and a `stiffness`
// attribute a StiffnessHint (the step check's advice).
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "core/impedance.hpp"

namespace stiction::python {

namespace py = pybind11;

// The element named `name` over the Python object `element`. std::invalid_argument when the
// object's sizes or signals are not what an impedance needs (reported at its scene table).
std::unique_ptr<core::Impedance> make_python_impedance(const std::string& name, py::object element);

}  // namespace stiction::python
