// Filled in by its own change (docs/python.md).
#include "bindings.hpp"

namespace stiction::python {

void bind_elements(py::module_&) {}

}  // namespace stiction::python
