// mrcal's optimization_inputs in a .cameramodel, read without mrcal, against mrcal itself:
// mrcal_optimization_inputs.py (python3-mrcal) counts the file's observations and gives
// mrcal's measurement vector x (its weighted residuals, mrcal.optimizer_callback), and
// writes the small models and the spoiled ones the malformed cases read.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "libcam/reproject/reproject.hpp"
#include "libcam/camera/example_cameras.hpp"
#include "libcam/error.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "temp_dir.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/cameramodel_text.hpp"
#include "libcam/io/observations.hpp"
#include "real_cameras.hpp"
#include "shell_output.hpp"

namespace {

using libcam::test::shell_output;

using namespace libcam;
namespace fs = std::filesystem;

// Beside this file (found from the docs folder: __FILE__ is relative to the build folder).
const fs::path kScript = fs::path(LIBCAM_DOCS_DIR).parent_path() / "tests/observations/mrcal_optimization_inputs.py";

nlohmann::json mrcal_summary(const fs::path& model) {
    return nlohmann::json::parse(
        shell_output("/usr/bin/python3 '" + kScript.string() + "' summary '" + model.string() + "'"));
}

// A folder of this test program's own, removed when it ends (two runs at once never share it).
const fs::path& scratch_folder() {
    static const libcam::test::TempDir folder;
    return folder.path();
}

fs::path small_model(const std::string& variant) {
    const fs::path model = scratch_folder() / (variant + ".cameramodel");
    shell_output("/usr/bin/python3 '" + kScript.string() + "' write '" + model.string() + "' " + variant);
    return model;
}

// Compares libcam's reading and reprojection of `model` with mrcal's; returns the largest
// difference between libcam's weighted residual and mrcal's measurement.
double compare_with_mrcal(const fs::path& model) {
    const nlohmann::json mrcal = mrcal_summary(model);
    const ObservationSet set = read_observations(model);
    CHECK(set.tool == ObservationTool::Mrcal);
    REQUIRE(set.board.has_value());
    CHECK(set.board->width == mrcal["width"].get<int>());
    CHECK(set.board->height == mrcal["height"].get<int>());
    const std::size_t corners = mrcal["corners"].get<std::size_t>();
    const std::size_t per_view = static_cast<std::size_t>(set.board->width * set.board->height);
    CHECK(set.views.size() >= mrcal["views"].get<std::size_t>());
    const std::vector<double> board_x = mrcal["board_x"].get<std::vector<double>>();
    const std::vector<double> point_x = mrcal["point_x"].get<std::vector<double>>();
    REQUIRE(set.observations.size() == corners + point_x.size() / 2);
    CHECK(set.points.size() >= per_view);

    const Reprojection r = reproject(set);
    double largest = 0.0;
    std::size_t outliers = 0, inliers = 0;
    for (std::size_t i = 0; i < set.observations.size(); ++i) {
        const Observation& o = set.observations[i];
        const double* x = i < corners ? &board_x[2 * i] : &point_x[2 * (i - corners)];
        if (!o.inlier) {
            ++outliers;
            CHECK(r.residuals[i].status == ResidualStatus::Outlier);
            continue;
        }
        ++inliers;
        CHECK(r.residuals[i].status == ResidualStatus::Counted);
        const Vec2 weighted = o.weight * r.residuals[i].residual;
        largest = std::max({largest, std::abs(weighted.x() - x[0]), std::abs(weighted.y() - x[1])});
    }
    CHECK(outliers >= mrcal["outliers"].get<std::size_t>());
    CHECK(r.summary.all.stats.count == inliers);
    if (point_x.empty()) {
        // mrcal's RMS over the inliers' x and y residuals, weighted and not: libcam's
        // weighted RMS of |d| is sqrt(2) times the one over components.
        REQUIRE(r.summary.all.weighted_rms_px.has_value());
        CHECK(*r.summary.all.weighted_rms_px / std::sqrt(2.0) ==
              Approx(mrcal["rms_weighted_inliers"].get<double>()).epsilon(1e-9));
        CHECK(r.summary.all.stats.rms_px / std::sqrt(2.0) ==
              Approx(mrcal["rms_unweighted_inliers"].get<double>()).epsilon(1e-9));
    }
    return largest;
}

}  // namespace

