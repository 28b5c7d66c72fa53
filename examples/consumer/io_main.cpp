// Reads a camera file (libcam JSON, OpenCV YAML or XML) with an installed libcam::io
// (no OpenCV, mrcal or Ceres anywhere in the build) and prints the ray through the
// lower-left pixel (pixel (0, 0) counted from the bottom, as a graphics camera counts).
// A file of a format that needs libcam::interop (mrcal's .cameramodel) is refused with
// a message that says so. Built as consumer_interop (LIBCAM_CONSUMER_INTEROP, linking
// libcam::interop), it registers interop's formats first and reads that file too.
// Usage: consumer_io CAMERA_FILE

#include <cstdio>
#include <string>

#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#ifdef LIBCAM_CONSUMER_INTEROP
#include "libcam/interop/formats.hpp"
#endif

int main(int argc, char** argv) {
    using namespace libcam;
    if (argc != 2) {
        std::fprintf(stderr, "usage: consumer_io CAMERA_FILE\n");
        return 2;
    }
    try {
#ifdef LIBCAM_CONSUMER_INTEROP
        register_interop_formats();
#endif
        const PreparedCamera camera(read_camera_file(argv[1]).camera);
        const Ray ray = camera.ray(opencv_pixel({0, 0}, PixelOrigin::BottomLeft, camera.camera().size));
        const Camera& description = camera.camera();
        std::printf("model %s size %ldx%ld\n", std::string(lens_info(description.lens.type).name).c_str(),
                    description.size.width, description.size.height);
        std::printf("direction %.17g %.17g %.17g\n", ray.direction.x(), ray.direction.y(), ray.direction.z());
        return ray.valid ? 0 : 1;
    } catch (const Error& error) {
        std::fprintf(stderr, "consumer_io: %s\n", error.what());
        return 1;
    }
}
