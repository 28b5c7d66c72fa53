// libcam's remap maps against OpenCV's (cv::initUndistortRectifyMap, cv::fisheye's and
// cv::omnidir's), the inverse map checked by projecting, the new camera chosen for real
// lenses, and the derived cameras against the pixel arithmetic worked by hand.

#include <catch2/catch.hpp>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <Eigen/LU>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/ccalib/omnidir.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/stitching/warpers.hpp>

#include <nlohmann/json.hpp>

#include "libcam/camera/example_cameras.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/convert/blender_camera.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/image_remap.hpp"
#include "libcam/interop/opencv.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/remap/derived_camera.hpp"
#include "libcam/remap/new_camera.hpp"
#include "libcam/remap/render_plan.hpp"
#include "cli_runner.hpp"
#include "temp_dir.hpp"
#include "real_cameras.hpp"

using namespace libcam;
using libcam::test::CliResult;
using libcam::test::read_whole_file;
using libcam::test::run_program;
using libcam::test::real_cameras_folder;
using libcam::test::real_cameras_present;
namespace fs = std::filesystem;

namespace {

const fs::path kRealCameras = real_cameras_folder();

Mat3 small_rotation() { return rotation_from_rvec(Vec3(0.02, -0.03, 0.01)); }

// A new camera turned by small_rotation(), keeping `keep`.
NewCameraRequest turned_request(Keep keep) {
    NewCameraRequest request;
    request.keep = keep;
    request.rotation = small_rotation();
    return request;
}

cv::Mat cv_matrix(const Mat3& m) {
    cv::Mat out(3, 3, CV_64F);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out.at<double>(r, c) = m(r, c);
    return out;
}

struct Comparison {
    double worst = 0;       // px, where both have a source
    std::size_t both = 0;   // pixels compared
    std::size_t opencv_only = 0;  // libcam flags, OpenCV gives a coordinate on the image
    std::size_t opencv_only_without_ray = 0;  // of those, OpenCV's source pixel has no ray at all
    double worst_opencv_only_ray_error = 0;  // rad: how far OpenCV's pixel's ray (where it has one) is from the target's
};

// libcam's map against OpenCV's (CV_32FC1 x and y), and for each pixel libcam flags while
// OpenCV gives a coordinate on the image, the angle between the target pixel's ray and
// the ray of OpenCV's source pixel (libcam's exact unprojection): who is right.
Comparison compare(const RemapMap& map, const cv::Mat& map_x, const cv::Mat& map_y, const PreparedCamera& target,
                   const PreparedCamera& source, const Mat3& rotation) {
    Comparison c;
    const long width = map.size.width;
    for (long y = 0; y < map.size.height; ++y) {
        for (long x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * width + x);
            const double ox = map_x.at<float>(static_cast<int>(y), static_cast<int>(x));
            const double oy = map_y.at<float>(static_cast<int>(y), static_cast<int>(x));
            if (map.has_source(i)) {
                c.worst = std::max(c.worst, std::hypot(map.x[i] - ox, map.y[i] - oy));
                ++c.both;
            } else if (on_image(ox, oy, map.source_size)) {
                ++c.opencv_only;
                const Unprojection target_ray = target.unproject(Vec2(double(x), double(y)));
                const Unprojection opencv_ray = source.unproject(Vec2(ox, oy));
                if (target_ray.valid && opencv_ray.valid) {
                    const Vec3 a = (rotation.transpose() * target_ray.direction).normalized();
                    c.worst_opencv_only_ray_error =
                        std::max(c.worst_opencv_only_ray_error, std::acos(std::clamp(a.dot(opencv_ray.direction.normalized()), -1.0, 1.0)));
                } else {
                    ++c.opencv_only_without_ray;  // past the lens's fold: that pixel sees no ray
                }
            }
        }
    }
    return c;
}

Camera real_camera(const std::string& file, const std::string& name = "") {
    return read_camera_file(kRealCameras / file, name).camera;
}

// How many pixels of a camera's image have a ray (the exact unprojection's).
std::size_t pixels_with_a_ray(const PreparedCamera& camera) {
    ValidFlags has_ray;
    Points3<double> rays;
    camera.unprojector().unproject_image(UnprojectMethod::Exact, rays, has_ray, 2);
    std::size_t count = 0;
    for (const std::uint8_t v : has_ray) count += v;
    return count;
}

// The "valid" pinhole chosen for a lens, turned by small_rotation(), and libcam's map from
// it to the lens: what each comparison with OpenCV starts from.
struct Undistortion {
    explicit Undistortion(const Camera& lens_camera)
        : lens(lens_camera),
          source(lens),
          pinhole(choose_new_camera(source, turned_request(Keep::Valid)).camera),
          target(pinhole),
          map(build_remap_map(target, source, {small_rotation(), UnprojectMethod::Exact, 2})) {}

    // OpenCV's arguments: the new camera's K and size, and R.
    cv::Mat new_K() const { return opencv_camera_matrix(pinhole.intrinsics); }
    cv::Size new_size() const { return {int(pinhole.size.width), int(pinhole.size.height)}; }
    static cv::Mat R() { return cv_matrix(small_rotation()); }
    // libcam's map against OpenCV's: every pixel compared, within float32's rounding.
    void check_against(const cv::Mat& map_x, const cv::Mat& map_y) const {
        const Comparison c = compare(map, map_x, map_y, target, source, small_rotation());
        INFO("worst " << c.worst << " px over " << c.both << " pixels");
        CHECK(c.both == map.x.size());
        CHECK(c.worst < 1e-3);  // OpenCV's map is float32
    }

    Camera lens;
    PreparedCamera source;
    Camera pinhole;
    PreparedCamera target;
    RemapMap map;
};

}  // namespace

