// Cross-checks against OpenCV: every expected pixel, normalised point and rotation
// comes from OpenCV's calib3d (projectPoints, undistortPoints, Rodrigues) or from the
// look-at formula worked here by hand; libcam only supplies the inputs.

#include <catch2/catch.hpp>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "libcam/convert/look_at_convert.hpp"
#include "libcam/interop/opencv.hpp"
#include "opencv_k.hpp"
#include "support.hpp"

using namespace libcam;
using libcam::test::check_opencv_k;
using libcam::test::random_look_at_camera;
using libcam::test::uniform;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

const ImageSize kSizes[] = {{1920, 1080}, {640, 4000}, {4000, 500}, {1000, 1000}, {3, 3}, {1, 1}, {7, 2}};

// At least 20 random look-at cameras over every axis and size, plus the extreme angles.
std::vector<LookAtCamera> test_cameras() {
    std::vector<LookAtCamera> cameras;
    for (int i = 0; i < 28; ++i) {
        const ImageSize size = kSizes[i % std::size(kSizes)];
        const FovAxis axis = libcam::test::random_axis(i);
        if (i % 7 == 3) cameras.push_back(random_look_at_camera(size, axis, 1.0, 1.0 + 1e-9));
        else if (i % 7 == 5) cameras.push_back(random_look_at_camera(size, axis, 179.0 - 1e-9, 179.0));
        else cameras.push_back(random_look_at_camera(size, axis));
    }
    return cameras;
}

// Pixels across the image: the four corners as pixel centres (0, W-1) and as image
// edges (-0.5, W-0.5), the centre and an interior third.
std::vector<Vec2> pixel_grid(const ImageSize& size) {
    const double W = static_cast<double>(size.width);
    const double H = static_cast<double>(size.height);
    const std::vector<double> xs{-0.5, 0.0, W / 3.0, (W - 1.0) / 2.0, W - 1.0, W - 0.5};
    const std::vector<double> ys{-0.5, 0.0, H / 3.0, (H - 1.0) / 2.0, H - 1.0, H - 0.5};
    std::vector<Vec2> pixels;
    for (double y : ys)
        for (double x : xs) pixels.emplace_back(x, y);
    return pixels;
}

