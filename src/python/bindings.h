// Each stage's Python bindings live in their own bind_<stage>.cpp and are registered here.
#pragma once

#include <pybind11/pybind11.h>

namespace hexdom::python {
void bind_segmentation(pybind11::module_& m);
void bind_cad(pybind11::module_& m);
void bind_auto(pybind11::module_& m);
}  // namespace hexdom::python
