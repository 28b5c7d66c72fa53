// The commands that read a file agree on what it is: `libcam info`, `libcam reproject` and
// `libcam dataset` each refuse a damaged file with the same one line and exit 1, or each
// read it. The files are written here, small, each with one damage; every expected line
// is worked by hand from the damage.

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "temp_dir.hpp"

namespace {

using libcam::test::CliResult;
using libcam::test::run_libcam;
using libcam::test::TempDir;
namespace fs = std::filesystem;

// A COLMAP text model: a 640x480 PINHOLE (f 500), images 1 and 2, each seeing points 10
// and 20 with their first and second 2-D points.
struct ColmapText {
    std::string cameras = "1 PINHOLE 640 480 500 500 320.5 240.5\n";
    std::string images = "1 1 0 0 0 0 0 0 1 a.jpg\n"
                         "323.5 244.5 10 445.5 303 20 100 100 -1\n"
                         "2 1 0 0 0 -1 0 0 1 b.jpg\n"
                         "70.5 241.5 10 320.5 303 20\n";
    std::string points = "10 0 0 2 255 0 0 3 1 0 2 0\n"
                         "20 1 0.5 4 0 255 0 0.25 1 1 2 1\n";

    ColmapText& replace(std::string ColmapText::*file, const std::string& from, const std::string& to) {
        std::string& text = this->*file;
        const std::size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
        return *this;
    }

    fs::path write(const fs::path& folder) const {
        fs::create_directories(folder);
        libcam::test::write_whole_file(folder / "cameras.txt", cameras);
        libcam::test::write_whole_file(folder / "images.txt", images);
        libcam::test::write_whole_file(folder / "points3D.txt", points);
        return folder;
    }
};

// The line without what a command that detects the file's format adds at its end
// ("(read as NeRF transforms.json, by its extension .json and its keys)"): a command
// told the format (dataset) has nothing to add.
std::string without_detection(const std::string& line) {
    const std::size_t at = line.rfind(" (read as ");
    return at != std::string::npos && line.ends_with(")\n") ? line.substr(0, at) + "\n" : line;
}

// Each command refuses with exit 1, nothing on stdout and the one line
// "libcam: error: <message>"; the commands' lines are the same.
void refused_alike(const std::vector<std::vector<std::string>>& commands, const std::string& message) {
    for (const std::vector<std::string>& command : commands) {
        const CliResult result = run_libcam(command);
        INFO(command.front() << ": " << result.describe());
        CHECK(result.exit_code == 1);
        CHECK(result.out.empty());
        CHECK(without_detection(result.err) == "libcam: error: " + message + "\n");
    }
}

std::vector<std::vector<std::string>> colmap_commands(const fs::path& model, const fs::path& out) {
    return {{"info", model.string()},
            {"reproject", model.string()},
            {"dataset", model.string(), "-o", out.string(), "--no-images"}};
}

}  // namespace