TEST_CASE("mrcal observations: the real solves in opencv8-0/1 and splined-0/1 give mrcal's own residuals") {
    const fs::path folder = test::real_cameras_folder("mrcal");
    if (!test::real_cameras_present(folder)) return;
    for (const char* name : {"opencv8-0.cameramodel", "opencv8-1.cameramodel"}) {
        INFO(name);
        // 186 board views of 10 x 10 corners, 3 of them outliers, OPENCV8.
        const double largest = compare_with_mrcal(folder / name);
        CHECK(largest < 1e-9);
    }
    for (const char* name : {"splined-0.cameramodel", "splined-1.cameramodel"}) {
        INFO(name);
        const double largest = compare_with_mrcal(folder / name);
        CHECK(largest < 1e-9);
    }
    const ObservationSet set = read_observations(folder / "opencv8-0.cameramodel");
    CHECK(set.views.size() == 186);
    CHECK(set.observations.size() == 18600);
    CHECK(set.cameras.size() == 1);
    CHECK(set.cameras[0].camera.lens.type == LensType::OpenCv8);
    CHECK(set.board->spacing == 0.077);
    const ObservationSet splined = read_observations(folder / "splined-0.cameramodel");
    CHECK(splined.cameras[0].camera.lens.type == LensType::SplinedStereographic);
    CHECK(splined.cameras[0].camera.lens.coefficients.size() == 4 + 2 * 30 * 20);
}

TEST_CASE("mrcal observations: a small solve with a warped board, weights, an outlier and points") {
    const fs::path model = small_model("good");
    CHECK(compare_with_mrcal(model) < 1e-9);
    const ObservationSet set = read_observations(model);
    // 2 board views of 3 x 2 corners and one view of the 3 points from the reference camera.
    CHECK(set.views.size() == 3);
    CHECK(set.points.size() == 6 + 3);
    CHECK(set.board->warp == Vec2(0.002, -0.001));
    // Corner (row 1, column 1) of a 3 x 2 board: x r = 1/2, y r = 1: z = 0.002 * 4 * 0.25.
    CHECK(set.points[4].x() == Approx(0.1));
    CHECK(set.points[4].y() == Approx(0.1));
    CHECK(set.points[4].z() == Approx(0.002).epsilon(1e-12));
}

TEST_CASE("mrcal observations: a malformed file gives one line naming the file, the array and the value") {
    const auto message_of = [](const fs::path& model) -> std::string {
        try {
            read_observations(model);
        } catch (const FileError& error) {
            return error.what();
        }
        return "no error";
    };
    const auto written = [](const std::string& name, const std::string& text) {
        const fs::path path = scratch_folder() / name;
        std::ofstream(path) << text;
        return path;
    };
    using Catch::Matchers::Contains;
    // A whole model's keys (libmrcal's parser reads the file's own camera first, as `libcam
    // info` does), so that each case reaches the optimization_inputs.
    const std::string head = "{\n    'lensmodel': 'LENSMODEL_PINHOLE',\n    'intrinsics': [1, 1, 0, 0],\n"
                             "    'extrinsics': [0, 0, 0, 0, 0, 0],\n    'imagersize': [640, 480],\n";
    CHECK_THAT(message_of(written("none.cameramodel", head + "}\n")), Contains("none.cameramodel: no 'optimization_inputs'"));
    CHECK_THAT(message_of(written("truncated.cameramodel", head + "    'optimization_inputs': b'P)h>@6aWAK2mk")),
               Contains("line 6: unterminated string"));  // as `libcam info` refuses it
    // base64.b85encode(b"not a zip archive!!") from Python: 20 bytes, not a zip.
    CHECK_THAT(message_of(written("corrupt.cameramodel",
                                  head + "    'optimization_inputs': b'Zf|rTVIX>Ga3EoFV`yo1Wg#H',\n}\n")),
               Contains("corrupt.cameramodel: optimization_inputs: not a zip archive"));
    CHECK_THAT(message_of(written("base85.cameramodel", head + "    'optimization_inputs': b'abc.de',\n}\n")),
               Contains("optimization_inputs: byte 3 ('.') is not base85"));
    CHECK_THAT(message_of(small_model("float32-intrinsics")),
               Contains("float32-intrinsics.cameramodel: optimization_inputs: intrinsics: dtype '<f4'"));
    CHECK_THAT(message_of(small_model("mismatched-imagersizes")),
               Contains("optimization_inputs: imagersizes: shape (2, 2) of <i4, expected (1, 2) of numbers"));
    CHECK_THAT(message_of(small_model("frame-out-of-range")),
               Contains("indices_frame_camintrinsics_camextrinsics: row 1: frame 7 is not one of the 2"));
    // A member said to inflate to 50 MB from 110 bytes: deflate makes at most about 1032
    // bytes of each, so it is refused before anything is inflated or allocated.
    CHECK_THAT(message_of(small_model("inflated-member")), Contains(": size 52428800 from 110 compressed bytes"));
}

