// COLMAP models' observations (io/detail/colmap_observations.hpp): the real models of
// the folder of real data beside the source tree (its SOURCES.md, section 1, gives their counts and the numbers COLMAP
// stored and model_analyzer printed), and small models written here whose numbers are
// worked by hand.

#include <Eigen/Geometry>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"

namespace {

using namespace libcam;
using libcam::test::real_data_path;
using libcam::test::real_data_present;

// What SOURCES.md says of one model.
struct RealModel {
    const char* path;             // in the real-data folder
    std::size_t images;
    std::size_t points;
    std::size_t observations;
    double stored_mean;           // the mean of ERROR, as model_analyzer prints it (6 digits)
    double recomputed_mean;       // SOURCES.md's independent recomputation
    double mean_tolerance;        // of libcam's recomputation against it
    double per_point_tolerance;   // of libcam's per-point means against ERROR
};

// Text models store 6 significant digits: SOURCES.md gives the largest per-point
// difference that rounding makes (0.0055 px); binary ones agree to 1e-12 px.
// The text models' recomputed means: SOURCES.md's recomputation takes the six-digit
// quaternions as written (0.953720, 0.973085, 0.342627); COLMAP normalises them on
// reading, as libcam does, and the same plain-Python recomputation with them normalised
// gives 0.953725, 0.973082 and 0.342625 (the values below).
constexpr double kText = 0.006;
constexpr double kBinary = 1e-6;

const RealModel kModels[] = {
    {"colmap-jasminekhalil-ar", 7, 2707, 9896, 0.953712, 0.953725, 2e-6, kText},
    {"colmap-vijayvamsi7-table/final_try_1_workspace", 10, 2167, 10461, 0.973087, 0.973082, 2e-6, kText},
    {"colmap-vijayvamsi7-table/final_try_1_workspace/sparse/0", 10, 2167, 10461, 0.973087, 0.973087, 1e-6, kBinary},
    {"colmap-bartoszek-test_colmap/sparse/0", 23, 1443, 5931, 0.848027, 0.848027, 1e-6, kBinary},
    {"colmap-halogenname-south-building/sparse/0", 5, 2013, 6760, 0.399172, 0.399172, 1e-6, kBinary},
    {"colmap-myhan1023-mouse/sparse/0", 56, 4443, 25656, 0.632516, 0.632516, 1e-6, kBinary},
    {"colmap-consideringname-ggbond-3dgs/distorted/sparse/0", 24, 1038, 4426, 0.434863, 0.434863, 1e-6, kBinary},
    {"kapture-samples/maupertuis/colmap/reconstruction", 4, 1039, 3355, 0.342600, 0.342625, 2e-6, kText},
};

}  // namespace

TEST_CASE("COLMAP observations: every real model reads, and reprojects to the ERROR COLMAP stored") {
    for (const RealModel& model : kModels) {
        const auto folder = real_data_path(model.path);
        if (!real_data_present(folder)) continue;
        INFO(model.path);
        const ObservationSet set = read_observations(folder);
        CHECK(set.tool == ObservationTool::Colmap);
        CHECK(set.pixel_offset == Vec2(0.5, 0.5));
        CHECK(set.views.size() == model.images);
        CHECK(set.points.size() == model.points);
        CHECK(set.observations.size() == model.observations);
        REQUIRE(set.reported.size() == 1);
        CHECK(set.reported[0].key == "mean_point_error_px");
        CHECK(set.reported[0].measure == ReportedMeasure::MeanOfPointMeans);
        CHECK(set.reported[0].value == Approx(model.stored_mean).margin(5e-7));
        const Reprojection r = reproject(set);
        CHECK(r.summary.all.stats.count == model.observations);
        REQUIRE(r.summary.reported.size() == 1);
        CHECK(r.summary.reported[0].recomputed == Approx(model.recomputed_mean).epsilon(0).margin(model.mean_tolerance));
        REQUIRE(r.summary.per_point_reported);
        CHECK(r.summary.per_point_reported->compared == model.points);
        CHECK(r.summary.per_point_reported->max_abs_difference <= model.per_point_tolerance);
    }
}