TEST_CASE("info, reproject and dataset refuse each damaged COLMAP model with the same line") {
    TempDir dir;
    const fs::path model = dir / "model";
    const std::string points_txt = (model / "points3D.txt").string();
    const std::string images_txt = (model / "images.txt").string();
    struct Damage {
        const char* what;
        std::function<void(ColmapText&)> damage;
        std::string message;
    };
    const std::vector<Damage> damages = {
        {"a track naming POINT2D_IDX 1000000",
         [](ColmapText& m) { m.replace(&ColmapText::points, "3 1 0 2 0", "3 1 0 2 1000000"); },
         points_txt + ": POINT3D_ID 10: TRACK[1]: POINT2D_IDX 1000000 is not one of image 2 (b.jpg)'s 2 POINTS2D"},
        {"the last image's line of 2-D points missing, its points in tracks",
         [](ColmapText& m) { m.replace(&ColmapText::images, "70.5 241.5 10 320.5 303 20\n", ""); },
         points_txt + ": POINT3D_ID 10: TRACK[1]: POINT2D_IDX 0 is not one of image 2 (b.jpg)'s 0 POINTS2D"},
        {"a 2-D point of a point points3D lacks",
         [](ColmapText& m) { m.replace(&ColmapText::images, "445.5 303 20", "445.5 303 99"); },
         images_txt + ": line 1: image 1 (a.jpg): POINTS2D[1]: POINT3D_ID 99 is not in points3D.txt"},
        {"a 2-D point its point's track leaves out",
         [](ColmapText& m) { m.replace(&ColmapText::points, "0.25 1 1 2 1", "0.25 1 1"); },
         images_txt + ": line 3: image 2 (b.jpg): POINTS2D[1]: POINT3D_ID 20's track in points3D.txt does not name it"},
        {"a track naming another point's 2-D point",
         [](ColmapText& m) { m.replace(&ColmapText::points, "0.25 1 1 2 1", "0.25 1 0 2 1"); },
         points_txt + ": POINT3D_ID 20: TRACK[0]: image 1 (a.jpg)'s POINTS2D[0] is POINT3D_ID 10's"},
        {"fx = 5e-324, which is positive but subnormal",
         [](ColmapText& m) { m.replace(&ColmapText::cameras, "640 480 500 500", "640 480 5e-324 500"); },
         (model / "cameras.txt").string() +
             ": line 1: camera 1: K.fx: 5e-324 is subnormal (a focal length must be at least 2.2250738585072014e-308)"},
    };
    for (const Damage& damage : damages) {
        CAPTURE(damage.what);
        ColmapText text;
        damage.damage(text);
        fs::remove_all(model);
        refused_alike(colmap_commands(text.write(model), dir / "out"), damage.message);
        CHECK_FALSE(fs::exists(dir / "out" / "sparse"));
    }
}

TEST_CASE("info, reproject and dataset all read a COLMAP model whose track links a 2-D point of no point") {
    TempDir dir;
    // Point 20's track names image 1's third 2-D point, which names no point: COLMAP links it.
    const fs::path model =
        ColmapText().replace(&ColmapText::points, "0.25 1 1 2 1", "0.25 1 1 2 1 1 2").write(dir / "model");
    for (const std::vector<std::string>& command : colmap_commands(model, dir / "out")) {
        const CliResult result = run_libcam(command);
        INFO(command.front() << ": " << result.describe());
        CHECK(result.exit_code == 0);
    }
    // Four observations and the linked one.
    const CliResult json = run_libcam({"reproject", model.string(), "--json"});
    CHECK(json.out.find("\"count\": 5") != std::string::npos);
}

TEST_CASE("info and dataset refuse a transforms.json whose k1 leaves the lens no scale, in one line") {
    TempDir dir;
    // k1 = 1e30: near the axis r = C t^(1/3) at t pixels off it. From 2^-20 of a pixel, r
    // moves per pixel (2^(-10/3) - 2^(-20/3)) C / (2^-10 - 2^-20) over the first 1/1024 and
    // (1 - 2^(-20/3)) C / (1 - 2^-20) over the whole pixel: 92.5 times less.
    const fs::path json = libcam::test::write_file(
        dir, "transforms.json",
        R"({"fl_x": 500, "fl_y": 500, "cx": 320, "cy": 240, "w": 640, "h": 480, "k1": 1e30,
            "frames": [{"file_path": "a.png", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]})");
    refused_alike({{"info", json.string()}, {"dataset", json.string(), "-o", (dir / "out").string(), "--no-images"}},
                  json.string() + ": \"frames[0]\": dist[0] (k1): 1e+30: the lens's scale changes by a factor of 92.5 "
                                  "within the pixel (1, 0) off the principal point (by at most 2 in a camera: its "
                                  "focal length is the lens's scale there)");
}

