// Filled in by its own change (docs/python.md).
#include "bindings.hpp"

namespace stiction::python {

void bind_pictures(py::module_&) {}

}  // namespace stiction::python
