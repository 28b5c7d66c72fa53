// Camera files: round trips through every format, files written by cv::FileStorage
// itself, malformed files (each must be refused with a message naming the key), and
// the atomic writer. Expected numbers are the inputs themselves, OpenCV's, or worked
// by hand here.

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cctype>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "temp_dir.hpp"
#include "libcam/camera/camera.hpp"
#include "libcam/camera/example_cameras.hpp"
#include "libcam/convert/look_at_convert.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/opencv.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "opencv_k.hpp"
#include "support.hpp"

using namespace libcam;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using libcam::test::error_of;
using libcam::test::relative_error;

using libcam::test::TempDir;
using libcam::test::check_opencv_k;

namespace {

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    REQUIRE(out.good());
}

std::vector<std::string> folder_listing(const fs::path& folder) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}


// The message names `key` as a key: not inside another word, and followed by a quote,
// colon, bracket or dot ("K", K[2][2], K.fx, image_width: ...).
class NamesKey : public Catch::MatcherBase<std::string> {
public:
    explicit NamesKey(std::string key) : key_(std::move(key)) {}
    bool match(const std::string& message) const override {
        auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
        for (std::size_t at = message.find(key_); at != std::string::npos; at = message.find(key_, at + 1)) {
            const std::size_t end = at + key_.size();
            const bool starts = at == 0 || !word(message[at - 1]);
            const bool ends = end < message.size() && std::string("\"':[.").find(message[end]) != std::string::npos;
            if (starts && ends) return true;
        }
        return false;
    }
    std::string describe() const override { return "names the key " + key_; }

private:
    std::string key_;
};

// The message came from a FileError or an InvalidArgument (see error_of).
class IsFileOrArgumentError : public Catch::MatcherBase<std::string> {
public:
    bool match(const std::string& message) const override {
        return message.starts_with("FileError: ") || message.starts_with("InvalidArgument: ");
    }
    std::string describe() const override { return "is a libcam FileError or InvalidArgument"; }
};
IsFileOrArgumentError is_file_or_argument_error() { return {}; }

const ImageSize kSizes[] = {{1920, 1080}, {640, 4000}, {4000, 500}, {1000, 1000}, {3, 3}, {1, 1}};

// Relative comparison of camera numbers (scale: the larger magnitude, or 1 near 0).
double rel(double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1.0}); }

void check_same_camera(const Camera& got, const Camera& expected, double tolerance) {
    CHECK(got.size == expected.size);
    CHECK(got.lens.type == LensType::Pinhole);
    CHECK(got.lens.coefficients.empty());
    CHECK(relative_error(got.intrinsics.fx, expected.intrinsics.fx) <= tolerance);
    CHECK(relative_error(got.intrinsics.fy, expected.intrinsics.fy) <= tolerance);
    CHECK(rel(got.intrinsics.cx, expected.intrinsics.cx) <= tolerance);
    CHECK(rel(got.intrinsics.cy, expected.intrinsics.cy) <= tolerance);
    CHECK(std::abs(got.intrinsics.skew - expected.intrinsics.skew) <= tolerance * expected.intrinsics.fx);
    CHECK((got.pose.R - expected.pose.R).cwiseAbs().maxCoeff() <= tolerance);
    const double t_scale = std::max(1.0, expected.pose.t.cwiseAbs().maxCoeff());
    CHECK((got.pose.t - expected.pose.t).cwiseAbs().maxCoeff() <= tolerance * t_scale);
}

constexpr CameraFormat kFormats[] = {CameraFormat::Json, CameraFormat::OpenCvYaml, CameraFormat::OpenCvXml,
                                     CameraFormat::Cameramodel, CameraFormat::Gl};

const char* extension(CameraFormat format) {
    switch (format) {
        case CameraFormat::Json: return ".json";
        case CameraFormat::OpenCvYaml: return ".yaml";
        case CameraFormat::OpenCvXml: return ".xml";
        case CameraFormat::Cameramodel: return ".cameramodel";
        case CameraFormat::Gl: return ".gl.json";
        default: return "";  // the formats of test_file_round_trips.cpp
    }
}

}  // namespace

// ---------------------------------------------------------------------------------
// Round trips

TEST_CASE("Round trip through every format: K, R, t and size come back", "[files]") {
    TempDir dir;
    for (int i = 0; i < 16; ++i) {
        const LookAtCamera fov = libcam::test::random_look_at_camera(kSizes[i % std::size(kSizes)], libcam::test::random_axis(i));
        const Camera camera = to_camera(fov);
        for (CameraFormat format : kFormats) {
            CAPTURE(i, to_string(format), fov.size.width, fov.size.height, fov.fov_deg);
            const double tolerance = format == CameraFormat::Gl ? 1e-9 : 1e-12;
            // By extension, and by content sniffing for a file without one.
            const fs::path named = dir.path() / ("camera" + std::to_string(i) + extension(format));
            const fs::path bare = dir.path() / ("camera" + std::to_string(i) + "-" + std::string(to_string(format)));
            write_camera_file(named, camera, format);
            write_camera_file(bare, camera, format);
            CHECK(slurp(named) == format_camera(camera, format));
            check_same_camera(read_camera_file(named).camera, camera, tolerance);
            check_same_camera(read_camera_file(bare).camera, camera, tolerance);
            check_same_camera(parse_camera(format_camera(camera, format), format, "memory").camera, camera, tolerance);
        }
    }
    // Nothing left behind but the files written.
    CHECK(folder_listing(dir.path()).size() == 16 * std::size(kFormats) * 2);
}

TEST_CASE("Round trip of a camera that is no look-at camera (skew, off-centre, fx != fy)", "[files]") {
    TempDir dir;
    Camera camera;
    camera.size = {1280, 720};
    camera.intrinsics = Intrinsics{1001.123456789012, 987.6543210987654, 700.25, 300.125, 0.0};
    camera.pose = Pose::from_rvec(Vec3(0.3, -2.1, 0.7), Vec3(-12.5, 0.001, 1e4));
    for (CameraFormat format : kFormats) {
        CAPTURE(to_string(format));
        const fs::path path = dir.path() / (std::string("odd") + extension(format));
        write_camera_file(path, camera, format);
        check_same_camera(read_camera_file(path).camera, camera, format == CameraFormat::Gl ? 1e-9 : 1e-12);
    }
    camera.intrinsics.skew = 3.5;
    for (CameraFormat format : {CameraFormat::Json, CameraFormat::OpenCvYaml, CameraFormat::OpenCvXml, CameraFormat::Gl}) {
        CAPTURE(to_string(format));
        const fs::path path = dir.path() / (std::string("skew") + extension(format));
        write_camera_file(path, camera, format);
        check_same_camera(read_camera_file(path).camera, camera, format == CameraFormat::Gl ? 1e-9 : 1e-12);
    }
}

TEST_CASE("JSON with \"fov_axis\" reads back the look-at camera: same fov, gaze and basis", "[files]") {
    TempDir dir;
    for (int i = 0; i < 24; ++i) {
        const FovAxis axis = libcam::test::random_axis(i);
        const LookAtCamera fov = i % 6 == 1   ? libcam::test::random_look_at_camera(kSizes[i % 6], axis, 1.0, 1.0 + 1e-9)
                              : i % 6 == 4 ? libcam::test::random_look_at_camera(kSizes[i % 6], axis, 179.0 - 1e-9, 179.0)
                                           : libcam::test::random_look_at_camera(kSizes[i % 6], axis);
        const fs::path path = dir.path() / ("fov" + std::to_string(i) + ".json");
        WriteOptions options;
        options.look_at_camera = fov;
        write_camera_file(path, to_camera(fov), CameraFormat::Json, options);
        const CameraFile file = read_camera_file(path);
        REQUIRE(file.look_at_camera.has_value());
        const LookAtCamera& back = *file.look_at_camera;
        CAPTURE(i, to_string(axis), fov.fov_deg, back.fov_deg, fov.size.width, fov.size.height);
        CHECK(back.fov_axis == fov.fov_axis);
        CHECK(back.size == fov.size);
        CHECK(relative_error(back.fov_deg, fov.fov_deg) <= 1e-12);
        CHECK((back.gaze.normalized() - fov.gaze.normalized()).norm() <= 1e-12);
        CHECK((back.eye - fov.eye).norm() <= 1e-12 * std::max(1.0, fov.eye.norm()));
        const Basis expected = fov.basis();
        const Basis got = back.basis();
        CHECK((got.u - expected.u).norm() <= 1e-12);
        CHECK((got.v - expected.v).norm() <= 1e-12);
        CHECK((got.w - expected.w).norm() <= 1e-12);
        // Same rays: the look-at ray of a corner pixel, compared as directions.
        const Vec2 corner(0.0, 0.0);
        CHECK((back.look_at_ray(corner).normalized() - fov.look_at_ray(corner).normalized()).norm() <= 1e-12);
    }
    // Without "fov_axis" there is no look-at camera in the file.
    const fs::path plain = dir.path() / "plain.json";
    write_camera_file(plain, to_camera(libcam::test::random_look_at_camera({640, 480}, FovAxis::Vertical)), CameraFormat::Json);
    CHECK_FALSE(read_camera_file(plain).look_at_camera.has_value());
}

// ---------------------------------------------------------------------------------
// OpenCV's own FileStorage

namespace {

cv::Mat cv_K(double fx, double fy, double cx, double cy) {
    return (cv::Mat_<double>(3, 3) << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0);
}

}  // namespace

