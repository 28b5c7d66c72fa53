// Rectified pairs (libcam/stereo): points seen by both cameras land on one row of both
// rectified images and their disparity gives back their depth or range, the geometry worked
// by hand from the 3-D points; the rotations against cv::stereoRectify's; the share of each
// image kept against OpenCV's alpha 0 and cv::fisheye::stereoRectify's.

#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <random>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/stereo/rectify.hpp"

using namespace libcam;

namespace {

Camera make_camera(LensType type, std::vector<double> coefficients, ImageSize size, Intrinsics K, const Vec3& rvec,
                   const Vec3& centre) {
    Camera camera;
    camera.size = size;
    camera.intrinsics = K;
    camera.lens = {type, std::move(coefficients)};
    camera.pose = Pose::from_centre(rotation_from_rvec(rvec), centre);
    return camera;
}

// A point of the world in a rectified camera's frame.
Vec3 in_rectified(const Camera& rectified, const Vec3& world) { return rectified.pose.camera_from_world(world); }

// A pinhole's pixel and LATLON's (column azimuth asin(x / |p|), row elevation atan2(y, z)),
// by hand from the rectified camera's K.
Vec2 rectified_pixel(LensType model, const Intrinsics& K, const Vec3& p) {
    if (model == LensType::Pinhole) return {K.fx * p.x() / p.z() + K.cx, K.fy * p.y() / p.z() + K.cy};
    return {K.fx * std::atan2(p.x(), std::hypot(p.y(), p.z())) + K.cx, K.fy * std::atan2(p.y(), p.z()) + K.cy};
}

bool inside(const Vec2& q, const ImageSize& size) {
    return q.x() >= 0 && q.y() >= 0 && q.x() <= static_cast<double>(size.width - 1) &&
           q.y() <= static_cast<double>(size.height - 1);
}

// Random points the two source cameras both see: directions within `half_angle` of the
// first camera's axis, 1 to 20 units away.
std::vector<Vec3> points_seen_by_both(const Camera& first, const Camera& second, double half_angle, std::size_t count) {
    const PreparedCamera a(first), b(second);
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), distance(1.0, 20.0);
    std::vector<Vec3> points;
    for (int tries = 0; points.size() < count && tries < 200000; ++tries) {
        const double theta = half_angle * std::sqrt(std::abs(unit(random))), phi = std::numbers::pi * unit(random);
        const Vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        const Vec3 world = first.pose.world_direction_from_camera(d) * distance(random) + first.pose.centre();
        const Projection pa = a.project(world), pb = b.project(world);
        if (pa.valid && pb.valid && inside(pa.pixel, first.size) && inside(pb.pixel, second.size)) points.push_back(world);
    }
    return points;
}

// Rows agree within 1e-6 px, depth (PINHOLE) or range (LATLON) from the disparity within 1e-7
// of the truth, the rectified x axis along the baseline within 1e-9 rad, one orientation.
void check_geometry(const RectifiedPair& pair, const Camera& first, const Camera& second, double half_angle) {
    const Camera& r0 = pair.cameras[0].camera;
    const Camera& r1 = pair.cameras[1].camera;
    CHECK((r0.pose.R - r1.pose.R).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(r0.intrinsics.fx == r1.intrinsics.fx);
    CHECK(r0.intrinsics.fy == r1.intrinsics.fy);
    CHECK(r0.intrinsics.cy == r1.intrinsics.cy);
    const Vec3 baseline = second.pose.centre() - first.pose.centre();
    CHECK(std::abs(pair.baseline - baseline.norm()) < 1e-15 * (1 + baseline.norm()) * 10);
    const Vec3 x_axis = r0.pose.R.row(0).transpose();  // the rectified x axis in the world
    CHECK(std::atan2(x_axis.cross(baseline).norm(), x_axis.dot(baseline)) < 1e-9);

    const std::vector<Vec3> points = points_seen_by_both(first, second, half_angle, 400);
    REQUIRE(points.size() > 100);
    double worst_row = 0, worst_depth = 0;
    std::size_t used = 0;
    for (const Vec3& world : points) {
        const Vec3 p0 = in_rectified(r0, world), p1 = in_rectified(r1, world);
        const Vec2 q0 = rectified_pixel(pair.model, r0.intrinsics, p0), q1 = rectified_pixel(pair.model, r1.intrinsics, p1);
        if (!inside(q0, r0.size) || !inside(q1, r1.size)) continue;
        ++used;
        worst_row = std::max(worst_row, std::abs(q0.y() - q1.y()));
        const double disparity = q0.x() - q1.x();
        if (pair.model == LensType::Pinhole) {
            const Vec3 back = point_from_disparity(pair, q0, disparity);
            worst_depth = std::max(worst_depth, std::abs(back.z() - p0.z()) / p0.z());
        } else {
            const double range = range_from_disparity(pair, q0, disparity);
            worst_depth = std::max(worst_depth, std::abs(range - p0.norm()) / p0.norm());
        }
    }
    INFO("points used " << used << ", rows apart by up to " << worst_row << " px, depth or range off by up to "
                        << worst_depth);
    REQUIRE(used > 50);
    CHECK(worst_row < 1e-6);
    CHECK(worst_depth < 1e-7);
}

cv::Mat cv_matrix(const auto& m) {
    cv::Mat out;
    cv::eigen2cv(Eigen::MatrixXd(m), out);
    return out;
}

// OpenCV's rectified first camera as a libcam camera: P1's K, turned by R1.
Camera opencv_rectified(const cv::Mat& P, const cv::Mat& R, const Camera& source, const cv::Size& size) {
    Camera camera;
    camera.size = {size.width, size.height};
    camera.intrinsics = {P.at<double>(0, 0), P.at<double>(1, 1), P.at<double>(0, 2), P.at<double>(1, 2), 0.0};
    camera.lens = {LensType::Pinhole, {}};
    Mat3 rotation;
    cv::cv2eigen(R, rotation);
    camera.pose = {rotation * source.pose.R, rotation * source.pose.t};
    return camera;
}

struct NarrowCase {
    const char* name;
    LensType type;
    std::vector<double> first, second;
};

}  // namespace

