// `libcam calibrate` as a user runs it: a folder of rendered board images to the JSON
// report, the chosen camera's file, and the observations file that `libcam reproject`
// reads back to calibrate's own RMS; and the refusals, one line each.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "libcam/io/camera_file.hpp"
#include "synthetic_sets.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

// Five views of the chessboard through the OPENCV5 lens, as PNG files, and one file
// named like an image that is not one.
void write_board_folder(const std::filesystem::path& folder) {
    const BoardSpec board = parse_board_spec("chessboard:9x6:0.03");
    std::vector<PoseSpec> poses = opencv5_poses();
    poses.resize(6);
    const std::vector<SyntheticView> views = render_views(opencv5_truth(), board, chessboard_texture(board), poses);
    for (std::size_t v = 0; v < views.size(); ++v) {
        cv::imwrite((folder / ("board" + std::to_string(v) + ".png")).string(), views[v].image);
    }
    write_whole_file(folder / "broken.png", "not an image");
    write_whole_file(folder / "notes.txt", "left alone: not named as an image");
}

}  // namespace

TEST_CASE("libcam calibrate: JSON report, -o, and --observations-out that libcam reproject reads back",
          "[calibrate][cli]") {
    TempDir dir;
    const std::filesystem::path images = dir / "images";
    std::filesystem::create_directory(images);
    write_board_folder(images);
    const CliResult run = run_libcam({"calibrate", images.string(), "--board", "chessboard:9x6:0.03", "--model",
                                      "OPENCV4,OPENCV5", "--json", "-o", (dir / "camera.yaml").string(),
                                      "--observations-out", (dir / "observations.yml").string(), "--progress", "never",
                                      "--at", "319.5,239.5", "--at", "40,30", "--heatmap", (dir / "sigma.png").string()});
    REQUIRE(run.exit_code == 0);
    INFO(run.describe());
    const nlohmann::json report = nlohmann::json::parse(run.out);
    CHECK(report["images"] == 7);
    CHECK(report["used"] == 6);
    REQUIRE(report["rejected"].size() == 1);
    CHECK(report["rejected"][0]["image"] == (images / "broken.png").string());
    CHECK(report["rejected"][0]["why"] == "cannot be read as an image");
    CHECK(report["corners"] == 6 * 54);
    const nlohmann::json& chosen = report["chosen"];
    CHECK(chosen["model"] == "OPENCV5");
    CHECK(chosen["image_size"] == nlohmann::json::array({640, 480}));
    CHECK(chosen["dist"].size() == 5);
    CHECK(report["candidates"].size() == 2);
    for (const char* key : {"model", "rms_px", "heldout_rms_px"}) CHECK(report["candidates"][0].contains(key));
    REQUIRE(report["views"].size() == 6);
    for (const char* key : {"image", "corners", "rms_px", "rvec", "tvec"}) CHECK(report["views"][0].contains(key));
    // The projection uncertainty at each --at pixel; each candidate's beside its held-out RMS.
    REQUIRE(report["uncertainty"].size() == 2);
    CHECK(report["uncertainty"][1]["pixel"] == nlohmann::json::array({40.0, 30.0}));
    const double centre_sigma = report["uncertainty"][0]["sigma_px"].get<double>();
    CHECK(centre_sigma > 0.0);
    CHECK(report["uncertainty"][1]["sigma_px"].get<double>() > centre_sigma);
    for (const char* key : {"noise_px", "centre_sigma_px", "worst_observed_sigma_px", "parameters"}) {
        CHECK(report["candidates"][1]["uncertainty"].contains(key));
    }
    CHECK(report["candidates"][1]["uncertainty"]["centre_sigma_px"].get<double>() == Approx(centre_sigma));
    CHECK(std::filesystem::file_size(dir / "sigma.png") > 1000);

    // The camera written is the one reported.
    const Camera written = read_camera_file(dir / "camera.yaml").camera;
    CHECK(written.intrinsics.fx == chosen["K"][0][0].get<double>());
    CHECK(written.intrinsics.cy == chosen["K"][1][2].get<double>());
    CHECK(written.lens.coefficients[0] == chosen["dist"][0].get<double>());

    // The board's true pose in view 0 (X_cam = R X_board + t), against the reported one.
    const Pose truth = board_pose(parse_board_spec("chessboard:9x6:0.03"), opencv5_poses()[0].centre,
                                  opencv5_poses()[0].tilt);
    const Vec3 tvec(report["views"][0]["tvec"][0], report["views"][0]["tvec"][1], report["views"][0]["tvec"][2]);
    // Either numbering of the corners (the board turned half a turn) is the same board.
    const Vec3 far_corner = truth.camera_from_world(Vec3(8 * 0.03, 5 * 0.03, 0.0));
    CHECK(std::min((tvec - truth.t).norm(), (tvec - far_corner).norm()) < 0.005);

    // libcam reproject reads the corners and poses back, and gives calibrate's own RMS.
    REQUIRE(report["outliers"]["corners"] == 0);
    const CliResult again = run_libcam({"reproject", (dir / "observations.yml").string(), "--json"});
    REQUIRE(again.exit_code == 0);
    const nlohmann::json reprojected = nlohmann::json::parse(again.out);
    CHECK(reprojected["count"] == 6 * 54);
    // The file's reader holds the board's corners in float as OpenCV's sample does: a few
    // 1e-9 m, a few 1e-6 px at these distances.
    CHECK(reprojected["rms_px"].get<double>() == Approx(chosen["rms_px"].get<double>()).margin(1e-5));

    // libcam uncertainty reads the same corners and poses from that file: the same sigma.
    const CliResult uncertainty =
        run_libcam({"uncertainty", (dir / "observations.yml").string(), "--at", "319.5,239.5", "--json"});
    INFO(uncertainty.describe());
    REQUIRE(uncertainty.exit_code == 0);
    const nlohmann::json sigma = nlohmann::json::parse(uncertainty.out);
    CHECK(sigma["at"][0]["sigma_px"].get<double>() == Approx(centre_sigma).epsilon(1e-3));
}