TEST_CASE("A file written by cv::FileStorage reads back through read_camera_file", "[files][opencv]") {
    TempDir dir;
    const double fx = 1234.5678901234567, fy = 1230.0000000000002, cx = 955.25, cy = 541.75;
    const cv::Mat rvec = (cv::Mat_<double>(3, 1) << 0.12345678901234567, -2.2, 0.75);
    const cv::Mat tvec = (cv::Mat_<double>(3, 1) << -1.5, 1e-7, 1234.5678);
    cv::Mat R_cv;
    cv::Rodrigues(rvec, R_cv);
    for (const char* name : {"by_opencv.yaml", "by_opencv.yml", "by_opencv.xml"}) {
        CAPTURE(name);
        const fs::path path = dir.path() / name;
        {
            cv::FileStorage fs_out(path.string(), cv::FileStorage::WRITE);
            REQUIRE(fs_out.isOpened());
            fs_out << "image_width" << 1920;
            fs_out << "image_height" << 1080;
            fs_out << "camera_matrix" << cv_K(fx, fy, cx, cy);
            fs_out << "distortion_coefficients" << cv::Mat::zeros(5, 1, CV_64F);
            fs_out << "rvec" << rvec;
            fs_out << "tvec" << tvec;
        }
        const Camera camera = read_camera_file(path).camera;
        CHECK(camera.size == ImageSize{1920, 1080});
        CHECK(camera.intrinsics.fx == fx);
        CHECK(camera.intrinsics.fy == fy);
        CHECK(camera.intrinsics.cx == cx);
        CHECK(camera.intrinsics.cy == cy);
        CHECK(camera.intrinsics.skew == 0.0);
        CHECK(camera.lens.type == LensType::Pinhole);
        for (int r = 0; r < 3; ++r) {
            CHECK(camera.pose.t(r) == tvec.at<double>(r));
            CHECK(std::abs(camera.pose.rvec()(r) - rvec.at<double>(r)) <= 1e-14);
            for (int c = 0; c < 3; ++c) CHECK(std::abs(camera.pose.R(r, c) - R_cv.at<double>(r, c)) <= 1e-15);
        }
    }

    // No rvec and tvec: the identity pose. distortion_coefficients as a 1x5 row works too.
    const fs::path bare = dir.path() / "intrinsics_only.yaml";
    {
        cv::FileStorage fs_out(bare.string(), cv::FileStorage::WRITE);
        fs_out << "camera_matrix" << cv_K(fx, fy, cx, cy);
        fs_out << "distortion_coefficients" << cv::Mat::zeros(1, 5, CV_64F);
        fs_out << "image_width" << 640;
        fs_out << "image_height" << 4000;
    }
    const Camera intrinsics_only = read_camera_file(bare).camera;
    CHECK(intrinsics_only.size == ImageSize{640, 4000});
    CHECK(intrinsics_only.intrinsics.fx == fx);
    CHECK(intrinsics_only.pose.R == Mat3::Identity());
    CHECK(intrinsics_only.pose.t == Vec3::Zero());
}

TEST_CASE("Stereo files written by cv::FileStorage: stereo_calib's pair and ORB-SLAM2's rectified pair, placed as "
          "cv::stereoRectify placed them",
          "[files][opencv]") {
    // A stereo calibration, rectified by OpenCV; both layouts written by cv::FileStorage.
    const cv::Size size(752, 480);
    const cv::Mat K1 = cv_K(458.654, 457.296, 367.215, 248.375), K2 = cv_K(457.587, 456.134, 379.999, 255.238);
    const cv::Mat D1 = (cv::Mat_<double>(1, 5) << -0.28340811, 0.07395907, 0.00019359, 1.76187114e-05, 0.0);
    const cv::Mat D2 = (cv::Mat_<double>(4, 1) << -0.28368365, 0.07451284, -0.00010473, -3.55590700e-05);
    cv::Mat R;
    cv::Rodrigues(cv::Mat((cv::Mat_<double>(3, 1) << 0.0031, -0.0143, 0.0021)), R);
    const cv::Mat T = (cv::Mat_<double>(3, 1) << -0.110074, 0.000399, -0.000853);
    cv::Mat R1, R2, P1, P2, Q;
    cv::stereoRectify(K1, D1, K2, D2, size, R, T, R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0);

    TempDir dir;
    const fs::path stereo_calib = dir.path() / "intrinsics.yml";
    {
        cv::FileStorage out(stereo_calib.string(), cv::FileStorage::WRITE);
        out << "M1" << K1 << "D1" << D1 << "M2" << K2 << "D2" << D2 << "R" << R << "T" << T;
    }
    ReadOptions sized;
    sized.size = ImageSize{size.width, size.height};
    const CameraSet pair = read_camera_set(stereo_calib, std::nullopt, sized);
    REQUIRE(pair.cameras.size() == 2);
    for (int r = 0; r < 3; ++r) {
        CHECK(pair.cameras[1].file.camera.pose.t(r) == T.at<double>(r));
        for (int c = 0; c < 3; ++c) CHECK(pair.cameras[1].file.camera.pose.R(r, c) == R.at<double>(r, c));
    }

    // ORB-SLAM2's stereo settings: Camera.* the rectified left camera (P1's K), Camera.bf
    // the baseline times fx, and the raw cameras with cv::stereoRectify's R and P.
    // cv::FileStorage refuses to write keys with a '.', which OpenCV reads and ORB-SLAM's
    // settings use: written with '_', then the prefix's '_' turned into the '.'.
    std::string text;
    {
        cv::FileStorage out("settings.yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
        out << "Camera_fx" << P1.at<double>(0, 0) << "Camera_fy" << P1.at<double>(1, 1) << "Camera_cx"
            << P1.at<double>(0, 2) << "Camera_cy" << P1.at<double>(1, 2);
        out << "Camera_k1" << 0.0 << "Camera_k2" << 0.0 << "Camera_p1" << 0.0 << "Camera_p2" << 0.0;
        out << "Camera_width" << size.width << "Camera_height" << size.height;
        out << "Camera_bf" << -P2.at<double>(0, 3) << "ThDepth" << 35;
        out << "LEFT_height" << size.height << "LEFT_width" << size.width << "LEFT_D" << D1 << "LEFT_K" << K1
            << "LEFT_R" << R1 << "LEFT_P" << P1;
        out << "RIGHT_height" << size.height << "RIGHT_width" << size.width << "RIGHT_D" << D2 << "RIGHT_K" << K2
            << "RIGHT_R" << R2 << "RIGHT_P" << P2;
        text = out.releaseAndGetString();
    }
    std::istringstream lines(text);
    std::string dotted;
    for (std::string line; std::getline(lines, line);) {
        for (const std::string prefix : {"Camera_", "LEFT_", "RIGHT_"}) {
            if (line.starts_with(prefix)) line[prefix.size() - 1] = '.';
        }
        dotted += line + "\n";
    }
    const fs::path orb = dir.path() / "EuRoC.yaml";
    write_text(orb, dotted);
    const CameraSet settings = read_camera_set(orb);
    REQUIRE(settings.cameras.size() == 4);
    CHECK(settings.cameras[0].name == "Camera1");
    CHECK(settings.cameras[1].name == "Camera2");
    CHECK(settings.cameras[2].name == "LEFT");
    CHECK(settings.cameras[3].name == "RIGHT");
    const Camera& left = settings.cameras[2].file.camera;
    const Camera& right = settings.cameras[3].file.camera;
    CHECK(left.lens.type == LensType::OpenCv5);
    CHECK(right.lens.type == LensType::OpenCv4);
    // The rectified right camera sits the baseline along x; the raw pair is the calibration's.
    const double baseline = -P2.at<double>(0, 3) / P2.at<double>(0, 0);
    CHECK(settings.cameras[1].file.camera.pose.centre().isApprox(Vec3(baseline, 0, 0), 1e-15));
    CHECK(std::abs(baseline - cv::norm(T)) <= 1e-12);
    const Pose right_from_left = right.pose.after(left.pose.inverse());
    for (int r = 0; r < 3; ++r) {
        CHECK(std::abs(right_from_left.t(r) - T.at<double>(r)) <= 1e-14);
        for (int c = 0; c < 3; ++c) CHECK(std::abs(right_from_left.R(r, c) - R.at<double>(r, c)) <= 1e-14);
    }
    // A point of the rectified frame seen by each raw camera: cv::undistortPoints with
    // that camera's R and P takes its pixel to P [X; 1], where the rectified camera sees it.
    const Vec3 point(0.4, -0.3, 3.0);
    for (const auto& [raw, K, D, Rr, P] :
         {std::tuple{left, K1, D1, R1, P1}, std::tuple{right, K2, D2, R2, P2}}) {
        const Projection seen = PreparedCamera(raw).project(point);
        REQUIRE(seen.valid);
        std::vector<cv::Point2d> rectified;
        cv::undistortPoints(std::vector<cv::Point2d>{{seen.pixel.x(), seen.pixel.y()}}, rectified, K, D, Rr, P,
                            cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-15));
        const cv::Mat homogeneous = P * cv::Mat((cv::Mat_<double>(4, 1) << point.x(), point.y(), point.z(), 1.0));
        const double w = homogeneous.at<double>(2);
        CHECK(std::abs(rectified[0].x - homogeneous.at<double>(0) / w) <= 1e-9);
        CHECK(std::abs(rectified[0].y - homogeneous.at<double>(1) / w) <= 1e-9);
    }
}

