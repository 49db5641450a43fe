#include "bindings.h"

namespace hexdom::python {
void bind_segmentation(pybind11::module_& /*m*/) {}
}  // namespace hexdom::python
