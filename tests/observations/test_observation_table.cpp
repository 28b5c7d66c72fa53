// A table of observations (CSV or JSON) read with a camera file: hand-made tables whose
// residuals are worked out by hand for a pinhole pair, and malformed rows.
//
// The camera file is OpenCV's stereo layout: two 640x480 pinholes, fx = fy = 500, centre
// (320, 240); camera1 at the world origin, camera2 at x_cam = X + (-0.1, 0, 0). So
//   (0, 0, 2)      -> camera1 (320, 240), camera2 (500 * -0.1 / 2 + 320, 240) = (295, 240)
//   (0.2, -0.1, 1) -> camera1 (420, 190), camera2 (500 * 0.1 + 320, 190)     = (370, 190)

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/observations.hpp"

namespace {

using namespace libcam;

std::filesystem::path write_file(const std::string& name, const std::string& text) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / ("libcam_test_observation_table_" + name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::filesystem::path stereo_pair() {
    return write_file("pair.yml",
                      "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n"
                      "M1: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]\n"
                      "D1: [ 0., 0., 0., 0., 0. ]\n"
                      "M2: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]\n"
                      "D2: [ 0., 0., 0., 0., 0. ]\n"
                      "R: [ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]\nT: [ -0.1, 0., 0. ]\n");
}

// Observed: camera1 sees (0, 0, 2) one pixel right of (320, 240) and (0.2, -0.1, 1)
// exactly; camera2 (named by position, 1, in the last row) sees (0, 0, 2) two pixels
// below (295, 240) and (0.2, -0.1, 1) exactly. Residuals (-1, 0), 0, (0, -2), 0.
const char* const kCsv =
    "# hand-made\r\n"
    "view, camera, X, Y, Z, x, y\r\n"
    "img0,camera1,0,0,2,321,240\r\n"
    "img0,camera1,0.2,-0.1,1,420,190\r\n"
    "\r\n"
    "img1,camera2,0,0,2,295,242\r\n"
    "\"img1\",1,0.2,-0.1,1,370,190\r\n";

const char* const kJson = R"([
  {"view": "img0", "camera": "camera1", "X": 0, "Y": 0, "Z": 2, "x": 321, "y": 240},
  {"view": "img0", "camera": "camera1", "X": 0.2, "Y": -0.1, "Z": 1, "x": 420, "y": 190},
  {"view": "img1", "camera": "camera2", "X": 0, "Y": 0, "Z": 2, "x": 295, "y": 242},
  {"view": "img1", "camera": 1, "X": 0.2, "Y": -0.1, "Z": 1, "x": 370, "y": 190}
])";

void check_worked_by_hand(const ObservationSet& set) {
    CHECK(set.tool == ObservationTool::Table);
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[0].name == "camera1");
    CHECK(set.cameras[1].name == "camera2");
    CHECK(set.cameras[1].camera.pose.t == Vec3::Zero());  // each view carries the pose
    REQUIRE(set.views.size() == 2);
    CHECK(set.views[0].name == "img0");
    CHECK(set.views[1].camera == 1);
    CHECK(set.views[1].pose.t.x() == Approx(-0.1).margin(1e-15));
    REQUIRE(set.observations.size() == 4);
    CHECK(set.point_ids == std::vector<std::int64_t>{1, 2, 3, 4});
    const Reprojection r = reproject(set);
    CHECK(r.residuals[0].residual.x() == Approx(-1.0).margin(1e-9));
    CHECK(r.residuals[0].residual.y() == Approx(0.0).margin(1e-9));
    CHECK(r.residuals[1].error_px == Approx(0.0).margin(1e-9));
    CHECK(r.residuals[2].projected.x() == Approx(295.0).margin(1e-9));
    CHECK(r.residuals[2].residual.y() == Approx(-2.0).margin(1e-9));
    CHECK(r.residuals[3].projected.x() == Approx(370.0).margin(1e-9));
    CHECK(r.residuals[3].error_px == Approx(0.0).margin(1e-9));
    CHECK(r.summary.all.stats.rms_px == Approx(std::sqrt(1.25)).epsilon(1e-12));  // sqrt((1 + 4) / 4)
    CHECK(r.summary.per_view[0].residuals.stats.rms_px == Approx(std::sqrt(0.5)).epsilon(1e-12));
    CHECK(r.summary.per_view[1].residuals.stats.rms_px == Approx(std::sqrt(2.0)).epsilon(1e-12));
}