TEST_CASE("OPENCV8 lens to a pinhole: libcam's map is cv::initUndistortRectifyMap's wherever OpenCV's forward model holds",
          "[remap][opencv]") {
    for (const char* name : {"wide", "strong"}) {
        CAPTURE(name);
        Camera lens = example_camera(name);
        if (lens.size.width > 2000) lens = binned(lens, 4);  // the wide lens: 1504x1004
        const Undistortion u(lens);
        CHECK(u.map.with_source == u.map.x.size());  // "valid": every pixel has a source
        cv::Mat map_x, map_y;
        cv::initUndistortRectifyMap(opencv_camera_matrix(lens.intrinsics), opencv_distortion(lens.lens), u.R(),
                                    u.new_K(), u.new_size(), CV_32FC1, map_x, map_y);
        u.check_against(map_x, map_y);

        // A wider pinhole ("all") reaches past the strong lens's fold-over radius: there
        // libcam has no source, and OpenCV's forward model lands on pixels that see other rays.
        const Camera wide_pinhole = choose_new_camera(u.source, turned_request(Keep::All)).camera;
        if (wide_pinhole.lens.type != LensType::Pinhole) continue;
        const PreparedCamera wide_target(wide_pinhole);
        const RemapMap wide_map = build_remap_map(wide_target, u.source, {small_rotation(), UnprojectMethod::Exact, 2});
        cv::initUndistortRectifyMap(opencv_camera_matrix(lens.intrinsics), opencv_distortion(lens.lens), u.R(),
                                    opencv_camera_matrix(wide_pinhole.intrinsics),
                                    cv::Size(int(wide_pinhole.size.width), int(wide_pinhole.size.height)), CV_32FC1, map_x,
                                    map_y);
        const Comparison w = compare(wide_map, map_x, map_y, wide_target, u.source, small_rotation());
        WARN(name << " to the pinhole that keeps everything: maps agree to " << w.worst << " px over " << w.both
                  << " pixels; OpenCV gives " << w.opencv_only << " pixels a source libcam flags: "
                  << w.opencv_only_without_ray << " of those sources see no ray at all (past the lens's fold), the "
                  << "rays of the others are up to " << w.worst_opencv_only_ray_error * 180 / M_PI
                  << " deg from the pixel's own");
        CHECK(w.worst < 1e-3);
        if (w.opencv_only > w.opencv_only_without_ray) CHECK(w.worst_opencv_only_ray_error > 1e-3);
    }
}

TEST_CASE("FISHEYE and MEI lenses to a pinhole: libcam's map is cv::fisheye's and cv::omnidir's", "[remap][opencv][real]") {
    if (!real_cameras_present()) return;
    SECTION("FISHEYE: the RealSense T265 (basalt's calibration)") {
        const Undistortion u(real_camera("basalt/t265_kb4_calib.json"));
        cv::Mat map_x, map_y;
        cv::fisheye::initUndistortRectifyMap(opencv_camera_matrix(u.lens.intrinsics), opencv_distortion(u.lens.lens),
                                             u.R(), u.new_K(), u.new_size(), CV_32FC1, map_x, map_y);
        u.check_against(map_x, map_y);
    }
    SECTION("MEI: the EuRoC camera VINS-Fusion calibrated (camodocal)") {
        const Undistortion u(real_camera("vins-fusion/euroc/cam0_mei.yaml"));
        cv::Mat map_x, map_y;
        cv::omnidir::initUndistortRectifyMap(opencv_camera_matrix(u.lens.intrinsics), opencv_distortion(u.lens.lens),
                                             cv::Mat(1, 1, CV_64F, cv::Scalar(opencv_xi(u.lens.lens))), u.R(),
                                             u.new_K(), u.new_size(), CV_32FC1, map_x, map_y,
                                             cv::omnidir::RECTIFY_PERSPECTIVE);
        u.check_against(map_x, map_y);
    }
}

TEST_CASE("A pinhole to a CYLINDRICAL panorama: libcam's map is OpenCV's stitching warper's (cv::CylindricalWarper)",
          "[remap][opencv]") {
    // A photo (fx != fy, principal point off centre) onto a cylinder of 700 px per radian,
    // the camera turned by R (d_cylinder = R d_photo, as libcam's rotation). OpenCV computes
    // in float: K and R are given to both as floats.
    const Mat3 R_float_rounded = small_rotation().cast<float>().cast<double>();
    const Mat3 R = nearest_rotation_if_rounded(R_float_rounded);  // within 3e-8 rad of OpenCV's
    Camera photo;
    photo.size = {1280, 960};
    photo.intrinsics = {900, 880, 650.25, 470.75, 0};
    const float scale = 700;
    cv::Mat_<float> K(3, 3, 0.0f), R_float(3, 3, 0.0f);
    K(0, 0) = 900, K(1, 1) = 880, K(0, 2) = 650.25f, K(1, 2) = 470.75f, K(2, 2) = 1;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) R_float(r, c) = static_cast<float>(R(r, c));
    cv::Mat map_x, map_y;
    const cv::Rect roi = cv::detail::CylindricalWarper(scale).buildMaps(cv::Size(1280, 960), K, R_float, map_x, map_y);
    // OpenCV's cylinder pixel (x, y) is at u = roi.x + x, v = roi.y + y (longitude u / scale,
    // height v / scale): libcam's CYLINDRICAL with f = scale and the principal point at -roi's corner.
    Camera cylinder;
    cylinder.size = {roi.width, roi.height};
    cylinder.intrinsics = {scale, scale, -double(roi.x), -double(roi.y), 0};
    cylinder.lens = {LensType::Cylindrical, {}};
    const PreparedCamera target(cylinder), source(photo);
    const RemapMap map = build_remap_map(target, source, {R, UnprojectMethod::Exact, 2});
    const Comparison c = compare(map, map_x, map_y, target, source, R);
    WARN("CYLINDRICAL " << roi.width << "x" << roi.height << " from a pinhole photo: libcam's map and OpenCV's agree to "
                        << c.worst << " px over " << c.both << " pixels; OpenCV alone gives " << c.opencv_only
                        << " a source on the photo");
    CHECK(c.both > map.x.size() / 2);
    CHECK(c.worst < 1e-3);  // OpenCV's float arithmetic
    CHECK(c.opencv_only == 0);
}

TEST_CASE("The float map is the double map rounded once: the same pixels without a source, every coordinate "
          "the double one rounded to float", "[sweep][remap]") {
    // Both directions (undistorting: a PINHOLE target, its rays from K^-1 row by row;
    // distorting: the lens's unprojection), turned and not, a lens whose corners have no
    // ray in the pinhole (the fisheye's, past 90 degrees) and a skewed pinhole.
    const Camera wide = binned(example_camera("wide"), 8);
    Camera fisheye = example_camera("fisheye");
    Camera fisheye_pinhole = fisheye;
    fisheye_pinhole.lens = Lens{};
    fisheye_pinhole.intrinsics.fx *= 0.3;  // a pinhole as wide as the lens sees
    fisheye_pinhole.intrinsics.fy *= 0.3;
    Camera wide_pinhole = wide;
    wide_pinhole.lens = Lens{};
    wide_pinhole.intrinsics.skew = 3.0;  // the skewed pinhole's rays too
    struct Pair {
        const char* name;
        Camera target, source;
    };
    for (const Pair& pair : {Pair{"wide undistorted", wide_pinhole, wide}, Pair{"wide distorted", wide, wide_pinhole},
                             Pair{"fisheye undistorted", fisheye_pinhole, fisheye},
                             Pair{"fisheye distorted", fisheye, fisheye_pinhole}}) {
        for (const Mat3& rotation : {Mat3(Mat3::Identity()), small_rotation()}) {
            for (UnprojectMethod method : {UnprojectMethod::Exact, UnprojectMethod::Fast}) {
                INFO(pair.name << (rotation.isIdentity() ? "" : ", turned") << ", method " << method_name(method));
                const PreparedCamera target(pair.target), source(pair.source);
                const RemapOptions options{rotation, method, 2};
                const RemapMap exact = build_remap_map(target, source, options);
                const RemapMapFloat rounded = build_remap_map<float>(target, source, options);
                REQUIRE(rounded.x.size() == exact.x.size());
                CHECK(rounded.with_source == exact.with_source);
                CHECK(rounded.size.width == exact.size.width);
                CHECK(rounded.source_size.height == exact.source_size.height);
                std::size_t differ = 0;
                for (std::size_t i = 0; i < exact.x.size(); ++i) {
                    const bool same = exact.has_source(i)
                                          ? rounded.x[i] == static_cast<float>(exact.x[i]) && rounded.y[i] == static_cast<float>(exact.y[i])
                                          : !rounded.has_source(i) && std::isnan(rounded.y[i]);
                    differ += same ? 0 : 1;
                }
                CHECK(differ == 0);
                // The cases hold pixels both with and without a source: a lens pixel whose
                // ray the pinhole does not see has none.
                if (pair.target.lens.type != LensType::Pinhole) CHECK(exact.with_source < exact.x.size());
                CHECK(exact.with_source > 0);
            }
        }
    }
}

