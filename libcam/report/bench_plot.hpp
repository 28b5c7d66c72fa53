#pragma once
// The picture of `libcam bench --plot`: for each camera, time per point against worst
// reprojection error of every unprojection method (one thread), both on log axes: the
// Pareto front of speed and accuracy.

#include <vector>

#include "libcam/check/bench.hpp"
#include "libcam/report/image.hpp"

namespace libcam {

// One panel per camera, two panels to a line. Throws Error when no row is an
// unprojection on one thread with a measured error.
Image plot_speed_accuracy(const std::vector<BenchRow>& rows);

}  // namespace libcam
