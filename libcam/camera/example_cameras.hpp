#pragma once
// A few calibrated cameras to try libcam on (`libcam bench --case NAME`) and to test it
// with: one copy of each, used by the command line, the benchmarks and the tests.

#include <string_view>
#include <vector>

#include "libcam/camera/camera.hpp"

namespace libcam {

struct ExampleCamera {
    std::string_view name;
    std::string_view description;
    Camera camera;
};

// "mild" and "strong" OPENCV8 lenses (the strong one folds over inside the image's
// corners), "fisheye" (FISHEYE, its corners past 90 degrees from the axis), and "wide": a
// real calibrated wide-angle lens (6016x4016, OPENCV8).
std::vector<ExampleCamera> example_cameras();

// The example camera of that name; throws InvalidArgument naming the choices otherwise.
Camera example_camera(std::string_view name);

}  // namespace libcam