TEST_CASE("COLMAP observations: the models whose ERROR column is not theirs, as SOURCES.md documents") {
    SECTION("bartoszek dense/0: the undistorter copied ERROR, in the original 3031-px-wide pixels") {
        const auto folder = real_data_path("colmap-bartoszek-test_colmap/dense/0/sparse");
        if (!real_data_present(folder)) return;
        const ObservationSet set = read_observations(folder);
        CHECK(set.views.size() == 23);
        CHECK(set.points.size() == 1443);
        CHECK(set.observations.size() == 5931);
        REQUIRE(set.reported.size() == 1);
        CHECK(set.reported[0].value == Approx(0.848027).margin(5e-7));
        const Reprojection r = reproject(set);
        CHECK(r.summary.reported[0].recomputed == Approx(0.279490).epsilon(0).margin(2e-6));
    }
    SECTION("ggbond sparse/0: undistorted to 299 px wide, ERROR copied from distorted/") {
        const auto folder = real_data_path("colmap-consideringname-ggbond-3dgs/sparse/0");
        if (!real_data_present(folder)) return;
        const ObservationSet set = read_observations(folder);
        CHECK(set.views.size() == 24);
        CHECK(set.observations.size() == 4426);
        CHECK(set.cameras[0].camera.size.width == 299);
        CHECK(set.reported[0].value == Approx(0.434863).margin(5e-7));
        const Reprojection r = reproject(set);
        CHECK(r.summary.reported[0].recomputed == Approx(0.437770).epsilon(0).margin(2e-6));
        REQUIRE(r.summary.per_point_reported);
        CHECK(r.summary.per_point_reported->max_abs_difference == Approx(0.037).margin(5e-4));
    }
    SECTION("splatam: ERROR last updated before the parameters changed") {
        const auto folder = real_data_path("colmap-splatam-kinect/sparse/0");
        if (!real_data_present(folder)) return;
        const ObservationSet set = read_observations(folder);
        CHECK(set.views.size() == 50);
        CHECK(set.points.size() == 5255);
        CHECK(set.observations.size() == 55090);
        CHECK(set.reported[0].value == Approx(1.239572).margin(5e-7));
        const Reprojection r = reproject(set);
        CHECK(r.summary.reported[0].recomputed == Approx(1.239325).epsilon(0).margin(2e-6));
        REQUIRE(r.summary.per_point_reported);
        CHECK(r.summary.per_point_reported->max_abs_difference == Approx(0.46).margin(0.005));
    }
}

TEST_CASE("COLMAP observations: one model as text and as binary gives the same cameras, poses and pixels") {
    const auto text_folder = real_data_path("colmap-vijayvamsi7-table/final_try_1_workspace");
    if (!real_data_present(text_folder)) return;
    const ObservationSet text = read_observations(text_folder / "images.txt");
    const ObservationSet binary = read_observations(text_folder / "sparse/0/points3D.bin");
    REQUIRE(text.cameras.size() == 10);
    REQUIRE(binary.cameras.size() == text.cameras.size());
    for (std::size_t i = 0; i < text.cameras.size(); ++i) {
        INFO("camera " << text.cameras[i].name);
        CHECK(text.cameras[i].name == binary.cameras[i].name);
        const Camera& a = text.cameras[i].camera;
        const Camera& b = binary.cameras[i].camera;
        CHECK(a.size == b.size);
        // 6 significant digits: f to 5e-6 relative, cx and cy (800.5, 600.5) to 5e-4 px.
        CHECK(a.intrinsics.fx == Approx(b.intrinsics.fx).epsilon(5e-6));
        CHECK(a.intrinsics.cx == Approx(b.intrinsics.cx).margin(5e-4));
        CHECK(a.intrinsics.cy == Approx(b.intrinsics.cy).margin(5e-4));
        CHECK(a.lens.coefficients[0] == Approx(b.lens.coefficients[0]).epsilon(5e-6));
    }
    REQUIRE(binary.views.size() == text.views.size());
    for (std::size_t i = 0; i < text.views.size(); ++i) {
        CHECK(text.views[i].name == binary.views[i].name);
        CHECK(text.views[i].camera == binary.views[i].camera);
        CHECK((text.views[i].pose.R - binary.views[i].pose.R).cwiseAbs().maxCoeff() < 1e-5);
        CHECK((text.views[i].pose.t - binary.views[i].pose.t).cwiseAbs().maxCoeff() < 1e-5 * (1 + binary.views[i].pose.t.norm()));
    }
    REQUIRE(binary.observations.size() == text.observations.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < text.observations.size(); ++i) {
        CHECK(text.observations[i].view == binary.observations[i].view);
        CHECK(text.point_ids[text.observations[i].point] == binary.point_ids[binary.observations[i].point]);
        largest = std::max(largest, (text.observations[i].pixel - binary.observations[i].pixel).cwiseAbs().maxCoeff());
    }
    CHECK(largest <= 0.005);  // 1234.56: 6 digits leave half a hundredth
}

