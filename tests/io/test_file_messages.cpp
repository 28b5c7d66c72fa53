// What a message says about a file that is not what it seems: the file, what libcam took
// it for (and why: its extension, its keys, its contents, or the default of its
// extension), the field and the value, on one printable line. Every file is made here,
// small, from the formats' documented keys; each expected message is written out whole.

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "error_message.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/observations.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;
using libcam::test::write_file;
using namespace std::string_literals;

namespace {

// One line of printable ASCII (the expected messages are ASCII: a byte outside it is a
// byte of the file let through).
bool printable_line(const std::string& message) {
    for (const char c : message) {
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7E) return false;
    }
    return true;
}

// The message of reading `path` (its format found by libcam), checked to be one printable line.
std::string read_error(const std::filesystem::path& path) {
    const std::string message = file_error_of([&] { (void)read_camera_set(path); });
    CHECK(printable_line(message));
    return message;
}

std::string observations_error(const std::filesystem::path& path) {
    const std::string message = file_error_of([&] { (void)read_observations(path); });
    CHECK(printable_line(message));
    return message;
}

// The formats a .json file may be besides libcam's own and gl, by their claims, in the
// table's order: what a message lists when a .json file is none of them.
const std::string kJsonFormats =
    "basalt, nerf, open3d, openicc, blender-json, opensfm, openmvg, gs-cameras, alicevision, gyroflow, "
    "py-ocamcalib, woodscape or driveworks-rig";

// 3D Gaussian Splatting's cameras.json holds, per camera, id, img_name, width, height,
// position, rotation, fy and fx (its utils/camera_utils.py camera_to_JSON).
const std::string kGsCameraWithoutFx =
    R"([{"id": 0, "img_name": "a", "width": 640, "height": 480, "position": [0, 0, 0],)"
    R"( "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fy": 500}])";

}  // namespace

TEST_CASE("A .json that fails its format's claims is read as the format its keys tell, not as libcam JSON",
          "[messages]") {
    const test::TempDir dir;
    // 3DGS without fx: its key img_name says 3DGS.
    const auto gs = write_file(dir, "cameras.json", kGsCameraWithoutFx);
    CHECK(read_error(gs) == gs.string() + ": \"[0].fx\": missing (read as 3D Gaussian Splatting cameras.json, by its "
                                          "extension .json and its key \"img_name\")");
    // A Gyroflow lens profile without its fisheye_params (Gyroflow's lens profiles hold
    // calib_dimension {w, h} and fisheye_params {camera_matrix, distortion_coeffs}).
    const auto gyroflow = write_file(dir, "lens.json", R"({"calib_dimension": {"w": 1920, "h": 1080}, "calibrator_version": "1.5"})");
    CHECK(read_error(gyroflow) == gyroflow.string() + ": \"fisheye_params\": missing (read as Gyroflow lens profile, by "
                                                      "its extension .json and its keys \"calib_dimension\", "
                                                      "\"calibrator_version\")");
    // OpenSfM's reconstruction.json is a list of reconstructions with cameras, shots and
    // points; one whose first reconstruction has only points is still OpenSfM's.
    const auto opensfm = write_file(dir, "reconstruction.json", R"([{"points": {}}])");
    CHECK(read_error(opensfm) == opensfm.string() + ": \"[0].cameras\": missing (read as OpenSfM reconstruction.json, "
                                                    "by its extension .json and its key \"points\")");
    // The same for reproject, which reads its observations: not "a libcam JSON file".
    CHECK(observations_error(opensfm) == read_error(opensfm));
}

TEST_CASE("A .json no format claims says it fell back to libcam JSON, which formats it is not, and why that failed",
          "[messages]") {
    const test::TempDir dir;
    const auto other = write_file(dir, "other.json", R"({"focal": 500})");
    CHECK(read_error(other) == other.string() + ": \"model\": missing (read as libcam JSON, the default for .json "
                                                "files: its keys are those of none of " + kJsonFormats + ")");
    // Cut short: no keys to tell the format by.
    const auto cut = write_file(dir, "cut.json", R"({"img_name": "a", "fx": )");
    const std::string cut_error = read_error(cut);
    CHECK(cut_error.starts_with(cut.string() + ": \"fx\": not valid JSON: "));
    CHECK(cut_error.ends_with(" (its keys, which tell the formats of .json files apart, cannot be read)"));
    // reproject says the same of a camera file that holds no observations.
    const auto camera = write_file(dir, "camera.json", R"({"model": "PINHOLE", "image_size": [640, 480],)"
                                                       R"( "K": [[500, 0, 319.5], [0, 500, 239.5], [0, 0, 1]],)"
                                                       R"( "rvec": [0, 0, 0], "t": [0, 0, 0]})");
    CHECK(observations_error(camera).starts_with(camera.string() + ": libcam JSON holds no observations (files that do: "));
    CHECK(observations_error(camera).ends_with(" (read as libcam JSON, the default for .json files: its keys are those "
                                               "of none of " + kJsonFormats + ")"));
}

