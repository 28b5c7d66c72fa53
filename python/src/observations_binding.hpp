#pragma once
// libcam.read_observations and libcam.reproject: a calibration's or reconstruction's own
// observations, and their residuals as numpy arrays (as `libcam reproject` prints them).

#include <pybind11/pybind11.h>

namespace libcam::python {

void bind_observations(pybind11::module_& m);

}  // namespace libcam::python