cv::Mat cv_K(const Intrinsics& k) {
    // Written out here rather than through libcam's opencv_camera_matrix, so a
    // transposed or misplaced entry there cannot hide here (it is checked below).
    return (cv::Mat_<double>(3, 3) << k.fx, k.skew, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
}
cv::Mat cv_vec(const Vec3& v) { return (cv::Mat_<double>(3, 1) << v.x(), v.y(), v.z()); }
Mat3 eigen_from_cv(const cv::Mat& m) {
    Mat3 out;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out(r, c) = m.at<double>(r, c);
    return out;
}
Vec3 vec_from_cv(const cv::Mat& m) { return {m.at<double>(0), m.at<double>(1), m.at<double>(2)}; }

std::vector<Vec2> cv_project(const std::vector<Vec3>& world, const Camera& camera) {
    std::vector<cv::Point3d> object;
    for (const Vec3& p : world) object.emplace_back(p.x(), p.y(), p.z());
    std::vector<cv::Point2d> image;
    const cv::Mat dist = cv::Mat::zeros(1, 5, CV_64F);  // as calibrateCamera reports a pinhole
    cv::projectPoints(object, cv_vec(camera.pose.rvec()), cv_vec(camera.pose.t), cv_K(camera.intrinsics), dist, image);
    std::vector<Vec2> out;
    for (const cv::Point2d& q : image) out.emplace_back(q.x, q.y);
    return out;
}

// Worst-case pixel error of an exact projection evaluated in double precision: the
// world point X = C + s d is rounded relative to |C| + s, R X + t cancels down to a
// camera point of depth ~s, so its direction carries a relative error of a few
// eps (|C| + s)/s, which the projection multiplies by f (1 + |m|^2). Where that is
// below 1e-9 px (almost everywhere) the bound asked for, 1e-9 px, is used as is.
double pixel_tolerance(const Camera& camera, const Vec2& pixel, double depth) {
    const Vec2 m = camera.intrinsics.normalized_from_pixel(pixel);
    const double f = std::max(camera.intrinsics.fx, camera.intrinsics.fy);
    const double conditioning = 16.0 * kEps * f * (1.0 + m.squaredNorm()) * (camera.pose.centre().norm() + depth) / depth;
    return std::max(1e-9, conditioning);
}

// The look-at formula's ray, worked here by hand, with the half-angle tangents per axis
// as docs/conventions.md ("Field-of-view axis") states them.
Vec3 hand_look_at_ray(const LookAtCamera& c, double x, double y) {
    const double W = static_cast<double>(c.size.width);
    const double H = static_cast<double>(c.size.height);
    const double t = std::tan(c.fov_deg * std::numbers::pi / 360.0);
    double tx = t, ty = t;
    switch (c.fov_axis) {
        case FovAxis::Both: break;
        case FovAxis::Horizontal: ty = t * H / W; break;
        case FovAxis::Vertical: tx = t * W / H; break;
        case FovAxis::Diagonal: tx = t * W / std::sqrt(W * W + H * H); ty = t * H / std::sqrt(W * W + H * H); break;
    }
    const Vec3 w = c.gaze.normalized();
    const Vec3 u = w.cross(c.up).normalized();
    const Vec3 v = u.cross(w);
    const double alpha = tx * (2.0 * x - W + 1.0) / W;
    const double beta = ty * (2.0 * y - H + 1.0) / H;
    return alpha * u + beta * v + w;
}

double max_abs(const Mat3& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("cv::projectPoints maps points along the ray through a pixel back to the pixel", "[opencv]") {
    const std::vector<double> depths{0.5, 3.0, 100.0, 1e4};
    int checked = 0;
    double worst_over_tolerance = 0.0;
    for (const LookAtCamera& fov : test_cameras()) {
        const Camera camera = to_camera(fov);
        const PreparedCamera prepared(camera);
        CAPTURE(fov.size.width, fov.size.height, fov.fov_deg, to_string(fov.fov_axis));
        for (const Vec2& pixel : pixel_grid(fov.size)) {
            const Ray ray = prepared.ray(pixel);
            REQUIRE(ray.valid);
            std::vector<Vec3> world;
            for (double depth : depths) world.push_back(ray.origin + depth * ray.direction);
            const std::vector<Vec2> projected = cv_project(world, camera);
            for (std::size_t i = 0; i < depths.size(); ++i) {
                const double error = (projected[i] - pixel).cwiseAbs().maxCoeff();
                const double tolerance = pixel_tolerance(camera, pixel, depths[i]);
                worst_over_tolerance = std::max(worst_over_tolerance, error / tolerance);
                CAPTURE(pixel.x(), pixel.y(), depths[i], projected[i].x(), projected[i].y(), tolerance);
                CHECK(error <= tolerance);
                ++checked;
            }
        }
    }
    CHECK(checked >= 20 * 36 * 4);
    CHECK(worst_over_tolerance <= 1.0);
}

TEST_CASE("cv::projectPoints meets 1e-9 px flat when the camera sits near the origin", "[opencv]") {
    // Same check with the eye moved to within 1 of the origin, where double precision
    // allows 1e-9 px at every depth and fov (measured worst: ~3e-10 px at fov 1 degree,
    // fx ~ 2.3e5): no conditioning allowance at all.
    for (int i = 0; i < 24; ++i) {
        LookAtCamera fov = i % 3 == 0 ? random_look_at_camera(kSizes[i % 3], libcam::test::random_axis(i), 1.0, 1.0 + 1e-9)
                                   : random_look_at_camera(kSizes[i % 3], libcam::test::random_axis(i));
        fov.eye = libcam::test::random_vector(1.0);
        const Camera camera = to_camera(fov);
        const PreparedCamera prepared(camera);
        CAPTURE(fov.size.width, fov.size.height, fov.fov_deg, to_string(fov.fov_axis));
        for (const Vec2& pixel : pixel_grid(fov.size)) {
            const Ray ray = prepared.ray(pixel);
            std::vector<Vec3> world;
            for (double depth : {0.5, 3.0, 100.0, 1e4}) world.push_back(ray.origin + depth * ray.direction);
            const std::vector<Vec2> projected = cv_project(world, camera);
            for (const Vec2& q : projected) {
                CAPTURE(pixel.x(), pixel.y(), q.x(), q.y());
                CHECK((q - pixel).cwiseAbs().maxCoeff() <= 1e-9);
            }
        }
    }
}

TEST_CASE("libcam's cv::Mat arguments hold K, rvec and tvec in OpenCV's layout", "[opencv]") {
    const Camera camera = to_camera(random_look_at_camera({1920, 1080}, FovAxis::Horizontal));
    const cv::Mat K = opencv_camera_matrix(camera.intrinsics);
    REQUIRE(camera.intrinsics.skew == 0.0);  // a look-at camera has none
    check_opencv_k(K, camera.intrinsics);
    // Centred principal point in OpenCV's pixel-centre convention: (W-1)/2, (H-1)/2.
    CHECK(camera.intrinsics.cx == 959.5);
    CHECK(camera.intrinsics.cy == 539.5);
    const cv::Mat t = opencv_vector(camera.pose.t);
    REQUIRE(t.rows == 3);
    REQUIRE(t.cols == 1);
    CHECK(vec_from_cv(t) == camera.pose.t);
    CHECK(opencv_distortion(camera.lens).total() == 0);
}

TEST_CASE("cv::undistortPoints with no distortion is K^-1 [x, y, 1]", "[opencv]") {
    for (const LookAtCamera& fov : test_cameras()) {
        const Camera camera = to_camera(fov);
        CAPTURE(fov.size.width, fov.size.height, fov.fov_deg, to_string(fov.fov_axis));
        const std::vector<Vec2> pixels = pixel_grid(fov.size);
        std::vector<cv::Point2d> source;
        for (const Vec2& p : pixels) source.emplace_back(p.x(), p.y());
        const cv::Mat K = cv_K(camera.intrinsics);
        std::vector<cv::Point2d> undistorted_none, undistorted_zeros;
        cv::undistortPoints(source, undistorted_none, K, cv::noArray());
        cv::undistortPoints(source, undistorted_zeros, K, cv::Mat::zeros(1, 5, CV_64F));
        const cv::Mat K_inverse = K.inv();  // OpenCV's own inverse (LU)
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            const Vec2 libcam_normalized = camera.intrinsics.normalized_from_pixel(pixels[i]);
            const cv::Mat h = K_inverse * (cv::Mat_<double>(3, 1) << pixels[i].x(), pixels[i].y(), 1.0);
            const Vec2 by_inverse(h.at<double>(0) / h.at<double>(2), h.at<double>(1) / h.at<double>(2));
            const Vec2 by_opencv(undistorted_none[i].x, undistorted_none[i].y);
            const Vec2 by_opencv_zeros(undistorted_zeros[i].x, undistorted_zeros[i].y);
            CAPTURE(pixels[i].x(), pixels[i].y(), libcam_normalized.x(), libcam_normalized.y(), by_opencv.x(), by_opencv.y());
            CHECK((by_opencv - libcam_normalized).cwiseAbs().maxCoeff() <= 1e-12);
            CHECK((by_opencv_zeros - libcam_normalized).cwiseAbs().maxCoeff() <= 1e-12);
            CHECK((by_inverse - libcam_normalized).cwiseAbs().maxCoeff() <= 1e-12);
            CHECK(std::abs(h.at<double>(2) - 1.0) <= 1e-15);

            // PreparedCamera::unproject returns the same K^-1 [x, y, 1] with z = 1.
            const Unprojection unprojection = PreparedCamera(camera).unproject(pixels[i]);
            REQUIRE(unprojection.valid);
            const Vec3& direction = unprojection.direction;
            CHECK(direction.z() == 1.0);
            CHECK((direction.head<2>() - by_opencv).cwiseAbs().maxCoeff() <= 1e-12);
        }
    }
}

TEST_CASE("cv::undistortPoints agrees with normalized_from_pixel for a hand-made K", "[opencv]") {
    // K chosen by hand with an off-centre principal point and fx != fy.
    const Intrinsics k{812.25, 640.5, 101.75, 733.125, 0.0};
    const cv::Mat K = cv_K(k);
    for (const Vec2& pixel : {Vec2(-0.5, -0.5), Vec2(0, 0), Vec2(1999.5, 1499.5), Vec2(101.75, 733.125), Vec2(913.0, 93.5)}) {
        std::vector<cv::Point2d> out;
        cv::undistortPoints(std::vector<cv::Point2d>{{pixel.x(), pixel.y()}}, out, K, cv::noArray());
        // Worked by hand: ((x - cx)/fx, (y - cy)/fy).
        const Vec2 expected((pixel.x() - 101.75) / 812.25, (pixel.y() - 733.125) / 640.5);
        CHECK(std::abs(out[0].x - expected.x()) <= 1e-14);
        CHECK(std::abs(out[0].y - expected.y()) <= 1e-14);
        CHECK((k.normalized_from_pixel(pixel) - expected).cwiseAbs().maxCoeff() <= 1e-15);
    }
}

TEST_CASE("cv::Rodrigues agrees with pose.R and pose.rvec() on random look-at cameras", "[opencv]") {
    for (const LookAtCamera& fov : test_cameras()) {
        const Pose pose = to_camera(fov).pose;
        cv::Mat R_cv;
        cv::Rodrigues(cv_vec(pose.rvec()), R_cv);
        CHECK(max_abs(eigen_from_cv(R_cv) - pose.R) <= 1e-14);

        cv::Mat rvec_cv;
        cv::Rodrigues(cv::Mat(3, 3, CV_64F, const_cast<double*>(Mat3(pose.R.transpose()).data())).clone(), rvec_cv);
        CHECK((vec_from_cv(rvec_cv) - pose.rvec()).cwiseAbs().maxCoeff() <= 1e-12);
    }
}

namespace {

// R from a rotation vector by OpenCV, the reference.
Mat3 cv_rotation(const Vec3& rvec) {
    cv::Mat R;
    cv::Rodrigues(cv_vec(rvec), R);
    return eigen_from_cv(R);
}
Vec3 cv_rvec(const Mat3& R) {
    cv::Mat m(3, 3, CV_64F);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m.at<double>(r, c) = R(r, c);
    cv::Mat rvec;
    cv::Rodrigues(m, rvec);
    return vec_from_cv(rvec);
}

}  // namespace

TEST_CASE("Rodrigues both ways near angle 0 and near pi, against cv::Rodrigues", "[opencv]") {
    const Vec3 axes[] = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 2, 3).normalized(),
                         Vec3(-0.3, 0.9, -0.1).normalized()};
    // cv::Rodrigues(R) returns exactly 0 below sin(angle) = 1e-5 and loses digits to acos
    // near 0 and pi (relative error ~ eps / sin(angle)), so the R -> rvec comparison uses
    // angles where OpenCV itself is good to 1e-12; rvec -> R is well conditioned everywhere.
    const double small_angles[] = {1e-3, 3e-3, 0.1};
    const double near_pi[] = {std::numbers::pi - 1e-2, std::numbers::pi - 2e-3, std::numbers::pi - 0.1};
    for (const Vec3& axis : axes) {
        for (double angle : {1e-12, 1e-8, 1e-6, 1e-3, 0.1, 1.0, 2.0, 3.0, std::numbers::pi - 1e-3,
                             std::numbers::pi - 1e-6, std::numbers::pi - 1e-9}) {
            const Vec3 rvec = angle * axis;
            CAPTURE(axis.transpose(), angle);
            CHECK(max_abs(rotation_from_rvec(rvec) - cv_rotation(rvec)) <= 1e-14);
            CHECK(max_abs(Pose::from_rvec(rvec, Vec3::Zero()).R - cv_rotation(rvec)) <= 1e-14);
            // libcam's own inverse returns the input rvec (R itself from OpenCV).
            CHECK((Pose{cv_rotation(rvec), Vec3::Zero()}.rvec() - rvec).cwiseAbs().maxCoeff() <= 1e-14);
        }
        for (double angle : small_angles) {
            const Vec3 rvec = angle * axis;
            const Pose pose{cv_rotation(rvec), Vec3::Zero()};
            CAPTURE(axis.transpose(), angle);
            CHECK((cv_rvec(pose.R) - pose.rvec()).cwiseAbs().maxCoeff() <= 1e-12);
            CHECK((pose.rvec() - rvec).cwiseAbs().maxCoeff() <= 1e-14);
        }
        for (double angle : near_pi) {
            const Vec3 rvec = angle * axis;
            const Pose pose{cv_rotation(rvec), Vec3::Zero()};
            CAPTURE(axis.transpose(), angle);
            CHECK((cv_rvec(pose.R) - pose.rvec()).cwiseAbs().maxCoeff() <= 1e-12);
            CHECK((pose.rvec() - rvec).cwiseAbs().maxCoeff() <= 1e-13);
        }
    }
}

