#pragma once
// `libcam dataset` from Python (libcam.dataset): the whole job in this process, or its
// plan: the model written and one picklable task per image, to run in other processes
// or on other machines (Dask, multiprocessing, a queue of one's own).

#include <pybind11/pybind11.h>

namespace libcam::python {

void bind_dataset(pybind11::module_& m);

}  // namespace libcam::python
