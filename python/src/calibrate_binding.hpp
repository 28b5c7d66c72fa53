#pragma once
// libcam.calibrate: board images, or the corners found in them, to a calibration, as the
// libcam program's calibrate command reports it.

#include <pybind11/pybind11.h>

namespace libcam::python {

void bind_calibrate(pybind11::module_& m);

}  // namespace libcam::python
