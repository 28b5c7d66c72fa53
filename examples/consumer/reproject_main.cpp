// Reprojects a set of observations made here (one camera, one view, one point) with an
// installed libcam::reproject. The camera at eye (0,5,5) looks at the origin (90 degrees,
// 3x3 pixels), so the origin projects to the centre pixel (1, 1); observed half a pixel
// to its right, at (1.5, 1), its residual is 0.5 pixels.

#include <cstdio>

#include "libcam/convert/look_at_convert.hpp"
#include "libcam/reproject/reproject.hpp"

int main() {
    using namespace libcam;
    const Camera camera = to_camera(LookAtCamera::look_at({0, 5, 5}, {0, 0, 0}, {0, 1, 0}, 90.0, FovAxis::Both, {3, 3}));
    ObservationSet set;
    set.source = "made by consumer_reproject";
    set.cameras.push_back({"camera", camera});
    set.views.push_back({"view", 0, camera.pose});
    set.points.push_back(Vec3::Zero());
    set.point_ids.push_back(1);
    set.observations.push_back({0, 0, Vec2(1.5, 1.0)});
    const Reprojection result = reproject(set);
    std::printf("residual_px %.17g\n", result.residuals.at(0).error_px);
    return 0;
}