TEST_CASE("Rotations of exactly 0 and exactly pi", "[opencv]") {
    // Identity: gaze +z, up -y is OpenCV's own camera frame.
    LookAtCamera fov;
    fov.gaze = Vec3(0, 0, 1);
    fov.up = Vec3(0, -1, 0);
    fov.size = {640, 480};
    const Pose identity = to_camera(fov).pose;
    CHECK(max_abs(identity.R - Mat3::Identity()) == 0.0);
    CHECK(identity.rvec().norm() == 0.0);
    CHECK(cv_rvec(identity.R).norm() == 0.0);

    // The default look-at camera (gaze -z, up +y): rows u = (1, 0, 0), -v = (0, -1, 0),
    // w = (0, 0, -1), i.e. diag(1, -1, -1), a rotation by pi about x.
    fov.gaze = Vec3(0, 0, -1);
    fov.up = Vec3(0, 1, 0);
    const Pose flipped = to_camera(fov).pose;
    Mat3 expected;
    expected << 1, 0, 0, 0, -1, 0, 0, 0, -1;
    CHECK(max_abs(flipped.R - expected) == 0.0);
    const Vec3 rvec = flipped.rvec();
    const Vec3 rvec_cv = cv_rvec(flipped.R);
    // At pi, r and -r are the same rotation: compare up to sign, and by the matrix.
    CHECK(std::min((rvec - rvec_cv).norm(), (rvec + rvec_cv).norm()) <= 1e-12);
    CHECK(std::abs(rvec.norm() - std::numbers::pi) <= 1e-15);
    CHECK(std::abs(std::abs(rvec.x()) - std::numbers::pi) <= 1e-15);
    CHECK(max_abs(cv_rotation(rvec) - expected) <= 1e-15);

    // Rotation by pi about y: gaze -z with up -y.
    fov.up = Vec3(0, -1, 0);
    const Pose about_y = to_camera(fov).pose;
    expected << -1, 0, 0, 0, 1, 0, 0, 0, -1;
    CHECK(max_abs(about_y.R - expected) == 0.0);
    CHECK(std::abs(std::abs(about_y.rvec().y()) - std::numbers::pi) <= 1e-15);
    CHECK(max_abs(cv_rotation(about_y.rvec()) - expected) <= 1e-15);
}

