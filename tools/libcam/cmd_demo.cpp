// libcam demo: the built-in example. Converts the seed's two cameras to calibrated
// cameras and checks every ray against OpenCV (projectPoints, undistortPoints,
// Rodrigues) and mrcal (mrcal_project).

#include <iomanip>
#include <iostream>
#include <opencv2/calib3d.hpp>
#include <sstream>

#include "commands.hpp"
#include "libcam/convert/fov_convert.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/opencv.hpp"

namespace libcam::cli {

namespace {

struct SeedExample {
    const char* title;
    FovCamera camera;
    std::vector<Vec2> pixels;  // seed pixels (bottom-left origin)
};

std::vector<SeedExample> seed_examples() {
    const ImageSize size{3, 3};
    // Pixel centres, then the lower-left corner (-0.5, -0.5) and the top centre (1, 2.5)
    // of the field of view, which sit on the image edges.
    const std::vector<Vec2> pixels = {{1, 1}, {0, 0}, {-0.5, -0.5}, {1, 2.5}, {2, 2}};
    return {
        {"seed 1: eye (0,0,0), gaze -z, up +y, 90 deg, 3x3",
         FovCamera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0, FovAxis::Both, size}, pixels},
        {"seed 2: eye (0,5,5), target (0,0,0), up +y, 90 deg, 3x3",
         FovCamera::look_at({0, 5, 5}, {0, 0, 0}, {0, 1, 0}, 90.0, FovAxis::Both, size), pixels},
    };
}

std::string vec(const Eigen::VectorXd& v) {
    std::ostringstream out;
    out << std::setprecision(6) << "(";
    for (Eigen::Index i = 0; i < v.size(); ++i) out << (i ? ", " : "") << v(i);
    return out.str() + ")";
}

struct Check {
    std::string name;
    double max_error = 0.0;
    double tolerance = 0.0;
    std::string unit;
    bool pass() const { return max_error <= tolerance; }
};

std::vector<Check> check_example(const SeedExample& example) {
    const Camera camera = to_camera(example.camera);
    const cv::Mat K = opencv_camera_matrix(camera.intrinsics);
    const cv::Mat dist = opencv_distortion(camera.lens);
    const cv::Mat rvec = opencv_vector(camera.pose.rvec());
    const cv::Mat tvec = opencv_vector(camera.pose.t);

    Check seed{"seed formula vs R^T K^-1 (angle)", 0, 1e-15, "rad"};
    Check project{"cv::projectPoints of points on each ray", 0, 1e-9, "px"};
    Check undistort{"cv::undistortPoints vs K^-1 [x, y, 1]", 0, 1e-12, ""};
    Check rodrigues{"cv::Rodrigues(rvec) vs R", 0, 1e-15, ""};
    Check mrcal{"mrcal_project of points on each ray", 0, 1e-9, "px"};

    cv::Mat R_cv;
    cv::Rodrigues(rvec, R_cv);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            rodrigues.max_error = std::max(rodrigues.max_error, std::abs(R_cv.at<double>(r, c) - camera.pose.R(r, c)));

    std::cout << "\n" << example.title << "\n";
    std::cout << "  K    = " << vec(camera.intrinsics.K().reshaped<Eigen::RowMajor>()) << "\n";
    std::cout << "  R    = " << vec(camera.pose.R.reshaped<Eigen::RowMajor>()) << "\n";
    std::cout << "  t    = " << vec(camera.pose.t) << "\n";
    std::cout << "  rvec = " << vec(camera.pose.rvec()) << "\n";
    std::cout << "  P    = " << vec(camera.P().reshaped<Eigen::RowMajor>()) << "\n";

    const PreparedCamera prepared(camera);
    for (const Vec2& seed_pixel : example.pixels) {
        const Vec3 seed_d = example.camera.seed_ray(seed_pixel, PixelOrigin::BottomLeft);
        const Vec2 pixel = opencv_pixel(seed_pixel, PixelOrigin::BottomLeft, camera.size);
        const Ray ray = prepared.ray(pixel);
        seed.max_error = std::max(seed.max_error, angle_between(seed_d, ray.direction));
        std::cout << "  seed pixel " << vec(seed_pixel) << ": d = " << vec(seed_d) << "   OpenCV pixel "
                  << vec(pixel) << "\n";

        std::vector<cv::Point3d> world_points;
        std::vector<Vec3> camera_points;
        for (double depth : {0.5, 1.0, 10.0, 1000.0}) {
            const Vec3 point = ray.origin + depth * ray.direction;
            world_points.emplace_back(point.x(), point.y(), point.z());
            camera_points.push_back(camera.pose.camera_from_world(point));
        }
        std::vector<cv::Point2d> projected;
        cv::projectPoints(world_points, rvec, tvec, K, dist, projected);
        for (const cv::Point2d& p : projected) {
            project.max_error = std::max(project.max_error, (Vec2(p.x, p.y) - pixel).norm());
        }
        for (const Vec2& q : mrcal_project_points(camera, camera_points)) {
            mrcal.max_error = std::max(mrcal.max_error, (q - pixel).norm());
        }
        std::vector<cv::Point2d> undistorted;
        cv::undistortPoints(std::vector<cv::Point2d>{{pixel.x(), pixel.y()}}, undistorted, K, dist);
        const Vec2 expected = camera.intrinsics.normalized_from_pixel(pixel);
        undistort.max_error =
            std::max(undistort.max_error, (Vec2(undistorted[0].x, undistorted[0].y) - expected).norm());
    }
    return {seed, project, undistort, rodrigues, mrcal};
}

}  // namespace

Runner add_demo(CLI::App& app) {
    app.add_subcommand("demo",
                       "The built-in example: convert the seed's cameras and check them against OpenCV and mrcal");
    return [] {
        std::cout << "libcam demo: the seed's cameras (pixel rows counted from the bottom, as in the seed)\n";
        bool all_pass = true;
        std::vector<Check> checks;
        for (const SeedExample& example : seed_examples()) {
            for (Check& check : check_example(example)) {
                check.name = std::string(example.title).substr(0, 6) + ": " + check.name;
                checks.push_back(check);
            }
        }
        std::cout << "\n" << std::left << std::setw(56) << "check" << std::setw(14) << "max error" << std::setw(12)
                  << "tolerance" << "result\n";
        for (const Check& check : checks) {
            std::ostringstream error;
            error << std::setprecision(3) << check.max_error;
            std::cout << std::setw(56) << check.name << std::setw(14) << error.str() << std::setw(12) << check.tolerance
                      << (check.pass() ? "pass" : "FAIL") << "\n";
            all_pass = all_pass && check.pass();
        }
        std::cout << (all_pass ? "\nall checks pass\n" : "\nSOME CHECKS FAILED\n");
        return all_pass ? 0 : 1;
    };
}

}  // namespace libcam::cli