TEST_CASE("mrcal observations: a .cameramodel of 558 views, over 1 MiB, is read by info and reproject alike") {
    // mrcal writes the inputs of its solve into the file: 558 views of a 10 x 10 board make
    // 1.06 MiB, which the camera's reader refused as "larger than 1 MiB" while reproject
    // read it.
    const fs::path model = small_model("many-views");
    REQUIRE(fs::file_size(model) > (std::uintmax_t{1} << 20));
    CHECK(compare_with_mrcal(model) < 1e-9);
    CHECK(mrcal_summary(model)["views"].get<int>() == 558);
    // The camera as `libcam info` reads it (libmrcal's parser): the solve's camera, as
    // mrcal_optimization_inputs.py gave it to mrcal.
    const Camera camera = read_camera_file(model).camera;
    CHECK(camera.lens.type == LensType::OpenCv4);
    CHECK(camera.intrinsics.fx == 800.0);
    CHECK(camera.intrinsics.fy == 810.0);
    CHECK(camera.lens.coefficients == std::vector<double>{-0.1, 0.02, 0.001, -0.002});
    CHECK(camera.size.width == 640);
    CHECK(camera.size.height == 480);
    // And the program: both commands take the file.
    const std::string program = "'" + std::string(LIBCAM_EXE) + "' ";
    CHECK_THAT(shell_output(program + "info '" + model.string() + "'"), Catch::Matchers::Contains("model     OPENCV4"));
    CHECK_THAT(shell_output(program + "reproject '" + model.string() + "'"),
               Catch::Matchers::Contains("55803 observations"));
}

TEST_CASE("mrcal observations: info's reader and reproject's refuse a damaged .cameramodel with the same line") {
    const auto message_of = [](const auto& read) -> std::string {
        try {
            read();
        } catch (const FileError& error) {
            return error.what();
        }
        return "no error";
    };
    const std::string head = "{\n    'lensmodel': 'LENSMODEL_PINHOLE',\n    'intrinsics': [1, 1, 0, 0],\n";
    const std::vector<std::pair<std::string, std::string>> damaged = {
        {head + "    'imagersize': [ 640, 480 ],\n    'optimization_inputs': b'P)h>@6aWAK2mk,\n}\n",
         "line 5: unterminated string"},
        {head + "    'valid_intrinsics_region': [[[[[[[[[ 0 ]]]]]]]]],\n}\n", "line 4: nested more than 8 deep"},
        {head + "    'imagersize': [ 640, 480 ]]],\n}\n", "line 4: unbalanced ']'"},
        {head + "    'imagersize': [ 640, 480 ,\n", "unbalanced brackets (truncated file?)"},
    };
    for (std::size_t i = 0; i < damaged.size(); ++i) {
        const fs::path path = scratch_folder() / ("damaged-" + std::to_string(i) + ".cameramodel");
        std::ofstream(path) << damaged[i].first;
        const std::string camera = message_of([&] { read_camera_file(path); });
        const std::string observations = message_of([&] { read_observations(path); });
        INFO(damaged[i].first);
        CHECK(camera == observations);
        CHECK_THAT(camera, Catch::Matchers::Contains(path.string() + ": " + damaged[i].second));
    }
    // The bound itself, at its edge: 256 MiB.
    CHECK_NOTHROW(detail::check_cameramodel_size(std::uintmax_t{256} << 20, "big.cameramodel"));
    CHECK(message_of([] { detail::check_cameramodel_size((std::uintmax_t{256} << 20) + 1, "big.cameramodel"); }) ==
          "big.cameramodel: 268435457 bytes: larger than the 256 MiB libcam reads as a .cameramodel");
}

