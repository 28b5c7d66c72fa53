#include "libcam/check/worked_examples.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "libcam/convert/look_at_convert.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/opencv.hpp"

namespace libcam {

namespace {

// The two example cameras, and the pixels each one looks at.
std::vector<WorkedExample> worked_examples() {
    const ImageSize size{3, 3};
    // Pixel centres, then the lower-left corner (-0.5, -0.5) and the top centre (1, 2.5)
    // of the field of view, which sit on the image edges.
    const std::vector<Vec2> pixels = {{1, 1}, {0, 0}, {-0.5, -0.5}, {1, 2.5}, {2, 2}};
    std::vector<WorkedExample> examples(2);
    examples[0].name = "example 1";
    examples[0].title = examples[0].name + ": eye (0,0,0), gaze -z, up +y, 90 deg, 3x3";
    examples[0].look_at_camera = LookAtCamera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0, FovAxis::Both, size};
    examples[1].name = "example 2";
    examples[1].title = examples[1].name + ": eye (0,5,5), target (0,0,0), up +y, 90 deg, 3x3";
    examples[1].look_at_camera = LookAtCamera::look_at({0, 5, 5}, {0, 0, 0}, {0, 1, 0}, 90.0, FovAxis::Both, size);
    for (WorkedExample& example : examples) {
        for (const Vec2& pixel : pixels) example.pixels.push_back({pixel, Vec3::Zero(), Vec2::Zero()});
    }
    return examples;
}

void keep_worst(WorkedExampleCheck& check, double error) { check.max_error = std::max(check.max_error, error); }

// cv::Rodrigues(rvec) against R, entry by entry.
double rodrigues_error(const Camera& camera) {
    cv::Mat R_cv;
    cv::Rodrigues(opencv_vector(camera.pose.rvec()), R_cv);
    double worst = 0.0;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(R_cv.at<double>(r, c) - camera.pose.R(r, c)));
    }
    return worst;
}

}  // namespace

std::vector<WorkedExample> check_worked_examples() {
    std::vector<WorkedExample> examples = worked_examples();
    for (WorkedExample& example : examples) {
        const Camera camera = to_camera(example.look_at_camera);
        example.camera = camera;
        const cv::Mat K = opencv_camera_matrix(camera.intrinsics);
        const cv::Mat dist = opencv_distortion(camera.lens);
        const cv::Mat rvec = opencv_vector(camera.pose.rvec());
        const cv::Mat tvec = opencv_vector(camera.pose.t);

        WorkedExampleCheck look_at{"look-at formula vs R^T K^-1 (angle)", 0, 1e-15, "rad"};
        WorkedExampleCheck project{"cv::projectPoints of points on each ray", 0, 1e-9, "px"};
        WorkedExampleCheck undistort{"cv::undistortPoints vs K^-1 [x, y, 1]", 0, 1e-12, ""};
        WorkedExampleCheck rodrigues{"cv::Rodrigues(rvec) vs R", 0, 1e-15, ""};
        WorkedExampleCheck mrcal{"mrcal_project of points on each ray", 0, 1e-9, "px"};
        rodrigues.max_error = rodrigues_error(camera);

        const PreparedCamera prepared(camera);
        for (WorkedExamplePixel& pixel : example.pixels) {
            pixel.look_at_direction = example.look_at_camera.look_at_ray(pixel.bottom_left_pixel, PixelOrigin::BottomLeft);
            pixel.opencv_pixel = opencv_pixel(pixel.bottom_left_pixel, PixelOrigin::BottomLeft, camera.size);
            const Ray ray = prepared.ray(pixel.opencv_pixel);
            keep_worst(look_at, angle_between(pixel.look_at_direction, ray.direction));

            std::vector<cv::Point3d> world_points;
            std::vector<Vec3> camera_points;
            for (double depth : {0.5, 1.0, 10.0, 1000.0}) {
                const Vec3 point = ray.origin + depth * ray.direction;
                world_points.emplace_back(point.x(), point.y(), point.z());
                camera_points.push_back(camera.pose.camera_from_world(point));
            }
            std::vector<cv::Point2d> projected;
            cv::projectPoints(world_points, rvec, tvec, K, dist, projected);
            for (const cv::Point2d& p : projected) keep_worst(project, (Vec2(p.x, p.y) - pixel.opencv_pixel).norm());
            for (const Vec2& q : mrcal_project_points(camera, camera_points)) {
                keep_worst(mrcal, (q - pixel.opencv_pixel).norm());
            }
            std::vector<cv::Point2d> undistorted;
            cv::undistortPoints(std::vector<cv::Point2d>{{pixel.opencv_pixel.x(), pixel.opencv_pixel.y()}}, undistorted, K, dist);
            const Vec2 expected = camera.intrinsics.normalized_from_pixel(pixel.opencv_pixel);
            keep_worst(undistort, (Vec2(undistorted[0].x, undistorted[0].y) - expected).norm());
        }
        example.checks = {look_at, project, undistort, rodrigues, mrcal};
    }
    return examples;
}

}  // namespace libcam