TEST_CASE("info and reproject refuse an OpenMVG or AliceVision view naming a missing intrinsic, in one line") {
    TempDir dir;
    const fs::path openmvg = libcam::test::write_file(
        dir, "sfm_data.json",
        R"({"sfm_data_version": "0.3", "root_path": "/x",
  "views": [{"key": 4, "value": {"polymorphic_id": 1073741824, "ptr_wrapper": {"id": 2147483649, "data": {
    "local_path": "", "filename": "v4.jpg", "width": 640, "height": 480, "id_view": 4, "id_intrinsic": 7, "id_pose": 4}}}}],
  "intrinsics": [{"key": 0, "value": {"polymorphic_id": 2147483649, "polymorphic_name": "pinhole",
    "ptr_wrapper": {"id": 2147483650, "data": {"width": 640, "height": 480, "focal_length": 500,
    "principal_point": [320, 240]}}}}],
  "extrinsics": [{"key": 4, "value": {"rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "center": [0, 0, 0]}}],
  "structure": [], "control_points": []})");
    refused_alike({{"info", openmvg.string()}, {"reproject", openmvg.string()}},
                  openmvg.string() + ": \"views[0].value.ptr_wrapper.data.id_intrinsic\": view 4 names intrinsic 7, "
                                     "which \"intrinsics\" lacks");
    const fs::path alicevision = libcam::test::write_file(
        dir, "cameras.sfm",
        R"({"version": ["1", "2", "6"],
  "views": [{"viewId": "4", "poseId": "4", "intrinsicId": "7", "path": "v4.jpg", "width": "640", "height": "480"}],
  "intrinsics": [{"intrinsicId": "1", "width": "640", "height": "480", "type": "pinhole", "focalLength": "20",
    "principalPoint": ["0", "0"]}],
  "poses": [{"poseId": "4", "pose": {"transform": {"rotation": ["1", "0", "0", "0", "1", "0", "0", "0", "1"],
    "center": ["0", "0", "0"]}}}]})");
    refused_alike({{"info", alicevision.string()}, {"reproject", alicevision.string()}},
                  alicevision.string() + ": \"views[0].intrinsicId\": view 4 names intrinsic 7, which \"intrinsics\" "
                                         "lacks");
}

namespace {

// A small mrcal solve written by mrcal's own API (tests/observations/mrcal_optimization_inputs.py:
// an OPENCV4 camera, fx 800, 640x480, seeing a board and points); `variant` as the script
// names it. Fails the test unless the script exits 0.
fs::path mrcal_solve(const TempDir& dir, const std::string& variant) {
    const fs::path script = fs::path(LIBCAM_DOCS_DIR).parent_path() / "tests/observations/mrcal_optimization_inputs.py";
    const fs::path model = dir / (variant + ".cameramodel");
    const CliResult written = libcam::test::run_program("/usr/bin/python3", {script.string(), "write", model.string(), variant});
    INFO(written.describe());
    REQUIRE(written.exit_code == 0);
    return model;
}

}  // namespace

TEST_CASE("info and reproject refuse a .cameramodel whose fx is 1e999 with the same line") {
    TempDir dir;
    const fs::path model = mrcal_solve(dir, "good");
    std::string text = libcam::test::read_whole_file(model);
    const std::string intrinsics = "'intrinsics': [ 800,";
    REQUIRE(text.find(intrinsics) != std::string::npos);
    text.replace(text.find(intrinsics), intrinsics.size(), "'intrinsics': [ 1e999,");
    libcam::test::write_whole_file(model, text);
    // libmrcal's parser refuses the number (its words are its own), for `info` as for `reproject`.
    const CliResult info = run_libcam({"info", model.string()});
    INFO(info.describe());
    const std::string prefix = "libcam: error: ";
    REQUIRE(info.err.starts_with(prefix));
    const std::string message = info.err.substr(prefix.size(), info.err.find('\n') - prefix.size());
    CHECK(message.starts_with(model.string() + ": "));
    CHECK(message.find("1e999") != std::string::npos);
    refused_alike({{"info", model.string()}, {"reproject", model.string()}}, message);
}

TEST_CASE("reproject refuses a .cameramodel whose solve kept no observations, whose camera info reads") {
    TempDir dir;
    const fs::path model = mrcal_solve(dir, "no-observations");
    CHECK(run_libcam({"info", model.string()}).exit_code == 0);
    refused_alike({{"reproject", model.string()}},
                  model.string() + ": optimization_inputs: observations_board and observations_point hold no "
                                   "observation (the solve's inputs were saved without them): nothing to reproject");
}