TEST_CASE("Narrow pairs rectify to a pinhole: rows, depth and the baseline, against cv::stereoRectify") {
    const ImageSize size{640, 480};
    for (const NarrowCase& c : {NarrowCase{"OPENCV5", LensType::OpenCv5, {-0.21, 0.06, 8e-4, -5e-4, -0.012},
                                           {-0.19, 0.045, -3e-4, 6e-4, -0.004}},
                                NarrowCase{"OPENCV4", LensType::OpenCv4, {-0.12, 0.02, 4e-4, 2e-4}, {-0.1, 0.015, -2e-4, 5e-4}}}) {
        INFO(c.name);
        const Camera first = make_camera(c.type, c.first, size, {520.0, 516.0, 318.5, 243.25, 0.0}, Vec3::Zero(), Vec3::Zero());
        const Camera second = make_camera(c.type, c.second, size, {512.0, 510.5, 325.0, 236.5, 0.0},
                                          Vec3(0.012, -0.018, 0.006), Vec3(0.12, 0.004, -0.003));
        const RectifiedPair pair = rectify_pair(first, second);
        INFO(pair.why);
        REQUIRE(pair.model == LensType::Pinhole);
        check_geometry(pair, first, second, 0.55);

        // OpenCV's rectification of the same pair (alpha 0, its default zero disparity).
        cv::Mat K1 = cv_matrix(first.intrinsics.K()), K2 = cv_matrix(second.intrinsics.K());
        cv::Mat D1(c.first, true), D2(c.second, true);
        const Mat3 R = second.pose.R * first.pose.R.transpose();
        const Vec3 T = second.pose.t - R * first.pose.t;
        cv::Mat R1, R2, P1, P2, Q;
        cv::stereoRectify(K1, D1, K2, D2, cv::Size(640, 480), cv_matrix(R), cv_matrix(T), R1, R2, P1, P2, Q,
                          cv::CALIB_ZERO_DISPARITY, 0.0);
        Mat3 cv_R1, cv_R2;
        cv::cv2eigen(R1, cv_R1);
        cv::cv2eigen(R2, cv_R2);
        CHECK((cv_R1 - pair.cameras[0].rotation).cwiseAbs().maxCoeff() < 1e-12);
        CHECK((cv_R2 - pair.cameras[1].rotation).cwiseAbs().maxCoeff() < 1e-12);
        // P: the same form (one f, one principal point, the second's x offset -f b); OpenCV's
        // view from a 9x9 grid of undistorted points, libcam's from every border pixel.
        const Intrinsics& K = pair.cameras[0].camera.intrinsics;
        const double f_cv = P1.at<double>(0, 0);
        std::printf("%s: f libcam %.6f, OpenCV %.6f; principal point libcam (%.4f, %.4f), OpenCV (%.4f, %.4f)\n",
                    c.name, K.fx, f_cv, K.cx, K.cy, P1.at<double>(0, 2), P1.at<double>(1, 2));
        CHECK(std::abs(K.fx - f_cv) < 0.01 * f_cv);
        CHECK(std::abs(K.cx - P1.at<double>(0, 2)) < 0.05);
        CHECK(std::abs(K.cy - P1.at<double>(1, 2)) < 0.05);
        CHECK(P1.at<double>(0, 2) == P2.at<double>(0, 2));
        CHECK(std::abs(P2.at<double>(0, 3) / P2.at<double>(0, 0) + pair.baseline) < 1e-12);
        // Q: OpenCV's and libcam's from the same formula; -1/Tx is 1 / baseline.
        CHECK(std::abs(Q.at<double>(3, 2) - pair.Q(3, 2)) < 1e-9 * std::abs(pair.Q(3, 2)));
        CHECK(pair.Q(2, 3) == K.fx);
        CHECK(pair.Q(0, 3) == -K.cx);
        CHECK(pair.Q(1, 3) == -K.cy);
        // The share of each source image kept, counted the same way for both, and the black
        // border of each view (pixels whose source is off the source image's pixels' area),
        // counted with OpenCV's own maps (cv::initUndistortRectifyMap): libcam's has none, and
        // keeps at least as much as OpenCV's alpha 0 wherever OpenCV's view has none either.
        for (std::size_t k = 0; k < 2; ++k) {
            const Camera& source = k == 0 ? first : second;
            const cv::Mat& K_source = k == 0 ? K1 : K2;
            const cv::Mat& D_source = k == 0 ? D1 : D2;
            const Camera cv_camera = opencv_rectified(k == 0 ? P1 : P2, k == 0 ? R1 : R2, source, cv::Size(640, 480));
            const double opencv_kept = kept_share(PreparedCamera(source), PreparedCamera(cv_camera), k == 0 ? cv_R1 : cv_R2);
            const auto black = [&](const cv::Mat& R_rect, const cv::Mat& K_rect) {
                cv::Mat map_x, map_y;
                cv::initUndistortRectifyMap(K_source, D_source, R_rect, K_rect, cv::Size(640, 480), CV_32FC1, map_x, map_y);
                int outside = 0;
                for (int y = 0; y < map_x.rows; ++y)
                    for (int x = 0; x < map_x.cols; ++x) {
                        const float u = map_x.at<float>(y, x), v = map_y.at<float>(y, x);
                        outside += (u < -0.5f || v < -0.5f || u > 639.5f || v > 479.5f) ? 1 : 0;
                    }
                return outside;
            };
            const int black_libcam = black(cv_matrix(pair.cameras[k].rotation), cv_matrix(pair.cameras[k].camera.intrinsics.K()));
            const int black_opencv = black(k == 0 ? R1 : R2, (k == 0 ? P1 : P2).colRange(0, 3));
            std::printf("%s camera %zu: kept libcam %.6f, OpenCV %.6f; pixels without a source: libcam %d, OpenCV %d\n",
                        c.name, k, pair.cameras[k].kept, opencv_kept, black_libcam, black_opencv);
            CHECK(black_libcam == 0);
            CHECK((pair.cameras[k].kept >= opencv_kept || black_opencv > 0));
        }

        // Keep::All keeps every pixel.
        RectifyRequest all;
        all.keep = Keep::All;
        const RectifiedPair whole = rectify_pair(first, second, all);
        CHECK(whole.cameras[0].kept == 1.0);
        CHECK(whole.cameras[1].kept == 1.0);
        check_geometry(whole, first, second, 0.55);
    }
}