TEST_CASE("A file whose extension names only XML or JSON formats must be that", "[messages]") {
    const test::TempDir dir;
    const std::string xml_formats = "(libcam reads .xml files as OpenCV XML, Agisoft Metashape XML or lensfun database XML)";
    const auto words = write_file(dir, "words.xml", "camera_matrix: [1, 2]\n");
    CHECK(read_error(words) == words.string() + ": not XML: it starts with 'camera_matrix: [1, 2]', not '<' " + xml_formats);
    // Random bytes: each shown as \xNN, the start cut after 24 characters.
    const auto random = write_file(dir, "random.xml", "\x8B\xE2x\xB4\x01\x02 and more bytes than are shown"s);
    CHECK(read_error(random) == random.string() + ": not XML: it starts with '\\x8B\\xE2x\\xB4\\x01\\x02 and more bytes "
                                                  "th...', not '<' " + xml_formats);
    // XML that does not parse is broken whichever format it was meant to be.
    const auto broken = write_file(dir, "broken.xml", "<opencv_storage><a></b>");
    CHECK(read_error(broken) == broken.string() + ": line 1: not valid XML: Start-end tags mismatch (its keys, which tell "
                                                  "the formats of .xml files apart, cannot be read)");
    // YAML that does not parse is read by the default, OpenCV's, which also takes XML.
    const auto yaml_cut = write_file(dir, "cut.yaml", "camera_matrix: [1, 2\n");
    CHECK(read_error(yaml_cut) == yaml_cut.string() + ": line 2: not valid YAML: end of sequence flow not found (read as "
                                                      "OpenCV YAML, the default for .yaml files: it does not parse, so its "
                                                      "keys could not tell which format it is)");
    const auto yaml = write_file(dir, "camera.json", "image_width: 640\n");
    CHECK(read_error(yaml) == yaml.string() + ": not JSON: it starts with 'image_width: 640', not '{' or '[' (libcam "
                                              "reads .json files as libcam JSON, gl JSON, basalt calibration JSON, NeRF "
                                              "transforms.json, Open3D camera JSON, OpenImuCameraCalibrator JSON, Blender "
                                              "camera JSON, OpenSfM reconstruction.json, OpenMVG sfm_data.json, 3D "
                                              "Gaussian Splatting cameras.json, AliceVision SfMData, Gyroflow lens "
                                              "profile, py-OCamCalib JSON, WoodScape calibration JSON or DriveWorks rig "
                                              "JSON)");
}

TEST_CASE("Text in UTF-16 or UTF-32 is refused as such, UTF-8 with a byte-order mark read", "[messages]") {
    const test::TempDir dir;
    const std::string line = "1 PINHOLE 640 480 500 500 320 240\n";
    std::string utf16le = "\xFF\xFE", utf16be, utf32le = "\xFF\xFE\0\0"s;
    for (const char c : line) {
        utf16le += std::string{c, '\0'};
        utf16be += std::string{'\0', c};
        utf32le += std::string{c, '\0', '\0', '\0'};
    }
    const std::string refused = " text: libcam reads camera files as UTF-8; save it as UTF-8";
    const auto le = write_file(dir, "cameras.txt", utf16le);
    CHECK(read_error(le) == le.string() + ": UTF-16" + refused);
    const auto be = write_file(dir, "camera.json", utf16be);
    CHECK(read_error(be) == be.string() + ": UTF-16" + refused);
    const auto wide = write_file(dir, "wide.txt", utf32le);
    CHECK(read_error(wide) == wide.string() + ": UTF-32" + refused);
    // Given as a COLMAP folder, the same.
    std::filesystem::create_directory(dir / "model");
    write_file(dir, "model/cameras.txt", utf16le);
    CHECK(read_error(dir / "model") == (dir / "model/cameras.txt").string() + ": UTF-16" + refused);
    // UTF-8's byte-order mark, which some editors write, is skipped.
    const auto marked = write_file(dir, "marked.txt", "\xEF\xBB\xBF" + line);
    CHECK(read_camera_set(marked).format == CameraFormat::Colmap);
}