TEST_CASE("OpenCV's stereo files read as a pair: an error names the file it is in, the line in that file, on one line",
          "[files][errors]") {
    // stereo_calib's two files, written by hand: the intrinsics (M1 D1 M2 D2, 21 lines) and
    // the extrinsics (R T), read as `libcam rectify intrinsics.yml extrinsics.yml` reads them.
    const std::string matrix_3x3 = "   rows: 3\n   cols: 3\n   dt: d\n   data: [ 530., 0., 340., 0., 530., 230., 0., 0., 1. ]\n";
    const std::string distortion = "   rows: 1\n   cols: 5\n   dt: d\n   data: [ -0.28, 0.1, 0.001, -0.0003, 0. ]\n";
    const std::string intrinsics = "%YAML:1.0\nM1: !!opencv-matrix\n" + matrix_3x3 + "D1: !!opencv-matrix\n" + distortion +
                                   "M2: !!opencv-matrix\n" + matrix_3x3 + "D2: !!opencv-matrix\n" + distortion;
    const std::string rotation = "R: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]\n";
    const auto extrinsics_with_t = [&](const std::string& t_data) {
        return "%YAML:1.0\n" + rotation + "T: !!opencv-matrix\n   rows: 3\n   cols: 1\n   dt: d\n   data: [ " + t_data + " ]\n";
    };
    ReadOptions sized;
    sized.size = ImageSize{640, 480};
    const auto error_reading = [&](const std::string& intrinsics_text, const std::string& extrinsics_text) {
        return error_of([&] {
            parse_opencv_stereo_files(intrinsics_text, "intrinsics.yml", extrinsics_text, "extrinsics.yml", sized);
        });
    };

    const CameraSet pair = parse_opencv_stereo_files(intrinsics, "intrinsics.yml", extrinsics_with_t("-3.3, 0.04, -0.01"),
                                                     "extrinsics.yml", sized);
    REQUIRE(pair.cameras.size() == 2);
    CHECK(pair.cameras[1].file.camera.pose.t.x() == -3.3);

    // A word in T's data: line 11 of the extrinsics file (its header, R's 5 lines, T's 5).
    CHECK_THAT(error_reading(intrinsics, extrinsics_with_t("-3.3, x, -0.01")),
               StartsWith("FileError: extrinsics.yml: line 11: \"T.data\"[1]"));
    // A 3x3 whose data holds 8 numbers, in M2 of the intrinsics: its data on line 16 of that file.
    std::string short_m2 = intrinsics;
    const std::size_t m2 = short_m2.find("M2:");
    short_m2.replace(short_m2.find(" 1. ]", m2), 5, " ]");
    CHECK_THAT(error_reading(short_m2, extrinsics_with_t("-3.3, 0.04, -0.01")), StartsWith("FileError: intrinsics.yml: line 16: "));

    // A file that ends in a key of several lines with no value (found by fuzzing: the key's
    // lines reached the message). The message names the line the key starts on (6: the
    // header, M2, rows and two blank lines before it) and stays one line: YAML folds the key
    // to "A", a line end, "2, 1.0e", and the line end is shown escaped.
    const std::string cut = "%YAML:1.0\nM2: !!opencv-matrix\n   rows:\n\n\nA\n\n 2, 1.0e\n";
    const std::string message = error_reading(cut, "");
    CHECK(message.find('\n') == std::string::npos);
    CHECK_THAT(message, StartsWith("FileError: intrinsics.yml: line 6: the file ends with the key \"A\\n2, 1.0e\" and no value"));
    // The same key twice.
    const std::string twice = "%YAML:1.0\n? \"a\\nb\"\n: 1\n? \"a\\nb\"\n: 2\n";
    const std::string repeated = error_reading(twice, "");
    CHECK(repeated.find('\n') == std::string::npos);
    CHECK_THAT(repeated, StartsWith("FileError: intrinsics.yml: line 4: the key \"a\\nb\" appears twice (first on line 2)"));
}

TEST_CASE("A file written by libcam's opencv-yaml/xml reads back through cv::FileStorage", "[files][opencv]") {
    TempDir dir;
    for (int i = 0; i < 8; ++i) {
        const Camera camera = to_camera(libcam::test::random_look_at_camera(kSizes[i % 6], libcam::test::random_axis(i)));
        for (CameraFormat format : {CameraFormat::OpenCvYaml, CameraFormat::OpenCvXml}) {
            CAPTURE(i, to_string(format));
            const fs::path path = dir.path() / (std::string("camera") + extension(format));
            write_camera_file(path, camera, format);
            cv::FileStorage in(path.string(), cv::FileStorage::READ);
            REQUIRE(in.isOpened());
            CHECK(static_cast<int>(in["image_width"]) == camera.size.width);
            CHECK(static_cast<int>(in["image_height"]) == camera.size.height);
            cv::Mat K, dist, rvec, tvec;
            in["camera_matrix"] >> K;
            in["distortion_coefficients"] >> dist;
            in["rvec"] >> rvec;
            in["tvec"] >> tvec;
            check_opencv_k(K, camera.intrinsics);
            REQUIRE(dist.total() == 5);
            CHECK(cv::countNonZero(dist) == 0);
            REQUIRE(rvec.total() == 3);
            REQUIRE(tvec.total() == 3);
            cv::Mat R;
            cv::Rodrigues(rvec, R);
            for (int r = 0; r < 3; ++r) {
                CHECK(tvec.at<double>(r) == camera.pose.t(r));
                for (int c = 0; c < 3; ++c) CHECK(std::abs(R.at<double>(r, c) - camera.pose.R(r, c)) <= 1e-14);
            }
        }
    }
}

// ---------------------------------------------------------------------------------
// Malformed files

namespace {

// A libcam JSON file assembled from (key, raw JSON value) pairs, so a test can drop or
// replace one key. The base camera, worked by hand: K = [500 0 319.5; 0 510 239.5;
// 0 0 1], R a quarter turn about z (x -> y), rvec (0, 0, pi/2), t (0.5, -1, 2),
// P = K [R | t] = [0 -500 319.5 889; 510 0 239.5 -31; 0 0 1 2].
struct JsonDoc {
    std::vector<std::pair<std::string, std::string>> entries{
        {"model", "\"PINHOLE\""},
        {"image_size", "[640, 480]"},
        {"K", "[[500, 0, 319.5], [0, 510, 239.5], [0, 0, 1]]"},
        {"dist", "[]"},
        {"R", "[[0, -1, 0], [1, 0, 0], [0, 0, 1]]"},
        {"t", "[0.5, -1, 2]"},
        {"rvec", "[0, 0, 1.5707963267948966]"},
        {"P", "[[0, -500, 319.5, 889], [510, 0, 239.5, -31], [0, 0, 1, 2]]"},
    };

    JsonDoc without(const std::string& key) const {
        JsonDoc doc = *this;
        std::erase_if(doc.entries, [&](const auto& entry) { return entry.first == key; });
        return doc;
    }
    JsonDoc with(const std::string& key, const std::string& value) const {
        JsonDoc doc = *this;
        for (auto& entry : doc.entries) {
            if (entry.first == key) {
                entry.second = value;
                return doc;
            }
        }
        doc.entries.emplace_back(key, value);
        return doc;
    }
    std::string text() const {
        std::string out = "{\n";
        for (std::size_t i = 0; i < entries.size(); ++i) {
            out += "  \"" + entries[i].first + "\": " + entries[i].second + (i + 1 < entries.size() ? ",\n" : "\n");
        }
        return out + "}\n";
    }
};

// OpenCV YAML as cv::FileStorage writes it, from (key, data) pairs; an empty data
// string drops the key. Matrices are given as "rows cols: values".
struct YamlDoc {
    std::vector<std::pair<std::string, std::string>> entries{
        {"image_width", "640"},
        {"image_height", "480"},
        {"camera_matrix", "3 3: 500., 0., 319.5, 0., 510., 239.5, 0., 0., 1."},
        {"distortion_coefficients", "5 1: 0., 0., 0., 0., 0."},
        {"rvec", "3 1: 0., 0., 1.5707963267948966"},
        {"tvec", "3 1: 0.5, -1., 2."},
    };
    YamlDoc with(const std::string& key, const std::string& value) const {
        YamlDoc doc = *this;
        for (auto& entry : doc.entries)
            if (entry.first == key) entry.second = value;
        return doc;
    }
    std::string text() const {
        std::string out = "%YAML:1.0\n---\n";
        for (const auto& [key, value] : entries) {
            if (value.empty()) continue;
            const auto colon = value.find(':');
            if (colon == std::string::npos) {
                out += key + ": " + value + "\n";
                continue;
            }
            std::istringstream shape(value.substr(0, colon));
            long long rows = 0, cols = 0;
            shape >> rows >> cols;
            out += key + ": !!opencv-matrix\n   rows: " + std::to_string(rows) + "\n   cols: " + std::to_string(cols) +
                   "\n   dt: d\n   data: [ " + value.substr(colon + 1) + " ]\n";
        }
        return out;
    }
};

}  // namespace

namespace {

// The size and K the hand-made files below write: 640x480, fx 500, fy 510, (319.5, 239.5).
void check_hand_made_size_and_k(const Camera& camera) {
    CHECK(camera.size == ImageSize{640, 480});
    CHECK(camera.intrinsics.fx == 500.0);
    CHECK(camera.intrinsics.fy == 510.0);
    CHECK(camera.intrinsics.cx == 319.5);
    CHECK(camera.intrinsics.cy == 239.5);
}

}  // namespace