TEST_CASE("libcam calibrate refuses in one line: a bad board spec, no usable image", "[calibrate][cli]") {
    TempDir dir;
    write_whole_file(dir / "broken.png", "not an image");
    const CliResult spec = run_libcam({"calibrate", (dir / "broken.png").string(), "--board", "chessboard:9x6"});
    CHECK(spec.exit_code == 2);
    CHECK(spec.out.empty());
    CHECK(spec.err ==
          "libcam: usage error: --board: board 'chessboard:9x6': form: expected chessboard:CxR:SQUARE (inner corners, "
          "square side in metres), got 2 parts (see --help)\n");
    const CliResult none = run_libcam({"calibrate", dir.path().string(), "--board", "chessboard:9x6:0.03"});
    CHECK(none.exit_code == 1);
    CHECK(none.out.empty());
    CHECK(none.err == "libcam: error: calibrate: 0 of 1 images usable, a calibration needs at least two; " +
                          (dir / "broken.png").string() + ": cannot be read as an image\n");
}

TEST_CASE("libcam calibrate with OpenCV's flags on OpenCV's sample images: its stored RMS and the model they support",
          "[calibrate][cli][real]") {
    const std::filesystem::path folder = std::filesystem::path(LIBCAM_REAL_DATA) / "opencv-stereo-samples";
    if (!std::filesystem::is_directory(folder)) {
        WARN("skipped: no folder opencv-stereo-samples in " LIBCAM_REAL_DATA);
        return;
    }
    // OpenCV's calibration sample's own output for these images: its flags and its RMS.
    cv::FileStorage stored((folder / "left_intrinsics.yml").string(), cv::FileStorage::READ);
    REQUIRE(stored.isOpened());
    const int flags = static_cast<int>(stored["flags"]);
    const double stored_rms = static_cast<double>(stored["avg_reprojection_error"]);
    std::vector<std::string> args = {"calibrate"};
    for (const char* name : {"01", "02", "03", "04", "05", "06", "07", "08", "09", "11", "12", "13", "14"}) {
        args.push_back((folder / ("left" + std::string(name) + ".jpg")).string());
    }
    for (const std::string& more : {std::string("--board"), std::string("chessboard:9x6:0.025"), std::string("--opencv-flags"),
                                    std::to_string(flags), std::string("--corners"), std::string("opencv-sample"),
                                    std::string("--keep-outliers"), std::string("--json"), std::string("--progress"),
                                    std::string("never")}) {
        args.push_back(more);
    }
    const CliResult run = run_libcam(args);
    INFO(run.describe());
    REQUIRE(run.exit_code == 0);
    const nlohmann::json report = nlohmann::json::parse(run.out);
    CHECK(report["held"] == "fx = fy");
    CHECK(report["corners"] == 13 * 54);
    bool found = false;
    for (const nlohmann::json& candidate : report["candidates"]) {
        if (candidate["model"] != "OPENCV5") continue;
        found = true;
        CHECK(candidate["params"] == 8);
        CHECK(std::abs(candidate["rms_px"].get<double>() / stored_rms - 1.0) < 0.01);
    }
    CHECK(found);
    const nlohmann::json& K = report["chosen"]["K"];
    CHECK(K[0][0].get<double>() == K[1][1].get<double>());
}