namespace {

// A .cameramodel holding the camera of `set` and `inputs` (mrcal_optimization_inputs'
// literal), written by hand as mrcal lays one out.
std::string model_text(const ObservationSet& set, const std::string& inputs) {
    const Camera& camera = set.cameras.front().camera;
    std::string intrinsics = libcam::format_number(camera.intrinsics.fx) + ", " + libcam::format_number(camera.intrinsics.fy) +
                             ", " + libcam::format_number(camera.intrinsics.cx) + ", " +
                             libcam::format_number(camera.intrinsics.cy);
    for (const double c : camera.lens.coefficients) intrinsics += ", " + libcam::format_number(c);
    return "{\n    'lensmodel': '" + mrcal_model_name(camera.lens.type, camera.lens.coefficients) + "',\n    'intrinsics': [ " +
           intrinsics + " ],\n    'imagersize': [ " + std::to_string(camera.size.width) + ", " +
           std::to_string(camera.size.height) + " ],\n    'extrinsics': [ 0, 0, 0, 0, 0, 0 ],\n    'optimization_inputs': " +
           inputs + ",\n    'icam_intrinsics': 0\n}\n";
}

}  // namespace

TEST_CASE("mrcal observations written by libcam: mrcal reads mrcal's real solve back with its own residuals") {
    const fs::path folder = test::real_cameras_folder("mrcal");
    if (!test::real_cameras_present(folder)) return;
    // mrcal's real OPENCV8 solve (a bowed board, 3 outliers) read, and its inputs written
    // again by libcam: mrcal's residuals of the copy are those of mrcal's own file.
    const fs::path original = folder / "opencv8-0.cameramodel";
    const ObservationSet set = read_observations(original);
    const fs::path copy = scratch_folder() / "opencv8-0-written.cameramodel";
    {
        std::ofstream out(copy);
        out << model_text(set, mrcal_optimization_inputs(set, 2.0));
    }
    const nlohmann::json expected = mrcal_summary(original), got = mrcal_summary(copy);
    for (const char* key : {"views", "height", "width", "corners", "outliers"}) CHECK(got[key] == expected[key]);
    CHECK(got["rms_weighted_inliers"].get<double>() == Approx(expected["rms_weighted_inliers"].get<double>()).epsilon(1e-12));
    const std::vector<double> x = got["board_x"].get<std::vector<double>>();
    const std::vector<double> x_expected = expected["board_x"].get<std::vector<double>>();
    REQUIRE(x.size() == x_expected.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) largest = std::max(largest, std::abs(x[i] - x_expected[i]));
    CHECK(largest < 1e-9);
    // And libcam reads its own writing back as it read mrcal's.
    const ObservationSet again = read_observations(copy);
    REQUIRE(again.observations.size() == set.observations.size());
    for (std::size_t i = 0; i < set.observations.size(); ++i) {
        CHECK(again.observations[i].pixel == set.observations[i].pixel);
        CHECK(again.observations[i].inlier == set.observations[i].inlier);
    }
    CHECK(again.board->warp == set.board->warp);
    CHECK(again.board->warp_solved == set.board->warp_solved);
}

TEST_CASE("mrcal observations written by libcam: what mrcal's inputs cannot hold is refused, saying why") {
    ObservationSet set;
    set.cameras.push_back({"0", libcam::example_camera("fisheye")});
    set.views.push_back({"v", 0, Pose{}});
    CHECK_THROWS_WITH(mrcal_optimization_inputs(set, 1.0), Catch::Contains("not of a board"));
    set.board = ObservedBoard{2, 2, 0.1};
    set.points = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), Vec3(0.1, 0.1, 0)};
    CHECK_THROWS_WITH(mrcal_optimization_inputs(set, 1.0), Catch::Contains("mrcal has no FISHEYE model"));
    set.points[3] = Vec3(0.1, 0.2, 0.0);
    CHECK_THROWS_WITH(mrcal_optimization_inputs(set, 1.0), Catch::Contains("point 3 is not where mrcal places"));
    set.points[3] = Vec3(0.1, 0.1, 0.0);
    set.cameras.front().camera = libcam::example_camera("mild");
    set.observations.push_back({.view = 0, .point = 4});
    CHECK_THROWS_WITH(mrcal_optimization_inputs(set, 1.0), Catch::Contains("point 4, which the set does not hold"));
    set.observations.clear();
    // An OPENCV8 camera beside an OPENCV4 one: mrcal solves one model for every camera.
    Camera second = libcam::example_camera("mild");
    second.lens = {LensType::OpenCv4, {0.0, 0.0, 0.0, 0.0}};
    set.cameras.push_back({"1", second});
    set.frames = {Pose{}};
    set.views.front().frame = 0;
    CHECK_THROWS_WITH(mrcal_optimization_inputs(set, 1.0), Catch::Contains("one lens model"));
}
