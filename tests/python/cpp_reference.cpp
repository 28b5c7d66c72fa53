// The C++ API's answers for the Python tests, which check that the module gives the same
// bits: reads a camera file and a file of raw float64 inputs, writes raw float64 outputs,
// each point's coordinates followed by 1 (valid) or 0.
//
//   cpp_reference CAMERA OPERATION INPUT OUTPUT
//
//   project            world points (x y z)   -> PreparedCamera::project: pixel (x y)
//   project-float      camera points          -> Projector<float>: pixel, in float
//   unproject-METHOD   pixels (x y)           -> Unprojector<double>, METHOD exact|fast|lut: direction
//   unproject-float    pixels                 -> Unprojector<float>, exact: direction, in float
//   rays               pixels                 -> PreparedCamera::rays: unit world direction

#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/formats.hpp"
#include "libcam/io/camera_file.hpp"

namespace {

std::vector<double> read_doubles(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<double> values(bytes.size() / sizeof(double));
    std::copy(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(values.size() * sizeof(double)),
              reinterpret_cast<char*>(values.data()));
    return values;
}

void write_doubles(const std::string& path, const std::vector<double>& values) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(double)));
}

template <class T, int K>
void append_point(std::vector<double>& out, const T (&coordinates)[K], bool valid) {
    for (int i = 0; i < K; ++i) out.push_back(double(coordinates[i]));
    out.push_back(valid ? 1.0 : 0.0);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 5) {
        std::cerr << "usage: cpp_reference CAMERA OPERATION INPUT OUTPUT\n";
        return 2;
    }
    try {
        libcam::register_interop_formats();
        const libcam::PreparedCamera camera(libcam::read_camera_file(argv[1]).camera);
        const std::string operation = argv[2];
        const std::vector<double> in = read_doubles(argv[3]);
        std::vector<double> out;
        if (operation == "project") {
            std::vector<libcam::Vec3> points;
            for (std::size_t i = 0; i + 2 < in.size(); i += 3) points.emplace_back(in[i], in[i + 1], in[i + 2]);
            for (const libcam::Projection& p : camera.project(points)) {
                append_point<double, 2>(out, {p.pixel.x(), p.pixel.y()}, p.valid);
            }
        } else if (operation == "project-float") {
            libcam::Points3<float> points;
            for (std::size_t i = 0; i + 2 < in.size(); i += 3) {
                points.x.push_back(float(in[i])), points.y.push_back(float(in[i + 1])), points.z.push_back(float(in[i + 2]));
            }
            libcam::Points2<float> pixels;
            libcam::ValidFlags valid;
            libcam::Projector<float>(camera).project(points, pixels, valid);
            for (std::size_t i = 0; i < valid.size(); ++i) append_point<float, 2>(out, {pixels.x[i], pixels.y[i]}, valid[i]);
        } else if (operation.rfind("unproject-", 0) == 0) {
            const std::string method_name = operation.substr(10);
            const bool in_float = method_name == "float";
            const std::optional<libcam::UnprojectMethod> method =
                in_float ? libcam::UnprojectMethod::Exact : libcam::method_from_name(method_name);
            if (!method) throw libcam::InvalidArgument("operation: unknown method '" + method_name + "'");
            const auto run = [&]<class T>(const libcam::Unprojector<T>& unprojector) {
                libcam::Points2<T> pixels;
                for (std::size_t i = 0; i + 1 < in.size(); i += 2) pixels.x.push_back(T(in[i])), pixels.y.push_back(T(in[i + 1]));
                libcam::Points3<T> directions;
                libcam::ValidFlags valid;
                unprojector.unproject(pixels, *method, directions, valid);
                for (std::size_t i = 0; i < valid.size(); ++i) {
                    append_point<T, 3>(out, {directions.x[i], directions.y[i], directions.z[i]}, valid[i]);
                }
            };
            if (in_float) {
                run(libcam::Unprojector<float>(camera));
            } else {
                run(camera.unprojector());
            }
        } else if (operation == "rays") {
            std::vector<libcam::Vec2> pixels;
            for (std::size_t i = 0; i + 1 < in.size(); i += 2) pixels.emplace_back(in[i], in[i + 1]);
            for (const libcam::Ray& ray : camera.rays(pixels)) {
                append_point<double, 3>(out, {ray.direction.x(), ray.direction.y(), ray.direction.z()}, ray.valid);
            }
        } else {
            throw libcam::InvalidArgument("operation: unknown '" + operation + "'");
        }
        write_doubles(argv[4], out);
    } catch (const std::exception& error) {
        std::cerr << "cpp_reference: " << error.what() << "\n";
        return 1;
    }
    return 0;
}