TEST_CASE("OCamCalib's calib_results.txt is OCamCalib's wherever its comment is, and without its comments",
          "[messages]") {
    const test::TempDir dir;
    // The toolbox's five sections (ocam_functions.cpp get_ocam_model reads them in this order).
    const std::string numbers = "5 -150 0 0.002 -1e-06 0\n\n3 200 100 10\n\n149.5 199.25\n\n1 0 0\n\n300 400\n";
    const std::string comment =
        "#polynomial coefficients for the DIRECT mapping function (ocam_model.ss in MATLAB). These are used by cam2world\n";
    for (const std::string& text : {"# my fisheye, calibrated on Monday\n" + comment + numbers, numbers,
                                    "\n\n" + numbers + "\n# image size: \"height\" and \"width\" of ocam_model\n"}) {
        const auto path = write_file(dir, "calib_results.txt", text);
        CHECK(read_camera_set(path).format == CameraFormat::OcamCalib);
    }
    // Broken, it is still OCamCalib's, and says so.
    const auto broken = write_file(dir, "calib.txt", comment + "5 -150 0 0.002 -1e-06 x0\n");
    CHECK(read_error(broken) == broken.string() + ": line 2: the DIRECT mapping polynomial (pol: count, a0, a1, ...): "
                                                  "expected a number, got 'x0' (read as OCamCalib calib_results.txt, by "
                                                  "its contents (OCamCalib's text))");
    // COLMAP's cameras.txt stays COLMAP's.
    const auto colmap = write_file(dir, "cameras.txt", "# Camera list\n1 PINHOLE 640 480 500 500 320 240\n");
    CHECK(read_camera_set(colmap).format == CameraFormat::Colmap);
    const auto wrong = write_file(dir, "wrong.txt", "1 PINHOL 640 480 500 500 320 240\n");
    CHECK(read_error(wrong).ends_with(" got 'PINHOL' (read as COLMAP model, the default for tables of numbers and words "
                                      "(--from-format names another))"));
}

TEST_CASE("NVM and Bundler messages show a file's bytes escaped, and refuse bytes that are not UTF-8", "[messages]") {
    const test::TempDir dir;
    ReadOptions options;
    options.size = ImageSize{640, 480};
    // NVM_V3: a camera line is name, focal, quaternion (4), centre (3), distortion, 0.
    const auto escape = write_file(dir, "a.nvm", "NVM_V3\n\n1\nimg.jpg 500 1\x1b[31m 0 0 0 0 0 0 0 0\n");
    CHECK(file_error_of([&] { (void)read_camera_set(escape, std::nullopt, options); }) ==
          escape.string() + ": line 4: camera 0 quaternion: expected a number, got '1\\x1B[31m'");
    const auto binary = write_file(dir, "b.nvm", "NVM_V3\n\n1\nimg\xFF\xFE.jpg 500 1 0 0 0 0 0 0 0 0\n");
    const std::string not_utf8 = binary.string() + ": byte 13: not UTF-8 (libcam reads .nvm files as VisualSfM NVM, "
                                                   "which is text)";
    CHECK(file_error_of([&] { (void)read_camera_set(binary, std::nullopt, options); }) == not_utf8);
    ObservationReadOptions observation_options;
    observation_options.size = ImageSize{640, 480};
    CHECK(file_error_of([&] { (void)read_observations(binary, observation_options); }) == not_utf8);
    // Bundler's bundle.out: "# Bundle file v0.3", then the counts, then f k1 k2 per camera.
    const auto bundle = write_file(dir, "bundle.out", "# Bundle file v0.3\n1 0\n5\x7f 0 0\n");
    CHECK(file_error_of([&] { (void)read_observations(bundle, observation_options); }) ==
          bundle.string() + ": line 3: camera 0 f: expected a number, got '5\\x7F'");
    // A long value is cut.
    const auto long_word = write_file(dir, "c.nvm", "NVM_V" + std::string(200, '3') + "\n");
    CHECK(file_error_of([&] { (void)read_camera_set(long_word, std::nullopt, options); }) ==
          long_word.string() + ": line 1: expected the header NVM_V3, got 'NVM_V" + std::string(55, '3') +
              "...' (205 bytes)");
}

TEST_CASE("A symlink loop is reported as the system says it, not as a file that is not there", "[messages]") {
    const test::TempDir dir;
    std::filesystem::create_directory(dir / "sparse");
    std::filesystem::create_symlink("cameras.bin", dir / "sparse/cameras.bin");  // points at itself
    CHECK(read_error(dir / "sparse") == (dir / "sparse/cameras.bin").string() + ": Too many levels of symbolic links");
    CHECK(observations_error(dir / "sparse") ==
          (dir / "sparse/cameras.bin").string() + ": Too many levels of symbolic links");
    std::filesystem::create_symlink("b.json", dir / "a.json");
    std::filesystem::create_symlink("a.json", dir / "b.json");
    CHECK(read_error(dir / "a.json") == (dir / "a.json").string() + ": cannot open: Too many levels of symbolic links");
    CHECK(read_error(dir / "absent.json") == (dir / "absent.json").string() + ": cannot open: No such file or directory");
}

TEST_CASE("A message that quotes a long key of a file is cut, still saying what the file was read as", "[messages]") {
    const test::TempDir dir;
    // OpenSfM's camera_models.json: cameras by name, each with its projection_type. A
    // name of 5000 characters, and no width.
    const std::string name(5000, 'n');
    const auto cameras = write_file(dir, "camera_models.json", "{\"" + name + "\": {\"projection_type\": \"perspective\"}}");
    const std::string error = read_error(cameras);
    const std::string read_as = " (read as OpenSfM reconstruction.json, by its extension .json and its keys)";
    CHECK(error.starts_with(cameras.string() + ": \".nnnnn"));
    CHECK(error.ends_with("..." + read_as));
    CHECK(error.size() == 2000 + 3 + read_as.size());
}