TEST_CASE("A PINHOLE target's map is each pixel's ray (Camera::unproject) projected by the source, to 1e-9 px",
          "[remap]") {
    const Camera lens = binned(example_camera("strong"), 4);
    Camera pinhole = lens;
    pinhole.lens = Lens{};
    pinhole.intrinsics.skew = 2.5;
    const PreparedCamera target(pinhole), source(lens);
    const Mat3 rotation = small_rotation();
    const RemapMap map = build_remap_map(target, source, {rotation, UnprojectMethod::Exact, 1});
    const std::size_t width = static_cast<std::size_t>(pinhole.size.width);
    double worst = 0;
    std::size_t disagree = 0;
    for (std::size_t i = 0; i < map.x.size(); ++i) {
        const Vec2 pixel(double(i % width), double(i / width));
        const Unprojection ray = target.unproject(pixel);
        REQUIRE(ray.valid);
        const Projection seen = source.project_camera_point(rotation.transpose() * ray.direction);
        const bool has = seen.valid && on_image(seen.pixel.x(), seen.pixel.y(), lens.size);
        if (has != map.has_source(i)) {
            ++disagree;
            continue;
        }
        if (has) worst = std::max(worst, (Vec2(map.x[i], map.y[i]) - seen.pixel).norm());
    }
    CHECK(disagree == 0);
    CHECK(worst <= 1e-9);
}

TEST_CASE("The inverse map (pinhole render to the lens): each source pixel's ray projects back onto its lens pixel "
          "within 1e-6 px, where cv::initInverseRectificationMap is off by more",
          "[remap][opencv]") {
    const Camera lens = example_camera("mild");
    const PreparedCamera prepared_lens(lens);
    NewCameraRequest request;
    request.keep = Keep::All;
    const Camera pinhole = choose_new_camera(prepared_lens, request).camera;
    REQUIRE(pinhole.lens.type == LensType::Pinhole);
    const PreparedCamera render(pinhole);
    // Target: the lens; source: the pinhole render.
    const RemapMap map = build_remap_map(prepared_lens, render, {Mat3::Identity(), UnprojectMethod::Exact, 2});
    CHECK(map.with_source == pixels_with_a_ray(prepared_lens));  // "all": every lens pixel with a ray is in the render

    double worst = 0;
    const Mat3 k_inverse = pinhole.intrinsics.K().inverse();
    for (std::size_t i = 0; i < map.x.size(); i += 7) {
        if (!map.has_source(i)) continue;
        const Vec3 ray = k_inverse * Vec3(map.x[i], map.y[i], 1.0);
        const Projection back = prepared_lens.project_camera_point(ray);
        REQUIRE(back.valid);
        const Vec2 pixel(double(i % std::size_t(lens.size.width)), double(i / std::size_t(lens.size.width)));
        worst = std::max(worst, (back.pixel - pixel).norm());
    }
    INFO("worst reprojection " << worst << " px");
    CHECK(worst < 1e-6);

    cv::Mat map_x, map_y;
    cv::initInverseRectificationMap(opencv_camera_matrix(lens.intrinsics), opencv_distortion(lens.lens), cv::Mat(),
                                    opencv_camera_matrix(pinhole.intrinsics),
                                    cv::Size(int(lens.size.width), int(lens.size.height)), CV_32FC1, map_x, map_y);
    double opencv_worst = 0;
    for (std::size_t i = 0; i < map.x.size(); ++i) {
        if (!map.has_source(i)) continue;
        const int x = int(i % std::size_t(lens.size.width)), y = int(i / std::size_t(lens.size.width));
        opencv_worst = std::max(opencv_worst, std::hypot(map.x[i] - map_x.at<float>(y, x), map.y[i] - map_y.at<float>(y, x)));
    }
    WARN("cv::initInverseRectificationMap is up to " << opencv_worst << " px from libcam's inverse map (whose pixels "
                                                       "reproject within " << worst << " px)");
    CHECK(opencv_worst > worst);
}

namespace {

// The new cameras chosen for a lens, pinhole, LONLAT and CYLINDRICAL, "valid" and "all": finite and
// not degenerate; "valid" gives every pixel a source, half a pixel inside the lens's
// image (interpolation never reads its border); "all" keeps every lens pixel that has a
// ray (the map back from the lens to the new camera finds each of them a source).
void check_new_cameras(const Camera& lens) {
    const PreparedCamera source(lens);
    for (const LensType model : {LensType::Pinhole, LensType::Lonlat, LensType::Cylindrical}) {
        for (const Keep keep : {Keep::Valid, Keep::All}) {
            NewCameraRequest request;
            request.model = model;
            request.keep = keep;
            request.threads = 2;
            const NewCamera chosen = choose_new_camera(source, request);
            CAPTURE(chosen.why);
            const double f = chosen.camera.intrinsics.fx;
            CHECK(std::isfinite(f));
            CHECK(f > 0.05 * lens.intrinsics.fx);
            CHECK(f < 20 * lens.intrinsics.fx);
            const PreparedCamera target(chosen.camera);
            if (keep == Keep::Valid) {
                const RemapMap map = build_remap_map(target, source, {Mat3::Identity(), UnprojectMethod::Exact, 2});
                CHECK(map.with_source == map.x.size());
                bool inside = true;
                for (std::size_t i = 0; i < map.x.size(); ++i) inside = inside && on_image(map.x[i], map.y[i], map.source_size, -0.5);
                CHECK(inside);
            } else {
                const RemapMap map = build_remap_map(source, target, {Mat3::Identity(), UnprojectMethod::Exact, 2});
                CHECK(map.with_source == pixels_with_a_ray(source));
            }
        }
    }
}

}  // namespace