TEST_CASE("COLMAP observations: a COLMAP 3.12 model's frames hold the poses its images.bin holds") {
    // COLMAP >= 3.12 writes rigs.bin and frames.bin; images.bin keeps each image's composed
    // cam_from_world, which the reader takes. Read frames.bin by COLMAP's layout
    // (ReadFramesBinary): u64 count; per frame u32 id, u32 rig id, qw qx qy qz tx ty tz,
    // u32 data count, then (i32 sensor type, u32 sensor id, u64 data id) each.
    const auto folder = real_data_path("colmap-halogenname-south-building/sparse/0");
    if (!real_data_present(folder / "frames.bin")) return;
    std::ifstream in(folder / "frames.bin", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::size_t at = 0;
    const auto next = [&](auto value) {
        REQUIRE(at + sizeof(value) <= bytes.size());
        std::memcpy(&value, bytes.data() + at, sizeof(value));
        at += sizeof(value);
        return value;
    };
    const ObservationSet set = read_observations(folder);
    const auto frames = next(std::uint64_t{});
    REQUIRE(frames == 5);
    for (std::uint64_t f = 0; f < frames; ++f) {
        next(std::uint32_t{});
        next(std::uint32_t{});
        double q[7];
        for (double& value : q) value = next(0.0);
        const Pose frame{Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix(), Vec3(q[4], q[5], q[6])};
        const auto data = next(std::uint32_t{});
        for (std::uint32_t d = 0; d < data; ++d) {
            next(std::int32_t{});
            next(std::uint32_t{});
            next(std::uint64_t{});
        }
        bool found = false;
        for (const ObservedView& view : set.views) {
            found = found || ((view.pose.R - frame.R).cwiseAbs().maxCoeff() < 1e-12 &&
                              (view.pose.t - frame.t).cwiseAbs().maxCoeff() < 1e-12);
        }
        CHECK(found);
    }
    CHECK(at == bytes.size());
}

// ---- a model made by hand ------------------------------------------------------------------
//
// A 640x480 PINHOLE, f 500, principal point (320.5, 240.5) in COLMAP's pixels = (320, 240)
// in OpenCV's. Image 1 at the origin, image 2 with t = (-1, 0, 0) (x_cam = X - 1). Point 10
// at (0, 0, 2), point 20 at (1, 0.5, 4). In COLMAP's pixels, u = 500 x / z + 320.5,
// v = 500 y / z + 240.5:
//   point 10 in image 1: (320.5, 240.5), seen at (323.5, 244.5): residual (-3, -4), 5 px
//   point 20 in image 1: (445.5, 303),   seen there:               0 px
//   point 10 in image 2: (70.5, 240.5),  seen at (70.5, 241.5):   residual (0, -1), 1 px
//   point 20 in image 2: (320.5, 303),   seen there:               0 px
// Point means 3 and 0: their mean 1.5. The ERROR column says 3 and 0.25 (mean 1.625), so
// the per-point comparison's largest difference is 0.25, at point 20.

namespace {

const char* const kCamerasText = "# Camera list with one line of data per camera:\n"
                                 "1 PINHOLE 640 480 500 500 320.5 240.5\n";
const char* const kImagesText = "# Image list with two lines of data per image:\n"
                                "1 1 0 0 0 0 0 0 1 a.jpg\n"
                                "323.5 244.5 10 445.5 303 20 100 100 -1\n"
                                "2 1 0 0 0 -1 0 0 1 b.jpg\n"
                                "70.5 241.5 10 320.5 303 20\n";
const char* const kPointsText = "# 3D point list with one line of data per point:\n"
                                "10 0 0 2 255 0 0 3 1 0 2 0\n"
                                "20 1 0.5 4 0 255 0 0.25 1 1 2 1\n";

void write_file(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

struct TextModel {
    std::string cameras = kCamerasText;
    std::string images = kImagesText;
    std::string points = kPointsText;

    void write(const std::filesystem::path& folder) const {
        write_file(folder / "cameras.txt", cameras);
        write_file(folder / "images.txt", images);
        write_file(folder / "points3D.txt", points);
    }
};

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
}

// The numbers worked out above, whatever form the model was written in.
void check_hand_made(const ObservationSet& set) {
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].name == "1");
    CHECK(set.cameras[0].camera.intrinsics.cx == 320.0);
    CHECK(set.cameras[0].camera.intrinsics.cy == 240.0);
    REQUIRE(set.views.size() == 2);
    CHECK(set.views[0].name == "a.jpg");
    CHECK(set.views[1].name == "b.jpg");
    CHECK(set.views[1].pose.t == Vec3(-1.0, 0.0, 0.0));
    CHECK(set.point_ids == std::vector<std::int64_t>{10, 20});
    REQUIRE(set.observations.size() == 4);  // the 2-D point with POINT3D_ID -1 is none
    CHECK(set.observations[0].pixel == Vec2(323.0, 244.0));
    CHECK(set.observations[2].view == 1);
    CHECK(set.observations[2].point == 0);
    REQUIRE(set.reported.size() == 1);
    CHECK(set.reported[0].value == Approx(1.625).epsilon(1e-15));
    CHECK(set.reported_per_point == std::vector<double>{3.0, 0.25});
    const Reprojection r = reproject(set);
    CHECK(r.residuals[0].residual.x() == Approx(-3.0).margin(1e-12));
    CHECK(r.residuals[0].residual.y() == Approx(-4.0).margin(1e-12));
    CHECK(r.residuals[2].error_px == Approx(1.0).margin(1e-12));
    CHECK(r.summary.reported[0].recomputed == Approx(1.5).margin(1e-12));
    REQUIRE(r.summary.per_point_reported);
    CHECK(r.summary.per_point_reported->max_abs_difference == Approx(0.25).margin(1e-12));
    CHECK(r.summary.per_point_reported->worst_item == "20");
}