TEST_CASE("The hand-made base files are valid, with the numbers worked by hand", "[files][errors]") {
    TempDir dir;
    const fs::path json_path = dir.path() / "base.json";
    write_text(json_path, JsonDoc{}.text());
    const fs::path yaml_path = dir.path() / "base.yaml";
    write_text(yaml_path, YamlDoc{}.text());
    for (const fs::path& path : {json_path, yaml_path}) {
        CAPTURE(path.string());
        const Camera camera = read_camera_file(path).camera;
        check_hand_made_size_and_k(camera);
        Mat3 R;
        R << 0, -1, 0, 1, 0, 0, 0, 0, 1;
        CHECK((camera.pose.R - R).cwiseAbs().maxCoeff() <= 1e-15);
        CHECK(camera.pose.t == Vec3(0.5, -1, 2));
        // X = (1, 0, 5): R X + t = (0.5, 0, 7): pixel (500 * 0.5 / 7 + 319.5, 239.5).
        const Projection q = PreparedCamera(camera).project(Vec3(1, 0, 5));
        REQUIRE(q.valid);
        CHECK(std::abs(q.pixel.x() - (250.0 / 7.0 + 319.5)) <= 1e-12);
        CHECK(std::abs(q.pixel.y() - 239.5) <= 1e-12);
    }
    // "R" alone, "rvec" alone, and no "dist" are each enough.
    CHECK_NOTHROW(parse_camera(JsonDoc{}.without("rvec").without("P").without("dist").text(), CameraFormat::Json, "x"));
    const Camera by_rvec = parse_camera(JsonDoc{}.without("R").text(), CameraFormat::Json, "x").camera;
    CHECK(std::abs(by_rvec.pose.R(1, 0) - 1.0) <= 1e-15);
    CHECK(std::abs(by_rvec.pose.R(0, 1) + 1.0) <= 1e-15);
}

TEST_CASE("Malformed libcam JSON is refused, naming the key", "[files][errors]") {
    TempDir dir;
    const JsonDoc base;
    struct Case {
        const char* what;
        std::string text;
        const char* key;
    };
    const std::vector<Case> cases{
        {"missing K", base.without("K").text(), "K"},
        {"missing image_size", base.without("image_size").text(), "image_size"},
        {"missing t", base.without("t").text(), "t"},
        {"missing R and rvec", base.without("R").without("rvec").text(), "R"},
        {"missing model", base.without("model").text(), "model"},
        {"K 2x3", base.with("K", "[[500, 0, 319.5], [0, 510, 239.5]]").text(), "K"},
        {"K rows of 2", base.with("K", "[[500, 0], [0, 510], [0, 0]]").text(), "K"},
        {"K not an array", base.with("K", "\"identity\"").text(), "K"},
        {"t with 2 numbers", base.with("t", "[0.5, -1]").text(), "t"},
        {"t with 4 numbers", base.with("t", "[0.5, -1, 2, 3]").text(), "t"},
        {"R 3x2", base.with("R", "[[0, -1], [1, 0], [0, 0]]").without("rvec").text(), "R"},
        {"rvec with 2 numbers", base.without("R").with("rvec", "[0, 0]").text(), "rvec"},
        {"P 3x3", base.with("P", "[[0, -500, 319.5], [510, 0, 239.5], [0, 0, 1]]").text(), "P"},
        {"NaN as a string in K", base.with("K", "[[\"NaN\", 0, 319.5], [0, 510, 239.5], [0, 0, 1]]").text(), "K"},
        {"null in t", base.with("t", "[0.5, null, 2]").text(), "t"},
        {"Infinity as a string in t", base.with("t", "[0.5, \"Infinity\", 2]").text(), "t"},
        {"R not a rotation (scaled)", base.with("R", "[[0, -1, 0], [1, 0, 0], [0, 0, 1.001]]").without("rvec").without("P").text(), "R"},
        {"R a reflection (det -1)", base.with("R", "[[0, -1, 0], [1, 0, 0], [0, 0, -1]]").without("rvec").without("P").text(), "R"},
        {"R with a NaN", base.with("R", "[[0, -1, 0], [1, 0, 0], [0, 0, \"nan\"]]").text(), "R"},
        {"rvec disagreeing with R", base.with("rvec", "[0, 0, 1.6]").text(), "rvec"},
        {"P disagreeing with K[R|t]", base.with("P", "[[0, -500, 319.5, 889], [510, 0, 239.5, -30], [0, 0, 1, 2]]").text(), "P"},
        {"K[2][2] != 1", base.with("K", "[[500, 0, 319.5], [0, 510, 239.5], [0, 0, 2]]").without("P").text(), "K"},
        {"K[1][0] != 0", base.with("K", "[[500, 0, 319.5], [3, 510, 239.5], [0, 0, 1]]").without("P").text(), "K"},
        {"K with fx < 0", base.with("K", "[[-500, 0, 319.5], [0, 510, 239.5], [0, 0, 1]]").without("P").text(), "K"},
        {"K with fy = 0", base.with("K", "[[500, 0, 319.5], [0, 0, 239.5], [0, 0, 1]]").without("P").text(), "K"},
        {"non-integer width", base.with("image_size", "[640.5, 480]").text(), "image_size"},
        {"zero height", base.with("image_size", "[640, 0]").text(), "image_size"},
        {"negative width", base.with("image_size", "[-640, 480]").text(), "image_size"},
        {"image_size as strings", base.with("image_size", "[\"640\", \"480\"]").text(), "image_size"},
        {"image_size with 3 numbers", base.with("image_size", "[640, 480, 3]").text(), "image_size"},
        {"image_size too large", base.with("image_size", "[640, 1e7]").text(), "image_size"},
        {"unknown model", base.with("model", "\"FISHEYE_FANCY\"").text(), "model"},
        {"model not a string", base.with("model", "7").text(), "model"},
        {"distortion for PINHOLE", base.with("dist", "[0.1, 0, 0, 0, 0]").text(), "dist"},
        {"unknown fov_axis", base.with("fov_axis", "\"sideways\"").text(), "fov_axis"},
    };
    int index = 0;
    for (const Case& c : cases) {
        const fs::path path = dir.path() / ("case" + std::to_string(index++) + ".json");
        write_text(path, c.text);
        const std::string message = error_of([&] { read_camera_file(path); });
        CAPTURE(c.what, c.text);
        CHECK_THAT(message, is_file_or_argument_error());
        CHECK_THAT(message, NamesKey(c.key));
        CHECK_THAT(message, Contains(path.string()));
    }
    // The value is named too where there is one.
    write_text(dir.path() / "model.json", base.with("model", "\"FISHEYE_FANCY\"").text());
    CHECK_THAT(error_of([&] { read_camera_file(dir.path() / "model.json"); }), Contains("FISHEYE_FANCY"));
}

TEST_CASE("JSON numbers that overflow to infinity are refused as a libcam error naming the key", "[files][errors]") {
    // JSON has no literal for infinity; 1e999 is the usual way one sneaks in.
    // nlohmann throws json::out_of_range (406, "number overflow") for 1e999; the reader
    // turns it into a FileError and finds the key with a second, SAX pass.
    TempDir dir;
    const JsonDoc base;
    for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
             {"t", "[0.5, 1e999, 2]"},
             {"K", "[[-1e999, 0, 319.5], [0, 510, 239.5], [0, 0, 1]]"},
             {"R", "[[0, -1, 0], [1, 0, 0], [0, 0, 1e999]]"}}) {
        const fs::path path = dir.path() / ("overflow-" + key + ".json");
        write_text(path, base.with(key, value).text());
        const std::string message = error_of([&] { read_camera_file(path); });
        CAPTURE(key, value);
        CHECK_THAT(message, is_file_or_argument_error());
        CHECK_THAT(message, Contains(path.string()));
        // Naming the key as well, as every other bad number is.
        CHECK_THAT(message, NamesKey(key));
    }
}