TEST_CASE("The new camera for real lenses: 'valid' leaves no pixel without a source, 'all' loses no lens pixel",
          "[sweep][remap][real]") {
    if (!real_cameras_present()) return;
    struct Lens {
        const char* file;
        int bin;
    };
    for (const Lens& entry : {Lens{"basalt/t265_kb4_calib.json", 1}, Lens{"vins-fusion/mynteye/left_mei.yaml", 1},
                              Lens{"mrcal/splined-0.cameramodel", 8}, Lens{"colmap-fiord-fisheye/cameras.txt", 4}}) {
        CAPTURE(entry.file);
        Camera lens = real_camera(entry.file);
        lens.pose = {};
        if (entry.bin > 1) lens = binned(lens, entry.bin);
        check_new_cameras(lens);
    }
}

TEST_CASE("The new camera where OpenCV's choosers fail: a fisheye whose corners have no ray, a lens whose corners wrap",
          "[sweep][remap][opencv]") {
    // (Section names without ':' past the first line: Catch 2.13 indents a wrapped name to
    // its ':', and loops forever printing one that has it near the end of a line.)
    SECTION("the fisheye of OpenCV's issue 23961, whose corners have no ray") {
        // cv::fisheye's new camera for it is degenerate; libcam's are not.
        Camera lens;
        lens.size = {1900, 1200};
        lens.intrinsics = {1.20017697e+03, 1.19942873e+03, 9.51246069e+02, 6.01045081e+02, -1.42041106e-01};
        lens.lens = {LensType::Fisheye, {-0.99137234, -0.1205525, 0.36863644, -1.0656211}};
        for (const double balance : {0.0, 1.0}) {
            cv::Mat K;
            cv::fisheye::estimateNewCameraMatrixForUndistortRectify(opencv_camera_matrix(lens.intrinsics),
                                                                    opencv_distortion(lens.lens), cv::Size(1900, 1200),
                                                                    cv::Matx33d::eye(), K, balance);
            const double f = K.at<double>(0, 0), cx = K.at<double>(0, 2);
            INFO("OpenCV, balance " << balance << ": f " << f << ", cx " << cx);
            // OpenCV 4.6: f 1.52 with cx 1.5e6 at balance 0, a negative f at 1 (NaN in later versions).
            CHECK_FALSE((std::isfinite(f) && f > 100 && cx > 0 && cx < 1900));
        }
        check_new_cameras(lens);
    }
    SECTION("the wide lens, whose corners wrap around as in OpenCV's issue 7332") {
        // cv::getOptimalNewCameraMatrix's alpha 0 ("no black pixels") gives pixels 1.66
        // times taller than wide (3.5 times on the lens at full size); libcam's cameras
        // keep square pixels and are what they say.
        const Camera lens = binned(example_camera("wide"), 4);
        const cv::Size size(int(lens.size.width), int(lens.size.height));
        const cv::Mat none_black = cv::getOptimalNewCameraMatrix(opencv_camera_matrix(lens.intrinsics),
                                                                 opencv_distortion(lens.lens), size, 0.0);
        const double aspect = none_black.at<double>(1, 1) / none_black.at<double>(0, 0);
        INFO("OpenCV's alpha 0 camera: fx " << none_black.at<double>(0, 0) << ", fy " << none_black.at<double>(1, 1));
        CHECK(aspect > 1.5);
        check_new_cameras(lens);
    }
}

TEST_CASE("The new camera with a field of view has it, edge to edge, and impossible requests say why", "[remap]") {
    const PreparedCamera lens(example_camera("fisheye"));
    NewCameraRequest request;
    request.keep.reset();
    request.fov_deg = 90;
    request.size = ImageSize{800, 600};
    const Camera pinhole = choose_new_camera(lens, request).camera;
    // 90 degrees across 800 pixels, edge to edge: f = 400 / tan 45 = 400; centre 399.5, 299.5.
    CHECK_THAT(pinhole.intrinsics.fx, Catch::WithinRel(400.0, 1e-15));
    CHECK(pinhole.intrinsics.fy == pinhole.intrinsics.fx);
    CHECK(pinhole.intrinsics.cx == 399.5);
    CHECK(pinhole.intrinsics.cy == 299.5);
    request.model = LensType::Lonlat;
    request.fov_deg = 180;
    // LONLAT: 180 degrees across 800 pixels: f = 800 / pi per radian.
    CHECK_THAT(choose_new_camera(lens, request).camera.intrinsics.fx, Catch::WithinRel(800.0 / M_PI, 1e-15));
    // CYLINDRICAL: across, as LONLAT; 90 degrees down 600 pixels, as a pinhole: f = 300 / tan 45.
    request.model = LensType::Cylindrical;
    CHECK_THAT(choose_new_camera(lens, request).camera.intrinsics.fx, Catch::WithinRel(800.0 / M_PI, 1e-15));
    request.fov_axis = FovAxis::Vertical;
    request.fov_deg = 90;
    CHECK_THAT(choose_new_camera(lens, request).camera.intrinsics.fx, Catch::WithinRel(300.0, 1e-15));
    request.fov_deg = 180;
    CHECK_THROWS_WITH(choose_new_camera(lens, request), Catch::Contains("vertical fov must be in (0, 180)"));
    request.model = LensType::Lonlat;
    request.fov_axis = FovAxis::Diagonal;
    CHECK_THROWS_WITH(choose_new_camera(lens, request), Catch::Contains("not diagonally"));
    request.model = LensType::Pinhole;
    request.fov_axis = FovAxis::Horizontal;
    request.fov_deg = 180;
    CHECK_THROWS_WITH(choose_new_camera(lens, request), Catch::Contains("must be in (0, 180)"));
    // A target looking backwards sees nothing of a lens that sees 100 degrees off its axis at most.
    NewCameraRequest away;
    away.rotation = rotation_from_rvec(Vec3(0, M_PI, 0));
    CHECK_THROWS_WITH(choose_new_camera(PreparedCamera(example_camera("mild")), away),
                      Catch::Contains("sees nothing along the target's axis"));
}

TEST_CASE("Derived cameras: the half-pixel rule for resizing and binning, crops and pads move the centre", "[remap]") {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500, 510, 319.5, 239.5, 0};
    // Half size: the edges (-0.5, 639.5) go to (-0.5, 319.5): cx' = 0.5 (319.5 + 0.5) - 0.5 = 159.5.
    const Camera half = scaled(camera, 0.5);
    CHECK(half.size == ImageSize{320, 240});
    CHECK(half.intrinsics.fx == 250);
    CHECK(half.intrinsics.fy == 255);
    CHECK(half.intrinsics.cx == 159.5);
    CHECK(half.intrinsics.cy == 119.5);
    // Binning 3 of 640: 213 columns (one dropped), cx' = (319.5 + 0.5) / 3 - 0.5.
    const Camera bin3 = binned(camera, 3);
    CHECK(bin3.size == ImageSize{213, 160});
    CHECK(bin3.intrinsics.cx == Approx(320.0 / 3 - 0.5).epsilon(1e-15));
    // Resizing each axis by its own factor: 1280 x 240.
    const Camera stretched = resized(camera, {1280, 240});
    CHECK(stretched.intrinsics.fx == 1000);
    CHECK(stretched.intrinsics.cx == 639.5);
    CHECK(stretched.intrinsics.fy == 255);
    const Camera crop = cropped(camera, 100, 50, 300, 250);
    CHECK(crop.size == ImageSize{200, 200});
    CHECK(crop.intrinsics.cx == 219.5);
    CHECK(crop.intrinsics.cy == 189.5);
    const Camera pad = padded(camera, 10, 20, 30, 40);
    CHECK(pad.size == ImageSize{680, 540});
    CHECK(pad.intrinsics.cx == 329.5);
    CHECK(pad.intrinsics.cy == 259.5);
    CHECK_THROWS_WITH(cropped(camera, 10, 10, 10, 20), Catch::Contains("x1 must exceed x0"));
    CHECK_THROWS_WITH(binned(camera, 1000), Catch::Contains("0x0"));
}