// The same model in COLMAP's binary layout (reconstruction_io_binary.cc), little-endian.
class Bytes {
public:
    template <class T>
    Bytes& put(T value) {
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        bytes_.append(raw, sizeof(T));
        return *this;
    }
    Bytes& name(const std::string& text) {
        bytes_.append(text.c_str(), text.size() + 1);
        return *this;
    }
    const std::string& str() const { return bytes_; }

private:
    std::string bytes_;
};

struct BinaryModel {
    std::uint64_t missing_point = 20;  // the POINT3D_ID image 2's second 2-D point names
    std::uint64_t track_length = 2;    // point 20's
    std::uint32_t last_index = 1;      // the POINT2D_IDX of point 20's last track element
    std::uint64_t image_count = 2;

    std::string cameras() const {
        Bytes b;
        b.put<std::uint64_t>(1).put<std::uint32_t>(1).put<std::int32_t>(1).put<std::uint64_t>(640).put<std::uint64_t>(480);
        for (const double p : {500.0, 500.0, 320.5, 240.5}) b.put(p);
        return b.str();
    }
    std::string images() const {
        Bytes b;
        b.put<std::uint64_t>(image_count);
        b.put<std::uint32_t>(1);
        for (const double p : {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}) b.put(p);
        b.put<std::uint32_t>(1).name("a.jpg").put<std::uint64_t>(3);
        b.put(323.5).put(244.5).put<std::uint64_t>(10);
        b.put(445.5).put(303.0).put<std::uint64_t>(20);
        b.put(100.0).put(100.0).put<std::uint64_t>(kNone);
        b.put<std::uint32_t>(2);
        for (const double p : {1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0}) b.put(p);
        b.put<std::uint32_t>(1).name("b.jpg").put<std::uint64_t>(2);
        b.put(70.5).put(241.5).put<std::uint64_t>(10);
        b.put(320.5).put(303.0).put<std::uint64_t>(missing_point);
        return b.str();
    }
    std::string points() const {
        Bytes b;
        b.put<std::uint64_t>(2);
        b.put<std::uint64_t>(10).put(0.0).put(0.0).put(2.0).put<std::uint8_t>(255).put<std::uint8_t>(0).put<std::uint8_t>(0);
        b.put(3.0).put<std::uint64_t>(2).put<std::uint32_t>(1).put<std::uint32_t>(0).put<std::uint32_t>(2).put<std::uint32_t>(0);
        b.put<std::uint64_t>(20).put(1.0).put(0.5).put(4.0).put<std::uint8_t>(0).put<std::uint8_t>(255).put<std::uint8_t>(0);
        b.put(0.25).put<std::uint64_t>(track_length).put<std::uint32_t>(1).put<std::uint32_t>(1).put<std::uint32_t>(2).put<std::uint32_t>(last_index);
        return b.str();
    }
    void write(const std::filesystem::path& folder) const {
        write_file(folder / "cameras.bin", cameras());
        write_file(folder / "images.bin", images());
        write_file(folder / "points3D.bin", points());
    }