TEST_CASE("Truncated, empty, missing and directory paths are refused with FileError", "[files][errors]") {
    TempDir dir;
    const Camera camera = to_camera(libcam::test::random_look_at_camera({640, 480}, FovAxis::Both));

    // Truncated JSON: every cut of a valid file.
    const std::string json = format_camera(camera, CameraFormat::Json);
    const fs::path json_path = dir.path() / "truncated.json";
    for (std::size_t cut : {std::size_t{1}, json.size() / 4, json.size() / 2, json.size() - 3}) {
        write_text(json_path, json.substr(0, cut));
        const std::string message = error_of([&] { read_camera_file(json_path); });
        CAPTURE(cut);
        CHECK_THAT(message, StartsWith("FileError: "));
        CHECK_THAT(message, Contains(json_path.string()));
    }

    // Truncated YAML, XML and .cameramodel: every cut is refused as a libcam error, with
    // one exception YAML cannot avoid: it has no end marker, so a cut at the end of a
    // line, after every required key (size and camera_matrix), is a whole file without
    // the optional keys after it (rvec, tvec). Such a prefix must read back what it holds.
    for (CameraFormat format : {CameraFormat::OpenCvYaml, CameraFormat::OpenCvXml, CameraFormat::Cameramodel}) {
        const std::string text = format_camera(camera, format);
        const fs::path path = dir.path() / (std::string("truncated") + extension(format));
        for (std::size_t cut = 1; cut + 2 < text.size(); cut += 1) {
            const std::string prefix = text.substr(0, cut);
            write_text(path, prefix);
            CAPTURE(to_string(format), cut, prefix);
            // Whole: the cut is at the end of a top-level entry (the next line starts a key).
            const std::string rest = text.substr(cut);
            const bool at_entry_end = rest.starts_with("\n") ? rest.size() > 1 && rest[1] != ' '
                                                              : prefix.back() == '\n' && rest.front() != ' ';
            const auto holds = [&](const char* key) { return prefix.find(std::string("\n") + key + ":") != std::string::npos; };
            if (format == CameraFormat::OpenCvYaml && at_entry_end && holds("camera_matrix")) {
                const Camera shorter = read_camera_file(path).camera;
                CHECK(shorter.intrinsics.K() == camera.intrinsics.K());
                CHECK(shorter.lens == (holds("distortion_coefficients") ? camera.lens : Lens{}));
                CHECK(shorter.pose.R.isApprox(holds("rvec") ? camera.pose.R : Mat3::Identity(), 1e-15));
                CHECK(shorter.pose.t == (holds("tvec") ? camera.pose.t : Vec3::Zero()));
                continue;
            }
            const std::string message = error_of([&] { read_camera_file(path); });
            CHECK_THAT(message, is_file_or_argument_error());
            CHECK_THAT(message, Contains(path.string()));
        }
    }

    // Empty and blank files, with and without a known extension.
    for (const char* name : {"empty.json", "empty.yaml", "empty.xml", "empty.cameramodel", "empty"}) {
        const fs::path path = dir.path() / name;
        write_text(path, "");
        CHECK_THAT(error_of([&] { read_camera_file(path); }), StartsWith("FileError: ") && Contains(path.string()) && Contains("empty"));
        write_text(path, "  \n\t\n");
        CHECK_THAT(error_of([&] { read_camera_file(path); }), StartsWith("FileError: ") && Contains(path.string()));
    }

    // A directory, and a path that does not exist.
    const fs::path folder = dir.path() / "folder.json";
    fs::create_directory(folder);
    CHECK_THAT(error_of([&] { read_camera_file(folder); }), StartsWith("FileError: ") && Contains(folder.string()));
    const fs::path missing = dir.path() / "no-such-file.json";
    CHECK_THAT(error_of([&] { read_camera_file(missing); }), StartsWith("FileError: ") && Contains(missing.string()));
    CHECK_THAT(error_of([&] { read_camera_file(dir.path() / "no-such-folder" / "camera.yaml"); }), StartsWith("FileError: "));

    // Content that is none of the formats, without an extension to go by.
    write_text(dir.path() / "mystery", "hello: world\n");
    CHECK_THAT(error_of([&] { read_camera_file(dir.path() / "mystery"); }), StartsWith("FileError: "));
    // A JSON array where an object belongs.
    write_text(dir.path() / "array.json", "[1, 2, 3]\n");
    CHECK_THAT(error_of([&] { read_camera_file(dir.path() / "array.json"); }), StartsWith("FileError: "));
}

TEST_CASE("YAML that hangs OpenCV 4.6's parser is refused by libcam's own, naming the line", "[files][errors]") {
    // Found by fuzzing when libcam still read OpenCV's files through cv::FileStorage,
    // which loops forever on them: a second document marker inside a flow sequence, and
    // a block entry after a key on the same line.
    const std::string head = "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n";
    struct Case {
        const char* what;
        std::string text;
        const char* says;
    };
    const std::vector<Case> cases{
        {"the fuzzer's second document", read_text_file(fs::path(LIBCAM_FUZZ_CORPUS) / "opencv-yaml/hang_second_document.yaml"),
         "line 5: a second YAML document"},
        {"the fuzzer's block entry", read_text_file(fs::path(LIBCAM_FUZZ_CORPUS) / "opencv-yaml/hang_block_entry.yaml"), "line 5"},
        {"--- inside a flow sequence", head + "data: [ 1.5,\n---\n 2. ]\n", "line "},
        {"a second document", head + "---\nimage_width: 320\n", "line 5: a second YAML document"},
        {"a document end, then more", head + "...\nimage_width: 320\n", "line 6: a second YAML document"},
        {"an unclosed flow sequence", head + "data: [ 1.5, 2.\n", "line "},
        {"a tab for indentation", head + "camera_matrix:\n\trows: 3\n", "line "},
        // yaml-cpp 0.7's LoadAll loops forever, allocating, on this one (libcam calls Load).
        {"a document that starts with ','", read_text_file(fs::path(LIBCAM_FUZZ_CORPUS) / "opencv-yaml/loop_leading_comma.yaml"),
         "text after the YAML document"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.what, c.text);
        const std::string message = error_of([&] { (void)parse_camera(c.text, CameraFormat::OpenCvYaml, "in.yaml"); });
        CHECK_THAT(message, StartsWith("FileError: in.yaml") && Contains(c.says));
    }
    // One document that ends with YAML's end marker is whole.
    const std::string k = "camera_matrix: [ 500., 0., 319.5, 0., 510., 239.5, 0., 0., 1. ]\n";
    CHECK_THAT(error_of([&] { (void)parse_camera(head + k + "...\n# end\n", CameraFormat::OpenCvYaml, "in.yaml"); }),
               Contains("expected a 3x3 matrix, got 9x1"));
    // Anchors and aliases are YAML too: K's data given once and referred to.
    const std::string aliased = head + "numbers: &k [ 500., 0., 319.5, 0., 510., 239.5, 0., 0., 1. ]\n"
                                       "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: *k\n";
    const Camera camera = parse_camera(aliased, CameraFormat::OpenCvYaml, "in.yaml").camera;
    CHECK(camera.intrinsics.fy == 510.0);
    CHECK(camera.intrinsics.cx == 319.5);
}

TEST_CASE("YAML past what a camera file needs is refused before it grows: aliases, nesting", "[files][errors]") {
    // Nine levels of aliases, each repeating the one below ten times, would make 10^9
    // values out of 100 lines ("billion laughs").
    std::string laughs = "a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n";
    for (int level = 1; level < 9; ++level) {
        const std::string below = "*a" + std::to_string(level - 1);
        laughs += "a" + std::to_string(level) + ": &a" + std::to_string(level) + " [";
        for (int k = 0; k < 10; ++k) laughs += (k ? ", " : "") + below;
        laughs += "]\n";
    }
    CHECK_THAT(error_of([&] { (void)parse_camera(laughs, CameraFormat::OpenCvYaml, "laughs.yaml"); }),
               StartsWith("FileError: laughs.yaml") && Contains("more than 200000 values"));
    // 100 nested lists, in YAML and (1000) in XML; 100000 in YAML, refused as soon as
    // the parser reaches the 33rd.
    const std::string deep = "image_width: " + std::string(100, '[') + std::string(100, ']') + "\n";
    CHECK_THAT(error_of([&] { (void)parse_camera(deep, CameraFormat::OpenCvYaml, "deep.yaml"); }),
               StartsWith("FileError: deep.yaml") && Contains("nested more than 32 levels"));
    const std::string deeper = "image_width: " + std::string(100000, '[') + std::string(100000, ']') + "\n";
    CHECK_THAT(error_of([&] { (void)parse_camera(deeper, CameraFormat::OpenCvYaml, "deeper.yaml"); }),
               StartsWith("FileError: deeper.yaml: line 1: nested more than 32 levels"));
    std::string deep_xml = "<?xml version=\"1.0\"?>\n<opencv_storage>";
    for (int i = 0; i < 1000; ++i) deep_xml += "<a>";
    for (int i = 0; i < 1000; ++i) deep_xml += "</a>";
    deep_xml += "</opencv_storage>\n";
    CHECK_THAT(error_of([&] { (void)parse_camera(deep_xml, CameraFormat::OpenCvXml, "deep.xml"); }),
               StartsWith("FileError: deep.xml") && Contains("nested more than 32 levels"));
}

namespace {

// K as cv::FileStorage reads it from `path` under `key`, for comparing with libcam's reader.
cv::Mat opencv_reads_matrix(const fs::path& path, const char* key) {
    cv::FileStorage in(path.string(), cv::FileStorage::READ);
    REQUIRE(in.isOpened());
    cv::Mat m;
    in[key] >> m;
    if (!m.empty()) m.convertTo(m, CV_64F);
    return m;
}

}  // namespace

