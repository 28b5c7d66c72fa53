#pragma once
// What the libcam program's commands do, as functions: fit, verify, the new camera for a
// lens, and the remap map between two cameras.

#include <pybind11/pybind11.h>

namespace libcam::python {

void bind_tools(pybind11::module_& m);

}  // namespace libcam::python