TEST_CASE("Bottom-left pixels (as the look-at formula counts them) project through OpenCV onto the flipped row",
          "[opencv][look-at]") {
    for (const LookAtCamera& fov : test_cameras()) {
        const Camera camera = to_camera(fov);
        const double H = static_cast<double>(fov.size.height);
        CAPTURE(fov.size.width, fov.size.height, fov.fov_deg, to_string(fov.fov_axis));
        for (const Vec2& bottom_left_pixel : pixel_grid(fov.size)) {
            const Vec3 d = fov.look_at_ray(bottom_left_pixel, PixelOrigin::BottomLeft);
            const Vec3 d_hand = hand_look_at_ray(fov, bottom_left_pixel.x(), bottom_left_pixel.y());
            // libcam's look-at ray is the look-at formula, worked by hand above.
            CHECK((d - d_hand).norm() <= 1e-12 * d_hand.norm());
            const Vec2 expected(bottom_left_pixel.x(), H - 1.0 - bottom_left_pixel.y());
            CHECK(opencv_pixel(bottom_left_pixel, PixelOrigin::BottomLeft, fov.size) == expected);
            const std::vector<Vec2> projected = cv_project({fov.eye + d}, camera);
            CAPTURE(bottom_left_pixel.x(), bottom_left_pixel.y(), projected[0].x(), projected[0].y());
            CHECK((projected[0] - expected).cwiseAbs().maxCoeff() <= pixel_tolerance(camera, expected, d.norm()));
        }
    }
}