    static constexpr std::uint64_t kNone = ~std::uint64_t{0};  // -1
};

// The message of the FileError reading `path` throws: one line.
std::string error_reading(const std::filesystem::path& path) {
    try {
        read_observations(path);
    } catch (const FileError& error) {
        const std::string message = error.what();
        CHECK(message.find('\n') == std::string::npos);
        return message;
    }
    FAIL("no error reading " << path.string());
    return {};
}

}  // namespace

TEST_CASE("COLMAP observations: a hand-made text model, its numbers worked by hand") {
    libcam::test::TempDir folder;
    TextModel model;
    SECTION("as COLMAP writes it") {
        model.write(folder.path());
        check_hand_made(read_observations(folder.path()));
    }
    SECTION("CRLF line ends and no final newline, named by its images.txt") {
        for (std::string* text : {&model.cameras, &model.images, &model.points}) {
            std::string crlf;
            for (const char c : *text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
            *text = crlf.substr(0, crlf.size() - 2);
        }
        model.write(folder.path());
        check_hand_made(read_observations(folder.path() / "images.txt"));
    }
    SECTION("kapture's commas between the fields") {
        model.images = "1, 1, 0, 0, 0, 0, 0, 0, 1, a.jpg\n"
                       "323.5, 244.5, 10, 445.5, 303, 20, 100, 100, -1\n"
                       "2, 1, 0, 0, 0, -1, 0, 0, 1, b.jpg\n"
                       "70.5, 241.5, 10, 320.5, 303, 20\n";
        model.write(folder.path());
        check_hand_made(read_observations(folder.path()));
    }
    SECTION("a point whose ERROR is -1 has none, and the mean is over the others") {
        model.points = replaced(model.points, "0.25", "-1");
        model.write(folder.path());
        const ObservationSet set = read_observations(folder.path());
        CHECK(std::isnan(set.reported_per_point[1]));
        CHECK(set.reported[0].value == 3.0);
    }
    SECTION("a track naming a 2-D point of no point links it to the point, as COLMAP's Reconstruction::AddPoint3D does") {
        model.points = replaced(model.points, "0.25 1 1 2 1", "0.25 1 1 2 1 1 2");
        model.write(folder.path());
        const ObservationSet set = read_observations(folder.path());
        REQUIRE(set.observations.size() == 5);
        // Image 1's third 2-D point, (100, 100) in COLMAP's pixels: point 20's, in OpenCV's.
        CHECK(set.observations[2].view == 0);
        CHECK(set.observations[2].point == 1);
        CHECK(set.observations[2].pixel == Vec2(99.5, 99.5));
    }
    SECTION("an image with no 2-D points, and one whose line of points is missing at the end") {
        model.images += "3 1 0 0 0 0 0 1 1 c.jpg\n\n4 1 0 0 0 0 0 2 1 d.jpg";
        model.write(folder.path());
        const ObservationSet set = read_observations(folder.path());
        CHECK(set.views.size() == 4);
        CHECK(set.observations.size() == 4);
    }
}

TEST_CASE("COLMAP observations: a hand-made binary model, the same numbers") {
    libcam::test::TempDir folder;
    BinaryModel model;
    model.write(folder.path());
    check_hand_made(read_observations(folder.path()));
    check_hand_made(read_observations(folder.path() / "images.bin"));
}

TEST_CASE("COLMAP observations: a malformed model is refused in one line naming the file, field and value") {
    libcam::test::TempDir folder;
    const auto images_txt = (folder.path() / "images.txt").string();
    const auto points_txt = (folder.path() / "points3D.txt").string();
    TextModel model;
    SECTION("a 2-D point of a 3-D point points3D lacks") {
        model.images = replaced(model.images, "445.5 303 20", "445.5 303 99");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              images_txt + ": line 2: image 1 (a.jpg): POINTS2D[1]: POINT3D_ID 99 is not in points3D.txt");
    }
    SECTION("an image of a camera cameras.txt lacks") {
        model.images = replaced(model.images, "0 0 1 b.jpg", "0 0 7 b.jpg");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              images_txt + ": line 4: image 2 (b.jpg): CAMERA_ID 7 is not in cameras.txt");
    }
    SECTION("a track naming an image images.txt lacks") {
        model.points = replaced(model.points, "3 1 0 2 0", "3 1 0 9 0");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) == points_txt + ": POINT3D_ID 10: TRACK[1]: IMAGE_ID 9 is not in images.txt");
    }
    SECTION("a track naming a POINT2D_IDX past its image's POINTS2D") {
        model.points = replaced(model.points, "3 1 0 2 0", "3 1 0 2 1000000");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              points_txt + ": POINT3D_ID 10: TRACK[1]: POINT2D_IDX 1000000 is not one of image 2 (b.jpg)'s 2 POINTS2D");
    }
    SECTION("a track naming a 2-D point of an image whose line of points is missing at the end") {
        model.images = replaced(model.images, "70.5 241.5 10 320.5 303 20\n", "");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              points_txt + ": POINT3D_ID 10: TRACK[1]: POINT2D_IDX 0 is not one of image 2 (b.jpg)'s 0 POINTS2D");
    }
    SECTION("a track naming another point's 2-D point") {
        model.points = replaced(model.points, "0.25 1 1 2 1", "0.25 1 0 2 1");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              points_txt + ": POINT3D_ID 20: TRACK[0]: image 1 (a.jpg)'s POINTS2D[0] is POINT3D_ID 10's");
    }
    SECTION("a track naming one 2-D point twice") {
        model.points = replaced(model.points, "3 1 0 2 0", "3 1 0 1 0");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              points_txt + ": POINT3D_ID 10: TRACK[1]: image 1 (a.jpg)'s POINTS2D[0] is in the track twice");
    }
    SECTION("a 2-D point its 3-D point's track does not name") {
        model.points = replaced(model.points, "0.25 1 1 2 1", "0.25 1 1");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              images_txt + ": line 4: image 2 (b.jpg): POINTS2D[1]: POINT3D_ID 20's track in points3D.txt does not name it");
    }
    SECTION("a line of 2-D points that stops inside a triple") {
        model.images = replaced(model.images, "320.5 303 20", "320.5 303");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) == images_txt + ": line 5: POINTS2D[1]: POINT3D_ID: the line ends before it");
    }
    SECTION("a pixel that is not a number") {
        model.images = replaced(model.images, "70.5 241.5", "70.5 nan");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              images_txt + ": line 5: POINTS2D[0]: Y: expected a finite number, got 'nan'");
    }
    SECTION("a point id twice") {
        model.points = replaced(model.points, "20 1 0.5", "10 1 0.5");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) == points_txt + ": POINT3D_ID 10 appears more than once");
    }
    SECTION("a track of an odd count") {
        model.points = replaced(model.points, "0.25 1 1 2 1", "0.25 1 1 2");
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              points_txt + ": line 3: TRACK: expected (IMAGE_ID, POINT2D_IDX) pairs, got an odd count");
    }
    SECTION("no points3D.txt") {
        write_file(folder.path() / "cameras.txt", model.cameras);
        write_file(folder.path() / "images.txt", model.images);
        CHECK(error_reading(folder.path()) ==
              folder.path().string() +
                  ": a COLMAP model is cameras.txt, images.txt and points3D.txt; points3D.txt is missing");
    }
}

