#include "bindings.h"

namespace hexdom::python {
void bind_cad(pybind11::module_& /*m*/) {}
}  // namespace hexdom::python