TEST_CASE("OpenCV YAML in the layouts OpenCV reads: header or not, '---' or not, CRLF, old names, lists",
          "[files][opencv]") {
    // Each text is read by libcam and by cv::FileStorage; both must find K = [500 0 319.5;
    // 0 510 239.5; 0 0 1], the size 640x480 and the coefficients written in the text.
    const std::string matrix_k = "!!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
                                 "   data: [ 500., 0., 319.5, 0., 510., 239.5, 0., 0., 1. ]\n";
    const std::string dist5 = "!!opencv-matrix\n   rows: 5\n   cols: 1\n   dt: d\n   data: [ -0.1, 0.02, 1e-4, -2e-4, 0.003 ]\n";
    const std::string body = "image_width: 640\nimage_height: 480\ncamera_matrix: " + matrix_k + "distortion_coefficients: " + dist5;
    const auto crlf = [](std::string text) {
        for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at + 2)) text.insert(at, "\r");
        return text;
    };
    struct Case {
        const char* what;
        std::string text;
        const char* k_key;  // where OpenCV finds K in this layout
    };
    const std::vector<Case> cases{
        {"as cv::FileStorage writes it", "%YAML:1.0\n---\n" + body, "camera_matrix"},
        {"without '---' (ORB-SLAM's settings)", "%YAML:1.0\n" + body, "camera_matrix"},
        {"CRLF line ends", crlf("%YAML:1.0\n---\n" + body), "camera_matrix"},
        {"comments and blank lines", "%YAML:1.0\n---\n# calibrated 2019\n\n" + body + "# end\n", "camera_matrix"},
        {"the calibration sample's older names",
         "%YAML:1.0\n---\nimage_Width: 640\nimage_Height: 480\nCamera_Matrix: " + matrix_k + "Distortion_Coefficients: " + dist5,
         "Camera_Matrix"},
        {"coefficients as a plain list",
         "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\ncamera_matrix: " + matrix_k +
             "distortion_coefficients: [ -0.1, 0.02, 1e-4, -2e-4, 0.003 ]\n",
         "camera_matrix"},
        {"data across lines, as OpenCV wraps it",
         "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n"
         "   dt: d\n   data: [ 500., 0., 319.5, 0.,\n       510., 239.5, 0., 0., 1. ]\ndistortion_coefficients: " + dist5,
         "camera_matrix"},
    };
    TempDir dir;
    int index = 0;
    for (const Case& c : cases) {
        CAPTURE(c.what, c.text);
        const fs::path path = dir.path() / ("layout" + std::to_string(index++) + ".yaml");
        write_text(path, c.text);
        const Camera camera = read_camera_file(path).camera;
        check_hand_made_size_and_k(camera);
        CHECK(camera.lens.type == LensType::OpenCv5);
        CHECK(camera.lens.coefficients == std::vector<double>{-0.1, 0.02, 1e-4, -2e-4, 0.003});
        // OpenCV reads the same K from the same file.
        check_opencv_k(opencv_reads_matrix(path, c.k_key), camera.intrinsics);
    }
}

TEST_CASE("fisheye_model and distortion_model say whose coefficients a file holds", "[files][opencv]") {
    const std::string head =
        "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n"
        "   dt: d\n   data: [ 300., 0., 319.5, 0., 300., 239.5, 0., 0., 1. ]\n";
    const std::string k4 = "distortion_coefficients: [ 0.05, -0.01, 0.002, -0.0003 ]\n";
    struct Case {
        const char* what;
        std::string text;
        LensType type;
    };
    const std::vector<Case> cases{
        {"no flag: cv::projectPoints", head + k4, LensType::OpenCv4},
        {"the calibration sample's fisheye_model: 0", head + "fisheye_model: 0\n" + k4, LensType::OpenCv4},
        {"the calibration sample's fisheye_model: 1", head + "fisheye_model: 1\n" + k4, LensType::Fisheye},
        {"ROS's equidistant", head + "distortion_model: equidistant\n" + k4, LensType::Fisheye},
        {"\"fisheye\", quoted", head + "distortion_model: \"fisheye\"\n" + k4, LensType::Fisheye},
        {"ROS's plumb_bob", head + "distortion_model: plumb_bob\n" + k4, LensType::OpenCv4},
    };
    // OpenCV projects a point through the coefficients with the function the file names
    // (cv::fisheye::projectPoints for FISHEYE); libcam's camera must give the same pixel.
    const Vec3 point(0.3, -0.2, 1.0);
    for (const Case& c : cases) {
        CAPTURE(c.what);
        const Camera camera = parse_camera(c.text, CameraFormat::OpenCvYaml, "in.yaml").camera;
        CHECK(camera.lens.type == c.type);
        CHECK(camera.lens.coefficients == std::vector<double>{0.05, -0.01, 0.002, -0.0003});
        const Vec2 by_opencv = opencv_project_points(camera, {point}).front();
        const Projection by_libcam = PreparedCamera(camera).project_camera_point(point);
        REQUIRE(by_libcam.valid);
        CHECK((by_libcam.pixel - by_opencv).norm() < 1e-9);
    }
    // cv::fisheye's coefficients all zero are the equidistant lens, not PINHOLE.
    const Camera zero = parse_camera(head + "fisheye_model: 1\ndistortion_coefficients: [ 0., 0., 0., 0. ]\n",
                                     CameraFormat::OpenCvYaml, "in.yaml")
                            .camera;
    CHECK(zero.lens.type == LensType::Fisheye);

    const std::vector<std::pair<std::string, std::string>> refused{
        {head + "distortion_model: kb8\n" + k4, "\"distortion_model\": 'kb8' is not a model"},
        {head + "fisheye_model: 1\ndistortion_model: plumb_bob\n" + k4, "disagrees with \"fisheye_model\""},
        {head + "fisheye_model: 2\n" + k4, "\"fisheye_model\": must be in [0, 1], got 2"},
        {head + "fisheye_model: 1\ndistortion_coefficients: [ 0.05, -0.01, 0.002, -0.0003, 0.1 ]\n",
         "expected cv::fisheye's 4 coefficients, got 5"},
        {head + "distortion_model: equidistant\n", "\"distortion_coefficients\": missing"},
    };
    for (const auto& [text, says] : refused) {
        CAPTURE(text);
        const std::string& yaml = text;  // clang 14 cannot capture a structured binding in a lambda
        CHECK_THAT(error_of([&] { (void)parse_camera(yaml, CameraFormat::OpenCvYaml, "in.yaml"); }),
                   StartsWith("FileError: in.yaml") && Contains(says));
    }
}

TEST_CASE("Metashape's XML written by libcam projects as cv::projectPoints and cv::fisheye do with the OpenCV lens",
          "[files][opencv][metashape]") {
    // Metashape's P1/P2 are OpenCV's p2/p1, its b1 is fx - fy and its cx, cy offsets from
    // the centre of pixels whose corner is (0, 0): the camera read back from the written
    // file must project every point where OpenCV's function does with the original lens.
    test::TempDir dir;
    const std::vector<Vec3> points{{0.1, 0.2, 1.0}, {-0.3, 0.25, 1.0}, {0.35, -0.3, 1.5}, {0.0, 0.0, 2.0}};
    for (const Lens& lens : {Lens{LensType::OpenCv5, {-0.2, 0.05, 1e-3, -2e-3, 0.01}},
                             Lens{LensType::OpenCv4, {0.1, -0.02, -4e-3, 3e-3}},
                             Lens{LensType::Fisheye, {0.01, -0.002, 3e-4, -4e-5}}}) {
        CAPTURE(lens_info(lens.type).name);
        Camera camera;
        camera.size = {1280, 720};
        camera.intrinsics = {1001.125, 987.5, 700.25, 300.125, 0.0};
        camera.lens = lens;
        const fs::path path = dir.path() / "cameras.xml";
        write_camera_file(path, camera, CameraFormat::Metashape);
        const Camera back = read_camera_file(path).camera;
        const std::vector<Vec2> by_opencv = opencv_project_points(camera, points);
        const PreparedCamera prepared(back);
        for (std::size_t i = 0; i < points.size(); ++i) {
            const Projection got = prepared.project_camera_point(points[i]);
            REQUIRE(got.valid);
            CHECK((got.pixel - by_opencv[i]).norm() < 1e-9);
        }
    }
}

