// Converts a look-at camera (eye (0,5,5) looking at the origin, 90 degrees, 3x3) to
// K, R, t with an installed libcam, and prints the ray through pixel (0, 0) counted from
// the bottom-left (as the look-at formula counts it): the lower-left pixel.

#include <cstdio>

#include "libcam/convert/look_at_convert.hpp"
#include "libcam/version.hpp"

int main() {
    using namespace libcam;
    const LookAtCamera fov = LookAtCamera::look_at({0, 5, 5}, {0, 0, 0}, {0, 1, 0}, 90.0, FovAxis::Both, {3, 3});
    const Camera camera = to_camera(fov);
    const Vec2 pixel = opencv_pixel({0, 0}, PixelOrigin::BottomLeft, camera.size);
    const Ray ray = PreparedCamera(camera).ray(pixel);
    std::printf("libcam %s\n", LIBCAM_VERSION);
    std::printf("fx %.17g fy %.17g cx %.17g cy %.17g\n", camera.intrinsics.fx, camera.intrinsics.fy,
                camera.intrinsics.cx, camera.intrinsics.cy);
    std::printf("origin %.17g %.17g %.17g\n", ray.origin.x(), ray.origin.y(), ray.origin.z());
    std::printf("direction %.17g %.17g %.17g\n", ray.direction.x(), ray.direction.y(), ray.direction.z());
    return ray.valid ? 0 : 1;
}