TEST_CASE("libcam calibrate refuses OpenCV's flags it does not take in one line", "[calibrate][cli]") {
    TempDir dir;
    write_whole_file(dir / "broken.png", "not an image");
    for (const char* flags : {"FIX_PRINCIPAL_POINT", "16386", "FIX_ASPECT", ""}) {
        const CliResult run =
            run_libcam({"calibrate", (dir / "broken.png").string(), "--board", "chessboard:9x6:0.03", "--opencv-flags", flags});
        INFO(flags << ": " << run.describe());
        CHECK(run.exit_code == 2);
        CHECK(run.out.empty());
        CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
        CHECK(run.err.find("--opencv-flags") != std::string::npos);
    }
}

TEST_CASE("libcam calibrate refuses a pair without both sides or with lists of different lengths in one line",
          "[calibrate][cli][pair]") {
    TempDir dir;
    write_whole_file(dir / "broken.png", "not an image");
    const std::string image = (dir / "broken.png").string();
    const CliResult one_side = run_libcam({"calibrate", "--left", image, "--board", "chessboard:9x6:0.03"});
    CHECK(one_side.exit_code == 2);
    CHECK(one_side.err == "libcam: usage error: a pair needs both --left and --right images (see --help)\n");
    const CliResult lengths =
        run_libcam({"calibrate", "--left", image, image, "--right", image, "--board", "chessboard:9x6:0.03", "-o",
                    (dir / "out").string()});
    CHECK(lengths.exit_code == 1);
    CHECK(lengths.out.empty());
    CHECK(lengths.err == "libcam: error: calibrate: 2 images of the first camera and 1 of the second: a pair needs one "
                         "of each per view\n");
    CHECK(!std::filesystem::exists(dir / "out"));
    // What is for one camera, and a pixel that is none, before any image is read.
    const CliResult heatmap = run_libcam({"calibrate", "--left", image, "--right", image, "--board",
                                          "chessboard:9x6:0.03", "--heatmap", (dir / "h.png").string()});
    CHECK(heatmap.exit_code == 2);
    CHECK(heatmap.err ==
          "libcam: usage error: --heatmap, --observations-out and --to are for one camera, not a pair (see --help)\n");
    const CliResult at = run_libcam({"calibrate", "--left", image, "--right", image, "--board", "chessboard:9x6:0.03",
                                     "--at", "twenty,30"});
    CHECK(at.exit_code == 2);
    CHECK(std::count(at.err.begin(), at.err.end(), '\n') == 1);
    CHECK(at.err.find("--at") != std::string::npos);
    CHECK(at.err.find("twenty") != std::string::npos);
}

TEST_CASE("libcam calibrate --pairs refuses a list with an odd count in one line", "[calibrate][cli][pair]") {
    TempDir dir;
    write_whole_file(dir / "list.yml", "%YAML:1.0\nimagelist:\n  - a.png\n  - b.png\n  - c.png\n");
    const CliResult run =
        run_libcam({"calibrate", "--pairs", (dir / "list.yml").string(), "--board", "chessboard:9x6:0.03"});
    CHECK(run.exit_code != 0);
    CHECK(run.out.empty());
    CHECK(run.err.find((dir / "list.yml").string() + ": imagelist: 3 names, an odd count") != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
}