std::string error_reading(const std::filesystem::path& table, const std::filesystem::path& cameras) {
    try {
        (void)read_observations(table, {.camera_file = cameras});
    } catch (const FileError& error) {
        return error.what();
    }
    return "(no error)";
}

}  // namespace

TEST_CASE("observation table: CSV with a camera file, worked by hand") {
    const std::filesystem::path cameras = stereo_pair();
    const std::filesystem::path table = write_file("table.csv", kCsv);
    check_worked_by_hand(read_observations(table, {.camera_file = cameras}));
    std::filesystem::remove(table);
    std::filesystem::remove(cameras);
}

TEST_CASE("observation table: JSON with a camera file, worked by hand") {
    const std::filesystem::path cameras = stereo_pair();
    const std::filesystem::path table = write_file("table.json", kJson);
    check_worked_by_hand(read_observations(table, {.camera_file = cameras}));
    std::filesystem::remove(table);
    std::filesystem::remove(cameras);
}

TEST_CASE("observation table: without a view column, each camera's rows are one view") {
    const std::filesystem::path cameras = stereo_pair();
    const std::filesystem::path table =
        write_file("no-view.csv", "x,y,camera,X,Y,Z\n321,240,camera1,0,0,2\n295,242,camera2,0,0,2\n420,190,0,0.2,-0.1,1\n");
    const ObservationSet set = read_observations(table, {.camera_file = cameras});
    REQUIRE(set.views.size() == 2);
    CHECK(set.views[0].name == "camera1");
    CHECK(set.views[1].name == "camera2");
    CHECK(set.observations[2].view == 0);
    const Reprojection r = reproject(set);
    CHECK(r.summary.all.stats.rms_px == Approx(std::sqrt(5.0 / 3.0)).epsilon(1e-12));
    std::filesystem::remove(table);
    std::filesystem::remove(cameras);
}

TEST_CASE("observation table: malformed rows name the row, the column and the value") {
    const std::filesystem::path cameras = stereo_pair();
    struct Case {
        const char* name;
        std::string text;
        std::vector<std::string> said;
    };
    const Case cases[] = {
        {"word.csv", "camera,X,Y,Z,x,y\ncamera1,0,0,2,321,240\ncamera1,0,0,2,abc,240\n",
         {"row 2 (line 3)", "column \"x\"", "expected a number, got 'abc'"}},
        {"infinite.csv", "camera,X,Y,Z,x,y\ncamera1,0,0,1e999,321,240\n", {"row 1 (line 2)", "column \"Z\"", "1e999"}},
        {"camera.csv", "camera,X,Y,Z,x,y\ncam9,0,0,2,321,240\n",
         {"row 1 (line 2)", "column \"camera\"", "'cam9'", "camera1"}},
        {"position.csv", "camera,X,Y,Z,x,y\n2,0,0,2,321,240\n", {"row 1 (line 2)", "column \"camera\"", "'2'"}},
        {"header.csv", "camera,X,Y,x,y\ncamera1,0,0,321,240\n", {"line 1", "no column \"Z\""}},
        {"fields.csv", "camera,X,Y,Z,x,y\ncamera1,0,0,2,321\n", {"row 1 (line 2)", "5 fields", "6 columns"}},
        {"two-cameras.csv", "view,camera,X,Y,Z,x,y\na,camera1,0,0,2,321,240\na,camera2,0,0,2,295,240\n",
         {"row 2 (line 3)", "column \"camera\"", "'camera2'", "view 'a'", "'camera1'"}},
        {"quote.csv", "camera,X,Y,Z,x,y\n\"camera1,0,0,2,321,240\n", {"line 2", "quote"}},
        {"empty.csv", "camera,X,Y,Z,x,y\n", {"no observations"}},
        {"missing.json", R"([{"camera": "camera1", "X": 0, "Y": 0, "Z": 2, "x": 321}])", {"\"[0].y\"", "missing"}},
        {"string.json", R"([{"camera": "camera1", "X": 0, "Y": "zero", "Z": 2, "x": 321, "y": 1}])",
         {"\"[0].Y\"", "zero"}},
        {"object.json", R"({"camera": "camera1"})", {"expected a list of observations"}},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        const std::filesystem::path table = write_file(c.name, c.text);
        const std::string message = error_reading(table, cameras);
        INFO(message);
        CHECK(message.find(table.string() + ":") == 0);
        CHECK(message.find('\n') == std::string::npos);
        for (const std::string& part : c.said) CHECK(message.find(part) != std::string::npos);
        std::filesystem::remove(table);
    }
    std::filesystem::remove(cameras);
}