TEST_CASE("A quarter turn of the camera is the quarter turn of its image: pixel (x, y) goes to (H - 1 - y, x)",
          "[remap]") {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500, 510, 300.25, 250.75, 0};
    camera.pose = Pose::from_rvec(Vec3(0.1, 0.2, -0.3), Vec3(1, 2, 3));
    const std::vector<Lens> lenses = {
        {LensType::OpenCv5, {-0.2, 0.05, 1e-3, -2e-3, 0.01}},
        {LensType::OpenCv12, {-0.2, 0.05, 1e-3, -2e-3, 0.01, 0.1, 0.01, 0.001, 1e-3, -2e-4, 3e-3, -4e-4}},
        {LensType::Fisheye, {0.01, -0.002, 3e-4, -4e-5}},
        {LensType::Mei, {1.2, -0.1, 0.01, 2e-3, -1e-3}},
        {LensType::ThinPrismFisheye, {0.01, -0.002, 1e-3, -2e-3, 3e-4, -4e-5, 2e-3, -1e-3}},
        {LensType::RadTanThinPrismFisheye, {0.01, -0.002, 3e-4, -4e-5, 1e-5, -1e-6, 1e-3, -2e-3, 1e-3, -2e-4, 3e-3, -4e-4}},
        {LensType::DoubleSphere, {-0.2, 0.6}},
    };
    for (const Lens& lens : lenses) {
        CAPTURE(lens_info(lens.type).name);
        camera.lens = lens;
        const PreparedCamera original(camera);
        const PreparedCamera once(quarter_turns(camera, 1));
        const PreparedCamera half(quarter_turns(camera, 2));
        const PreparedCamera back(quarter_turns(camera, 4));
        CHECK(once.camera().size == ImageSize{480, 640});
        double worst = 0;
        for (int i = 0; i < 50; ++i) {
            const Vec3 world(0.3 * std::sin(i), 0.2 * std::cos(3 * i), 0) ;
            const Vec3 point = camera.pose.R.transpose() * (Vec3(world.x(), world.y(), 1.0) - camera.pose.t);
            const Projection p = original.project(point);
            const Projection q = once.project(point);
            const Projection r = half.project(point);
            REQUIRE(p.valid);
            REQUIRE(q.valid);
            worst = std::max(worst, (q.pixel - Vec2(479 - p.pixel.y(), p.pixel.x())).norm());
            worst = std::max(worst, (r.pixel - Vec2(639 - p.pixel.x(), 479 - p.pixel.y())).norm());
            worst = std::max(worst, (back.project(point).pixel - p.pixel).norm());
        }
        CHECK(worst < 1e-9);
    }
    camera.lens = {LensType::Lonlat, {}};
    CHECK_THROWS_WITH(quarter_turns(camera, 1), Catch::Contains("LONLAT lens does not look the same turned"));
    camera.lens = {};
    camera.intrinsics.skew = 1;
    CHECK_THROWS_WITH(quarter_turns(camera, 3), Catch::Contains("skew"));
}

namespace {

// An OpenEXR file's float channels, by name, row by row.
std::map<std::string, std::vector<float>> read_exr_channels(const fs::path& path) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    std::map<std::string, std::vector<float>> channels;
    Imf::FrameBuffer frame;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
        std::vector<float>& data = channels[it.name()];
        data.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
        frame.insert(it.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data.data()), sizeof(float),
                                          sizeof(float) * static_cast<std::size_t>(width)));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return channels;
}

}  // namespace

TEST_CASE("STMap: u, v of the source's format with Nuke's pixel centres and y up, and the format inside an overscan",
          "[remap]") {
    // Two target pixels: one from source pixel (0, 2) of a 4x3 source, one with no source.
    RemapMap map;
    map.size = {2, 1};
    map.source_size = {4, 3};
    map.x = {0.0, std::numeric_limits<double>::quiet_NaN()};
    map.y = {2.0, std::numeric_limits<double>::quiet_NaN()};
    map.with_source = 1;
    test::TempDir dir;
    write_stmap_file(dir.path() / "whole.exr", map, {{4, 3}, 0, 0});
    auto channels = read_exr_channels(dir.path() / "whole.exr");
    REQUIRE(channels.size() == 4);
    // Pixel (0, 2)'s centre is at Nuke's (0.5, 0.5) of a 4x3 format: u = 0.5 / 4, v = 0.5 / 3.
    CHECK(channels["R"][0] == Approx(0.125).margin(1e-7));
    CHECK(channels["G"][0] == Approx(1.0 / 6.0).margin(1e-7));
    CHECK(channels["B"][0] == 0.0f);
    CHECK(channels["A"][0] == 1.0f);
    CHECK(channels["R"][1] == -1.0f);
    CHECK(channels["G"][1] == -1.0f);
    CHECK(channels["A"][1] == 0.0f);
    // The same source with a margin of 1 pixel left and top around a 2x1 format: the pixel
    // is in the left margin (u < 0) and below the format (v < 0, Nuke's y is up).
    write_stmap_file(dir.path() / "overscan.exr", map, {{2, 1}, 1, 1});
    channels = read_exr_channels(dir.path() / "overscan.exr");
    CHECK(channels["R"][0] == Approx(-0.25).margin(1e-7));
    CHECK(channels["G"][0] == Approx(-0.5).margin(1e-7));
    CHECK_THROWS_WITH(write_stmap_file(dir.path() / "map.png", map, {{4, 3}, 0, 0}),
                      Catch::Contains("map.png: an STMap is written as .exr"));
    CHECK_FALSE(fs::exists(dir.path() / "map.png"));
}

