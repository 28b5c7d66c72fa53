#include "libcam/interop/opencv.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/ccalib/omnidir.hpp>

#include <algorithm>
#include <vector>

#include "libcam/error.hpp"

namespace libcam {

cv::Mat opencv_camera_matrix(const Intrinsics& k) {
    return (cv::Mat_<double>(3, 3) << k.fx, k.skew, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
}

cv::Mat opencv_distortion(const Lens& lens) {
    const OpenCvFunction function = lens_info(lens.type).opencv;
    if (function == OpenCvFunction::None) {
        throw NotRepresentable("lens: OpenCV has no model " + std::string(lens_info(lens.type).name));
    }
    if (function == OpenCvFunction::Omnidir) {
        // xi goes apart (opencv_xi); UCM is cv::omnidir without distortion.
        cv::Mat dist = cv::Mat::zeros(1, 4, CV_64F);
        std::copy(lens.coefficients.begin() + 1, lens.coefficients.end(), dist.ptr<double>());
        return dist;
    }
    cv::Mat dist(1, static_cast<int>(lens.coefficients.size()), CV_64F);
    std::copy(lens.coefficients.begin(), lens.coefficients.end(), dist.ptr<double>());
    return dist;
}

double opencv_xi(const Lens& lens) {
    if (lens_info(lens.type).opencv != OpenCvFunction::Omnidir) {
        throw NotRepresentable("lens: " + std::string(lens_info(lens.type).name) + " is not a cv::omnidir model");
    }
    return lens.coefficients.at(0);
}

cv::Mat opencv_vector(const Vec3& v) { return (cv::Mat_<double>(3, 1) << v.x(), v.y(), v.z()); }

OpenCvCamera::OpenCvCamera(const Camera& camera)
    : function(lens_info(camera.lens.type).opencv),
      K(opencv_camera_matrix(camera.intrinsics)),
      dist(opencv_distortion(camera.lens)),
      xi(function == OpenCvFunction::Omnidir ? opencv_xi(camera.lens) : 0.0) {}

void opencv_project(const OpenCvCamera& camera, cv::InputArray points, cv::OutputArray pixels) {
    const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
    switch (camera.function) {
        case OpenCvFunction::Fisheye: cv::fisheye::projectPoints(points, pixels, zero, zero, camera.K, camera.dist); return;
        case OpenCvFunction::Omnidir:
            cv::omnidir::projectPoints(points, pixels, zero, zero, camera.K, camera.xi, camera.dist);
            return;
        case OpenCvFunction::ProjectPoints: cv::projectPoints(points, zero, zero, camera.K, camera.dist, pixels); return;
        case OpenCvFunction::None: break;
    }
    throw NotRepresentable("lens: OpenCV has no model for this camera");
}

void opencv_undistort(const OpenCvCamera& camera, cv::InputArray pixels, cv::OutputArray normalized,
                      const std::optional<cv::TermCriteria>& criteria) {
    switch (camera.function) {
        case OpenCvFunction::Fisheye:
            if (criteria) cv::fisheye::undistortPoints(pixels, normalized, camera.K, camera.dist, cv::noArray(), cv::noArray(), *criteria);
            else cv::fisheye::undistortPoints(pixels, normalized, camera.K, camera.dist);
            return;
        case OpenCvFunction::Omnidir: {
            if (criteria) throw InvalidArgument("criteria: cv::omnidir::undistortPoints has no stopping rule to set");
            // OpenCV 4.6's gives (x/z, y/z) of the ray (newer sources give the point of the
            // unified model's plane).
            const cv::Mat xi(1, 1, CV_64F, cv::Scalar(camera.xi));
            cv::omnidir::undistortPoints(pixels, normalized, camera.K, camera.dist, xi, cv::noArray());
            return;
        }
        case OpenCvFunction::ProjectPoints:
            if (criteria) cv::undistortPoints(pixels, normalized, camera.K, camera.dist, cv::noArray(), cv::noArray(), *criteria);
            else cv::undistortPoints(pixels, normalized, camera.K, camera.dist);
            return;
        case OpenCvFunction::None: break;
    }
    throw NotRepresentable("lens: OpenCV has no model for this camera");
}

std::vector<Vec2> opencv_project_points(const Camera& camera, const std::vector<Vec3>& camera_points) {
    camera.validate();
    if (camera_points.empty()) return {};
    std::vector<cv::Point3d> object;
    for (const Vec3& p : camera_points) object.emplace_back(p.x(), p.y(), p.z());
    std::vector<cv::Point2d> image;
    opencv_project(OpenCvCamera(camera), object, image);
    std::vector<Vec2> pixels;
    for (const cv::Point2d& q : image) pixels.emplace_back(q.x, q.y);
    return pixels;
}

}  // namespace libcam