TEST_CASE("The two worked example cameras (3x3, 90 degrees), worked by hand, through OpenCV", "[opencv][look-at]") {
    // Example camera 1: eye at 0, gaze -z, up +y; pixel (0, 0) counted from the
    // bottom-left has d = (-2/3, -2/3, -1) and is the lower-left pixel, OpenCV pixel (0, 2).
    const LookAtCamera fov = LookAtCamera::look_at(Vec3::Zero(), Vec3(0, 0, -1), Vec3(0, 1, 0), 90.0, FovAxis::Both, {3, 3});
    const Camera camera = to_camera(fov);
    CHECK(std::abs(camera.intrinsics.fx - 1.5) <= 1e-15);
    CHECK(std::abs(camera.intrinsics.fy - 1.5) <= 1e-15);
    CHECK(camera.intrinsics.cx == 1.0);
    CHECK(camera.intrinsics.cy == 1.0);
    const std::vector<Vec2> q = cv_project({Vec3(-2.0 / 3, -2.0 / 3, -1), Vec3(0, 0, -1), Vec3(-1, -1, -1), Vec3(0, 1, -1)}, camera);
    CHECK((q[0] - Vec2(0, 2)).norm() <= 1e-14);
    CHECK((q[1] - Vec2(1, 1)).norm() <= 1e-14);
    // The lower-left corner of the field of view is the image corner (-0.5, H - 0.5).
    CHECK((q[2] - Vec2(-0.5, 2.5)).norm() <= 1e-14);
    // The top centre of the field of view (0, 1, -1): (1, -0.5).
    CHECK((q[3] - Vec2(1, -0.5)).norm() <= 1e-14);

    // Example camera 2: eye (0, 5, 5) looking at the origin; pixel (0, 0) counted from the
    // bottom-left has d = (-2/3, -sqrt2/3 - 1/sqrt2, sqrt2/3 - 1/sqrt2).
    const LookAtCamera fov2 = LookAtCamera::look_at(Vec3(0, 5, 5), Vec3::Zero(), Vec3(0, 1, 0), 90.0, FovAxis::Both, {3, 3});
    const Camera camera2 = to_camera(fov2);
    const double s2 = std::sqrt(2.0);
    const Vec3 d00(-2.0 / 3, -s2 / 3 - 1 / s2, s2 / 3 - 1 / s2);
    const std::vector<Vec2> q2 = cv_project({Vec3(0, 5, 5) + d00, Vec3(0, 5, 5) + 7.0 * d00}, camera2);
    CHECK((q2[0] - Vec2(0, 2)).norm() <= 1e-12);
    CHECK((q2[1] - Vec2(0, 2)).norm() <= 1e-12);
}