TEST_CASE("A T265-like fisheye pair rectifies to LATLON and keeps its view, where cv::fisheye::stereoRectify does not") {
    // The RealSense T265's two Kannala-Brandt lenses as basalt calibrated them (188 and 185
    // degrees across), 6.3 cm apart, from basalt's t265_kb4_calib.json.
    const ImageSize size{848, 800};
    const std::vector<double> d1{-0.006762412326815424, 0.045170283325720005, -0.043515167278210636, 0.008374959821591333};
    const std::vector<double> d2{-0.00917659267037002, 0.05074013237676034, -0.04804389088255095, 0.009643678532407407};
    const Pose world_to_first = Pose::from_rvec(Vec3(-0.019400560921204107, 0.004297106513544982, -3.1371630768231658),
                                                Vec3(0.01168633749025138, 0.001504398760782252, -0.0064630649863360295));
    const Pose world_to_second = Pose::from_rvec(Vec3(-0.007982215316109197, 0.002312581685148513, -3.140676931768997),
                                                 Vec3(-0.05148791986202231, 0.000911303166058534, -0.006486932037055609));
    Camera first = make_camera(LensType::Fisheye, d1, size, {286.60144163375526, 286.4617087423328, 422.2765876951761,
                                                             395.2246466040553, 0.0}, Vec3::Zero(), Vec3::Zero());
    Camera second = make_camera(LensType::Fisheye, d2, size, {286.94962264945974, 286.69078453656994, 431.3293011565108,
                                                              390.0750907521924, 0.0}, Vec3::Zero(), Vec3::Zero());
    first.pose = world_to_first;
    second.pose = world_to_second;
    const RectifiedPair pair = rectify_pair(first, second);
    INFO(pair.why);
    REQUIRE(pair.model == LensType::Latlon);
    std::printf("T265 pair: %s\n", pair.why.c_str());
    check_geometry(pair, first, second, 1.35);

    cv::Mat K1 = cv_matrix(first.intrinsics.K()), K2 = cv_matrix(second.intrinsics.K());
    const Mat3 R = second.pose.R * first.pose.R.transpose();
    const Vec3 T = second.pose.t - R * first.pose.t;
    cv::Mat R1, R2, P1, P2, Q;
    cv::fisheye::stereoRectify(K1, cv::Mat(d1, true), K2, cv::Mat(d2, true), cv::Size(848, 800), cv_matrix(R), cv_matrix(T),
                               R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY);
    for (std::size_t k = 0; k < 2; ++k) {
        const Camera& source = k == 0 ? first : second;
        const cv::Mat& cv_R = k == 0 ? R1 : R2;
        Mat3 rotation;
        cv::cv2eigen(cv_R, rotation);
        const Camera cv_camera = opencv_rectified(k == 0 ? P1 : P2, cv_R, source, cv::Size(848, 800));
        const double opencv_kept = kept_share(PreparedCamera(source), PreparedCamera(cv_camera), rotation);
        std::printf("fisheye camera %zu: kept LATLON %.6f, cv::fisheye::stereoRectify %.6f (its f %.3f px, principal "
                    "point (%.1f, %.1f))\n",
                    k, pair.cameras[k].kept, opencv_kept, cv_camera.intrinsics.fx, cv_camera.intrinsics.cx,
                    cv_camera.intrinsics.cy);
        CHECK(pair.cameras[k].kept >= 0.95);
        // OpenCV's pinhole holds about two thirds of the rays, at a tenth of the resolution.
        CHECK(opencv_kept < 0.7);
        CHECK(cv_camera.intrinsics.fx < 0.15 * pair.cameras[k].camera.intrinsics.fx);
    }
}