TEST_CASE("Overscan: the least margin around a render that gives every lens pixel with a ray a source", "[remap]") {
    // A radial-tangential lens (EuRoC's cam0) and a centred 80-degree pinhole of its size.
    Camera lens_camera;
    lens_camera.size = {752, 480};
    lens_camera.intrinsics = {458.654, 457.296, 367.215, 248.375, 0.0};
    lens_camera.lens = {LensType::OpenCv4, {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05}};
    const PreparedCamera lens(lens_camera);
    NewCameraRequest request;
    request.keep.reset();
    request.fov_deg = 80;
    const Camera render = choose_new_camera(lens, request).camera;
    for (const Mat3& rotation : {Mat3(Mat3::Identity()), small_rotation()}) {
        const Overscan margins = overscan_for(lens, render, rotation, 2);
        INFO("left " << margins.left << ", top " << margins.top << ", right " << margins.right << ", bottom " << margins.bottom);
        CHECK(margins.left > 0);
        CHECK(margins.top > 0);
        CHECK(margins.right > 0);
        CHECK(margins.bottom > 0);
        const Camera with_margins = padded(render, margins.left, margins.top, margins.right, margins.bottom);
        RemapOptions options;
        options.rotation = rotation.transpose();
        const RemapMap map = build_remap_map(lens, PreparedCamera(with_margins), options);
        CHECK(map.with_source == pixels_with_a_ray(lens));
        // Every source on the span of the render's pixel centres, and each margin the least:
        // a pixel less on any side leaves some source off it.
        double low_x = 1e300, low_y = 1e300, high_x = -1e300, high_y = -1e300;
        for (std::size_t i = 0; i < map.x.size(); ++i) {
            if (!map.has_source(i)) continue;
            low_x = std::min(low_x, map.x[i]);
            low_y = std::min(low_y, map.y[i]);
            high_x = std::max(high_x, map.x[i]);
            high_y = std::max(high_y, map.y[i]);
        }
        const double last_x = double(with_margins.size.width - 1), last_y = double(with_margins.size.height - 1);
        CHECK(low_x >= 0);
        CHECK(low_x < 1);
        CHECK(low_y >= 0);
        CHECK(low_y < 1);
        CHECK(high_x <= last_x);
        CHECK(high_x > last_x - 1);
        CHECK(high_y <= last_y);
        CHECK(high_y > last_y - 1);
    }
    // A fisheye that sees past 90 degrees: no pinhole margin holds it, and the error says so.
    Camera fisheye = example_camera("fisheye");
    CHECK_THROWS_WITH(overscan_for(PreparedCamera(fisheye), render), Catch::Contains("give the render a wider view"));
}

TEST_CASE("The render plan: the lens itself when Blender draws it, else a pinhole with margins or Blender's fisheye, "
          "with a source for every lens pixel that has a ray",
          "[remap]") {
    SECTION("a pinhole Blender draws as it is") {
        Camera pinhole;
        pinhole.size = {640, 480};
        pinhole.intrinsics = {500, 510, 300.5, 250.25, 0.0};
        pinhole.lens = {LensType::Pinhole, {}};
        const RenderPlan plan = plan_render(PreparedCamera(pinhole));
        CHECK_FALSE(plan.needs_warp);
        CHECK(plan.render.intrinsics.K() == pinhole.intrinsics.K());
        CHECK(plan.render.size == pinhole.size);
    }
    SECTION("a radial-tangential lens renders as a pinhole with its K and margins") {
        Camera lens_camera;  // EuRoC's cam0
        lens_camera.size = {752, 480};
        lens_camera.intrinsics = {458.654, 457.296, 367.215, 248.375, 0.0};
        lens_camera.lens = {LensType::OpenCv4, {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05}};
        lens_camera.pose = Pose::from_rvec(Vec3(0.1, 0.2, -0.3), Vec3(1, 2, 3));
        const PreparedCamera lens(lens_camera);
        const RenderPlan plan = plan_render(lens, 2);
        INFO(plan.why);
        REQUIRE(plan.render.lens.type == LensType::Pinhole);
        const Overscan& m = plan.margins;
        CHECK(m.left > 0);
        CHECK(m.right > 0);
        CHECK(plan.render.size == ImageSize{752 + m.left + m.right, 480 + m.top + m.bottom});
        CHECK(plan.render.intrinsics.fx == lens_camera.intrinsics.fx);
        CHECK(plan.render.intrinsics.fy == lens_camera.intrinsics.fy);
        CHECK(plan.render.intrinsics.cx == lens_camera.intrinsics.cx + double(m.left));
        CHECK(plan.render.intrinsics.cy == lens_camera.intrinsics.cy + double(m.top));
        CHECK(plan.render.pose.R == lens_camera.pose.R);
        CHECK(plan.render.pose.t == lens_camera.pose.t);
        const RemapMap warp = build_remap_map(lens, PreparedCamera(plan.render));
        CHECK(warp.with_source == pixels_with_a_ray(lens));
    }
    SECTION("a fisheye that sees past 90 degrees renders as Blender's equidistant fisheye") {
        const Camera fisheye = binned(example_camera("fisheye"), 4);  // 400x300: small for the sanitizer run
        const PreparedCamera lens(fisheye);
        const RenderPlan plan = plan_render(lens, 2);
        INFO(plan.why);
        REQUIRE(plan.render.lens.type == LensType::Fisheye);
        CHECK(plan.render.lens.coefficients == std::vector<double>{0, 0, 0, 0});
        CHECK(plan.render.size.width == plan.render.size.height);
        CHECK(plan.render.intrinsics.fx == std::max(fisheye.intrinsics.fx, fisheye.intrinsics.fy));
        // Blender draws it: FISHEYE_EQUIDISTANT with the field of view W / f.
        const BlenderCamera blender = blender_from_camera(plan.render);
        CHECK(blender.type == BlenderCameraType::FisheyeEquidistant);
        CHECK(blender.fisheye_fov == Approx(double(plan.render.size.width) / plan.render.intrinsics.fx));
        // Its image circle (theta <= fov / 2, where Blender renders) holds every lens ray.
        std::vector<Vec2> pixels;
        for (long y = 0; y < fisheye.size.height; ++y) {
            for (long x = 0; x < fisheye.size.width; ++x) pixels.emplace_back(x, y);
        }
        double widest = 0;
        for (const Unprojection& ray : lens.unproject(pixels, 2)) {
            if (ray.valid) widest = std::max(widest, angle_between(ray.direction, Vec3::UnitZ()));
        }
        INFO("widest ray " << widest << " rad");
        CHECK(widest > std::numbers::pi / 2);
        CHECK(blender.fisheye_fov / 2 > widest);
        CHECK(blender.fisheye_fov / 2 < widest + 5 / plan.render.intrinsics.fx);  // a few pixels of margin, no more
        const RemapMap warp = build_remap_map(lens, PreparedCamera(plan.render));
        CHECK(warp.with_source == pixels_with_a_ray(lens));
    }
}