TEST_CASE("COLMAP observations: a malformed binary model is refused, never read past its end") {
    libcam::test::TempDir folder;
    const auto images_bin = (folder.path() / "images.bin").string();
    const auto points_bin = (folder.path() / "points3D.bin").string();
    BinaryModel model;
    SECTION("a 2-D point of a 3-D point points3D.bin lacks") {
        // Image 2 starts after the count (8 bytes) and image 1: id 4, pose 56, camera 4,
        // "a.jpg" and its NUL 6, point count 8, three 2-D points 72: byte 158.
        model.missing_point = 99999;
        model.write(folder.path());
        CHECK(error_reading(folder.path()) == images_bin + ": byte 158: image 2 (b.jpg): POINTS2D[1]: POINT3D_ID 99999 "
                                                           "is not in points3D.bin");
    }
    SECTION("a track naming a POINT2D_IDX past its image's POINTS2D") {
        model.last_index = 7;
        model.write(folder.path());
        CHECK(error_reading(folder.path()) ==
              points_bin + ": POINT3D_ID 20: TRACK[1]: POINT2D_IDX 7 is not one of image 2 (b.jpg)'s 2 POINTS2D");
    }
    SECTION("a count of images the file cannot hold") {
        model.image_count = std::uint64_t{1} << 40;
        model.write(folder.path());
        // Each image takes at least 73 bytes: its id (4), quaternion (32), translation (24),
        // camera id (4), an empty name's NUL (1) and its count of points (8).
        const auto size = std::filesystem::file_size(images_bin);
        CHECK(error_reading(folder.path()) ==
              images_bin + ": byte 8: the number of images is 1099511627776, more than the " + std::to_string(size - 8) +
                  " bytes left of the file's " + std::to_string(size) + " can hold (at least 73 bytes each)");
    }
    SECTION("a track longer than the file") {
        // Point 20's track begins after the count (8), point 10 (51 bytes and a track of two,
        // 16) and its own 51 bytes: byte 126.
        model.track_length = std::uint64_t{1} << 61;
        model.write(folder.path());
        // Each element of a track is an image id and a point's index (4 + 4 bytes).
        const auto size = std::filesystem::file_size(points_bin);
        CHECK(error_reading(folder.path()) == (points_bin + ": byte 126: point 20: the track length 2305843009213693952 "
                                                             "is more than the " + std::to_string(size - 126) +
                                               " bytes left of the file's " + std::to_string(size) +
                                               " can hold (at least 8 bytes each)"));
    }
    SECTION("every shorter points3D.bin") {
        const std::string whole = model.points();
        model.write(folder.path());
        for (std::size_t size = 0; size < whole.size(); ++size) {
            write_file(folder.path() / "points3D.bin", whole.substr(0, size));
            CHECK_THROWS_AS(read_observations(folder.path()), FileError);
        }
    }
}