TEST_CASE("A pair past 180 degrees rectifies to LATLON, rows and ranges right beside and behind the lens") {
    const ImageSize size{640, 480};
    // An equidistant fisheye (FISHEYE, no distortion) of 180 px per radian: 204 degrees across.
    const Camera first = make_camera(LensType::Fisheye, {0, 0, 0, 0}, size, {180.0, 180.0, 319.5, 239.5, 0.0}, Vec3::Zero(),
                                     Vec3::Zero());
    const Camera second = make_camera(LensType::Fisheye, {0, 0, 0, 0}, size, {181.0, 180.5, 321.0, 238.0, 0.0},
                                      Vec3(0.01, 0.02, -0.005), Vec3(0.3, 0.01, 0.02));
    const RectifiedPair pair = rectify_pair(first, second);
    INFO(pair.why);
    REQUIRE(pair.model == LensType::Latlon);
    CHECK(pair.why.find("LATLON") != std::string::npos);
    check_geometry(pair, first, second, 1.7);
    CHECK(pair.cameras[0].kept >= 0.95);
    CHECK(pair.cameras[1].kept >= 0.95);
    // A pinhole cannot be asked to hold it all: it keeps what it can, and says so.
    RectifyRequest pinhole;
    pinhole.model = LensType::Pinhole;
    pinhole.keep = Keep::All;
    const RectifiedPair narrow = rectify_pair(first, second, pinhole);
    CHECK(narrow.why.find("no pinhole holds") != std::string::npos);
    CHECK(narrow.cameras[0].kept < pair.cameras[0].kept);
}

TEST_CASE("Two cameras at one centre, or an invalid one, are refused with the reason") {
    const ImageSize size{320, 240};
    const Camera first = make_camera(LensType::Pinhole, {}, size, {300.0, 300.0, 159.5, 119.5, 0.0}, Vec3::Zero(), Vec3::Zero());
    const Camera turned = make_camera(LensType::Pinhole, {}, size, {300.0, 300.0, 159.5, 119.5, 0.0}, Vec3(0, 0.1, 0), Vec3::Zero());
    CHECK_THROWS_WITH(rectify_pair(first, turned), Catch::Contains("same centre"));
    Camera broken = make_camera(LensType::Pinhole, {}, size, {300.0, 300.0, 159.5, 119.5, 0.0}, Vec3::Zero(), Vec3(0.1, 0, 0));
    broken.intrinsics.fx = -1;
    CHECK_THROWS_WITH(rectify_pair(first, broken), Catch::Contains("second camera"));
    RectifyRequest bad;
    bad.model = LensType::Lonlat;
    CHECK_THROWS_WITH(rectify_pair(first, broken, bad), Catch::Contains("PINHOLE or LATLON"));
}