TEST_CASE("Maps for cv::remap: float and fixed point sample the same image, and a source-less pixel stays black",
          "[remap][opencv]") {
    const Camera lens = binned(example_camera("wide"), 8);
    const PreparedCamera source(lens);
    NewCameraRequest request;
    request.keep = Keep::All;
    const PreparedCamera target(choose_new_camera(source, request).camera);
    const RemapMap map = build_remap_map(target, source);
    cv::Mat image(int(lens.size.height), int(lens.size.width), CV_8UC3);
    cv::randu(image, 10, 250);
    const cv::Mat ours = remap_image(image, map, Interpolation::Linear);
    const auto [fixed_xy, fixed_a] = opencv_fixed_point_map(map);
    CHECK(fixed_xy.type() == CV_16SC2);
    CHECK(fixed_a.type() == CV_16UC1);
    cv::Mat theirs;
    cv::remap(image, theirs, fixed_xy, fixed_a, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    std::size_t black = 0, differ = 0;
    for (std::size_t i = 0; i < map.x.size(); ++i) {
        const cv::Vec3b a = ours.at<cv::Vec3b>(int(i / std::size_t(map.size.width)), int(i % std::size_t(map.size.width)));
        if (!map.has_source(i)) {
            black += a == cv::Vec3b(0, 0, 0) ? 1 : 0;
            continue;
        }
        const cv::Vec3b b = theirs.at<cv::Vec3b>(int(i / std::size_t(map.size.width)), int(i % std::size_t(map.size.width)));
        differ += cv::norm(a, b, cv::NORM_INF) > 1 && on_image(map.x[i], map.y[i], map.source_size, -0.5) ? 1 : 0;
    }
    CHECK(black == map.x.size() - map.with_source);
    CHECK(differ == 0);
    CHECK_THROWS_WITH(remap_image(cv::Mat(3, 3, CV_8UC1), map, Interpolation::Linear), Catch::Contains("3x3 pixels"));
}

TEST_CASE("libcam remap and derive, as a user runs them: images, the map, the camera, and one-line errors",
          "[remap][cli]") {
    test::TempDir dir;
    const fs::path lens_file = dir.path() / "lens.json";
    Camera lens = binned(example_camera("wide"), 16);  // 376x251
    write_camera_file(lens_file, lens, CameraFormat::Json);
    cv::Mat image(int(lens.size.height), int(lens.size.width), CV_8UC3, cv::Scalar(40, 120, 200));
    cv::imwrite((dir.path() / "photo.png").string(), image);
    const std::string exe = LIBCAM_EXE;
    const fs::path out = dir.path() / "out";
    CliResult r = run_program(exe, {"remap", "--from", lens_file.string(), "--to-pinhole", "valid", "--camera-out",
                                    (dir.path() / "pinhole.yaml").string(), "--camera-format", "opencv-yaml",
                                    "--map-out", (dir.path() / "map.npy").string(), (dir.path() / "photo.png").string(),
                                    "-o", out.string()});
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("camera: PINHOLE 376x251"));
    CHECK_THAT(r.out, Catch::Contains("100% of its pixels have a source (0 without)"));
    const cv::Mat written = cv::imread((out / "photo.png").string());
    REQUIRE(!written.empty());
    CHECK(cv::norm(written, cv::Mat(written.size(), CV_8UC3, cv::Scalar(40, 120, 200)), cv::NORM_INF) <= 1);
    // The .npy: NumPy's header for a (251, 376, 2) float32 array, then the data.
    const std::string npy = read_whole_file(dir.path() / "map.npy");
    CHECK(npy.substr(0, 6) == "\x93NUMPY");
    CHECK_THAT(npy, Catch::Contains("'descr': '<f4', 'fortran_order': False, 'shape': (251, 376, 2)"));
    CHECK(npy.size() == 128 + 251 * 376 * 2 * 4);
    CHECK(read_camera_file(dir.path() / "pinhole.yaml").camera.lens.type == LensType::Pinhole);
    // The EXR: OpenEXR's magic number, and its two float channels R and G in the header.
    r = run_program(exe, {"remap", "--from", lens_file.string(), "--to-lonlat", "all", "--map-out",
                          (dir.path() / "map.exr").string()});
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("camera: LONLAT"));
    const std::string exr = read_whole_file(dir.path() / "map.exr");
    CHECK(exr.substr(0, 4) == std::string("\x76\x2f\x31\x01", 4));
    CHECK(exr.find(std::string("R\0\x02\0\0\0", 6)) != std::string::npos);  // channel R, FLOAT (2)
    CHECK(exr.find(std::string("G\0\x02\0\0\0", 6)) != std::string::npos);
    // A cylinder that keeps the whole lens: the camera file says so.
    r = run_program(exe, {"remap", "--from", lens_file.string(), "--to-cylindrical", "all", "--map-out",
                          (dir.path() / "cylinder.npy").string(), "--camera-out", (dir.path() / "cylinder.json").string()});
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("camera: CYLINDRICAL"));
    CHECK(read_camera_file(dir.path() / "cylinder.json").camera.lens.type == LensType::Cylindrical);

    // Errors: one line, non-zero, nothing written.
    r = run_program(exe, {"remap", "--from", lens_file.string(), (dir.path() / "missing.png").string(), "-o",
                          (dir.path() / "out2").string()});
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::Contains("missing.png: no such image file"));
    cv::imwrite((dir.path() / "small.png").string(), cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)));
    r = run_program(exe, {"remap", "--from", lens_file.string(), (dir.path() / "small.png").string(), "-o",
                          (dir.path() / "out3").string()});
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::Contains("small.png: image: 10x10 pixels, but the source camera's image is 376x251"));
    CHECK_FALSE(fs::exists(dir.path() / "out3" / "small.png"));
    r = run_program(exe, {"remap", "--from", lens_file.string(), "--to-pinhole", "some", "--map-out", "m.npy"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("--to-pinhole: expected valid"));
    r = run_program(exe, {"remap", "--from", lens_file.string(), "--map-out", (dir.path() / "map.png").string()});
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::Contains("a map is written as .exr or .npy"));
    // A bad STMap name is found before anything is written: no camera file either.
    r = run_program(exe, {"remap", "--from", lens_file.string(), "--camera-out", (dir.path() / "early.json").string(),
                          "--stmap-out", (dir.path() / "st.tif").string()});
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::Contains("st.tif: an STMap is written as .exr, not '.tif'"));
    CHECK_FALSE(fs::exists(dir.path() / "early.json"));
    r = run_program(exe, {"remap", "--from", lens_file.string(), "--overscan", "auto", "--stmap-out",
                          (dir.path() / "st.exr").string()});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("--overscan: the margins of a render, for --inverse"));
    // Distorting a 60-degree render to a lens, with the margins it needs and the STMap.
    const fs::path mild_file = dir.path() / "mild.json";
    write_camera_file(mild_file, binned(example_camera("mild"), 4), CameraFormat::Json);  // 400x300
    r = run_program(exe, {"remap", "--from", mild_file.string(), "--to-fov", "60", "--inverse", "--overscan", "auto",
                          "--stmap-out", (dir.path() / "st.exr").string(), "--camera-out",
                          (dir.path() / "render.json").string()});
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("overscan: left "));
    CHECK_THAT(r.out, Catch::Contains("for a 400x300 format"));
    CHECK_THAT(r.out, Catch::Contains("100% of its pixels have a source"));
    CHECK(read_exr_channels(dir.path() / "st.exr").size() == 4);
    CHECK(read_camera_file(dir.path() / "render.json").camera.size.width > 400);

    r = run_program(exe, {"derive", "--from", lens_file.string(), "--bin", "2"});
    REQUIRE(r.exit_code == 0);
    CHECK(parse_camera(r.out, CameraFormat::Json, "stdout").camera.size == ImageSize{188, 125});
    r = run_program(exe, {"derive", "--from", lens_file.string(), "--bin", "2", "--crop", "0,0,2,2"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("give one of --resize"));
}