TEST_CASE("Malformed OpenCV YAML and XML are refused, naming the key", "[files][errors]") {
    TempDir dir;
    const YamlDoc base;
    struct Case {
        const char* what;
        std::string text;
        const char* key;
    };
    const std::vector<Case> cases{
        {"missing camera_matrix", base.with("camera_matrix", "").text(), "camera_matrix"},
        {"missing image_width", base.with("image_width", "").text(), "image_width"},
        {"missing image_height", base.with("image_height", "").text(), "image_height"},
        {"camera_matrix 2x3", base.with("camera_matrix", "2 3: 500., 0., 319.5, 0., 510., 239.5").text(), "camera_matrix"},
        {"camera_matrix with .nan", base.with("camera_matrix", "3 3: .nan, 0., 319.5, 0., 510., 239.5, 0., 0., 1.").text(), "camera_matrix"},
        {"camera_matrix with .inf", base.with("camera_matrix", "3 3: 500., 0., .inf, 0., 510., 239.5, 0., 0., 1.").text(), "camera_matrix"},
        {"camera_matrix[2][2] = 2", base.with("camera_matrix", "3 3: 500., 0., 319.5, 0., 510., 239.5, 0., 0., 2.").text(), "camera_matrix"},
        {"camera_matrix fx = 0", base.with("camera_matrix", "3 3: 0., 0., 319.5, 0., 510., 239.5, 0., 0., 1.").text(), "camera_matrix"},
        {"tvec with 2 numbers", base.with("tvec", "2 1: 0.5, -1.").text(), "tvec"},
        {"tvec with .nan", base.with("tvec", "3 1: 0.5, .nan, 2.").text(), "tvec"},
        {"rvec with .inf", base.with("rvec", "3 1: 0., .inf, 0.").text(), "rvec"},
        {"rvec with 4 numbers", base.with("rvec", "4 1: 0., 0., 1., 0.").text(), "rvec"},
        {"zero width", base.with("image_width", "0").text(), "image_width"},
        {"non-integer width", base.with("image_width", "640.5").text(), "image_width"},
        {"negative height", base.with("image_height", "-480").text(), "image_height"},
        {"width as a string", base.with("image_width", "\"wide\"").text(), "image_width"},
        {"distortion .nan", base.with("distortion_coefficients", "5 1: 0., .nan, 0., 0., 0.").text(), "distortion_coefficients"},
        // OpenCV 4.6 reads integers as 32-bit int, wrapping: 4294967936 would read as 640,
        // 4294967299 rows as 3. libcam reads them whole and refuses them.
        {"width 2^32 + 640", base.with("image_width", "4294967936").text(), "image_width"},
        {"height -2^32 + 480", base.with("image_height", "-4294966816").text(), "image_height"},
        {"rows 2^32 + 3", base.with("camera_matrix", "4294967299 1: 500., 0., 319.5").text(), "camera_matrix.rows"},
        {"width past long long", base.with("image_width", "99999999999999999999999").text(), "image_width"},
        {"a word in the data", base.with("tvec", "3 1: 0.5, one, 2.").text(), "tvec.data"},
        {"data shorter than rows x cols", base.with("camera_matrix", "3 3: 500., 0., 319.5, 0., 510.").text(),
         "camera_matrix.data"},
    };
    int index = 0;
    for (const Case& c : cases) {
        const fs::path path = dir.path() / ("case" + std::to_string(index++) + ".yaml");
        write_text(path, c.text);
        const std::string message = error_of([&] { read_camera_file(path); });
        CAPTURE(c.what, c.text);
        CHECK_THAT(message, is_file_or_argument_error());
        CHECK_THAT(message, NamesKey(c.key));
        CHECK_THAT(message, Contains(path.string()));
    }

    // XML: one missing key and one bad value, in cv::FileStorage's own XML.
    const Camera camera = to_camera(libcam::test::random_look_at_camera({640, 480}, FovAxis::Horizontal));
    std::string xml = format_camera(camera, CameraFormat::OpenCvXml);
    const auto start = xml.find("<camera_matrix");
    const auto end = xml.find("</camera_matrix>");
    REQUIRE(start != std::string::npos);
    REQUIRE(end != std::string::npos);
    const fs::path no_k = dir.path() / "no_k.xml";
    write_text(no_k, xml.substr(0, start) + xml.substr(end + std::string("</camera_matrix>").size()));
    std::string message = error_of([&] { read_camera_file(no_k); });
    CHECK_THAT(message, is_file_or_argument_error());
    CHECK_THAT(message, NamesKey("camera_matrix"));
    std::string bad_width = xml;
    const auto width_at = bad_width.find("<image_width>");
    REQUIRE(width_at != std::string::npos);
    bad_width.replace(width_at, bad_width.find("</image_width>") - width_at, "<image_width>0");
    const fs::path zero_width = dir.path() / "zero_width.xml";
    write_text(zero_width, bad_width);
    message = error_of([&] { read_camera_file(zero_width); });
    CHECK_THAT(message, is_file_or_argument_error());
    CHECK_THAT(message, NamesKey("image_width"));

    // An integer past OpenCV's 32-bit int, and a word where a number belongs.
    std::string wrapping_width = xml;
    wrapping_width.replace(width_at, wrapping_width.find("</image_width>") - width_at, "<image_width>4294967936");
    const fs::path wrapping = dir.path() / "wrapping_width.xml";
    write_text(wrapping, wrapping_width);
    message = error_of([&] { read_camera_file(wrapping); });
    CHECK_THAT(message, is_file_or_argument_error());
    CHECK_THAT(message, NamesKey("image_width") && Contains("4294967936"));
    std::string wrapping_k = xml;
    const auto data_at = wrapping_k.find("<data>", start);
    REQUIRE(data_at != std::string::npos);
    const auto first_number = wrapping_k.find_first_not_of(" \n", data_at + std::string("<data>").size());
    wrapping_k.replace(first_number, wrapping_k.find(' ', first_number) - first_number, "5.7e12x");
    const fs::path wrapping_data = dir.path() / "word_in_k.xml";
    write_text(wrapping_data, wrapping_k);
    message = error_of([&] { read_camera_file(wrapping_data); });
    CHECK_THAT(message, is_file_or_argument_error());
    CHECK_THAT(message, NamesKey("camera_matrix.data") && Contains("5.7e12x") && Contains("line "));
}

TEST_CASE("Malformed .cameramodel and gl files are refused", "[files][errors]") {
    TempDir dir;
    const std::string legacy =
        "{\n    'lens_model': 'LENSMODEL_PINHOLE',\n    'intrinsics': [ 1000., 1000., 319.5, 239.5 ],\n"
        "    'imagersize': [ 640, 480 ],\n    'extrinsics': [ 0, 0, 0, 0, 0, 0 ]\n}\n";
    const fs::path legacy_path = dir.path() / "legacy.cameramodel";
    write_text(legacy_path, legacy);
    CHECK_THAT(error_of([&] { read_camera_file(legacy_path); }),
               StartsWith("FileError: ") && Contains("lens_model") && Contains(legacy_path.string()));
    // Sniffed without an extension, too.
    const fs::path legacy_bare = dir.path() / "legacy_model";
    write_text(legacy_bare, "# old file\n" + legacy);
    CHECK_THAT(error_of([&] { read_camera_file(legacy_bare); }), StartsWith("FileError: ") && Contains("lens_model"));

    // Missing intrinsics; fx = 0.
    const fs::path no_intrinsics = dir.path() / "no_intrinsics.cameramodel";
    write_text(no_intrinsics, "{\n    'lensmodel': 'LENSMODEL_PINHOLE',\n    'imagersize': [ 640, 480 ],\n"
                              "    'extrinsics': [ 0, 0, 0, 0, 0, 0 ]\n}\n");
    CHECK_THAT(error_of([&] { read_camera_file(no_intrinsics); }), is_file_or_argument_error());
    const fs::path zero_fx = dir.path() / "zero_fx.cameramodel";
    write_text(zero_fx, "{\n    'lensmodel': 'LENSMODEL_PINHOLE',\n    'intrinsics': [ 0, 1000., 319.5, 239.5 ],\n"
                        "    'imagersize': [ 640, 480 ],\n    'extrinsics': [ 0, 0, 0, 0, 0, 0 ]\n}\n");
    CHECK_THAT(error_of([&] { read_camera_file(zero_fx); }), is_file_or_argument_error() && Contains("fx"));

    // gl, written by hand: 640x480, fx 500, fy 510, centred principal point, near 0.1,
    // far 1000, pose R = I, t = (0.5, -1, 2). projection: 2 fx / W = 1.5625,
    // 2 fy / H = 2.125, 1 - (2 cx + 1) / W = 0, (2 cy + 1) / H - 1 = 0,
    // A = -(f + n) / (f - n), B = -2 f n / (f - n); view = diag(1, -1, -1) [R | t].
    JsonDoc gl;
    gl.entries = {
        {"projection", "[[1.5625, 0, 0, 0], [0, 2.125, 0, 0], [0, 0, " + format_number(-1000.1 / 999.9) + ", " +
                           format_number(-200.0 / 999.9) + "], [0, 0, -1, 0]]"},
        {"view", "[[1, 0, 0, 0.5], [0, -1, 0, 1], [0, 0, -1, -2], [0, 0, 0, 1]]"},
        {"viewport", "[0, 0, 640, 480]"},
        {"near", "0.1"},
        {"far", "1000"},
        {"depth_range", "\"minus-one-to-one\""},
    };
    const fs::path gl_path = dir.path() / "hand.gl.json";
    write_text(gl_path, gl.text());
    const Camera from_gl = read_camera_file(gl_path).camera;
    CHECK(from_gl.size == ImageSize{640, 480});
    CHECK(from_gl.intrinsics.fx == 500.0);
    CHECK(from_gl.intrinsics.fy == 510.0);
    CHECK(from_gl.intrinsics.cx == 319.5);
    CHECK(from_gl.intrinsics.cy == 239.5);
    CHECK(from_gl.pose.R == Mat3::Identity());
    CHECK(from_gl.pose.t == Vec3(0.5, -1, 2));

    const std::vector<std::pair<JsonDoc, const char*>> bad_gl{
        {gl.with("projection", "[[1.5625, 0, 0, 0], [0, 2.125, 0, 0], [0, 0, -1.0002, -0.2], [0, 0, 1, 0]]"), "projection"},
        {gl.with("projection", "[[1.5625, 0, 0, 0], [0, 2.125, 0, 0], [0, 0, -1.0002, -0.2]]"), "projection"},
        {gl.with("projection", "[[-1.5625, 0, 0, 0], [0, 2.125, 0, 0], [0, 0, -1.0002, -0.2], [0, 0, -1, 0]]"), "projection"},
        {gl.with("viewport", "[5, 0, 640, 480]"), "viewport"},
        {gl.with("viewport", "[0, 0, 640.5, 480]"), "viewport"},
        {gl.with("viewport", "[0, 0, 640]"), "viewport"},
        {gl.with("view", "[[1, 0, 0, 0.5], [0, -1, 0, 1], [0, 0, -1, -2], [0, 0, 1, 1]]"), "view"},
        {gl.with("view", "[[2, 0, 0, 0.5], [0, -1, 0, 1], [0, 0, -1, -2], [0, 0, 0, 1]]"), "R"},
        {gl.with("depth_range", "\"zero-to-two\""), "depth_range"},
    };
    int index = 0;
    for (const auto& [doc, key] : bad_gl) {
        const fs::path path = dir.path() / ("bad-gl-" + std::to_string(index++) + ".json");
        write_text(path, doc.text());
        const std::string message = error_of([&] { read_camera_file(path); });
        CAPTURE(doc.text());
        CHECK_THAT(message, is_file_or_argument_error());
        CHECK_THAT(message, NamesKey(key));
        CHECK_THAT(message, Contains(path.string()));
    }
}

