// Fits the simplest lens model to a 60-degree graphics camera through an installed
// libcam::fit: the look-at form itself (LOOK_AT), within a pixel over the whole image.

#include <cstdio>
#include <string>

#include "libcam/convert/look_at_convert.hpp"
#include "libcam/fit/fit.hpp"

int main() {
    using namespace libcam;
    const LookAtCamera fov = LookAtCamera::look_at({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 60.0, FovAxis::Horizontal, {640, 480});
    const FitReport report = fit_scene(to_camera(fov), Scene::whole_image(), FitOptions{});
    if (!report.chosen) {
        std::printf("no candidate within the tolerance\n");
        return 1;
    }
    const CandidateReport& chosen = report.candidates[*report.chosen];
    std::printf("chosen %s max %.3g px\n", std::string(chosen.fit.candidate.name).c_str(), chosen.max_px);
}
