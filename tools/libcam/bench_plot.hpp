#pragma once
// The picture of `libcam bench --plot`: for each camera, time per point against worst
// reprojection error of every unprojection method (one thread), both on log axes: the
// Pareto front of speed and accuracy.

#include <vector>

#include "bench_measure.hpp"

namespace libcam::cli {

// The PNG file's bytes.
std::vector<unsigned char> plot_speed_accuracy(const std::vector<BenchRow>& rows);

}  // namespace libcam::cli