TEST_CASE("Formats that cannot hold a camera say so, and write nothing", "[files][errors]") {
    TempDir dir;
    Camera camera = to_camera(libcam::test::random_look_at_camera({640, 480}, FovAxis::Diagonal));
    camera.intrinsics.skew = 1.0;
    const fs::path path = dir.path() / "skew.cameramodel";
    CHECK_THROWS_AS(write_camera_file(path, camera, CameraFormat::Cameramodel), NotRepresentable);
    CHECK(fs::is_empty(dir.path()));
    // An invalid camera is refused by every writer before anything is written.
    Camera broken = to_camera(libcam::test::random_look_at_camera({640, 480}, FovAxis::Diagonal));
    broken.intrinsics.fx = -1.0;
    for (CameraFormat format : kFormats) {
        CAPTURE(to_string(format));
        CHECK_THAT(error_of([&] { write_camera_file(dir.path() / "broken", broken, format); }),
                   StartsWith("InvalidArgument: ") && NamesKey("K"));
    }
    CHECK(fs::is_empty(dir.path()));
    CHECK_THROWS_AS(camera_format_from_string("png"), InvalidArgument);
    CHECK(camera_format_from_string("opencv-yaml") == CameraFormat::OpenCvYaml);
    CHECK(camera_format_from_path("a/b.yml") == CameraFormat::OpenCvYaml);
    CHECK_FALSE(camera_format_from_path("a/b.txt").has_value());
}

// ---------------------------------------------------------------------------------
// Atomic writes

namespace {

// True when this process can create files in a folder it has made read-only (root, or
// CAP_DAC_OVERRIDE): then permissions cannot make a write fail.
bool ignores_folder_permissions(const fs::path& read_only_folder) {
    const fs::path probe = read_only_folder / "probe";
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd < 0) return false;
    ::close(fd);
    ::unlink(probe.c_str());
    return true;
}

}  // namespace

TEST_CASE("write_file_atomically replaces a file and keeps its permissions", "[files][atomic]") {
    TempDir dir;
    const fs::path path = dir.path() / "camera.json";
    write_file_atomically(path, "first\n");
    CHECK(slurp(path) == "first\n");
    ::chmod(path.c_str(), 0640);
    write_file_atomically(path, "second, longer contents\n");
    CHECK(slurp(path) == "second, longer contents\n");
    struct stat status {};
    REQUIRE(::stat(path.c_str(), &status) == 0);
    CHECK((status.st_mode & 07777) == 0640);
    write_file_atomically(path, "");
    CHECK(slurp(path).empty());
    CHECK(folder_listing(dir.path()) == std::vector<std::string>{"camera.json"});
    CHECK(read_text_file(path).empty());
    CHECK_THROWS_AS(read_text_file(dir.path() / "absent"), FileError);
    CHECK_THROWS_AS(read_text_file(dir.path()), FileError);
}

TEST_CASE("sync_folder flushes a folder, and names what is no folder", "[files][atomic]") {
    TempDir dir;
    CHECK_NOTHROW(sync_folder(dir.path()));
    const fs::path file = dir.path() / "camera.json";
    write_file_atomically(file, "{}\n");
    CHECK_THAT(error_of([&] { sync_folder(file); }),
               StartsWith("FileError: " + file.string() + ": cannot open the folder to flush it: "));
    const fs::path absent = dir.path() / "absent";
    CHECK_THAT(error_of([&] { sync_folder(absent); }), StartsWith("FileError: " + absent.string() + ": "));
    CHECK_THAT(error_of([&] { write_file_atomically(absent / "camera.json", "{}"); }), Contains(absent.string()));
}

TEST_CASE("write_file_atomically fails cleanly: FileError, old file intact, no temporary left", "[files][atomic]") {
    TempDir dir;
    const fs::path folder = dir.path() / "target";
    fs::create_directory(folder);
    const fs::path path = folder / "camera.yaml";
    std::string old_contents = "%YAML:1.0\n---\nold: contents\n";
    for (int i = 0; i < 64; ++i) old_contents += "# padding line " + std::to_string(i) + "\n";
    write_text(path, old_contents);
    const std::string new_contents(4096, 'x');

    SECTION("in a folder made read-only") {
        REQUIRE(::chmod(folder.c_str(), 0555) == 0);
        if (ignores_folder_permissions(folder)) {
            ::chmod(folder.c_str(), 0755);
            WARN("running with privileges that ignore folder permissions: the read-only case is covered by the other sections");
        } else {
            const std::string message = error_of([&] { write_file_atomically(path, new_contents); });
            CHECK_THAT(message, StartsWith("FileError: ") && Contains(path.string()));
            ::chmod(folder.c_str(), 0755);
            CHECK(slurp(path) == old_contents);
            CHECK(folder_listing(folder) == std::vector<std::string>{"camera.yaml"});
        }
    }

    SECTION("when the target is a folder (rename fails after the temporary is written)") {
        const fs::path occupied = folder / "occupied";
        fs::create_directory(occupied);
        write_text(occupied / "inside", "keep");
        const std::string message = error_of([&] { write_file_atomically(occupied, new_contents); });
        CHECK_THAT(message, StartsWith("FileError: ") && Contains(occupied.string()));
        CHECK(fs::is_directory(occupied));
        CHECK(slurp(occupied / "inside") == "keep");
        CHECK(slurp(path) == old_contents);
        CHECK(folder_listing(folder) == std::vector<std::string>{"camera.yaml", "occupied"});
    }

    SECTION("when the write itself fails (file size limit) over an existing file") {
        // RLIMIT_FSIZE makes write() fail with EFBIG past the limit; SIGXFSZ is ignored
        // so the failure is a return value, as a full disk would give.
        struct rlimit saved {};
        REQUIRE(::getrlimit(RLIMIT_FSIZE, &saved) == 0);
        const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
        struct rlimit limited = saved;
        limited.rlim_cur = 100;
        REQUIRE(::setrlimit(RLIMIT_FSIZE, &limited) == 0);
        const std::string message = error_of([&] { write_file_atomically(path, new_contents); });
        ::setrlimit(RLIMIT_FSIZE, &saved);
        std::signal(SIGXFSZ, old_handler);
        CHECK_THAT(message, StartsWith("FileError: ") && Contains(path.string()));
        CHECK(slurp(path) == old_contents);
        CHECK(folder_listing(folder) == std::vector<std::string>{"camera.yaml"});
    }

    SECTION("when the parent folder does not exist") {
        const fs::path nowhere = folder / "no-such-folder" / "camera.yaml";
        const std::string message = error_of([&] { write_file_atomically(nowhere, new_contents); });
        CHECK_THAT(message, StartsWith("FileError: ") && Contains(nowhere.string()));
        CHECK_FALSE(fs::exists(folder / "no-such-folder"));
        CHECK(folder_listing(folder) == std::vector<std::string>{"camera.yaml"});
    }

    SECTION("in /proc/self, which refuses new files") {
        const fs::path proc_path = fs::path("/proc/self") / "libcam-camera.json";
        const std::string message = error_of([&] { write_file_atomically(proc_path, new_contents); });
        CHECK_THAT(message, StartsWith("FileError: ") && Contains(proc_path.string()));
        CHECK_FALSE(fs::exists(proc_path));
    }

    SECTION("write_camera_file over an existing camera in a failing folder keeps the old camera") {
        const Camera camera = to_camera(libcam::test::random_look_at_camera({640, 480}, FovAxis::Both));
        const fs::path camera_path = folder / "good.json";
        write_camera_file(camera_path, camera, CameraFormat::Json);
        const std::string before = slurp(camera_path);
        Camera other = camera;
        other.intrinsics.fx *= 2.0;
        struct rlimit saved {};
        REQUIRE(::getrlimit(RLIMIT_FSIZE, &saved) == 0);
        const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
        struct rlimit limited = saved;
        limited.rlim_cur = 64;
        REQUIRE(::setrlimit(RLIMIT_FSIZE, &limited) == 0);
        const std::string message = error_of([&] { write_camera_file(camera_path, other, CameraFormat::Json); });
        ::setrlimit(RLIMIT_FSIZE, &saved);
        std::signal(SIGXFSZ, old_handler);
        CHECK_THAT(message, StartsWith("FileError: "));
        CHECK(slurp(camera_path) == before);
        CHECK(read_camera_file(camera_path).camera.intrinsics.fx == camera.intrinsics.fx);
        CHECK(folder_listing(folder) == std::vector<std::string>{"camera.yaml", "good.json"});
    }
}

TEST_CASE("The fuzzing seed of the wide lens is the library's example camera \"wide\", digit for digit") {
    // The corpus file is data for the fuzzer (and the documentation's example file); the
    // camera itself is written once, in camera/example_cameras.cpp. They must not drift.
    const Camera from_file = read_camera_file(fs::path(LIBCAM_FUZZ_CORPUS) / "json" / "opencv8.json").camera;
    const Camera example = example_camera("wide");
    CHECK(from_file.size == example.size);
    CHECK(from_file.intrinsics.K() == example.intrinsics.K());
    CHECK(from_file.lens == example.lens);
    CHECK(from_file.pose.R == example.pose.R);
    CHECK(from_file.pose.t == example.pose.t);
}