TEST_CASE("libcam render-plan and libcam project, as a user runs them: the plan's files, the warp, one-line errors",
          "[remap][cli]") {
    test::TempDir dir;
    const std::string exe = LIBCAM_EXE;
    const fs::path fisheye_file = dir.path() / "fisheye.json";
    const Camera fisheye = binned(example_camera("fisheye"), 4);  // 400x300, past 90 degrees
    write_camera_file(fisheye_file, fisheye, CameraFormat::Json);
    const fs::path plan = dir.path() / "plan";
    CliResult r = run_program(exe, {"render-plan", "--from", fisheye_file.string(), "-o", plan.string()});
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("render camera: the lens (FISHEYE) sees rays up to"));
    CHECK_THAT(r.out, Catch::Contains("Blender's equidistant fisheye"));
    const Camera render = read_camera_file(plan / "render.json").camera;
    CHECK(render.lens.type == LensType::Fisheye);
    CHECK(read_camera_file(plan / "lens.json").camera.intrinsics.K() == fisheye.intrinsics.K());
    CHECK_THAT(read_whole_file(plan / "render.py"), Catch::Contains("FISHEYE_EQUIDISTANT"));
    CHECK(read_exr_channels(plan / "warp.exr").size() == 2);
    // The render, turned into the lens's image by the command the plan prints.
    cv::imwrite((dir.path() / "render.png").string(),
                cv::Mat(int(render.size.height), int(render.size.width), CV_8UC1, cv::Scalar(90)));
    CHECK_THAT(r.out, Catch::Contains("then: libcam remap --from " + (plan / "render.json").string() + " --to " +
                                      (plan / "lens.json").string()));
    r = run_program(exe, {"remap", "--from", (plan / "render.json").string(), "--to", (plan / "lens.json").string(),
                          (dir.path() / "render.png").string(), "-o", (dir.path() / "lens").string()});
    REQUIRE(r.exit_code == 0);
    const cv::Mat lens_image = cv::imread((dir.path() / "lens" / "render.png").string(), cv::IMREAD_GRAYSCALE);
    CHECK(lens_image.cols == 400);
    CHECK(lens_image.rows == 300);
    CHECK(lens_image.at<unsigned char>(150, 200) == 90);
    // --fit-blender: Blender's polynomial fisheye cannot follow this lens within 0.1 px, and
    // render-plan says by how much before planning the warp.
    r = run_program(exe, {"render-plan", "--from", fisheye_file.string(), "-o", (dir.path() / "plan3").string(),
                          "--fit-blender"});
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("fit: Blender's FISHEYE_LENS_POLYNOMIAL reproduces the lens within"));
    CHECK_THAT(r.out, Catch::Contains("not within the tolerance 0.1 px: planning a warp instead"));
    CHECK(fs::exists(dir.path() / "plan3" / "warp.exr"));
    // A pinhole is drawn as it is: nothing to warp.
    const fs::path pinhole_file = dir.path() / "pinhole.json";
    r = run_program(exe, {"convert", "--fov", "60", "--size", "640x480", "-o", pinhole_file.string()});
    REQUIRE(r.exit_code == 0);
    r = run_program(exe, {"render-plan", "--from", pinhole_file.string(), "-o", (dir.path() / "plan2").string()});
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("Blender draws PINHOLE as it is"));
    CHECK_FALSE(fs::exists(dir.path() / "plan2" / "warp.exr"));
    // A plan written over an earlier one removes the earlier plan's warp map when it needs
    // none, or writes its own in the other format, rather than leave it to be taken for its
    // own.
    r = run_program(exe, {"render-plan", "--from", fisheye_file.string(), "-o", plan.string(), "--map-format", "npy"});
    REQUIRE(r.exit_code == 0);
    CHECK(fs::exists(plan / "warp.npy"));
    CHECK_FALSE(fs::exists(plan / "warp.exr"));
    CHECK_THAT(r.out, Catch::Contains("removed " + (plan / "warp.exr").string() + ", an earlier plan's warp map\n"));
    r = run_program(exe, {"render-plan", "--from", pinhole_file.string(), "-o", plan.string()});
    REQUIRE(r.exit_code == 0);
    CHECK_FALSE(fs::exists(plan / "warp.npy"));
    CHECK_THAT(r.out, Catch::Contains("removed " + (plan / "warp.npy").string() +
                                      ", an earlier plan's warp map (this plan needs none)"));
    CHECK(read_camera_file(plan / "render.json").camera.lens.type == LensType::Pinhole);
    // Errors.
    r = run_program(exe, {"render-plan", "--from", fisheye_file.string()});
    CHECK(r.exit_code == 2);
    r = run_program(exe, {"render-plan", "--from", fisheye_file.string(), "-o", plan.string(), "--map-format", "png"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("--map-format: expected exr or npy, got 'png'"));

    // libcam project: a 640x480 camera of 60 degrees vertically... here the fov on both
    // axes: fx = 320 / tan(30 deg), fy = 240 / tan(30 deg), centre (319.5, 239.5), looking
    // along -z from the origin with y up: the world point (0.5, -0.25, -2) is x 0.25, y 0.125
    // (down) in the camera's normalised coordinates.
    r = run_program(exe, {"project", "--from", pinhole_file.string(), "--points", "0.5,-0.25,-2", "0,0,1", "--json"});
    REQUIRE(r.exit_code == 0);
    const nlohmann::json projected = nlohmann::json::parse(r.out);
    const double f_tan = 1 / std::tan(30 * std::numbers::pi / 180);
    CHECK(projected["pixels"][0]["valid"] == true);
    CHECK(projected["pixels"][0]["pixel"][0].get<double>() == Approx(319.5 + 320 * f_tan * 0.25).epsilon(1e-12));
    CHECK(projected["pixels"][0]["pixel"][1].get<double>() == Approx(239.5 + 240 * f_tan * 0.125).epsilon(1e-12));
    CHECK(projected["pixels"][1]["valid"] == false);  // behind the camera
    CHECK(projected["pixels"][1]["pixel"].is_null());
    r = run_program(exe, {"project", "--from", pinhole_file.string(), "--points", "1,2"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("--points"));
}
