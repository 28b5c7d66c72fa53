// libcam::stereo from the installed package: two pinholes side by side, 0.5 apart, looking
// the same way, rectified; a point 4 in front of the first camera gives, by hand, the
// disparity f b / Z and back its depth 4.

#include <cstdio>

#include "libcam/stereo/rectify.hpp"

int main() {
    libcam::Camera left;
    left.size = {640, 480};
    left.intrinsics = {500.0, 500.0, 319.5, 239.5, 0.0};
    libcam::Camera right = left;
    right.pose = libcam::Pose::from_centre(libcam::Mat3::Identity(), libcam::Vec3(0.5, 0.0, 0.0));
    const libcam::RectifiedPair pair = libcam::rectify_pair(left, right);
    const double f = pair.cameras[0].camera.intrinsics.fx;
    const libcam::Vec2 pixel(pair.cameras[0].camera.intrinsics.cx, pair.cameras[0].camera.intrinsics.cy);
    const libcam::Vec3 point = libcam::point_from_disparity(pair, pixel, f * 0.5 / 4.0);
    std::printf("baseline %.17g depth %.17g\n", pair.baseline, point.z());
    return 0;
}
